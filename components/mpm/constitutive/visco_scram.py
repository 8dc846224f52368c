"""ViscoSCRAM (Bennett et al. 1998; Uintah's ViscoScram): PBX 9501 as five Maxwell elements
in parallel whose deviatoric stress is softened by a statistical crack radius c.

Deck tags (``<constitutive_model type="visco_scram">``, Uintah's names): ``PR`` (Poisson
ratio nu), ``G1..G5`` (shear moduli G_k), ``RTau1..RTau5`` (inverse relaxation times 1/tau_k,
1/s), ``CrackParameterA`` (a), ``InitialCrackRadius`` (c0), ``CrackPowerValue`` (m),
``CrackMaxGrowthRate`` (v_max), ``StressIntensityF`` (K_0), ``CrackFriction`` (mu'),
``CrackGrowthRate`` (the crack-speed factor in tension), ``CoeffThermalExpansion`` (alpha,
default 0), ``use_time_temperature_equation`` with ``T0``, ``C1``, ``C2`` (WLF shift of the
tau_k). Per step, with D = sym(L) - alpha dT/dt I and G = sum G_k,
K = 2G(1 + nu) / (3(1 - 2nu)):

    p^{n+1} = p^n + K tr(D) dt                                        (hypoelastic mean stress)
    c' = v_res (K_I / K_1)^m  (K_I < K')  or  v_res (1 - K_0m^2 / K_I^2)  (crack growth)
    S_k' = 2 G_k D' - S_k / tau_k
           - G_k / G [3 c^2 c' / a^3 S + (c/a)^3 / (1 + (c/a)^3) (2 G D' - sum_j S_j / tau_j - 3 c^2 c' / a^3 S)]
    sigma^{n+1} = sum_k S_k^{n+1} + p^{n+1} I

with S = sum_k S_k, K_I = sqrt(3 pi c / 2) sigma_e, v_res = exp(0.90564746 ln(sqrt(3/2)|D'|)
- 2.90178468) (PBX 9501 baseline). Both the crack radius and each element's S_k are advanced by
classical RK4 as Uintah does: element k's stages add its own increment to every element, and
the elements are updated in order (element k sees the new S_j of j < k).

State (carried): p.pStatedata_vs (the five S_k), p.crackRad, p.tempPrevious (the particle's
temperature one step back, for alpha dT/dt).
``energy`` receives the work increment D : (sigma^n + sigma^{n+1})/2 V dt. The step is at most
1 microsecond (MAX_DELT, Uintah's: larger steps make the model unstable).

Not implemented (refused): ``randomize_parameters`` (Uintah draws drand48), ``useObjectiveRate``;
the EOS options change only MPMICE's solid EOS: ``useJWLEOS`` is its JWL there
(components/ice/eos.py SOLID_JWL), ``useJWLCEOS``, ``useMurnahanEOS``, ``useBirchMurnaghanEOS``
are refused (components/mpmice).

Internal heating (Uintah's p.dTdt, Hackett and Bennett 2000), added to p.temperature at the
step's end as Uintah's finalParticleUpdate does, with rho = rho_0 / det F^{n+1} and c_v the
material's <specific_heat>:

    dT/dt = [sum_k S_k:S_k / (2 G_k tau_k)                             (viscoelastic work)
             + (S:S 3 c^2 c'/a^3 + (c/a)^3 S:Sdot_c) / (2G)] / (rho c_v)   (crack growth work)
            - Gamma T tr(D)                                            (volume change)

with S, the S_k and c at the step's end, c' the step's crack speed, Sdot_c = (2G D - S 3 c^2 c'/a^3
- sum_k S_k / tau_k) / (1 + (c/a)^3) and T the step's starting temperature (elements with G_k = 0
carry no stress and add nothing). ``Beta``,
``DCp_DTemperature`` and the reaction tags the PBX decks carry (``Chi``, ``delH``,
``Z``, ``EoverR``, ``dynamic_coeff_friction``, ``volfracHE``, ``rho0``) are read and not used
(Uintah's stress update does not use them either).
"""
from __future__ import annotations

from dataclasses import dataclass, fields

import numpy as np
from numba import njit

ENERGY_IS_INCREMENT = True
USES_TEMPERATURE = True
NEEDS_TEMPERATURE = True            # p.temperature and p.dTdt follow the state (old[-1], new[-1])
MAX_DELT = 1.0e-6
STATE = ("p.pStatedata_vs", "p.crackRad", "p.tempPrevious")
MATERIAL_PROPERTIES = ("density", "specific_heat")     # the material's, for rho c_v of the heating

VRES_A, VRES_B = 0.90564746, -2.90178468        # PBX 9501 baseline crack-speed fit
NOT_IMPLEMENTED = ("randomize_parameters", "useObjectiveRate")
EOS_FLAGS = ("useJWLEOS", "useJWLCEOS", "useMurnahanEOS", "useBirchMurnaghanEOS")
_REQUIRED = ("PR", "CrackParameterA", "CrackPowerValue", "CrackMaxGrowthRate", "StressIntensityF", "CrackFriction",
             "InitialCrackRadius", "CrackGrowthRate", "G1", "G2", "G3", "G4", "G5",
             "RTau1", "RTau2", "RTau3", "RTau4", "RTau5", "Beta", "Gamma", "DCp_DTemperature")
_BOOLS = ("use_time_temperature_equation",) + NOT_IMPLEMENTED + EOS_FLAGS + ("useModifiedEOS",)


@dataclass(frozen=True)
class Params:
    PR: float
    CrackParameterA: float
    CrackPowerValue: float
    CrackMaxGrowthRate: float
    StressIntensityF: float
    CrackFriction: float
    InitialCrackRadius: float
    CrackGrowthRate: float
    G1: float
    G2: float
    G3: float
    G4: float
    G5: float
    RTau1: float
    RTau2: float
    RTau3: float
    RTau4: float
    RTau5: float
    Beta: float
    Gamma: float
    DCp_DTemperature: float
    CoeffThermalExpansion: float = 0.0
    use_time_temperature_equation: bool = False
    T0: float = 298.0
    C1: float = 6.5
    C2: float = 120.0
    randomize_parameters: bool = False
    useObjectiveRate: bool = False
    useModifiedEOS: bool = False
    useJWLEOS: bool = False
    useJWLCEOS: bool = False
    useMurnahanEOS: bool = False
    useBirchMurnaghanEOS: bool = False
    gamma: float = 0.0
    P0: float = 0.0
    bulkPrime: float = 0.0
    A: float = 0.0
    B: float = 0.0
    C: float = 0.0
    Cv: float = 0.0
    R1: float = 0.0
    R2: float = 0.0
    om: float = 0.0
    Chi: float = 0.0
    delH: float = 0.0
    Z: float = 0.0
    EoverR: float = 0.0
    dynamic_coeff_friction: float = 0.0
    volfracHE: float = 0.0
    rho0: float = 0.0
    density: float = 0.0            # the material's <density> and <specific_heat> (MATERIAL_PROPERTIES)
    specific_heat: float = 0.0

    @classmethod
    def from_ups(cls, d):
        for k in _REQUIRED:
            if k not in d:
                raise KeyError(f"constitutive_model visco_scram: missing <{k}>")
        for k in NOT_IMPLEMENTED:
            if d.get(k, "False") == "True":
                raise KeyError(f"<{k}> true is not implemented (false is accepted)")
        if not -1.0 < float(d["PR"]) < 0.5:
            raise KeyError(f"<PR> {d['PR']} must lie in (-1, 0.5) (the bulk modulus 2G(1+PR)/(3(1-2PR)) "
                           "must be positive and finite)")
        for k in ("CrackParameterA", "InitialCrackRadius", "StressIntensityF", "CrackPowerValue"):
            if float(d[k]) <= 0.0:
                raise KeyError(f"<{k}> must be positive")
        if sum(float(d[f"G{k}"]) for k in range(1, 6)) <= 0.0 or min(float(d[f"G{k}"]) for k in range(1, 6)) < 0.0:
            raise KeyError("<G1>..<G5> must be >= 0 with a positive sum")
        if min(float(d[f"RTau{k}"]) for k in range(1, 6)) < 0.0:
            raise KeyError("<RTau1>..<RTau5> (inverse relaxation times) must be >= 0")
        vals = {}
        for f in fields(cls):
            if f.name in d:
                vals[f.name] = d[f.name] == "True" if f.name in _BOOLS else float(d[f.name])
        return cls(**vals)

    @property
    def shear_modulus(self):
        return self.G1 + self.G2 + self.G3 + self.G4 + self.G5

    @property
    def bulk_modulus(self):
        """K = 2G(1 + nu) / (3(1 - 2nu)): MPMICE's solid EOS uses it."""
        G = self.shear_modulus
        return 2.0 * G * (1.0 + self.PR) / (3.0 * (1.0 - 2.0 * self.PR))

    def eos_flag(self):
        """The first EOS option set (MPMICE runs useJWLEOS, refuses the others), or None."""
        return next((k for k in EOS_FLAGS if getattr(self, k)), None)


def initial_state(params, n, temperature):
    """S_k = 0, c = InitialCrackRadius, previous temperature = the initial one."""
    return (np.zeros((n, 5, 3, 3)), np.full(n, params.InitialCrackRadius), np.array(temperature, float).copy())


@njit(cache=True, inline="always")
def _maxwell_rate(Dp, Sk, Gk, tauk_inv, Ssum, Stau, G, c, cdot, a3, out):
    """dS_k/dt of one Maxwell element at crack radius c (the bracket of the module docstring)."""
    con1 = 3.0 * c * c * cdot / a3
    con3 = c * c * c / a3
    con2 = 1.0 + con3
    for i in range(3):
        for j in range(3):
            inner = 2.0 * G * Dp[i, j] - Stau[i, j] - Ssum[i, j] * con1
            out[i, j] = 2.0 * Gk * Dp[i, j] - Sk[i, j] * tauk_inv - (Ssum[i, j] * con1 + inner * con3 / con2) * (Gk / G)


@njit(cache=True, inline="always")
def _stage(S, p, k, inc, scale, Dp, Gm, Rt, G, c, cdot, a3, Ssum, Stau, Sk, out, dt):
    """RK stage of element k with its previous increment `inc` * scale added to every element."""
    for i in range(3):
        for j in range(3):
            Ssum[i, j] = 0.0
            Stau[i, j] = 0.0
    for jm in range(5):
        for i in range(3):
            for j in range(3):
                s = S[p, jm, i, j] + scale * inc[i, j]
                Ssum[i, j] += s
                Stau[i, j] += s * Rt[jm]
    for i in range(3):
        for j in range(3):
            Sk[i, j] = S[p, k, i, j] + scale * inc[i, j]
    _maxwell_rate(Dp, Sk, Gm[k], Rt[k], Ssum, Stau, G, c, cdot, a3, out)
    for i in range(3):
        for j in range(3):
            out[i, j] *= dt


@njit(cache=True, inline="always")
def _det(F, p):
    return (F[p, 0, 0] * (F[p, 1, 1] * F[p, 2, 2] - F[p, 1, 2] * F[p, 2, 1])
            - F[p, 0, 1] * (F[p, 1, 0] * F[p, 2, 2] - F[p, 1, 2] * F[p, 2, 0])
            + F[p, 0, 2] * (F[p, 1, 0] * F[p, 2, 1] - F[p, 1, 1] * F[p, 2, 0]))


@njit(cache=True, inline="always")
def _heating_rate(S, p, Gm, Rt, G, c, cdot, a3, D, trD, gamma_v, T, rho_cv, Ssum, Stau):
    """dT/dt of the module docstring (Hackett and Bennett 2000): viscoelastic and crack growth
    work over rho c_v, less the volume change term."""
    wve = 0.0
    for i in range(3):
        for j in range(3):
            Ssum[i, j] = 0.0
            Stau[i, j] = 0.0
    for k in range(5):
        s2 = 0.0
        for i in range(3):
            for j in range(3):
                s = S[p, k, i, j]
                s2 += s * s
                Ssum[i, j] += s
                Stau[i, j] += s * Rt[k]
        if Gm[k] > 0.0:
            wve += s2 / (2.0 * Gm[k]) * Rt[k]
    coa3 = c * c * c / a3
    topc = 3.0 * coa3 / c * cdot
    ss = 0.0
    srate = 0.0
    for i in range(3):
        for j in range(3):
            ss += Ssum[i, j] * Ssum[i, j]
            srate += Ssum[i, j] * (2.0 * G * D[i, j] - Ssum[i, j] * topc - Stau[i, j]) / (1.0 + coa3)
    wcr = (ss * topc + srate * coa3) / (2.0 * G)
    return (wve + wcr) / rho_cv - gamma_v * T * trD


@njit(cache=True)
def kernel(nu, alpha, cdot0, K0, mm, arad, vmax, cf, Gm, Rt0, time_temp, T0, C1, C2, gamma_v, rho0, cv, L, F_new,
           vol, mass, vel, dt, stress_old, stress_new, S_old, S_new, c_old, c_new, T, T_prev_old, T_prev_new,
           energy, dTdt_heat):
    """Every particle's stress, Maxwell stresses, crack radius and heating rate dT/dt; returns the
    wave speed (3,)."""
    ws = np.zeros(3)
    G = Gm.sum()
    bulk = 2.0 * G * (1.0 + nu) / (3.0 * (1.0 - 2.0 * nu))
    a3 = arad * arad * arad
    sq15 = np.sqrt(1.5)
    sqpi = np.sqrt(np.pi)
    D = np.empty((3, 3))
    Dp = np.empty((3, 3))
    sdev = np.empty((3, 3))
    Rt = np.empty(5)
    Ssum, Stau, Sk = np.empty((3, 3)), np.empty((3, 3)), np.empty((3, 3))
    rk1, rk2, rk3, rk4 = np.empty((3, 3)), np.empty((3, 3)), np.empty((3, 3)), np.empty((3, 3))
    zero = np.zeros((3, 3))
    for p in range(L.shape[0]):
        S_new[p] = S_old[p]
        T_prev_new[p] = T[p]
        for k in range(5):
            Rt[k] = Rt0[k]
        if time_temp:                                   # WLF shift a_T of the relaxation times
            dT = T[p] - T0
            aT = np.exp(-C1 * dT / (C2 + dT))
            for k in range(5):
                Rt[k] /= aT
        dTdt = (T[p] - T_prev_old[p]) / dt if dt > 0.0 else 0.0
        for i in range(3):
            for j in range(3):
                D[i, j] = 0.5 * (L[p, i, j] + L[p, j, i]) - (alpha * dTdt if i == j else 0.0)
        trD = D[0, 0] + D[1, 1] + D[2, 2]
        sm_old = (stress_old[p, 0, 0] + stress_old[p, 1, 1] + stress_old[p, 2, 2]) / 3.0
        dn2 = 0.0
        sn2 = 0.0
        for i in range(3):
            for j in range(3):
                Dp[i, j] = D[i, j] - (trD / 3.0 if i == j else 0.0)
                sdev[i, j] = stress_old[p, i, j] - (sm_old if i == j else 0.0)
                dn2 += Dp[i, j] * Dp[i, j]
                sn2 += sdev[i, j] * sdev[i, j]
        ed_eff = sq15 * np.sqrt(dn2)
        vres = np.exp(VRES_A * np.log(ed_eff) + VRES_B) if ed_eff > 1e-8 else 0.0
        comp = -1.0 if sm_old > 0.0 else 0.0            # -1 in mean tension
        vres *= (1.0 + comp) - cdot0 * comp
        sigmae = np.sqrt(sn2 - comp * 3.0 * sm_old * sm_old)
        crad = c_old[p]
        sqrtc = np.sqrt(crad)
        KI = sq15 * sqpi * sqrtc * sigmae                # stress intensity
        xmup = (1.0 + comp) * np.sqrt(45.0 / (2.0 * (3.0 - 2.0 * cf * cf))) * cf
        a = -xmup * sm_old * sqrtc                      # friction on the crack faces
        b = 1.0 + a / K0
        K0m = K0 * np.sqrt(1.0 + np.pi * a * b / K0)
        Kprime = K0m * np.sqrt(1.0 + 2.0 / mm)
        K1 = Kprime * (1.0 + mm / 2.0) ** (1.0 / mm)
        vres = min(vres, vmax)
        cc = vres * dt
        if KI < Kprime:
            fac = (KI / (K1 * sqrtc)) ** mm
            cdot = vres * (KI / K1) ** mm
            rk1c = cc * fac * sqrtc ** mm
            rk2c = cc * fac * np.sqrt(crad + 0.5 * rk1c) ** mm
            rk3c = cc * fac * np.sqrt(crad + 0.5 * rk2c) ** mm
            rk4c = cc * fac * np.sqrt(crad + rk3c) ** mm
        else:
            fac = K0m * K0m * crad / (KI * KI)
            cdot = vres * (1.0 - K0m * K0m / (KI * KI))
            rk1c = cc * (1.0 - fac / crad)
            rk2c = cc * (1.0 - fac / (crad + 0.5 * rk1c))
            rk3c = cc * (1.0 - fac / (crad + 0.5 * rk2c))
            rk4c = cc * (1.0 - fac / (crad + rk3c))
        for k in range(5):
            if time_temp and Rt[k] * dt > 0.1:           # relaxes within the step: no stress
                for i in range(3):
                    for j in range(3):
                        S_new[p, k, i, j] = 0.0
                continue
            _stage(S_new, p, k, zero, 0.0, Dp, Gm, Rt, G, crad, cdot, a3, Ssum, Stau, Sk, rk1, dt)
            _stage(S_new, p, k, rk1, 0.5, Dp, Gm, Rt, G, crad + 0.5 * rk1c, cdot, a3, Ssum, Stau, Sk, rk2, dt)
            _stage(S_new, p, k, rk2, 0.5, Dp, Gm, Rt, G, crad + 0.5 * rk2c, cdot, a3, Ssum, Stau, Sk, rk3, dt)
            _stage(S_new, p, k, rk3, 1.0, Dp, Gm, Rt, G, crad + rk3c, cdot, a3, Ssum, Stau, Sk, rk4, dt)
            for i in range(3):
                for j in range(3):
                    S_new[p, k, i, j] += (rk1[i, j] + rk4[i, j]) / 6.0 + (rk2[i, j] + rk3[i, j]) / 3.0
        sm_new = sm_old + trD * bulk * dt
        e = 0.0
        for i in range(3):
            for j in range(3):
                s = sm_new if i == j else 0.0
                for k in range(5):
                    s += S_new[p, k, i, j]
                stress_new[p, i, j] = s
                e += D[i, j] * 0.5 * (s + stress_old[p, i, j])
        c_new[p] = crad + (rk1c + rk4c) / 6.0 + (rk2c + rk3c) / 3.0
        energy[p] = e * vol[p] * dt
        dTdt_heat[p] = _heating_rate(S_new, p, Gm, Rt, G, c_new[p], cdot, a3, D, trD, gamma_v, T[p],
                                     rho0 * cv / _det(F_new, p), Ssum, Stau)
        cs = np.sqrt((bulk + 4.0 * G / 3.0) * vol[p] / mass[p])
        for d in range(3):
            ws[d] = max(ws[d], cs + abs(vel[p, d]))
    return ws


def update(params, L, F_old, F_new, vol, mass, vel, dt, stress_old, stress_new, energy, old, new, temperature=None):
    """Stress, Maxwell stresses, crack radius and previous temperature (old -> new tuples of
    STATE's arrays, then p.temperature -> p.dTdt, the heating rate); `temperature`: p.temperature
    (None: the one in `old`). Returns the wave speed (3,)."""
    S_old, c_old, Tp_old, T_old = old
    S_new, c_new, Tp_new, dTdt = new
    T = T_old if temperature is None else temperature
    pr = params
    Gm = np.array([pr.G1, pr.G2, pr.G3, pr.G4, pr.G5])
    Rt = np.array([pr.RTau1, pr.RTau2, pr.RTau3, pr.RTau4, pr.RTau5])
    return kernel(pr.PR, pr.CoeffThermalExpansion, pr.CrackGrowthRate, pr.StressIntensityF, pr.CrackPowerValue,
                  pr.CrackParameterA, pr.CrackMaxGrowthRate, pr.CrackFriction, Gm, Rt,
                  pr.use_time_temperature_equation, pr.T0, pr.C1, pr.C2, pr.Gamma, pr.density, pr.specific_heat,
                  L, F_new, vol, mass, vel, dt, stress_old, stress_new, S_old, S_new, c_old, c_new, T, Tp_old,
                  Tp_new, energy, dTdt)
