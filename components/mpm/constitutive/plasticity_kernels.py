"""The sub-models of Uintah's elastic_plastic (ElasticPlasticHP) as numba functions.

Each family is one inline function whose first argument is the sub-model's code; the
kernel factory of elastic_plastic_hp.py calls them with that code as a compile-time
constant, so every deck gets a kernel with only its own branch. Parameter vectors hold
the deck tags in the order of the tables in elastic_plastic_hp.py. Formulas and their
guards follow Uintah's PlasticityModels/ (the references name the source paper).
"""
import math

from numba import njit

# flow stress models (FLOW table order)
ISO, JC, ZA, MTS, SCG, PTW = 0, 1, 2, 3, 4, 5
# shear modulus, melting temperature, equation of state, specific heat
CONST_SHEAR, MTS_SHEAR, SCG_SHEAR, NP_SHEAR = 0, 1, 2, 3
CONST_TM, SCG_TM, BPS_TM, LINEAR_TM = 0, 1, 2, 3
HYPER_EOS, MIE_GRUNEISEN, HYPO_EOS = 0, 1, 2
CONST_CP, COPPER_CP, STEEL_CP = 0, 1, 2


@njit(cache=True)
def _jc(fp, ep, edot, T):
    """Johnson and Cook (1983): (A + B ep^n)(1 + C ln edot*)(1 - T*^m) and its derivatives
    (JohnsonCookFlow: edot* is the total strain rate over epdot_0, T* uses T_r and T_m)."""
    A, B, C, n, m, edot0, Tr, Tm = fp[0], fp[1], fp[2], fp[3], fp[4], fp[5], fp[6], fp[7]
    e = edot / edot0
    rate = (1.0 + e) ** C if e < 1.0 else 1.0 + C * math.log(e)
    drate = C * (1.0 + e) ** (C - 1.0) if e < 1.0 else C / e
    Ts = 1.0 if T > Tm else (T - Tr) / (Tm - Tr)
    temp = 1.0 - Ts if Ts < 0.0 else 1.0 - Ts ** m
    strain = A + B * ep ** n
    dstrain = B * n * ep ** (n - 1.0) if ep > 0.0 else 0.0
    return strain * rate * temp, dstrain * rate * temp, strain * temp * drate


@njit(cache=True)
def _za(fp, ep, epdot, T):
    """Zerilli and Armstrong (1987): c0 + K ep^n + B exp(-beta T) + B0 sqrt(ep) exp(-alpha T),
    alpha, beta = alpha_0 - alpha_1 ln epdot, ... (ZAFlow, plastic strain rate)."""
    c0, B, beta0, beta1, B0, alpha0, alpha1, K, n = fp[0], fp[1], fp[2], fp[3], fp[4], fp[5], fp[6], fp[7], fp[8]
    epd = 1.0e-8 if epdot == 0.0 else epdot
    T = 0.0 if T < 0.0 else T
    alpha = alpha0 - alpha1 * math.log(epd)
    beta = beta0 - beta1 * math.log(epd)
    e0 = 0.0 if ep < 0.0 else ep
    sig = c0 + K * e0 ** n + B * math.exp(-beta * T) + B0 * math.sqrt(e0) * math.exp(-alpha * T)
    e1 = 1.0e-8 if ep <= 0.0 else ep
    dsig_dep = K * n * e1 ** (n - 1.0) + 0.5 * B0 * math.exp(-alpha * T) / math.sqrt(e1)
    dsig_depdot = (B * beta1 * T * math.exp(-beta * T) + B0 * math.sqrt(e0) * alpha1 * T * math.exp(-alpha * T)) / epd
    return sig, dsig_dep, dsig_depdot


@njit(cache=True)
def _mts_sigma_e(fp, theta0, sigma_es, ep):
    """MTS structure evolution: sigma_e after ep with theta = theta0 (1 - tanh(alpha X)/tanh(alpha)),
    four implicit midpoint sub-steps capped at sigma_es (MTSFlow::computeSigma_e)."""
    sigma_e = 0.0
    if ep == 0.0:
        return sigma_e
    alpha = fp[19]
    dep = ep / 4.0
    beta = dep * theta0
    delta = beta / math.tanh(alpha)
    gamma = 0.5 * alpha / sigma_es
    for _ in range(4):
        phi = sigma_e + beta
        psi = sigma_e * gamma
        f = 1.0e6
        while abs(f) > 1.0:
            t = math.tanh(psi + gamma * sigma_e)
            f = sigma_e + delta * t - phi
            sigma_e = abs(sigma_e - f / (1.0 + delta * gamma * (1.0 - t * t)))
        if sigma_e > sigma_es:
            return sigma_es
    return sigma_e


@njit(cache=True)
def _mts(fp, ep, edot, T, mu):
    """Follansbee and Kocks (1988) mechanical threshold stress: sigma_a + (S_i sigma_i +
    S_e sigma_e) mu/mu_0 (MTSFlow, total strain rate), with d/d ep and d/d edot."""
    (sigma_a, mu0, koverbcubed, g0i, g0e, edot0i, edot0e, p_i, q_i, p_e, q_e,
     a1, a2, thetaIV, alpha, edot_es0, Tc) = (fp[0], fp[1], fp[4], fp[5], fp[6], fp[7], fp[8], fp[9], fp[10],
                                              fp[11], fp[12], fp[15], fp[16], fp[18], fp[19], fp[20], fp[23])
    if T > Tc:
        sigma_i, g0es, sigma_es0, a0, a3 = fp[25], fp[26], fp[27], fp[28], fp[29]
        g0i = fp[24]
    else:
        sigma_i, g0es, sigma_es0, a0, a3 = fp[13], fp[21], fp[22], fp[14], fp[17]
    e = 1.0e-7 if edot == 0.0 else edot
    ratio = mu / mu0
    CC = koverbcubed * T / mu
    S_i = 0.0
    if p_i > 0.0:
        q = 1.0 - (CC / g0i * math.log(edot0i / e)) ** (1.0 / q_i)
        if q > 0.0:
            S_i = q ** (1.0 / p_i)
    logee = math.log(edot0e / e)
    q = 1.0 - (CC / g0e * logee) ** (1.0 / q_e)
    S_e = q ** (1.0 / p_e) if q > 0.0 else 0.0
    theta0 = a0 + a1 * math.log(e) + a2 * math.sqrt(e) - a3 * T
    sigma_es = sigma_es0 * (e / edot_es0) ** (CC / g0es)
    sigma_e = _mts_sigma_e(fp, theta0, sigma_es, ep)
    sig = sigma_a + (S_i * sigma_i + S_e * sigma_e) * ratio
    FX = math.tanh(alpha * sigma_e / sigma_es) / math.tanh(alpha)
    dsig_dep = ratio * S_e * (theta0 * (1.0 - FX) + thetaIV * FX)
    ratioi = 0.0
    if p_i > 0.0:
        logei = math.log(edot0i / e)
        Kl = (CC / g0i * logei) ** (1.0 / q_i)
        ratioi = (ratio * sigma_i * Kl) / (p_i * q_i) * (1.0 - Kl) ** (1.0 / p_i) / (e * logei * (1.0 - Kl))
    Kl = (CC / g0e * logee) ** (1.0 / q_e)
    ratioe = (ratio * sigma_e * Kl) / (p_e * q_e) * (1.0 - Kl) ** (1.0 / p_e) / (e * logee * (1.0 - Kl))
    return sig, dsig_dep, ratioi + ratioe


@njit(cache=True)
def _scg_thermal(fp, epdot, T, tol):
    """The thermally activated part of Steinberg-Lund: the tau with epdot = C1 tau /
    (C1 C2 + tau exp(2 U_k/(k T) (1 - tau/sigma_P)^2)), Newton then bisection
    (SCGFlow::computeThermallyActivatedYieldStress)."""
    C1, C2, Uk, kb, sP = fp[11], fp[12], fp[13], fp[14], fp[15]
    if epdot < tol:
        return 0.0
    UkT = 2.0 * Uk / (kb * T)
    Z4 = C2 * C1
    tau = sP
    Z0 = 1.0 - tau / sP
    Z1 = UkT * Z0
    Z6 = Z4 + math.exp(Z0 * Z1) * tau
    if epdot > C1 * tau / Z6:
        return tau
    tau = 0.0
    Z0 = 1.0
    Z1 = UkT
    Z6 = Z4 + math.exp(Z0 * Z1) * tau
    if epdot < C1 * tau / Z6:
        return tau
    tau = 0.5 * sP
    while True:
        Z0 = 1.0 - tau / sP
        Z1 = UkT * Z0
        Z5 = math.exp(Z0 * Z1) * tau
        Z6 = Z4 + Z5
        f = epdot - C1 * tau / Z6
        fp_ = -C1 * (2.0 * Z5 * Z1 * tau + sP * Z4) / (sP * Z6 * Z6)
        old = tau
        tau -= f / fp_
        if math.isnan(tau) or abs(tau - old) < tol * tau or not abs(f) > tol:
            break
    if math.isnan(tau):
        hi, lo = sP, tol
        tau = 0.5 * (hi + lo)
        while hi - lo > tol:
            Z0 = 1.0 - lo / sP
            f_lo = epdot - C1 * lo / (Z4 + math.exp(Z0 * UkT * Z0) * lo)
            Z0 = 1.0 - tau / sP
            f = epdot - C1 * tau / (Z4 + math.exp(Z0 * UkT * Z0) * tau)
            if f_lo * f > 0.0:
                lo = tau
            else:
                hi = tau
            tau = 0.5 * (hi + lo)
    return min(max(tau, 0.0), sP)


@njit(cache=True)
def _scg(fp, ep, epdot, T, mu):
    """Steinberg, Cochran and Guinan (1980) with Steinberg-Lund (1989) rate dependence:
    (Y_T(epdot, T) + min(sigma_0 (1 + beta (ep + ep_0))^n, Y_max)) mu/mu_0 (SCGFlow). The
    rate derivative is Uintah's finite difference, taken (as there) at epdot = ep."""
    mu0, sigma0, beta, n, ep0, Ymax = fp[0], fp[3], fp[4], fp[5], fp[6], fp[7]
    ratio = mu / mu0
    Ya = 1.0 + beta * (ep + ep0)
    sig = (_scg_thermal(fp, epdot, T, 1.0e-6) + min(sigma0 * Ya ** n, Ymax)) * ratio
    dsig_dep = sigma0 * ratio * n * beta * Ya ** (n - 1.0)
    t1 = _scg_thermal(fp, ep, T, 1.0e-6)
    t2 = _scg_thermal(fp, 1.01 * ep, T, 1.0e-6)
    return sig, dsig_dep, (t2 - t1) / 0.01 * ratio


@njit(cache=True)
def _ptw(fp, ep, epdot, T, mu, Tm, rho):
    """Preston, Tonks and Wallace (2003): 2 mu tauhat with the thermal and overdriven-shock
    saturation and yield stresses (PTWFlow, its derivatives as there)."""
    theta, p, s0, sinf, kappa, gamma, y0, yinf, y1, y2, beta, M = (fp[0], fp[1], fp[2], fp[3], fp[4], fp[5],
                                                                  fp[6], fp[7], fp[8], fp[9], fp[10], fp[11])
    epd = 1.0e-8 if epdot <= 0.0 else epdot
    xidot = 0.5 * (4.0 * math.pi * rho / (3.0 * M * 1.66043998903379e-27)) ** (1.0 / 3.0) * math.sqrt(mu / rho)
    edot = epd / xidot
    That = T / Tm
    ups = kappa * That * math.log(gamma / edot)
    zeta = math.erf(ups)
    th_s, th_y = s0 - (s0 - sinf) * zeta, y0 - (y0 - yinf) * zeta
    sh_s = s0 * (edot / gamma) ** beta
    sh_y = min(y1 * (edot / gamma) ** y2, sh_s)
    ts, ty = th_s, th_y
    if epd > 1.0e3:
        ts, ty = max(th_s, sh_s), max(th_y, sh_y)
    tauhat = ts
    if ts != ty:
        A = (s0 - ty) / p
        C = math.exp((ts - ty) / A) - 1.0
        tauhat = ts + A * math.log(1.0 - C / (C + 1.0) * math.exp(-theta / (A * C) * ep))
    ts, ty = max(th_s, sh_s), max(th_y, sh_y)        # d/d ep: with the shock terms always
    dsig_dep = 0.0
    if ts != ty:
        A = (s0 - ty) / p
        C = math.exp((ts - ty) / A) - 1.0
        E = theta / (A * C)
        dsig_dep = A * E / (math.exp(E * ep) / (C / (C + 1.0)) - 1.0)
    alpha, bet = s0 - sinf, y0 - yinf
    delta, phi = s0 - y0, alpha - bet
    eta, lam = phi * zeta, bet * zeta
    sig = delta + lam
    Xi = delta - eta
    iota = p * Xi / sig
    Phi, Lam = phi + bet, eta + Xi
    Dl = math.exp(iota) - 1.0
    Th = theta * p * ep / (sig * Dl)
    Om = math.exp(-Th) / math.exp(iota)
    Z1 = -Dl * Om + 1.0
    Z2 = Phi * Lam * p
    Z8 = Z1 * sig
    Z9 = Om * Dl
    Z12 = math.exp(-ups * ups) * 2.0 * kappa * That / (p * epd) / (Z1 * sig * math.sqrt(math.pi))
    d = Z12 * ((Phi - phi) * (Th * sig * Z9 - math.log(Z1) * Z8) - Th * Z2 * (Z9 + Om) + (alpha * p * Z8 - Om * Z2))
    if epd > 1.0e3:
        d = max(d, beta * s0 * (edot / gamma) ** beta / epd)
    return 2.0 * tauhat * mu, 2.0 * mu * dsig_dep, 2.0 * mu * d


@njit(cache=True)
def flow_stress(code, fp, ep, epdot, edot, T, mu, Tm, rho):
    """(sigma_y, d sigma_y/d ep, d sigma_y/d epdot) of flow model `code` at plastic strain ep,
    plastic strain rate epdot, total strain rate edot, temperature T, shear modulus mu,
    melting temperature Tm and density rho."""
    if code == ISO:          # IsoHardeningFlow: sigma_Y + K ep
        return fp[1] + fp[0] * ep, fp[0], 0.0
    if code == JC:
        return _jc(fp, ep, edot, T)
    if code == ZA:
        return _za(fp, ep, epdot, T)
    if code == MTS:
        return _mts(fp, ep, edot, T, mu)
    if code == SCG:
        return _scg(fp, ep, epdot, T, mu)
    return _ptw(fp, ep, epdot, T, mu, Tm, rho)


@njit(cache=True)
def shear_modulus(code, sp, mu_init, T, Tm, pressure, rho, rho0):
    """mu of shear model `code` (pressure = tr(sigma)/3, tension positive, as Uintah's state)."""
    if code == CONST_SHEAR:
        return mu_init
    if code == MTS_SHEAR:    # Varshni (1970): mu_0 - D/(exp(T_0/T) - 1)
        return sp[0] - sp[1] / (math.exp(sp[2] / T) - 1.0)
    eta = (rho / rho0) ** (1.0 / 3.0)
    if code == SCG_SHEAR:    # Steinberg et al. (1980): mu_0 (1 + A P/eta - B (T - 300))
        return sp[0] * (1.0 + sp[1] * (-pressure) / eta - sp[2] * (T - 300.0))
    # Nadal and Le Poac (2003), NPShear: sp = mu_0, zeta, slope_mu_p_over_mu0, C, m
    That = T / Tm
    if That <= 0.0:
        return sp[0]
    if That > 1.0 + sp[1]:
        return 1.0e-8
    J = 1.0 + math.exp((That - 1.0) / (sp[1] * (1.0 - That / (1.0 + sp[1]))))
    if not math.isfinite(J):
        return 1.0e-8
    t1 = sp[0] * (1.0 + sp[2] * (-pressure) / eta)
    k_amu = 1.3806503e4 / 1.6605402
    mu = 1.0 / J * (t1 * (1.0 - That) + rho * k_amu * T / (sp[3] * sp[4]))
    return max(mu, 1.0e-8)


@njit(cache=True)
def melt_temperature(code, mp, Tm_init, pressure, rho, rho0):
    """T_m of melting model `code`."""
    if code == CONST_TM:
        return Tm_init
    if code == SCG_TM:       # Lindemann law (SCGMeltTemp): T_m0 exp(2a(1 - 1/eta)) eta^(2(Gamma_0 - a - 1/3))
        eta = rho / rho0
        return mp[2] * math.exp(2.0 * mp[1] * (1.0 - 1.0 / eta)) * eta ** (2.0 * (mp[0] - mp[1] - 1.0 / 3.0))
    if code == BPS_TM:       # Burakovsky, Preston and Silbar (2000), BPSMeltTemp
        B0, dB, G0, dG, kappa, z, b2rhoTm, alpha, lam, a, factor, kb = (mp[0], mp[1], mp[2], mp[3], mp[4], mp[5],
                                                                        mp[6], mp[7], mp[8], mp[9], mp[10], mp[11])
        p = -pressure
        vws = a ** 3.0 / factor
        kbTm = (kappa * lam * vws * G0) / (8.0 * math.pi * math.log(z - 1.0)) * math.log(alpha * alpha / (4.0 * b2rhoTm))
        eta = (1.0 + dB / B0 * p) ** (1.0 / dB)
        return kbTm / kb / eta * (1.0 + dG / G0 * p / eta ** (1.0 / 3.0))
    # LinearMeltTemp: mp = T_m0, form (1 pressure, 2 volume, 0 constant), coefficient
    if mp[1] == 1.0:
        return mp[0] + mp[2] * pressure
    if mp[1] == 2.0:
        return mp[0] * (1.0 + mp[2] * rho0 / rho)
    return mp[0]


@njit(cache=True)
def eos_pressure(code, qp, K, p_old, trD, dt, rho, rho0, e):
    """The hydrostatic stress p (sigma = s + p I, tension positive) of EOS `code`; e is the
    specific internal energy p.energy (Mie-Gruneisen)."""
    if code == HYPER_EOS:        # HyperElasticEOS (Uintah's default): K/2 (J - 1/J)
        J = rho0 / rho
        return 0.5 * K * (J - 1.0 / J)
    if code == HYPO_EOS:         # DefaultHypoElasticEOS: p + K tr(D) dt
        return p_old + trD * (K * dt)
    # MieGruneisenEOSEnergy (Steinberg 1991), qp = C_0, Gamma_0, S_1, S_2, S_3
    C0, G0, S1, S2, S3 = qp[0], qp[1], qp[2], qp[3], qp[4]
    eta = 1.0 - rho0 / rho
    if eta >= 0.0:
        d = 1.0 - S1 * eta - S2 * eta * eta - S3 * eta * eta * eta
        p = rho0 * G0 * e + rho0 * C0 * C0 * eta * (1.0 - 0.5 * G0 * eta) / (d * d)
    else:
        p = rho0 * G0 * e + rho0 * C0 * C0 * eta
    return -p


@njit(cache=True)
def isentropic_dTdt(code, qp, T, rho0, rho, trD):
    """dT/dt of isentropic compression: -T Gamma_0 rho_0 tr(D)/rho for Mie-Gruneisen, else 0."""
    if code == MIE_GRUNEISEN:
        return -T * qp[1] * rho0 * trD / rho
    return 0.0


@njit(cache=True)
def specific_heat(code, cpp, cp_init, T):
    """c_p of model `code`: the material's <specific_heat>, CopperCp's two-branch fit, or SteelCp's
    (4340 steel, Lederman et al.: a power-law singularity at the transition temperature Tc)."""
    if code == CONST_CP:
        return cp_init
    if code == STEEL_CP:
        Tc = cpp[0]
        if T == Tc:            # as Uintah: the singular point is taken 1 K below
            T = T - 1.0
        if T < Tc:
            t = 1.0 - T / Tc
            return cpp[1] - cpp[2] * t + cpp[3] / t ** cpp[4]
        t = T / Tc - 1.0
        return cpp[5] + cpp[6] * t + cpp[7] / t ** cpp[8]
    if T < cpp[0]:
        return cpp[1] * T * T * T - cpp[2] * T * T + cpp[3] * T - cpp[4]
    return cpp[5] * T + cpp[6]


# yield conditions (elastic_plastic_hp.YIELD order); Gurson's parameter vector: q1, q2, q3, k, f_c
VON_MISES, GURSON = 0, 1


@njit(cache=True)
def gurson_yield(gp, sig_eq, sig_flow, tr_sig, f):
    """(Phi, sigma_eff) of the Gurson-Tvergaard-Needleman condition (GursonYield):
    Phi = sig_eq^2 - sig_flow^2 (1 + q3 f*^2 - 2 q1 f* cosh(q2 tr_sig/(2 sig_flow))), with
    f* = f_c + k (f - f_c) above f_c, the cosh argument capped at +-30, and sigma_eff the
    sqrt of the subtracted term (von Mises with sig_flow where that term is negative)."""
    q1, q2, q3, k, fc = gp[0], gp[1], gp[2], gp[3], gp[4]
    fs = fc + k * (f - fc) if f > fc else f
    arg = 0.5 * q2 * tr_sig / sig_flow
    if abs(arg) > 30.0:
        arg = math.copysign(30.0, arg)
    a = 1.0 + q3 * fs * fs
    b = 2.0 * q1 * fs * math.cosh(arg)
    if a - b < 0.0:
        return sig_eq * sig_eq - sig_flow * sig_flow, sig_flow
    sig2 = sig_flow * sig_flow * (a - b)
    return sig_eq * sig_eq - sig2, math.sqrt(sig2)


@njit(cache=True)
def void_nucleation(pp, ep):
    """Chu and Needleman's strain-controlled nucleation factor A = f_n/(s_n sqrt(2 pi))
    exp(-((ep - e_n)/s_n)^2/2); pp = f_n, e_n, s_n."""
    t = (ep - pp[1]) / pp[2]
    return pp[0] / (pp[2] * math.sqrt(2.0 * math.pi)) * math.exp(-0.5 * t * t)


@njit(cache=True)
def porosity_update(pp, f, D, dt, ep):
    """Void volume fraction after a plastic step (ElasticPlasticHP::updatePorosity), forward
    Euler: growth (1 - f) tr D in expansion plus nucleation A(ep) sqrt(2/3) |dev D|."""
    trD = D[0, 0] + D[1, 1] + D[2, 2]
    grow = (1.0 - f) * trD if trD > 0.0 else 0.0
    ee = 0.0
    for i in range(3):
        for j in range(3):
            e = D[i, j] - (trD / 3.0 if i == j else 0.0)
            ee += e * e
    return f + dt * (void_nucleation(pp, ep) * math.sqrt(ee / 1.5) + grow)


@njit(cache=True)
def biswajit_increment(S, eta, sy_eff, mu, dt):
    """The plastic multiplier increment of Uintah's "biswajit" return (after Zocher, Maudlin,
    Chen and Flower-Maudlin 2000: all the deviatoric rate plastic, the flow direction the
    yield-surface normal q = 3 S of the stress S at the start of the step) and the plastic
    strain rate it implies, (delGamma, epdot); delGamma <= 0 when that estimate fails."""
    qs, qq, ee, ue, uq = 0.0, 0.0, 0.0, 0.0, 0.0
    for i in range(3):
        for j in range(3):
            q = 3.0 * S[i, j]
            qs += q * S[i, j]
            qq += q * q
            ee += eta[i, j] * eta[i, j]
    sqrtqs, sqrtqq, etaeta = math.sqrt(qs), math.sqrt(qq), math.sqrt(ee)
    cplus, dplus = 0.0, 0.0
    for i in range(3):
        for j in range(3):
            u = 3.0 * S[i, j] / sqrtqs
            cplus += u * u
            dplus += u * eta[i, j]
    gdot = dplus / cplus                             # the rate at the start of the step
    if not gdot > 0.0:
        return 0.0, 0.0
    for i in range(3):
        for j in range(3):
            ue += eta[i, j] / etaeta * eta[i, j]
            uq += 3.0 * S[i, j] / sqrtqq * eta[i, j]
    AA = 2.0 / math.sqrt(cplus)
    BB = -(ue + uq)
    CC = -gdot * cplus * (ue - uq)
    disc = max(BB * BB - 4.0 * AA * CC, 0.0)
    dstar = (-BB + math.sqrt(disc)) / (2.0 * AA)
    dg_elastic = (math.sqrt(2.0) * sy_eff - sqrtqs) / (2.0 * mu * cplus)    # the part of the step to yield
    dg = dstar / cplus * dt - dg_elastic
    return dg, (1.0 / math.sqrt(1.5) * sqrtqq * dg) / (sqrtqs * dt)
