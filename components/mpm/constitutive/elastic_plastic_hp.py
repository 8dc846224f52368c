"""Uintah's elastic_plastic with sub-models (ElasticPlasticHP): hypoelastic-plastic J2 flow
with temperature-, rate- and pressure-dependent flow stress, shear modulus and melting.

Per particle and step, as Uintah's explicit computeStressTensor: rotate D and sigma into the
material frame with the R of F^n = R U (polar decomposition); the shear modulus and melting
temperature at the start of the step; trial deviatoric stress s* = s + 2 mu dev(D) dt; the
von Mises check f = q*^2 - sigma_y^2 with sigma_y at the plastic strain ep + epdot dt; if f >= 0
the radial return s = s* - 2 mu dgamma s*/|s*| with dgamma from Newton iterations on
g = |s*| - sqrt(2/3) sigma_y(ep + sqrt(2/3) dgamma, epdot = sqrt(2/3) dgamma/dt) - 2 mu dgamma
(Simo and Hughes 1998, box 3.1, with Uintah's tolerances); above the melting temperature
s = 0; the pressure from the equation of state; the stress rotated back with the R of
F^{n+1}; the wave speed with that step's mu (the first step's with <shear_modulus>, as Uintah's
computeStableTimeStep). The temperature rate p.dTdt = chi sigma_y epdot/(rho c_p) (plastic work to heat,
<taylor_quinney_coeff> chi) + the isentropic rate of the EOS; the MPM component adds
p.dTdt dt to p.temperature (Uintah's finalParticleUpdate). p.energy, the specific internal
energy the Mie-Gruneisen EOS reads, accumulates the stress work.

Deck (``<constitutive_model type="elastic_plastic">`` with a ``<flow_model>``, or
``type="elastic_plastic_hp"``): ``shear_modulus``, ``bulk_modulus``,
``taylor_quinney_coeff`` (0.9), ``tolerance``, ``initial_material_temperature`` (294 K, the
reference temperature of T-dependent sub-models), ``compute_specific_heat``,
sub-models ``flow_model`` (FLOW), ``yield_condition`` (YIELD), ``equation_of_state``
(EOS; none: Uintah's default hyperelastic K/2 (J - 1/J)), ``shear_modulus_model`` (SHEAR),
``melting_temp_model`` (MELT), ``specific_heat_model`` (CP), ``stability_check`` (STABILITY,
used with an erosion). Tags Uintah's model reads and uses only in code pysus does not have
(implicit MPM, MPMICE's modified EOS) are accepted and recorded.
With the material's ``<erosion algorithm="...">`` (not "none") the model localizes its
particles itself, as Uintah's: p.localizedMPM = 1 (for good) where T > T_m, or, in a plastic
step, where the porosity passes the TEPLA rule f^2/f_c^2 > 1 (``check_TEPLA_failure_criterion``,
f_c = ``critical_porosity``), or where the ``stability_check`` finds a bifurcation of the
material-frame stress with Uintah's von Mises elastic-plastic tangent C_ep = C_e - (C_e:r)
(r:C_e)/(r:C_e:r - h dsigma_y/dep) (r = 3 dev sigma, h = sigma:r/sigma_y): Drucker's
(C_ep:D):D <= 0, Becker's (Becker 2002) two non-negative roots of its quadratic in the
extreme principal stresses, or a flow stress <= 0; a localized particle's porosity is set to
0 and it adds no stress work to p.energy. With an erosion the porosity (p.porosity) is carried
and evolves in plastic steps with the vonMises condition too. The erosion itself is Uintah's
ErosionModel (damage.py): F and L of the particles localized at the step's start eroded before
the stress, p.timeofloc and the stress of the localized after it.
``<damage_model type="johnson_cook">`` (a sibling in the material): Uintah's JohnsonCookDamage,
a p.damage that leaves the stress alone (damage.johnson_cook_damage; D1 .. D5,
``initial_mean_scalar_damage``, ``initial_std_scalar_damage``, ``critical_scalar_damage``,
``initial_scalar_damage_distrib`` constant or gauss: Uintah's seeded draws as the porosity's);
``hancock_mackenzie``: Uintah's HancockMacKenzieDamage (Hancock and MacKenzie 1976), also a
diagnostic p.damage, D += epdot dt exp(1.5 p / sigma_eq) / 1.65 with sigma_eq the von Mises
stress in mean tension and 1 Pa otherwise, as Uintah (damage.hancock_mackenzie_damage; the same
initial tags, ``critical_scalar_damage`` read and unused as in Uintah).
``yield_condition type="gurson"`` (GursonYield, with ``plastic_convergence_algo`` biswajit as
Uintah requires): the trial stress yields where sigma_eq^2 >= sigma_y^2 (1 + q3 f*^2 - 2 q1 f*
cosh(q2 tr/(2 sigma_y))), tr Uintah's trial trace 3 p + 2 mu tr(D) dt; the biswajit return
(ElasticPlasticHP::computePlasticStateBiswajit) takes the plastic multiplier from the rate
and the stress at the step's start (plasticity_kernels.biswajit_increment) and scales the
trial deviatoric stress to sigma_y(ep, epdot); where that estimate fails, the radial return
above. In a plastic step the porosity p.porosity grows by (1 - f) tr D dt (expansion) and
nucleates by A(ep) sqrt(2/3) |dev D| dt; its initial value is f_0 or Uintah's seeded
Gaussian draws (uintah_random.py) in Uintah's order of particle creation.
``deviatoric_stress_model`` (DEV): ``hypoElastic`` (the default, the trial stress above) or
``hypoViscoElastic`` with Maxwell elements ``<mu>[mu_1, ...]</mu>`` ``<tau>[tau_1, ...]</tau>``:
each element j carries its deviatoric stress s_j (Uintah's sigmaDevj), the trial stress is
s* = s + dt sum_j (2 mu_j eta - s_j/tau_j) (an element whose rate is under 1e-4 of its
elastic rate 2 mu_j |eta| left out, as Uintah), the radial return uses <shear_modulus>, and
s_j += dt (2 mu_j (eta - d_p) - s_j/tau_j) with d_p = dgamma n/dt the plastic rate; the
dissipated power sum_j |s_j|^2/(2 mu_j tau_j) heats as chi/(rho c_p) times it. The s_j are
rotated into the material frame with R^n and back with R^{n+1} as sigma (Uintah leaves them
unrotated into the step and rotates them with R^{n+1 T} ... R^{n+1} after it: the same without
rotation); melted, they are set to zero (Uintah leaves them unset). A step longer than the
smallest tau stops the run (Uintah's InternalError).
With <MPM><artificial_viscosity> the model's bulk modulus sets the viscosity and the viscous
work heats the particle (artificial_viscosity.py). The kernel for a deck's choice of sub-models
is made by `kernel_for` (one compiled kernel per choice, cached).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from framework.errors import RunStopped
from framework.problemspec import Param

from . import damage
from . import plasticity_kernels as pk
from ._common import det3, inv3, max_wavespeed
from .uintah_random import STATE_SIZE, gauss, musil_start

ENERGY_IS_INCREMENT = True
# carried per-particle state (labels.STATE names), in the order of `old`/`new` in update();
# hypoViscoElastic adds the Maxwell element stresses sigmaDev0, sigmaDev1, ... (state_of)
STATE = ("p.plasticStrain", "p.plasticStrainRate", "p.energy", "p.strainRate")
# with the gurson yield condition or an erosion also the void fraction and Uintah's localization
# flag (set only with an erosion); with an erosion the time of localization; with a johnson_cook
# damage model its p.damage
GURSON_STATE = ("p.porosity", "p.localizedMPM")
EROSION_STATE = ("p.timeofloc",)
DAMAGE_STATE = ("p.damage",)
MAX_MAXWELL_ELEMENTS = 8          # labels.MAX_MAXWELL_ELEMENTS
NEEDS_TEMPERATURE = True
LOCALIZES = True                  # with an <erosion> it localizes its particles itself (materials.py)

def _F(doc=""):
    """A required float tag."""
    return Param("float", doc=doc)


def _opt(default, doc=""):
    return Param("float", default, doc=doc)


# deck type -> (code, {tag: Param}); the parameter vector holds the tags in this order
FLOW = {
    "isotropic_hardening": (pk.ISO, {"K": _F("hardening modulus (Pa)"), "sigma_Y": _F("yield stress (Pa)")}),
    "johnson_cook": (pk.JC, {"A": _F(), "B": _F(), "C": _F(), "n": _F(), "m": _F(), "epdot_0": _opt(1.0),
                             "T_r": _opt(298.0), "T_m": _opt(1793.0)}),
    "zerilli_armstrong": (pk.ZA, {"c_0": _opt(0.0, "else sigma_g + k_H sqrt_l_inv"), "B": _F(), "beta_0": _F(),
                                  "beta_1": _F(), "B_0": _F(), "alpha_0": _F(), "alpha_1": _F(), "K": _F(),
                                  "n": _F()}),
    "mts_model": (pk.MTS, {k: _F() for k in ("sigma_a", "mu_0", "D", "T_0", "koverbcubed", "g_0i", "g_0e",
                                             "edot_0i", "edot_0e", "p_i", "q_i", "p_e", "q_e", "sigma_i", "a_0",
                                             "a_1", "a_2", "a_3", "theta_IV", "alpha", "edot_es0", "g_0es",
                                             "sigma_es0")}
                  | {"T_c": _opt(10400.0), "g_0i_c": _opt(0.57582), "sigma_i_c": _opt(896.14e6),
                     "g_0es_c": _opt(0.294), "sigma_es0_c": _opt(478.36e6), "a_0_c": _opt(7.5159e9),
                     "a_3_c": _opt(3.7796e6)}),
    "steinberg_cochran_guinan": (pk.SCG, {k: _F() for k in ("mu_0", "A", "B", "sigma_0", "beta", "n", "epsilon_p0",
                                                            "Y_max", "T_m0", "a", "Gamma_0")}
                                 | {"C1": _opt(0.0), "C2": _opt(0.0), "energy_to_form_kink_pair": _F(),
                                    "Boltzmann_constant": _F(), "Peierls_stress": _F()}),
    "preston_tonks_wallace": (pk.PTW, {k: _F() for k in ("theta", "p", "s0", "sinf", "kappa", "gamma", "y0", "yinf",
                                                         "y1", "y2", "beta", "M")}
                              | {k: _opt(0.0, "in Uintah's decks, not read by its PTWFlow")
                                 for k in ("G0", "alpha", "alphap")}),
}
# ZA without c_0: c_0 = sigma_g + k_H sqrt_l_inv; SCG without C1, C2: from the dislocation data
ZA_C0 = {"sigma_g": _F(), "k_H": _F(), "sqrt_l_inv": _F()}
SCG_C = {k: _F() for k in ("dislocation_density", "length_of_dislocation_segment",
                           "distance_between_Peierls_valleys", "length_of_Burger_vector", "Debye_frequency",
                           "width_of_kink_loop", "drag_coefficient")}
SHEAR = {"constant_shear": (pk.CONST_SHEAR, {}),
         "mts_shear": (pk.MTS_SHEAR, {"mu_0": _F(), "D": _F(), "T_0": _F()}),
         "scg_shear": (pk.SCG_SHEAR, {"mu_0": _F(), "A": _F(), "B": _F()}),
         "np_shear": (pk.NP_SHEAR, {"mu_0": _F(), "zeta": _F(), "slope_mu_p_over_mu0": _F(), "C": _F(), "m": _F()})}
MELT = {"constant_Tm": (pk.CONST_TM, {}),
        "scg_Tm": (pk.SCG_TM, {"Gamma_0": _F(), "a": _F(), "T_m0": _F()}),
        "bps_Tm": (pk.BPS_TM, {k: _F() for k in ("B0", "dB_dp0", "G0", "dG_dp0", "kappa", "z", "b2rhoTm", "alpha",
                                                 "lambda", "a", "v_ws_a3_factor", "Boltzmann_Constant")}),
        "linear_Tm": (pk.LINEAR_TM, {})}
EOS = {"default_hyper": (pk.HYPER_EOS, {}), "default_hypo": (pk.HYPO_EOS, {}),
       "mie_gruneisen": (pk.MIE_GRUNEISEN, {"C_0": _F(), "Gamma_0": _F(), "S_alpha": _F(), "S_2": _opt(0.0),
                                            "S_3": _opt(0.0)})}
CP = {"constant_Cp": (pk.CONST_CP, {}),
      "copper_Cp": (pk.COPPER_CP, {"T_transition": _opt(270.0), "A_LowT": _opt(0.0000416), "B_LowT": _opt(0.027),
                                   "C_LowT": _opt(6.21), "D_LowT": _opt(142.6), "A_HighT": _opt(0.1009),
                                   "B_HighT": _opt(358.4)}),
      "steel_Cp": (pk.STEEL_CP, {"T_transition": _opt(1040.0), "A_LowT": _opt(190.14), "B_LowT": _opt(273.75),
                                 "C_LowT": _opt(418.30), "n_LowT": _opt(0.2), "A_HighT": _opt(465.21),
                                 "B_HighT": _opt(267.52), "C_HighT": _opt(58.16), "n_HighT": _opt(0.35)})}
YIELD = {"vonMises": (pk.VON_MISES, {}),
         "gurson": (pk.GURSON, {"q1": _F(), "q2": _F(), "q3": _F(), "k": _F("f* slope above f_c"),
                                "f_c": _F("critical porosity of f*")})}
ALGO = {"radialReturn": False, "biswajit": True}
HYPO_ELASTIC, HYPO_VISCO_ELASTIC = 0, 1
DEV = {"hypoElastic": HYPO_ELASTIC, "hypoViscoElastic": HYPO_VISCO_ELASTIC}
# <stability_check> types (consulted only with an erosion): index = kernel code
STABILITY = ("none", "drucker", "becker", "drucker_becker")
NO_CHECK, DRUCKER, BECKER, DRUCKER_BECKER = range(4)
# <damage_model type="johnson_cook"> (Uintah's JohnsonCookDamage, a diagnostic p.damage)
JC_DAMAGE = {"D1": _F(), "D2": _F(), "D3": _F(), "D4": _F(), "D5": _F(),
             "initial_mean_scalar_damage": _opt(0.0, "D_0"),
             "initial_std_scalar_damage": _opt(0.0, "its std with gauss"),
             "critical_scalar_damage": _opt(1.0e-10, "a damage below it is set to 0"),
             "initial_scalar_damage_distrib": Param("str", "constant", ("constant", "gauss"),
                                                    "D_0 everywhere, or |N(D_0, std)| from Uintah's seeded "
                                                    "generator")}
# <damage_model type="hancock_mackenzie"> (Uintah's HancockMacKenzieDamage, a diagnostic p.damage)
HM_DAMAGE = {k: JC_DAMAGE[k] for k in ("initial_mean_scalar_damage", "initial_std_scalar_damage",
                                       "initial_scalar_damage_distrib")}
HM_DAMAGE["critical_scalar_damage"] = _opt(1.0, "read, unused (as Uintah)")

TOP = {
    "shear_modulus": Param("float", doc="mu at the reference state (Pa)", above=0.0),
    "bulk_modulus": Param("float", doc="K (Pa)", above=0.0),
    "taylor_quinney_coeff": Param("float", 0.9, doc="fraction of plastic work turned to heat", at_least=0.0),
    "tolerance": Param("float", 1.0e-10, doc="read as in Uintah (its flow models ignore it)", above=0.0),
    "initial_material_temperature": Param("float", 294.0, doc="reference T of the EOS energy (K)", above=0.0),
    "compute_specific_heat": Param("bool", False, doc="c_p from <specific_heat_model>, else the material's"),
    "plastic_convergence_algo": Param("str", "radialReturn", tuple(ALGO),
                                      "radialReturn, or biswajit (needed by gurson)"),
    "evolve_porosity": Param("bool", True, doc="porosity grows and nucleates in plastic steps (gurson)"),
    "check_TEPLA_failure_criterion": Param("bool", True, doc="with erosion: localize where f > f_c"),
    "do_melting": Param("bool", True, doc="read; Uintah's model does not use it"),
    "useModifiedEOS": Param("bool", False, doc="MPMICE's rho(p) only"),
    "coeff_thermal_expansion": Param("float", 0.0, doc="implicit MPM only"),
    "isothermal": Param("bool", False, doc="read; Uintah's model does not use it"),
    "check_max_stress_failure": Param("bool", False, (False,), "read; Uintah's model does not use it"),
    "critical_stress": Param("float", 0.0, doc="read; Uintah's model does not use it"),
}
# porosity (Uintah's defaults): used by the gurson yield condition, read and not used with vonMises
TOP.update({
    "initial_mean_porosity": Param("float", 0.002, doc="f_0"),
    "initial_std_porosity": Param("float", 0.002, doc="std of f_0 with gauss"),
    "critical_porosity": Param("float", 0.5, doc="f_c of the TEPLA rule (with erosion)", above=0.0),
    "frac_nucleation": Param("float", 0.1, doc="f_n, volume fraction of void-nucleating particles"),
    "meanstrain_nucleation": Param("float", 0.3, doc="e_n, mean plastic strain of nucleation"),
    "stddevstrain_nucleation": Param("float", 0.1, doc="s_n, its standard deviation (> 0 with gurson)"),
    "initial_porosity_distrib": Param("str", "constant", ("constant", "gauss"),
                                      "f_0 everywhere, or |N(f_0, std)| from Uintah's seeded generator"),
})


@dataclass(frozen=True)
class Params:
    shear_modulus: float
    bulk_modulus: float
    density: float
    melt_temp: float
    specific_heat: float
    taylor_quinney: float
    initial_temperature: float
    codes: tuple                     # (flow, shear, melt, eos, cp) sub-model codes
    flow: np.ndarray
    shear: np.ndarray
    melt: np.ndarray
    eos: np.ndarray
    cp: np.ndarray
    dev: int = HYPO_ELASTIC          # deviatoric stress model (DEV)
    maxwell_mu: np.ndarray = None    # hypoViscoElastic: mu_j and tau_j of the Maxwell elements
    maxwell_tau: np.ndarray = None
    yield_code: int = pk.VON_MISES   # YIELD; gurson's q1, q2, q3, k, f_c in yield_params
    yield_params: np.ndarray = None
    biswajit: bool = False           # <plastic_convergence_algo>biswajit
    porosity: np.ndarray = None      # f_n, e_n, s_n, evolve (1/0), f_0, std f_0
    porosity_gauss: bool = False
    erosion: int = 0                 # damage.EROSION code of the material's <erosion> (0: none)
    char_time: float = 1.0e-99       # its <char_time>
    stability: int = NO_CHECK        # <stability_check> (with an erosion)
    tepla: bool = False              # <check_TEPLA_failure_criterion> (with an erosion)
    critical_porosity: float = 0.5
    jc_damage: np.ndarray = None     # johnson_cook damage: D1 .. D5, critical damage
    damage_temps: tuple = (294.0, 1.0e30)    # its T_room, T_melt (the material's)
    damage_init: tuple = (0.0, 0.0, False)   # the damage's D_0, std, gauss
    damage_kind: str = None          # <damage_model type>: johnson_cook, hancock_mackenzie (p.damage), or None

    @property
    def draws_initial_state(self):
        """The initial porosity or damage is drawn (it needs Uintah's order of particle creation)."""
        return ((self.porosity_gauss and (self.yield_code == pk.GURSON or self.erosion != 0))
                or (self.damage_kind is not None and self.damage_init[2]))

    @property
    def has_porosity(self):
        """p.porosity and p.localizedMPM are carried (gurson, or an erosion's TEPLA rule)."""
        return self.yield_code == pk.GURSON or self.erosion != 0


def state_of(params):
    """The carried state names of this deck's model: STATE, GURSON_STATE with gurson, and one
    sigmaDevj per Maxwell element."""
    st = (STATE + (GURSON_STATE if params.has_porosity else ()) + (EROSION_STATE if params.erosion else ())
          + (DAMAGE_STATE if params.damage_kind is not None else ()))
    if params.dev != HYPO_VISCO_ELASTIC:
        return st
    return st + tuple(f"sigmaDev{j}" for j in range(len(params.maxwell_mu)))


def _numbers(node, tag):
    """The list [a, b, ...] of positive numbers in <tag> of `node`."""
    c = node.child(tag, required=True)
    text = c.text()
    words = text[1:-1].replace(",", " ").split() if text.startswith("[") and text.endswith("]") else None
    try:
        vals = [float(w) for w in words] if words else None
    except ValueError:
        vals = None
    if not vals or not all(math.isfinite(v) and v > 0.0 for v in vals):
        raise c.error(f"<{tag}> '{text}' is not accepted; accepted: a list [a, b, ...] of positive numbers, "
                      "one per Maxwell element")
    return np.array(vals)


def _deviatoric(cm):
    """(code, mu_j, tau_j) of <deviatoric_stress_model>: hypoElastic (none), hypoViscoElastic."""
    node = cm.child("deviatoric_stress_model")
    if node is None or node.attr("type", choices=tuple(DEV)) == "hypoElastic":
        return HYPO_ELASTIC, np.zeros(0), np.zeros(0)
    mu, tau = _numbers(node, "mu"), _numbers(node, "tau")
    if len(mu) != len(tau):
        raise node.error(f"<mu> has {len(mu)} and <tau> {len(tau)} values; accepted: one mu and one tau per "
                         "Maxwell element")
    if len(mu) > MAX_MAXWELL_ELEMENTS:
        raise node.error(f"{len(mu)} Maxwell elements; accepted: at most {MAX_MAXWELL_ELEMENTS}")
    return HYPO_VISCO_ELASTIC, mu, tau


def _vector(node, table):
    vals = node.read(table) if node is not None else {k: p.default for k, p in table.items()}
    return vals, np.array([float(v) for v in vals.values()])


def _submodel(cm, tag, table, default):
    """(code, parameter vector, node) of the sub-model <tag type="...">; `default` if absent."""
    node = cm.child(tag)
    if node is None:
        if default is None:
            raise cm.error(f'missing <{tag} type="..."> ; accepted types: {", ".join(table)}')
        code, params = table[default]
        return code, _vector(None, params)[1], None
    kind = node.attr("type", choices=tuple(table))
    code, params = table[kind]
    return code, _vector(node, params)[1], node


def read_params(cm, material, props):
    """Params from the <constitutive_model> node `cm` of `material` (props: the material's
    density, melt_temp, specific_heat)."""
    top = cm.read(TOP)
    yc = cm.child("yield_condition", required=True)
    yield_code, yield_params = YIELD[yc.attr("type", choices=tuple(YIELD))][0], np.zeros(0)
    if yield_code == pk.GURSON:
        yield_params = _vector(yc, YIELD["gurson"][1])[1]
        if top["plastic_convergence_algo"] != "biswajit":
            raise yc.error('the gurson yield condition needs <plastic_convergence_algo>biswajit'
                           '</plastic_convergence_algo> (as Uintah); accepted: that, or type="vonMises"')
        if not top["stddevstrain_nucleation"] > 0.0:
            sn = cm.child("stddevstrain_nucleation")
            raise (sn if sn is not None else cm).error(
                f"<stddevstrain_nucleation> {top['stddevstrain_nucleation']:g} is not accepted with gurson; "
                "accepted: a positive number (the nucleation's spread in plastic strain)")
    porosity = np.array([top["frac_nucleation"], top["meanstrain_nucleation"], top["stddevstrain_nucleation"],
                         1.0 if top["evolve_porosity"] else 0.0, top["initial_mean_porosity"],
                         top["initial_std_porosity"]])
    st = cm.child("stability_check")
    stability = STABILITY.index(st.attr("type", choices=STABILITY)) if st is not None else NO_CHECK
    jc, damage_init, damage_kind = None, (0.0, 0.0, False), None
    dm = material.child("damage_model")      # Uintah: deprecated, "does not influence the stress state"
    if dm is not None:
        damage_kind = dm.attr("type", choices=("hancock_mackenzie", "johnson_cook"))
        d = dm.read(JC_DAMAGE if damage_kind == "johnson_cook" else HM_DAMAGE)
        if damage_kind == "johnson_cook":
            jc = np.array([d["D1"], d["D2"], d["D3"], d["D4"], d["D5"], d["critical_scalar_damage"]])
        damage_init = (d["initial_mean_scalar_damage"], d["initial_std_scalar_damage"],
                       d["initial_scalar_damage_distrib"] == "gauss")
    er = material.child("erosion")
    erosion, char_time = damage.read_erosion(er) if er is not None else (0, 1.0e-99)
    if erosion and yc.attr("type") == "gurson" and stability != NO_CHECK:
        raise st.error(f'<stability_check type="{STABILITY[stability]}"> with the gurson yield condition and an '
                       '<erosion> is not implemented (its elastic-plastic tangent); accepted: type="none", or '
                       'the vonMises yield condition')
    node = cm.child("flow_model", required=True)
    kind = node.attr("type", choices=tuple(FLOW))
    code, table = FLOW[kind]
    vals, flow = _vector(node, table)
    if code == pk.JC and not vals["T_m"] > vals["T_r"]:
        raise node.error("johnson_cook needs <T_m> > <T_r> (T* = (T - T_r)/(T_m - T_r))")
    if code == pk.JC and not vals["epdot_0"] > 0.0:
        raise node.child("epdot_0").error("<epdot_0> must be positive")
    if code == pk.ZA and vals["c_0"] == 0.0:
        z = node.read(ZA_C0)
        flow[0] = z["sigma_g"] + z["k_H"] * z["sqrt_l_inv"]
    if code == pk.SCG and (vals["C1"] == 0.0 or vals["C2"] == 0.0):
        d = node.read(SCG_C)
        rho, L, a, b = (d["dislocation_density"], d["length_of_dislocation_segment"],
                        d["distance_between_Peierls_valleys"], d["length_of_Burger_vector"])
        flow[11] = rho * L * a * b * b * d["Debye_frequency"] / (2.0 * d["width_of_kink_loop"] ** 2)
        flow[12] = d["drag_coefficient"] / (rho * b * b)
    shear_code, shear, _ = _submodel(cm, "shear_modulus_model", SHEAR, "constant_shear")
    melt_code, melt, mnode = _submodel(cm, "melting_temp_model", MELT, "constant_Tm")
    if melt_code == pk.LINEAR_TM:
        melt = _linear_melt(mnode)
    eos_code, eos, _ = _submodel(cm, "equation_of_state", EOS, "default_hyper")
    cp_code, cp, _ = _submodel(cm, "specific_heat_model", CP, "constant_Cp")
    if not top["compute_specific_heat"]:
        cp_code = pk.CONST_CP
    if props["specific_heat"] <= 0.0 and cp_code == pk.CONST_CP:
        raise material.error("elastic_plastic needs the material's <specific_heat> > 0 (plastic heating)")
    if props["melt_temp"] <= 0.0:
        raise material.child("melt_temp").error("<melt_temp> must be positive")
    dev, maxwell_mu, maxwell_tau = _deviatoric(cm)
    return Params(top["shear_modulus"], top["bulk_modulus"], props["density"], props["melt_temp"],
                  props["specific_heat"], top["taylor_quinney_coeff"], top["initial_material_temperature"],
                  (code, shear_code, melt_code, eos_code, cp_code), flow, shear, melt, eos, cp,
                  dev, maxwell_mu, maxwell_tau, yield_code, yield_params, ALGO[top["plastic_convergence_algo"]],
                  porosity, top["initial_porosity_distrib"] == "gauss", erosion, char_time, stability,
                  top["check_TEPLA_failure_criterion"], top["critical_porosity"], jc,
                  (props["room_temp"], props["melt_temp"]), damage_init, damage_kind)


def _linear_melt(node):
    """LinearMeltTemp's forms: T_m0 + b p (b, or a T_m0/K_T), T_m0 (1 + a rho_0/rho), or T_m0."""
    v = node.read({"T_m0": _F(), "a": _opt(-999.0), "b": _opt(-999.0), "Gamma_0": _opt(-999.0),
                   "K_T": _opt(-999.0)})
    if v["a"] != -999.0 and v["K_T"] != -999.0:
        return np.array([v["T_m0"], 1.0, v["a"] * v["T_m0"] / v["K_T"]])
    if v["b"] != -999.0:
        return np.array([v["T_m0"], 1.0, v["b"]])
    if v["a"] != -999.0:
        return np.array([v["T_m0"], 2.0, v["a"]])
    if v["Gamma_0"] != -999.0:
        return np.array([v["T_m0"], 0.0, 0.0])
    raise node.error("linear_Tm needs <a> and <K_T>, <b>, <a>, or <Gamma_0>")


def initial_state(params, n, temperature=None, creation_order=None):
    """Plastic strain, its rate, specific energy, strain rate and Maxwell element stresses of
    new particles: zero (whatever their temperature); with gurson or an erosion the
    localization flag 0 and the porosity f_0, or with gauss |N(f_0, std)| drawn, as Uintah, in
    its order of particle creation in the patch (`creation_order`: the particles' indices in
    that order); with an erosion p.timeofloc -1e99; with johnson_cook damage p.damage D_0 or
    its gauss draws (a generator of its own, the same seed)."""
    names = state_of(params)
    out = tuple(np.zeros(n) for _ in STATE)
    order = np.arange(n) if creation_order is None else creation_order
    if params.has_porosity:
        f0, std = params.porosity[4], params.porosity[5]
        f = np.full(n, f0)
        if params.porosity_gauss and n:
            f[order] = initial_porosity(n, f0, std)
        out += (f, np.zeros(n))
    if params.erosion:
        out += (np.full(n, -1.0e99),)
    if params.damage_kind is not None:
        d0, std, gauss_ = params.damage_init
        d = np.full(n, d0)
        if gauss_ and n:              # JohnsonCookDamage's own generator, also seed 0 per patch
            d[order] = initial_porosity(n, d0, std)
        out += (d,)
    return out + tuple(np.zeros((n, 3, 3)) for _ in names[len(out):])


@njit(cache=True)
def initial_porosity(n, f0, std):
    """n draws |N(f0, std)| of Uintah's Gaussian(f0, std, seed 0) (ElasticPlasticHP's initial
    porosity with gauss: the generator restarts with seed 0 for every patch and material)."""
    st = np.zeros(STATE_SIZE, np.int64)
    musil_start(0, st)
    out = np.empty(n)
    for p in range(n):
        out[p] = abs(gauss(st, f0, std, 1.0))
    return out


@njit(cache=True)
def polar_rotation(F, R, Rinv):
    """R of F = R U (Higham's Newton iteration R <- (R + R^-T)/2, to round-off)."""
    for i in range(3):
        for j in range(3):
            R[i, j] = F[i, j]
    for _ in range(100):
        inv3(R, Rinv)
        change = 0.0
        for i in range(3):
            for j in range(3):
                r = 0.5 * (R[i, j] + Rinv[j, i])
                change = max(change, abs(r - R[i, j]))
                R[i, j] = r
        if change < 1.0e-15:
            break


@njit(cache=True)
def _rotate(R, A, out, forward, B):
    """out = R A R^T (forward) or R^T A R, as two products (B: scratch)."""
    for i in range(3):
        for m in range(3):
            s = 0.0
            for k in range(3):
                s += (R[i, k] if forward else R[k, i]) * A[k, m]
            B[i, m] = s
    for i in range(3):
        for j in range(3):
            s = 0.0
            for m in range(3):
                s += B[i, m] * (R[j, m] if forward else R[m, j])
            out[i, j] = s


@njit(cache=True, error_model="numpy")
def _unstable(check, K, mu, sig, D, sy, dsy_dep):
    """Uintah's stability checks of a plastic particle (stress sig and rate of deformation D in
    the material frame): with the von Mises elastic-plastic tangent C_ep = C_e - (C_e:r)(r:C_e)/
    (r:C_e:r - h dsigma_y/dep), r = 3 dev(sig), h = sig:r/sigma_y (VonMisesYield), Drucker's
    (C_ep:D):D <= 0, or Becker's: the quadratic in x^2 of the principal stresses s1 >= s3 and
    C_ep has two non-negative roots (Becker 2002)."""
    E = 9.0 * K * mu / (3.0 * K + mu)
    nu = E / (2.0 * mu) - 1.0
    fac = E / ((1.0 + nu) * (1.0 - 2.0 * nu))
    c11, c12 = fac * (1.0 - nu), fac * nu
    Ce = np.zeros((3, 3, 3, 3))
    for i in range(3):
        for k in range(3):
            Ce[i, i, k, k] = c11 if i == k else c12
            if i != k:
                Ce[i, k, i, k] = Ce[i, k, k, i] = mu
    tr = (sig[0, 0] + sig[1, 1] + sig[2, 2]) / 3.0
    r = np.empty((3, 3))
    for i in range(3):
        for j in range(3):
            r[i, j] = (sig[i, j] - (tr if i == j else 0.0)) * 3.0
    sr = 0.0
    for i in range(3):
        for j in range(3):
            sr += sig[i, j] * r[i, j]
    fqhq = dsy_dep * (sr / sy)
    Cr, rC = np.zeros((3, 3)), np.zeros((3, 3))
    rCr = 0.0
    for i in range(3):
        for j in range(3):
            for k in range(3):
                for m in range(3):
                    Cr[i, j] += Ce[i, j, k, m] * r[k, m]
                    rC[i, j] += r[k, m] * Ce[k, m, i, j]
            rCr += rC[i, j] * r[i, j]
    M = np.empty((3, 3, 3, 3))
    for i in range(3):
        for j in range(3):
            for k in range(3):
                for m in range(3):
                    M[i, j, k, m] = Ce[i, j, k, m] - Cr[i, j] * rC[k, m] / (-fqhq + rCr)
    if check != BECKER:                         # Drucker: (C_ep:D):D <= 0
        val = 0.0
        for i in range(3):
            for j in range(3):
                rate = 0.0
                for k in range(3):
                    for m in range(3):
                        rate += M[i, j, k, m] * D[k, m]
                val += rate * D[i, j]
        if val <= 0.0:
            return True
        if check == DRUCKER:
            return False
    s0, s2 = damage.extreme_eigenvalues_sym(sig[0, 0], sig[1, 1], sig[2, 2], sig[0, 1], sig[0, 2], sig[1, 2])
    A = M[2, 0, 2, 0] * (-s2 + 2.0 * M[2, 2, 2, 2])
    C = M[2, 0, 2, 0] * (-s0 + 2.0 * M[0, 0, 0, 0])
    B = (M[2, 0, 2, 0] * (s2 - 2.0 * M[0, 0, 2, 2] + s0 - 2.0 * M[2, 2, 0, 0]) + s0 * (M[2, 2, 0, 0] - M[2, 2, 2, 2])
         + s2 * (M[0, 0, 2, 2] - M[0, 0, 0, 0]) + 2.0 * (-M[0, 0, 2, 2] * M[2, 2, 0, 0] + M[0, 0, 0, 0] * M[2, 2, 2, 2]))
    disc = B * B - 4.0 * A * C
    if disc < 0.0:
        return False
    a2 = 2.0 * (A + 1.0e-20) if check == DRUCKER_BECKER else 2.0 * A
    y_plus, y_minus = (-B + math.sqrt(disc)) / a2, (-B - math.sqrt(disc)) / a2
    return not (y_plus < 0.0 or y_minus < 0.0)


_KERNELS = {}


def kernel_for(codes, dev=HYPO_ELASTIC, yield_code=pk.VON_MISES, biswajit=False, erode=False, stability=NO_CHECK,
               tepla=False):
    """The stress kernel of one choice of sub-models (flow, shear, melt, eos, cp), deviatoric
    model `dev`, yield condition and return algorithm: the codes are compile-time constants
    of the closure, so each choice compiles (and caches) its own. mw_mu, mw_inv_tau (mu_j,
    1/tau_j) and sd_old, sd_new (n, elements, 3, 3) are the Maxwell elements' (empty with
    hypoElastic); gp, pp the yield condition's and porosity's parameters, f_old, f_new the
    porosity (empty without gurson or erosion); edot_old the strain rate of the previous step.
    With `erode` (an erosion) a particle localizes (loc_old -> loc_new) when melted, or in a
    plastic step by the TEPLA rule f > f_c (`tepla`, f_c = fc) or the `stability` check."""
    key = (codes, dev, yield_code, biswajit, erode, stability, tepla)
    if key in _KERNELS:
        return _KERNELS[key]
    FLOW_C, SHEAR_C, MELT_C, EOS_C, CP_C = codes
    VISCO = dev == HYPO_VISCO_ELASTIC
    GURSON = yield_code == pk.GURSON
    BISWAJIT = biswajit
    ERODE, STAB, TEPLA = erode, stability, tepla
    POROUS = GURSON or ERODE

    def kernel(G0, K, rho0, Tm0, cp0, chi, L, F_old, F_new, vol, mass, vel, dt, s_old, s_new,
               fp, sp, mp, qp, cpp, T_p, ep_old, epdot_old, e_old, ep_new, epdot_new, e_new, edot_new, dTdt,
               work, mw_mu, mw_inv_tau, sd_old, sd_new, gp, pp, f_old, f_new, edot_old, loc_old, loc_new, fc):
        ws = np.zeros(3)
        R, Rinv = np.empty((3, 3)), np.empty((3, 3))
        D, sig, tmp, B = np.empty((3, 3)), np.empty((3, 3)), np.empty((3, 3)), np.empty((3, 3))
        n_mw = mw_mu.shape[0]
        sdm, eta, rate_j, sdot = np.empty((n_mw, 3, 3)), np.empty((3, 3)), np.empty((3, 3)), np.empty((3, 3))
        s23 = math.sqrt(2.0 / 3.0)
        S_old, eta_b = np.empty((3, 3)), np.empty((3, 3))
        for p in range(L.shape[0]):
            edot_prev = edot_old[p]                         # (edot_old may be edot_new at t = 0)
            J = det3(F_new[p])
            rho = rho0 / J
            for i in range(3):
                for j in range(3):
                    tmp[i, j] = 0.5 * (L[p, i, j] + L[p, j, i])
            polar_rotation(F_old[p], R, Rinv)
            _rotate(R, tmp, D, False, B)                    # D in the material frame
            _rotate(R, s_old[p], sig, False, B)
            trD = D[0, 0] + D[1, 1] + D[2, 2]
            pres = (sig[0, 0] + sig[1, 1] + sig[2, 2]) / 3.0
            DD = 0.0
            for i in range(3):
                for j in range(3):
                    DD += D[i, j] * D[i, j]
            edot = s23 * math.sqrt(DD)
            edot_new[p] = edot
            T = T_p[p]
            cp = pk.specific_heat(CP_C, cpp, cp0, T)
            Tm = pk.melt_temperature(MELT_C, mp, Tm0, pres, rho, rho0)
            mu = pk.shear_modulus(SHEAR_C, sp, G0, T, Tm, pres, rho, rho0)
            c = math.sqrt((K + 4.0 * mu / 3.0) / rho)
            ss = 0.0
            if VISCO:
                # trial s* = s + dt sum_j (2 mu_j eta - s_j/tau_j), the Maxwell elements' rates
                for i in range(3):
                    for j in range(3):
                        eta[i, j] = D[i, j] - (trD / 3.0 if i == j else 0.0)
                        sdot[i, j] = 0.0
                for k in range(n_mw):
                    _rotate(R, sd_old[p, k], sdm[k], False, B)
                    n_el, n_tr = 0.0, 0.0
                    for i in range(3):
                        for j in range(3):
                            el = 2.0 * mw_mu[k] * eta[i, j]
                            rate_j[i, j] = el - sdm[k, i, j] * mw_inv_tau[k]
                            n_el += el * el
                            n_tr += rate_j[i, j] * rate_j[i, j]
                    if math.sqrt(n_tr) > 1.0e-4 * math.sqrt(n_el):
                        for i in range(3):
                            for j in range(3):
                                sdot[i, j] += rate_j[i, j]
                for i in range(3):
                    for j in range(3):
                        tmp[i, j] = sig[i, j] - (pres if i == j else 0.0) + sdot[i, j] * dt
                        ss += tmp[i, j] * tmp[i, j]
            else:
                # trial deviatoric stress s* = s + 2 mu dev(D) dt, q* = sqrt(3/2) |s*|
                for i in range(3):
                    for j in range(3):
                        tmp[i, j] = sig[i, j] - (pres if i == j else 0.0) + 2.0 * mu * dt * (
                            D[i, j] - (trD / 3.0 if i == j else 0.0))
                        ss += tmp[i, j] * tmp[i, j]
            norm_s = math.sqrt(ss)
            ep, epdot = ep_old[p] + epdot_old[p] * dt, epdot_old[p]
            sy = pk.flow_stress(FLOW_C, fp, ep, epdot, edot, T, mu, Tm, rho)[0]
            plastic = newton = False
            fac, dg = 1.0, 0.0
            if GURSON:      # Uintah's trial trace: 3 p + 2 mu tr(D) dt
                phi, sy_eff = pk.gurson_yield(gp, math.sqrt(1.5) * norm_s, sy, 3.0 * pres + trD * (2.0 * mu * dt),
                                              f_old[p])
            else:
                phi, sy_eff = 1.5 * ss - sy * sy, sy
            if T > Tm:                                   # melted: no deviatoric stress
                fac = 0.0
            elif phi >= 0.0:
                plastic = newton = True
            if plastic and BISWAJIT:
                # the rate-based estimate from the stress at the start of the step, then scaled
                # to the flow stress; where it fails, the radial return below
                nS = 0.0
                for i in range(3):
                    for j in range(3):
                        S_old[i, j] = sig[i, j] - (pres if i == j else 0.0)
                        eta_b[i, j] = D[i, j] - (trD / 3.0 if i == j else 0.0)
                        nS += S_old[i, j] * S_old[i, j]
                if nS > 0.0:
                    dgb, epd = pk.biswajit_increment(S_old, eta_b, sy_eff, mu, dt)
                    if dgb > 0.0 and epd <= edot_prev:
                        epdot, ep = epd, ep_old[p] + epd * dt
                        sy = pk.flow_stress(FLOW_C, fp, ep, epdot, edot, T, mu, Tm, rho)[0]
                        denom = 1.0 + (3.0 * math.sqrt(2.0) * mu * dgb) / sy
                        st = 0.0
                        for i in range(3):
                            for j in range(3):
                                tmp[i, j] = tmp[i, j] / denom
                                st += tmp[i, j] * tmp[i, j]
                        fac = sy / (math.sqrt(1.5) * math.sqrt(st))
                        newton = False
            if newton:                                   # radial return (Newton on dgamma)
                tol = min(dt, 1.0e-6)
                epdot, ep = edot, ep_old[p]
                dg = epdot * dt / s23
                count = 0
                while True:
                    count += 1
                    sy, dsy_dep, dsy_depdot = pk.flow_stress(FLOW_C, fp, ep, epdot, edot, T, mu, Tm, rho)
                    g = norm_s - s23 * sy - 2.0 * mu * dg
                    Dg = -2.0 / 3.0 * (dsy_depdot / dt + dsy_dep) - 2.0 * mu
                    dg_old = dg
                    dg -= g / Dg
                    inc = max(s23 * dg, 0.0)
                    epdot = inc / dt
                    ep = ep_old[p] + inc
                    if abs(dg - dg_old) < tol or count > 100 or not abs(g) > sy / 1000.0:
                        break
                sy = pk.flow_stress(FLOW_C, fp, ep, epdot, edot, T, mu, Tm, rho)[0]
                fac = 1.0 - 2.0 * mu * dg / norm_s
            p_new = pk.eos_pressure(EOS_C, qp, K, pres, trD, dt, rho, rho0, e_old[p])
            rate = pk.isentropic_dTdt(EOS_C, qp, T, rho0, rho, trD)
            if VISCO:
                # s_j += dt (2 mu_j (eta - d_p) - s_j/tau_j), d_p = dgamma n/dt; the dissipation heats
                power = 0.0
                for k in range(n_mw):
                    ns = 0.0
                    for i in range(3):
                        for j in range(3):
                            if T > Tm:
                                v = 0.0
                            else:
                                dp = (tmp[i, j] / norm_s * dg) / dt if newton else 0.0
                                v = sdm[k, i, j] + (2.0 * mw_mu[k] * (eta[i, j] - dp)
                                                    - sdm[k, i, j] * mw_inv_tau[k]) * dt
                            rate_j[i, j] = v
                            ns += v * v
                    sdm[k] = rate_j
                    power += ns * mw_inv_tau[k] / (2.0 * mw_mu[k])
                rate += power * (chi / (rho * cp))
            if plastic:
                ep_new[p], epdot_new[p] = ep, epdot
                rate += sy * epdot * chi / (rho * cp)        # plastic work to heat
                if POROUS:
                    f_new[p] = pk.porosity_update(pp, f_old[p], D, dt, ep) if pp[3] != 0.0 else f_old[p]
            else:
                ep_new[p], epdot_new[p] = ep_old[p], 0.0
                if POROUS:
                    f_new[p] = f_old[p]
            dTdt[p] = rate
            for i in range(3):
                for j in range(3):
                    sig[i, j] = fac * tmp[i, j] + (p_new if i == j else 0.0)
            localized = False
            if ERODE:       # Uintah's checks: melted; in a plastic step TEPLA, then the stability check
                localized = loc_old[p] != 0.0
                if T > Tm:
                    localized = True
                elif plastic:
                    if TEPLA and f_new[p] * f_new[p] / (fc * fc) > 1.0:
                        localized = True
                    if STAB != NO_CHECK and not localized:
                        sy, dsy_dep, _ = pk.flow_stress(FLOW_C, fp, ep, epdot, edot, T, mu, Tm, rho)
                        localized = not sy > 0.0 or _unstable(STAB, K, mu, sig, D, sy, dsy_dep)
                if localized:
                    f_new[p] = 0.0
                loc_new[p] = 1.0 if localized else 0.0
            polar_rotation(F_new[p], R, Rinv)
            _rotate(R, sig, s_new[p], True, B)
            for k in range(n_mw):
                _rotate(R, sdm[k], sd_new[p, k], True, B)
            _rotate(R, D, tmp, True, B)
            vol_old = mass[p] / rho0 * det3(F_old[p])
            w = 0.0
            for i in range(3):
                for j in range(3):
                    w += tmp[i, j] * 0.5 * (s_new[p, i, j] + s_old[p, i, j])
            w *= 0.5 * (vol[p] + vol_old) * dt              # stress work of the step
            if localized:                                   # none for a localized particle
                w = 0.0
            work[p] = w
            e_new[p] = e_old[p] + w / mass[p]
            max_wavespeed(ws, c, vel, p)
        return ws

    # its own name per choice: numba's cache keeps one file and one environment per name (two
    # cached closures of one name clash when both are loaded in a process)
    kernel.__name__ = kernel.__qualname__ = ("elastic_plastic_kernel_" + "_".join(map(str, codes))
                                             + ("_visco" if VISCO else "") + ("_gurson" if GURSON else "")
                                             + ("_biswajit" if BISWAJIT else "")
                                             + (f"_erode{STAB}{int(TEPLA)}" if ERODE else ""))
    _KERNELS[key] = njit(cache=True)(kernel)
    return _KERNELS[key]


_NO_MAXWELL = np.zeros(0)
_NO_POROSITY = np.array([0.1, 0.3, 0.1, 0.0, 0.002, 0.002])     # Uintah's defaults, not evolved


def update(params, L, F_old, F_new, vol, mass, vel, dt, stress_old, stress_new, energy, old, new, time=0.0):
    """Stress, state and temperature rate of one material's particles; returns the wave speed.
    old = (the state of state_of(params) ..., p.temperature); new = the same updated, with p.dTdt
    last; `energy` receives the stress-work increment; `time`: the step's start (an erosion's
    time of localization). With an erosion, the particles localized at the step's start have
    their F and L eroded first (F_new in place) and the localized their stress after; with a
    johnson_cook damage model p.damage follows from the new stress."""
    at = {name: k for k, name in enumerate(state_of(params))}
    ep, epdot, e, edot_o = old[:4]
    ep_n, epdot_n, e_n, edot_n = new[:4]
    T, dTdt = old[-1], new[-1]
    f_o = f_n = loc_o = loc_n = _NO_MAXWELL
    if params.has_porosity:
        f_o, f_n = old[at["p.porosity"]], new[at["p.porosity"]]
        loc_o, loc_n = old[at["p.localizedMPM"]], new[at["p.localizedMPM"]]
        if not params.erosion:
            loc_n[:] = loc_o              # gurson without an erosion: never set
    if params.erosion:
        L = damage.erode_kinematics(params.erosion, loc_o, F_old, F_new, L)
    k0 = len(at) - (len(params.maxwell_mu) if params.dev == HYPO_VISCO_ELASTIC else 0)    # first Maxwell stress
    kern = kernel_for(params.codes, params.dev, params.yield_code, params.biswajit, params.erosion != 0,
                      params.stability, params.tepla)
    n = len(L)
    if params.dev == HYPO_VISCO_ELASTIC:
        if dt > params.maxwell_tau.min():
            raise RunStopped(f"elastic_plastic hypoViscoElastic: the time step {dt:g} is longer than the Maxwell "
                             f"element's tau {params.maxwell_tau.min():g} (Uintah stops there too); a smaller "
                             "<delt_max> or <timestep_multiplier> avoids it")
        mw_mu, mw_inv_tau = params.maxwell_mu, 1.0 / params.maxwell_tau
        sd_old = np.stack(old[k0:-1], axis=1) if n else np.zeros((0, len(mw_mu), 3, 3))
        sd_new = np.empty_like(sd_old)
    else:
        mw_mu = mw_inv_tau = _NO_MAXWELL
        sd_old = sd_new = np.zeros((0, 0, 3, 3))
    ws = kern(params.shear_modulus, params.bulk_modulus, params.density, params.melt_temp, params.specific_heat,
              params.taylor_quinney, L, F_old, F_new, vol, mass, vel, dt, stress_old, stress_new,
              params.flow, params.shear, params.melt, params.eos, params.cp, T, ep, epdot, e,
              ep_n, epdot_n, e_n, edot_n, dTdt, energy, mw_mu, mw_inv_tau, sd_old, sd_new,
              _NO_MAXWELL if params.yield_params is None else params.yield_params,
              _NO_POROSITY if params.porosity is None else params.porosity, f_o, f_n, edot_o, loc_o, loc_n,
              params.critical_porosity)
    for k, out in enumerate(new[k0:-1]):
        out[:] = sd_new[:, k]
    if params.damage_kind == "johnson_cook":     # Uintah's damage models, then its erosion
        i = at["p.damage"]                        # (updateStress_DamageErosionModels)
        damage.johnson_cook_damage(params.jc_damage, params.damage_temps[0], params.damage_temps[1], dt,
                                   stress_new, epdot_n, T, old[i], new[i])
    elif params.damage_kind == "hancock_mackenzie":
        i = at["p.damage"]
        damage.hancock_mackenzie_damage(dt, stress_new, epdot_n, old[i], new[i])
    if params.erosion:
        i = at["p.timeofloc"]
        damage.erode_stress(params.erosion, params.char_time, time, stress_new, loc_o, loc_n, old[i], new[i])
    if dt == 0.0 and len(vel):      # the first step's: with <shear_modulus>, not the shear model's mu
        c = math.sqrt((params.bulk_modulus + 4.0 * params.shear_modulus / 3.0) / params.density)
        ws = np.max(c + np.abs(vel), axis=0)
    return ws
