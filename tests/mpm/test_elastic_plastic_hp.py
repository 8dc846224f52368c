"""elastic_plastic with Uintah's sub-models (constitutive/elastic_plastic_hp.py).

Uintah's adiabatic copper set (StandAlone/inputs/MPM/adiCu{JC,ZA,MTS,SCG,PTW}4000s696K.ups: OFHC
copper at 696 K pulled at 4000/s, one flow-stress model per deck) checked two ways:

- against sus: tests/mpm/data/adiCu*_sus.txt hold sus's particle state after each of its first
  40 steps on those decks; every step is redone by pysus's model from sus's state at the step
  before, with the velocity gradient L = (F^{n+1} (F^n)^-1 - I)/dt of sus's F (Uintah's
  F^{n+1} = (I + L dt) F^n), and must give sus's stress, plastic strain, its rate, strain rate,
  p.energy and temperature (T^n + p.dTdt dt: its change to 0.1 %) to about the 9 digits of the
  extract;
- against the closed form of the JC, ZA, MTS and SCG flow models (written out below, independently of the kernels):
  homogeneous uniaxial stress at 4000/s with adiabatic heating dT/d ep = chi sigma_y/(rho c_p)
  integrated with RK4; the model, driven with the lateral rate that keeps the lateral stress
  zero, must follow sigma_y(ep, T(ep)) within 2 % (mean of two steps; 4 % for one).
"""
import math
from pathlib import Path

import numpy as np
import pytest

from components.mpm.constitutive import elastic_plastic_hp as hp
from components.mpm.materials import MATERIAL
from framework.problemspec import InputError, ProblemSpec

from .helpers import MPM_INPUTS, deck_text, run

DATA = Path(__file__).parent / "data"

# sub-model blocks of Uintah's decks adiCu*4000s696K.ups (parameters as there)
FLOWS = {
    "JC": """<flow_model type="johnson_cook"><A>90.0e6</A><B>292.0e6</B><C>0.025</C><n>0.31</n><m>1.09</m>
             </flow_model>""",
    "ZA": """<flow_model type="zerilli_armstrong"><sigma_g>46.5e6</sigma_g><k_H>5.0e6</k_H><sqrt_l_inv>3.7</sqrt_l_inv>
             <B>0.0</B><beta_0>0.0</beta_0><beta_1>0.0</beta_1><B_0>890.0e6</B_0><alpha_0>0.0028</alpha_0>
             <alpha_1>0.000115</alpha_1><K>0.0</K><n>0.0</n></flow_model>""",
    "MTS": """<flow_model type="mts_model"><sigma_a>40.0e6</sigma_a><mu_0>47.7e9</mu_0><D>3.0e9</D><T_0>180</T_0>
             <koverbcubed>0.823e6</koverbcubed><g_0i>0.0</g_0i><g_0e>1.6</g_0e><edot_0i>0.0</edot_0i>
             <edot_0e>1.0e7</edot_0e><p_i>0.0</p_i><q_i>0.0</q_i><p_e>0.666667</p_e><q_e>1.0</q_e>
             <sigma_i>0.0</sigma_i><a_0>2390.0e6</a_0><a_1>12.0e6</a_1><a_2>1.696e6</a_2><a_3>0.0</a_3>
             <theta_IV>0.0</theta_IV><alpha>2</alpha><edot_es0>1.0e7</edot_es0><g_0es>0.2625</g_0es>
             <sigma_es0>770.0e6</sigma_es0></flow_model>
             <shear_modulus_model type="mts_shear"><mu_0>47.7e9</mu_0><D>3.0e9</D><T_0>180</T_0></shear_modulus_model>""",
    "SCG": """<flow_model type="steinberg_cochran_guinan"><mu_0>47.7e9</mu_0><sigma_0>0.125e9</sigma_0>
             <Y_max>0.64e9</Y_max><beta>36</beta><n>0.45</n><A>28.0e-12</A><B>0.92e-3</B><T_m0>1790.0</T_m0>
             <Gamma_0>1.99</Gamma_0><a>1.5</a><epsilon_p0>0.0</epsilon_p0><C1>0.71e6</C1><C2>0.012e6</C2>
             <energy_to_form_kink_pair>0.31</energy_to_form_kink_pair>
             <Boltzmann_constant>8.617385e-5</Boltzmann_constant><Peierls_stress>0.5e8</Peierls_stress></flow_model>
             <shear_modulus_model type="scg_shear"><mu_0>47.7e9</mu_0><A>28.0e-12</A><B>0.92e-3</B></shear_modulus_model>
             <melting_temp_model type="scg_Tm"><T_m0>1360.0</T_m0><Gamma_0>1.99</Gamma_0><a>1.5</a></melting_temp_model>""",
    "PTW": """<flow_model type="preston_tonks_wallace"><theta>0.025</theta><p>2.0</p><s0>0.0085</s0><sinf>0.00055</sinf>
             <kappa>0.11</kappa><gamma>0.00001</gamma><y0>0.0001</y0><yinf>0.0001</yinf><y1>0.094</y1><y2>0.575</y2>
             <beta>0.25</beta><M>63.54</M><G0>518e8</G0><alpha>0.20</alpha><alphap>0.20</alphap></flow_model>
             <shear_modulus_model type="np_shear"><mu_0>50.7e9</mu_0><slope_mu_p_over_mu0>28.0e-12</slope_mu_p_over_mu0>
             <zeta>0.04</zeta><C>0.057</C><m>63.55</m></shear_modulus_model>
             <melting_temp_model type="scg_Tm"><T_m0>1360.0</T_m0><Gamma_0>1.99</Gamma_0><a>1.5</a></melting_temp_model>""",
}

MATERIAL_XML = """<material name="OFHCCu">
  <density>8930.0</density><thermal_conductivity>386.0</thermal_conductivity><specific_heat>414.0</specific_heat>
  <melt_temp>1356.0</melt_temp>
  <constitutive_model type="elastic_plastic">
    <tolerance>1.0e-12</tolerance><initial_material_temperature>696.0</initial_material_temperature>
    <shear_modulus>46.0e9</shear_modulus><bulk_modulus>129.0e9</bulk_modulus>
    <taylor_quinney_coeff>0.9</taylor_quinney_coeff>
    <equation_of_state type="mie_gruneisen"><C_0>3940</C_0><Gamma_0>2.02</Gamma_0><S_alpha>1.489</S_alpha>
    </equation_of_state>
    {model}
    <yield_condition type="vonMises"/>
    <stability_check type="none"/>
    <compute_specific_heat>false</compute_specific_heat>
    <specific_heat_model type="constant_Cp"/>
  </constitutive_model>
</material>"""
RHO, CP, CHI, MU, RATE, T0 = 8930.0, 414.0, 0.9, 46.0e9, 4000.0, 696.0


def params(model, replace=None):
    text = MATERIAL_XML.format(model=FLOWS.get(model, model))
    if replace:
        text = text.replace(*replace)
    mat = ProblemSpec.from_string(text)
    P = hp.read_params(mat.child("constitutive_model"), mat, mat.read(MATERIAL))
    mat.attr("name")
    mat.child("constitutive_model").attr("type")         # read by Material
    mat.check_all_used()            # every tag of the deck's model is read
    return P


def step(P, L, F_old, F_new, stress, state, T, dt, mass=8.93e-3):
    """One update of one particle; returns (stress, (ep, epdot, e, edot, dTdt))."""
    vol = np.array([mass / RHO * np.linalg.det(F_new[0])])
    out = np.empty((1, 3, 3))
    new = tuple(np.empty(1) for _ in range(5))
    hp.update(P, L, F_old, F_new, vol, np.array([mass]), np.zeros((1, 3)), dt, stress, out, np.empty(1),
              tuple(np.array([v]) for v in state) + (np.array([T]),), new)
    return out, tuple(v[0] for v in new)


@pytest.mark.parametrize("model", ["JC", "ZA", "MTS", "SCG", "PTW"])
def test_steps_match_sus(model):
    d = np.loadtxt(DATA / f"adiCu{model}_sus.txt")
    t, F, S = d[:, 0], d[:, 1:10].reshape(-1, 3, 3), d[:, 10:19].reshape(-1, 3, 3)
    ep, epdot, e, edot, T = d[:, 19], d[:, 20], d[:, 21], d[:, 22], d[:, 23]
    P = params(model)
    plastic = 0
    for k in range(len(t) - 1):
        dt = t[k + 1] - t[k]
        L = (F[k + 1] @ np.linalg.inv(F[k]) - np.eye(3)) / dt
        s, (ep1, epdot1, e1, edot1, dTdt) = step(P, L[None], F[k][None], F[k + 1][None], S[k][None].copy(),
                                                 (ep[k], epdot[k], e[k], edot[k]), T[k], dt)
        assert np.abs(s[0] - S[k + 1]).max() < 2e-5 * np.abs(S[k + 1]).max(), k
        assert ep1 == pytest.approx(ep[k + 1], rel=2e-6), k
        assert epdot1 == pytest.approx(epdot[k + 1], rel=1e-5), k
        assert edot1 == pytest.approx(edot[k + 1], rel=1e-5), k
        plastic += epdot1 > 0
        if np.trace(L) >= 0.0:       # sus adds its artificial-viscosity heating where tr D < 0
            assert e1 == pytest.approx(e[k + 1], rel=2e-6), k
            assert abs(T[k] + dTdt * dt - T[k + 1]) < 1e-3 * abs(T[k + 1] - T[k]) + 2e-6, k
    assert plastic == len(t) - 1         # every step yields: the radial return is what is checked


# -- the closed forms (Uintah's formulas written out in numpy, uniaxial stress at 4000/s) -----
def _jc(ep, T, p):
    Ts = (T - 298.0) / (1793.0 - 298.0)
    return (90e6 + 292e6 * ep ** 0.31) * (1.0 + 0.025 * math.log(RATE)) * (1.0 - Ts ** 1.09)


def _za(ep, T, p):
    return 46.5e6 + 5.0e6 * 3.7 + 890e6 * math.sqrt(ep) * math.exp(-(0.0028 - 0.000115 * math.log(RATE)) * T)


def _mts(ep, T, p):
    mu = 47.7e9 - 3.0e9 / (math.exp(180.0 / T) - 1.0)
    CC = 0.823e6 * T / mu
    S_e = (1.0 - (CC / 1.6 * math.log(1.0e7 / RATE))) ** (1.0 / 0.666667)
    theta0 = 2390e6 + 12e6 * math.log(RATE) + 1.696e6 * math.sqrt(RATE)
    sigma_es = 770e6 * (RATE / 1.0e7) ** (CC / 0.2625)
    f = lambda s: theta0 * (1.0 - math.tanh(2.0 * s / sigma_es) / math.tanh(2.0))   # noqa: E731
    s, h = 0.0, ep / 200.0                      # d sigma_e/d ep = theta(sigma_e), RK4
    for _ in range(200):
        k1 = f(s)
        k2 = f(s + 0.5 * h * k1)
        k3 = f(s + 0.5 * h * k2)
        s += h / 6.0 * (k1 + 2 * k2 + 2 * k3 + f(s + h * k3))
    return 40e6 + S_e * s * mu / 47.7e9


def _scg(ep, T, p):
    mu = 47.7e9 * (1.0 + 28e-12 * (-p) - 0.92e-3 * (T - 300.0))
    C1, C2, sP, UkT = 0.71e6, 0.012e6, 0.5e8, 2.0 * 0.31 / (8.617385e-5 * T)
    rate = lambda tau: C1 * tau / (C1 * C2 + tau * math.exp(UkT * (1.0 - tau / sP) ** 2))   # noqa: E731
    lo, hi = 0.0, sP                            # Steinberg-Lund: the tau that gives the rate
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if rate(mid) < RATE else (lo, mid)
    return (0.5 * (lo + hi) + min(0.125e9 * (1.0 + 36.0 * ep) ** 0.45, 0.64e9)) * mu / 47.7e9


CLOSED = {"JC": _jc, "ZA": _za, "MTS": _mts, "SCG": _scg}


def closed_form(model, ep_max, n=400):
    """(ep, sigma_y) along the adiabatic path dT/d ep = chi sigma_y/(rho c_p) (RK4 in ep)."""
    f = CLOSED[model]
    heat = lambda ep, T: CHI * f(ep, T, f(ep, T, 0.0) / 3.0) / (RHO * CP)     # noqa: E731
    ep, T, h = 1e-9, T0, ep_max / n
    out = []
    for _ in range(n + 1):
        out.append((ep, f(ep, T, f(ep, T, 0.0) / 3.0)))
        k1 = heat(ep, T)
        k2 = heat(ep + 0.5 * h, T + 0.5 * h * k1)
        k3 = heat(ep + 0.5 * h, T + 0.5 * h * k2)
        T += h / 6.0 * (k1 + 2 * k2 + 2 * k3 + heat(ep + h, T + h * k3))
        ep += h
    return np.array(out).T


@pytest.mark.parametrize("model", ["JC", "ZA", "MTS", "SCG"])
def test_adiabatic_uniaxial_stress_follows_closed_form(model):
    P = params(model)
    dt, nsteps = 1.0e-6, 110                     # true strain 0.44 at 4000/s
    F = np.eye(3)[None].copy()
    s = np.zeros((1, 3, 3))
    state, T = (0.0, 0.0, 0.0, 0.0), T0
    eps, sig = [], []
    for _ in range(nsteps):
        # the lateral rate a that keeps sigma_xx = 0: secant iterations on the trial update
        a0, a1 = -0.5 * RATE, -0.3 * RATE
        g = []
        for a in (a0, a1):
            L = np.diag([a, a, RATE])[None]
            g.append(step(P, L, F, (np.eye(3) + L[0] * dt) @ F, s.copy(), state, T, dt)[0][0, 0, 0])
        for _ in range(30):
            a0, a1 = a1, a1 - g[1] * (a1 - a0) / (g[1] - g[0])
            L = np.diag([a1, a1, RATE])[None]
            F1 = (np.eye(3) + L[0] * dt) @ F
            s1, new = step(P, L, F, F1, s.copy(), state, T, dt)
            g = [g[1], s1[0, 0, 0]]
            if abs(g[1]) < 1e-6 * abs(s1[0, 2, 2]):
                break
        F, s, state, T = F1, s1, new[:4], T + new[4] * dt
        eps.append(new[0])
        sig.append(s[0, 2, 2])
    eps, sig = np.array(eps), np.array(sig)
    ref_ep, ref_sig = closed_form(model, eps.max())
    sel = eps > 0.05
    err = sig[sel] / np.interp(eps[sel], ref_ep, ref_sig) - 1.0
    # Uintah's yield check reads ep + epdot dt of the step before, so the plastic strain of
    # consecutive steps alternates about the curve: each step within 4 %, two in a row within 2 %
    # (measured: JC 0.6 %, ZA 0.9 %, MTS 1.7 %, SCG 0.9 %; at ep = 0.44 all within 1.2 %)
    assert np.abs(err).max() < 0.04
    assert np.abs(0.5 * (err[1:] + err[:-1])).max() < 0.02
    assert eps.max() > 0.4


@pytest.mark.parametrize("replace, words", [
    (('type="johnson_cook"', 'type="johnson_cook_2"'), ("flow_model", "johnson_cook_2", "zerilli_armstrong")),
    (("<B>292.0e6</B>", ""), ("<B>",)),
    (('<yield_condition type="vonMises"/>', '<yield_condition type="gurson"/>'), ("yield_condition", "q1")),
    (('<yield_condition type="vonMises"/>', '<yield_condition type="gurson"><q1>1.5</q1><q2>1</q2><q3>2.25</q3>'
      '<k>4</k><f_c>0.05</f_c></yield_condition>'), ("gurson", "biswajit")),       # as Uintah
    (('<yield_condition type="vonMises"/>', '<yield_condition type="drucker_prager"/>'), ("gurson", "vonMises")),
    (("<tolerance>", "<plastic_convergence_algo>newton</plastic_convergence_algo><tolerance>"),
     ("biswajit", "radialReturn")),
    (("<shear_modulus>46.0e9", "<shear_modulus>-46.0e9"), ("shear_modulus", "-46.0e9")),
    (('type="mie_gruneisen"', 'type="tillotson"'), ("equation_of_state", "tillotson", "mie_gruneisen")),
    (("<m>1.09</m>", "<m>1.09</m><T_m>200</T_m>"), ("johnson_cook", "T_m", "T_r")),
    (("<n>0.31</n>", "<n>0.31</n><rate_exponent>2</rate_exponent>"), ("rate_exponent",)),
])
def test_bad_input_is_one_clean_line(replace, words):
    with pytest.raises(InputError) as e:
        params("JC", replace)
    msg = str(e.value)
    assert "\n" not in msg
    for w in words:
        assert w in msg, msg


def test_isotropic_hardening_is_linear_radial_return():
    """isotropic_hardening (sigma_Y + K ep), hyperelastic EOS: a uniaxial-strain step that
    yields gives the classical radial return q = sigma_Y + K ep with dgamma = (q* - sigma_Y)/(3 mu + K)."""
    model = '<flow_model type="isotropic_hardening"><K>1.0e9</K><sigma_Y>100.0e6</sigma_Y></flow_model>'
    P = params(model, ('<equation_of_state type="mie_gruneisen"><C_0>3940</C_0><Gamma_0>2.02</Gamma_0>'
                       '<S_alpha>1.489</S_alpha>\n    </equation_of_state>', ""))
    assert P.codes[3] == 0
    dt = 1e-6
    L = np.diag([0.0, 0.0, 3000.0])[None]
    s, new = step(P, L, np.eye(3)[None], (np.eye(3) + L[0] * dt)[None], np.zeros((1, 3, 3)),
                  (0.0, 0.0, 0.0, 0.0), 300.0, dt)
    q_trial = 3.0 * MU * 2.0 / 3.0 * 3000.0 * dt            # sqrt(3/2)|2 mu dev(D) dt|
    ep = (q_trial - 100e6) / (3.0 * MU + 1.0e9)
    assert new[0] == pytest.approx(ep, rel=1e-9)
    dev = s[0] - np.trace(s[0]) / 3.0 * np.eye(3)
    assert math.sqrt(1.5 * np.sum(dev * dev)) == pytest.approx(100e6 + 1.0e9 * ep, rel=1e-9)


def test_adiabatic_copper_deck_runs_near_sus(tmp_path):
    """inputs/MPM/adiabatic_copper_jc.ups through MPM (p.dTdt into p.temperature, the state
    carried by relocation) for 40 steps: the stretch F_zz is the piston's, and the plastic
    strain and the temperature stay within 2 % and 1 % of sus on Uintah's deck. (They are not
    closer because sus also applies its symmetry BC to g.velocity in interpolateParticlesToGrid
    and has artificial viscosity: the single particle's lateral motion differs.)"""
    text = deck_text(MPM_INPUTS / "adiabatic_copper_jc.ups", maxTime=1.0)
    text = text.replace("<maxTime>", "<max_Timesteps>40</max_Timesteps><maxTime>")
    _, da = run(text, tmp_path)
    d = np.loadtxt(DATA / "adiCuJC_sus.txt")
    k = len(da.times) - 1
    p = da.particles(1, k)
    assert da.times[k] == pytest.approx(d[39, 0], rel=0.02)
    F = p["p.deformationMeasure"][0]
    assert F[2, 2] == pytest.approx(d[39, 9], rel=1e-4)
    assert p["p.plasticStrain"][0] == pytest.approx(d[39, 19], rel=0.02)
    assert p["p.temperature"][0] == pytest.approx(d[39, 23], rel=0.01)
    assert p["p.temperature"][0] > 690.0 and p["p.plasticStrain"][0] > 0.15


def _steel_cp_uintah(T, Tc=1040.0):
    """Uintah's SteelCp::computeSpecificHeat with its default (4340 steel) constants."""
    if T == Tc:
        T -= 1.0
    if T < Tc:
        t = 1.0 - T / Tc
        return 190.14 - 273.75 * t + 418.30 / t ** 0.2
    t = T / Tc - 1.0
    return 465.21 + 267.52 * t + 58.16 / t ** 0.35


@pytest.mark.parametrize("T", [300.0, 560.0, 1000.0, 1040.0, 1100.0, 1500.0])
def test_steel_cp_is_uintahs(T):
    """<specific_heat_model type="steel_Cp"> (SteelCp, as Uintah's SteadyBurn_2dRT steel): both
    branches and the transition point (taken 1 K below), from the deck's defaults; a tag overrides."""
    from components.mpm.constitutive import plasticity_kernels as pk
    old = '<compute_specific_heat>false</compute_specific_heat>\n    <specific_heat_model type="constant_Cp"/>'
    new = '<compute_specific_heat>true</compute_specific_heat><specific_heat_model type="steel_Cp">{}</specific_heat_model>'
    P = params("JC", (old, new.format("")))
    assert P.codes[4] == pk.STEEL_CP
    assert pk.specific_heat(pk.STEEL_CP, P.cp, 414.0, T) == pytest.approx(_steel_cp_uintah(T), rel=1e-14)
    Q = params("JC", (old, new.format("<T_transition>900</T_transition>")))
    assert pk.specific_heat(pk.STEEL_CP, Q.cp, 414.0, T) == pytest.approx(_steel_cp_uintah(T, 900.0), rel=1e-14)


@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_hancock_mackenzie_damage_is_uintahs_formula(sign):
    """<damage_model type="hancock_mackenzie"> (Uintah's HancockMacKenzieDamage): p.damage starts
    at initial_mean_scalar_damage and grows by epdot dt exp(1.5 p / sigma_eq) / 1.65 with the new
    stress (sigma_eq von Mises in mean tension; in compression 1 Pa, so exp(-1.5 |p|) = 0 for any
    real pressure and the damage stays); the stress is the model's without it."""
    dm = ("</material>", '<damage_model type="hancock_mackenzie"><initial_mean_scalar_damage>0.01'
                         '</initial_mean_scalar_damage><critical_scalar_damage>0.5</critical_scalar_damage>'
                         '</damage_model></material>')
    P, P0 = params("JC", dm), params("JC")
    assert P.damage_kind == "hancock_mackenzie" and hp.state_of(P)[-1] == "p.damage"
    dt, L = 1e-6, np.diag([sign * 4000.0, 0.0, 0.0])[None]
    F_old, F_new = np.eye(3)[None], (np.eye(3) + L[0] * dt)[None]
    vol, mass = np.array([1e-9 * np.linalg.det(F_new[0])]), np.array([RHO * 1e-9])
    out = {}
    for par in (P, P0):
        old = hp.initial_state(par, 1, np.array([T0]))
        new = tuple(np.empty_like(a) for a in old) + (np.empty(1),)
        s = np.empty((1, 3, 3))
        hp.update(par, L, F_old, F_new, vol, mass, np.zeros((1, 3)), dt, np.zeros((1, 3, 3)), s, np.empty(1),
                  old + (np.array([T0]),), new)
        out[par is P] = s[0], new
    (s, new), (s0, _) = out[True], out[False]
    assert np.array_equal(s, s0)
    d_old = hp.initial_state(P, 1, np.array([T0]))[-1][0]
    assert d_old == 0.01
    epdot, damage = new[1][0], new[len(hp.state_of(P)) - 1][0]
    assert epdot > 0.0
    p = np.trace(s) / 3.0
    seq = math.sqrt(1.5 * ((s - p * np.eye(3)) ** 2).sum()) if p > 0.0 else 1.0
    assert (p > 0.0) == (sign > 0.0)
    assert damage == pytest.approx(0.01 + epdot * dt * math.exp(1.5 * p / seq) / 1.65, rel=1e-14)
    assert (damage > 0.01) == (sign > 0.0)
