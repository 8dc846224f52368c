"""Uintah's damage and erosion models of an MPM material: ``<damage_model type="Brittle">`` and
``type="ThresholdVar"`` with ``<erosion algorithm="...">``.

The damage model is a sibling of ``<constitutive_model>`` in the material (Uintah's
DamageModelFactory); after the constitutive model has computed p.stress+, it changes it.
Uintah asks for an ``<erosion algorithm="...">`` beside either model and refuses the deck
without one.

Brittle (Uintah's BrittleDamage; Oliver et al.'s isotropic softening): tags
``brittle_damage_initial_threshold`` (r0, Pa^1/2), ``brittle_damage_fracture_energy``
(G_f), ``brittle_damage_constant_D`` (D), ``brittle_damage_max_damage_increment`` (the most
damage may grow in a step), ``brittle_damage_allowRecovery``,
``brittle_damage_recoveryCoeff``, ``brittle_damage_printDamage``; E from the constitutive
model's bulk and shear moduli, E = 9 K G / (3 K + G).  State: p.epsf (the energy threshold
r, r0 at the start) and p.damage (d, 0).  Each step, with the new F, V and stress:

    in tension (tr sigma > 0): e = (I - (F F^T)^-1)/2, tau = sqrt(E) max eig(e)
        tau > r:  C = r0 V^(1/3) (1 + D) ln(1 + D) / (G_f D),
                  d = 0.999/D ((1 + D)/(1 + D exp(-C (tau - r0))) - 1)  (at most d_old + the
                  increment), r = tau, sigma *= 1 - d
        else, once damaged: sigma *= 1 - d_old
    in compression, once damaged: sigma *= 1 - d_old

(with recovery a damaged particle's stress is also scaled by the recovery coefficient and
its damage flagged negative, as Uintah's; Uintah skips the factor 1 - d of compression when
printing).  Uintah leaves its particle loop at the first undamaged particle in compression
(a ``return``); each particle is updated here, which is the same for a lone damaged particle.
Brittle damage never localizes a particle, so its erosion algorithm changes nothing.

ThresholdVar (Uintah's ThresholdDamageVar): ``<variable_properties>`` with ``<entry>``s of
``color``, ``mean`` and ``std``: a particle's failure threshold p.epsf is the mean at its
p.color (interpolated as UCNHVar's moduli); Threshold (ThresholdDamage): the one
``failure_mean`` (and ``failure_std``) for every particle; ``failure_distrib`` "constant"
(p.epsf = the mean) or one of Uintah's random draws, made as Uintah makes them
(uintah_random.py: its MusilRNG, seeded per patch from ``failure_seed``, 0, and the patch's
Uintah ID; the particles drawn for in the order Uintah creates them on the patch,
materials.uintah_creation_order), so that p.epsf is sus's on the same patch layout:

    gauss    |mean + std sqrt(-2 ln x) cos(2 pi y)|, two values x, y; ThresholdVar: a new
             generator for each particle, seeded with the patch's seed + the particle's number
             on the patch; Threshold: one generator per patch
    weibull  eta (-ln y)^(1/std), eta = mean / Gamma(1 + 1/std) (std is the Weibull modulus);
             ThresholdVar: a new generator with the patch's seed for each particle (so the
             same y for all of a patch's particles, as Uintah's); Threshold: one per patch

(Uintah's models also have a "uniform" draw and a volume ``<scaling>``, which its input
specification refuses, and so does pysus).  ``failure_criteria`` MaximumPrincipalStress (the largest eigenvalue of p.stress+ above
p.epsf) or MaximumPrincipalStrain (of the Almansi strain (I - (F F^T)^-1)/2) or MohrCoulomb
(p.epsf is the cohesion c, with ``friction_angle`` phi (degrees) and
``tensile_cutoff_fraction_of_cohesion`` f: in tension when sigma_1 > f c, p.localizedMPM = 1; in
shear when (sigma_1 - sigma_3)/2 > c cos phi - (sigma_1 + sigma_3) sin phi / 2, p.localizedMPM = 2,
sigma_1 and sigma_3 the largest and smallest principal stresses),
``LocalizeParticles`` (true).  A particle that meets it is localized (p.localizedMPM = 1, for good).  The erosion
then acts on the localized particles (Uintah's ErosionModel), with p.timeofloc the step-start
time at which it localized and D = exp(-(t - p.timeofloc)/char_time) (<char_time>, 1e-99: 1
in the step of localization, 0 after):

    ZeroStress      F^{n+1} = F^n (before the stress; V is not changed), L = 0, sigma *= D
    AllowNoTension  F^{n+1} = J^(1/3) I, L = tr(L)/3 I; sigma *= D if tr sigma > 0, else p I
    AllowNoShear    F^{n+1} = J^(1/3) I, L = tr(L)/3 I; sigma = p I
    PreserveStress, none: nothing.

The UCNH family (comp_neo_hook, UCNH, UCNHVar) leaves a particle localized at the step's
start out of the strain energy, as Uintah's.  An ``<erosion>`` without a damage model is
read and does nothing (in Uintah no particle localizes then), whatever the constitutive model
(but elastic_plastic's own failure, elastic_plastic.py, and elastic_plastic_hp's own
localization, elastic_plastic_hp.py, which use the erosion here). elastic_plastic_hp's
``<damage_model type="johnson_cook">`` is johnson_cook_damage below.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numba import njit

from .uintah_random import STATE_SIZE, gauss, musil_start, patch_seed, weibull

TYPES = ("Brittle", "Threshold", "ThresholdVar")
EROSION = {"none": 0, "AllowNoTension": 1, "ZeroStress": 2, "AllowNoShear": 3, "PreserveStress": 4}
CRITERIA = {"MaximumPrincipalStress": 0, "MaximumPrincipalStrain": 1, "MohrCoulomb": 2}
DISTRIBUTIONS = {"constant": 0, "gauss": 1, "weibull": 2}


@dataclass(frozen=True)
class Brittle:
    r0: float                      # brittle_damage_initial_threshold
    Gf: float                      # brittle_damage_fracture_energy
    D: float                       # brittle_damage_constant_D
    max_increment: float           # brittle_damage_max_damage_increment
    allow_recovery: bool
    recovery_coeff: float
    print_damage: bool
    youngs: float                  # E = 9 K G / (3 K + G) of the constitutive model

    STATE = ("p.epsf", "p.damage")

    def initial_state(self, n, color):
        """p.epsf = r0, p.damage = 0 (Uintah's initializeLabels)."""
        return np.full(n, self.r0), np.zeros(n)

    def apply(self, F_new, vol_new, stress_new, old, new, color=None, time=0.0):
        """Scale p.stress+ by the damage; (p.epsf, p.damage) old -> new."""
        (r_old, d_old), (r_new, d_new) = old, new
        brittle_kernel(self.r0, self.Gf, self.D, self.max_increment, self.allow_recovery, self.recovery_coeff,
                       self.print_damage, self.youngs, F_new, vol_new, stress_new, r_old, d_old, r_new, d_new)


@dataclass(frozen=True)
class ThresholdVar:
    colors: tuple
    means: tuple
    criterion: int                 # CRITERIA
    localize: bool                 # <LocalizeParticles>
    erosion: int                   # EROSION code
    char_time: float
    stds: tuple = (0.0,)           # the std (gauss) or Weibull modulus at each color
    distribution: int = 0          # DISTRIBUTIONS code
    seed: int = 0                  # <failure_seed>
    by_color: bool = True          # ThresholdVar (draws per particle), else Threshold (per patch)
    friction_angle: float = 0.0    # MohrCoulomb: phi (degrees)
    tensile_cutoff: float = 0.0    # MohrCoulomb: the tensile strength over the cohesion

    STATE = ("p.epsf", "p.localizedMPM", "p.timeofloc")

    @property
    def random(self):
        """The thresholds are drawn (they need the patch and Uintah's particle order)."""
        return self.distribution != 0

    @property
    def erodes_F(self):
        """The erosion changes F^{n+1} of localized particles (ZeroStress, AllowNo...)."""
        return self.erosion in (1, 2, 3)

    def initial_state(self, n, color, draw=None):
        """p.epsf = the mean at the particle's color, or drawn (draw = (the particles' order of
        creation in Uintah, the patch's Uintah ID)); not localized, p.timeofloc = -1e99."""
        eps = np.empty(n)
        C, M = np.array(self.colors, float), np.array(self.means, float)
        if self.random:
            order, patch_id = draw
            draw_thresholds(self.distribution, self.by_color, patch_seed(self.seed, patch_id), C, M,
                            np.array(self.stds, float), order, color, eps)
        else:
            threshold_at(C, M, color, eps)
        return eps, np.zeros(n), np.full(n, -1.0e99)

    def erode_kinematics(self, loc_old, F_old, F_new, L):
        """Uintah's updateVariables_Erosion on the particles localized at the step's start (F in
        place); returns the L the model then reads (a changed copy when one is eroded)."""
        return erode_kinematics(self.erosion, loc_old, F_old, F_new, L)

    def apply(self, F_new, vol_new, stress_new, old, new, color=None, time=0.0):
        """Localize by the criterion, then erode the stress; (p.epsf, p.localizedMPM,
        p.timeofloc) old -> new."""
        (eps_old, loc_old, tl_old), (eps_new, loc_new, tl_new) = old, new
        threshold_kernel(self.criterion, self.localize, self.erosion, self.char_time, time, F_new, stress_new,
                         eps_old, loc_old, tl_old, eps_new, loc_new, tl_new, self.friction_angle,
                         self.tensile_cutoff)


@njit(cache=True)
def threshold_at(C, M, color, out):
    """The mean failure threshold at each particle's color (UCNHVar's interpolation)."""
    n = C.shape[0]
    for p in range(color.shape[0]):
        c = color[p]
        out[p] = M[0]
        if c >= C[n - 1]:
            out[p] = M[n - 1]
            continue
        for i in range(1, n):
            if c <= C[i]:
                s = (C[i] - c) / (C[i] - C[i - 1])
                out[p] = M[i - 1] * s + M[i] * (1.0 - s)
                break


@njit(cache=True, inline="always")
def mean_std_at(C, M, S, c):
    """(mean, std) at color c: ThresholdDamageVar's findPropertiesFromColor."""
    n = C.shape[0]
    if c >= C[n - 1]:
        return M[n - 1], S[n - 1]
    for i in range(1, n):
        if c <= C[i]:
            s = (C[i] - c) / (C[i] - C[i - 1])
            return M[i - 1] * s + M[i] * (1.0 - s), S[i - 1] * s + S[i] * (1.0 - s)
    return M[0], S[0]


@njit(cache=True)
def draw_thresholds(dist, by_color, seed, C, M, S, order, color, out):
    """p.epsf of a patch's particles drawn as Uintah's initializeLabels (module docstring), in
    Uintah's order of creation `order`; `seed` is the patch's."""
    st = np.zeros(STATE_SIZE, np.int64)
    if not by_color:                            # one generator for the patch
        musil_start(seed, st)
    for num in range(order.shape[0]):
        p = order[num]
        mean, std = mean_std_at(C, M, S, color[p])
        if dist == 1:
            if by_color:
                musil_start(seed + num, st)
            out[p] = abs(gauss(st, mean, std, 1.0))
        else:
            if by_color:
                musil_start(seed, st)
            out[p] = weibull(st, mean, std, 1.0)


@njit(cache=True)
def erosion_kinematics(code, loc, F_old, F_new, L, has_L):
    """ZeroStress: F^{n+1} = F^n, L = 0; AllowNoTension, AllowNoShear: F^{n+1} = J^(1/3) I,
    L = tr(L)/3 I; on the localized particles."""
    for p in range(F_new.shape[0]):
        if loc[p] == 0.0:
            continue
        if code == 2:
            F_new[p] = F_old[p]
            if has_L:
                L[p] = 0.0
        else:
            c = np.cbrt(_det33(F_new[p]))
            F_new[p] = 0.0
            F_new[p, 0, 0] = F_new[p, 1, 1] = F_new[p, 2, 2] = c
            if has_L:
                tr = (L[p, 0, 0] + L[p, 1, 1] + L[p, 2, 2]) / 3.0
                L[p] = 0.0
                L[p, 0, 0] = L[p, 1, 1] = L[p, 2, 2] = tr


@njit(cache=True, inline="always")
def _det33(A):
    return (A[0, 0] * (A[1, 1] * A[2, 2] - A[1, 2] * A[2, 1]) - A[0, 1] * (A[1, 0] * A[2, 2] - A[1, 2] * A[2, 0])
            + A[0, 2] * (A[1, 0] * A[2, 1] - A[1, 1] * A[2, 0]))


@njit(cache=True, inline="always")
def almansi_max(F, p):
    """The largest eigenvalue of the Almansi strain (I - (F F^T)^-1)/2 of particle p."""
    b00 = F[p, 0, 0] ** 2 + F[p, 0, 1] ** 2 + F[p, 0, 2] ** 2
    b11 = F[p, 1, 0] ** 2 + F[p, 1, 1] ** 2 + F[p, 1, 2] ** 2
    b22 = F[p, 2, 0] ** 2 + F[p, 2, 1] ** 2 + F[p, 2, 2] ** 2
    b01 = F[p, 0, 0] * F[p, 1, 0] + F[p, 0, 1] * F[p, 1, 1] + F[p, 0, 2] * F[p, 1, 2]
    b02 = F[p, 0, 0] * F[p, 2, 0] + F[p, 0, 1] * F[p, 2, 1] + F[p, 0, 2] * F[p, 2, 2]
    b12 = F[p, 1, 0] * F[p, 2, 0] + F[p, 1, 1] * F[p, 2, 1] + F[p, 1, 2] * F[p, 2, 2]
    det = b00 * (b11 * b22 - b12 * b12) - b01 * (b01 * b22 - b12 * b02) + b02 * (b01 * b12 - b11 * b02)
    i00, i11, i22 = (b11 * b22 - b12 * b12) / det, (b00 * b22 - b02 * b02) / det, (b00 * b11 - b01 * b01) / det
    i01, i02, i12 = (b02 * b12 - b01 * b22) / det, (b01 * b12 - b02 * b11) / det, (b01 * b02 - b00 * b12) / det
    return max_eigenvalue_sym(0.5 * (1.0 - i00), 0.5 * (1.0 - i11), 0.5 * (1.0 - i22), -0.5 * i01, -0.5 * i02,
                              -0.5 * i12)


@njit(cache=True)
def threshold_kernel(criterion, localize, erosion, char_time, time, F, stress, eps_old, loc_old, tl_old, eps_new,
                     loc_new, tl_new, friction_angle=0.0, tensile_cutoff=0.0):
    """ThresholdVar's localization, then the erosion of the stress (module docstring)."""
    phi = friction_angle * (np.pi / 180.0)
    for p in range(F.shape[0]):
        eps_new[p] = eps_old[p]
        loc_new[p] = loc_old[p]
        tl_new[p] = tl_old[p]
        if localize and loc_old[p] == 0.0 and criterion == 2:      # Mohr-Coulomb: tension, then shear
            s1, s3 = extreme_eigenvalues_sym(stress[p, 0, 0], stress[p, 1, 1], stress[p, 2, 2],
                                             0.5 * (stress[p, 0, 1] + stress[p, 1, 0]),
                                             0.5 * (stress[p, 0, 2] + stress[p, 2, 0]),
                                             0.5 * (stress[p, 1, 2] + stress[p, 2, 1]))
            c = eps_old[p]
            if s1 > tensile_cutoff * c:
                loc_new[p] = 1.0
            if (s1 - s3) / 2.0 > c * np.cos(phi) - (s1 + s3) * np.sin(phi) / 2.0:
                loc_new[p] = 2.0
        elif localize and loc_old[p] == 0.0:
            if criterion == 0:
                m = max_eigenvalue_sym(stress[p, 0, 0], stress[p, 1, 1], stress[p, 2, 2],
                                       0.5 * (stress[p, 0, 1] + stress[p, 1, 0]),
                                       0.5 * (stress[p, 0, 2] + stress[p, 2, 0]),
                                       0.5 * (stress[p, 1, 2] + stress[p, 2, 1]))
            else:
                m = almansi_max(F, p)
            if m > eps_old[p]:
                loc_new[p] = 1.0
        if erosion != 0:
            erode_stress_of(p, erosion, char_time, time, stress, loc_old, loc_new, tl_new)


@njit(cache=True, inline="always")
def erode_stress_of(p, erosion, char_time, time, stress, loc_old, loc_new, tl_new):
    """Uintah's updateStress_Erosion for particle p: the time of localization, then the stress
    of a localized particle scaled by D = exp(-(t - p.timeofloc)/char_time) (ZeroStress; and
    AllowNoTension in tension) or made its pressure (AllowNoShear; AllowNoTension in
    compression)."""
    if loc_old[p] != loc_new[p]:
        tl_new[p] = time
    if loc_new[p] == 0.0 or erosion == 4:     # PreserveStress keeps the stress
        return
    pr = (stress[p, 0, 0] + stress[p, 1, 1] + stress[p, 2, 2]) / 3.0
    D = np.exp(-(time - tl_new[p]) / char_time)
    if erosion == 2 or (erosion == 1 and pr > 0.0):
        stress[p] *= D
    else:
        stress[p] = 0.0
        stress[p, 0, 0] = stress[p, 1, 1] = stress[p, 2, 2] = pr


@njit(cache=True)
def erode_stress(erosion, char_time, time, stress, loc_old, loc_new, tl_old, tl_new):
    """The erosion of the stress of every particle (erode_stress_of), for a constitutive model
    that localizes its particles itself (elastic_plastic_hp)."""
    for p in range(stress.shape[0]):
        tl_new[p] = tl_old[p]
        erode_stress_of(p, erosion, char_time, time, stress, loc_old, loc_new, tl_new)


def erode_kinematics(code, loc_old, F_old, F_new, L):
    """Uintah's updateVariables_Erosion on the particles localized at the step's start (F in
    place); returns the L the model then reads (a changed copy when one is eroded)."""
    if code not in (1, 2, 3) or not loc_old.any():
        return L
    has_L = L is not None and len(L) == len(F_new)
    if has_L:
        L = L.copy()
    erosion_kinematics(code, loc_old, F_old, F_new, L if has_L else F_new, has_L)   # F_new: no L
    return L


@njit(cache=True, inline="always")
def _mean_and_von_mises(stress, p):
    """Particle p's mean stress and von Mises stress sqrt(3/2 s:s), s the deviator."""
    mean = (stress[p, 0, 0] + stress[p, 1, 1] + stress[p, 2, 2]) / 3.0
    ss = 0.0
    for i in range(3):
        for j in range(3):
            s = stress[p, i, j] - (mean if i == j else 0.0)
            ss += s * s
    return mean, np.sqrt(ss * 1.5)


@njit(cache=True, error_model="numpy")
def johnson_cook_damage(jc, Tr, Tm, dt, stress, epdot, T, d_old, d_new):
    """Uintah's JohnsonCookDamage (Johnson and Cook 1985), a diagnostic p.damage that leaves the
    stress alone: D += epdot dt / eps_f, eps_f = (D1 + D2 exp(D3 sigma*)) (1 + D4 ln epdot)
    (or (1 + epdot)^D4 below 1) (1 + D5 T*), sigma* = p/sigma_eq within [-1.5, 1.5],
    T* = (T - T_room)/(T_melt - T_room); a damage under the critical <critical_scalar_damage>
    is set to 0. jc = D1, D2, D3, D4, D5, the critical damage."""
    for p in range(stress.shape[0]):
        mean, eq = _mean_and_von_mises(stress, p)
        star = mean / eq if eq != 0.0 else 0.0
        star = min(1.5, max(-1.5, star))
        rate = (1.0 + epdot[p]) ** jc[3] if epdot[p] < 1.0 else 1.0 + jc[3] * np.log(epdot[p])
        eps_f = (jc[0] + jc[1] * np.exp(jc[2] * star)) * rate * (1.0 + jc[4] * ((T[p] - Tr) / (Tm - Tr)))
        d = d_old[p] + epdot[p] * dt / eps_f
        d_new[p] = 0.0 if d < jc[5] else d


@njit(cache=True, error_model="numpy")
def hancock_mackenzie_damage(dt, stress, epdot, d_old, d_new):
    """Uintah's HancockMacKenzieDamage (Hancock and MacKenzie 1976), a diagnostic p.damage that
    leaves the stress alone: D += epdot dt exp(1.5 p / sigma_eq) / 1.65, p the mean stress,
    sigma_eq the von Mises stress where p > 0 and 1 (Pa) otherwise, as Uintah's."""
    for p in range(stress.shape[0]):
        mean, eq = _mean_and_von_mises(stress, p)
        if mean <= 0.0:
            eq = 1.0
        d_new[p] = d_old[p] + epdot[p] * dt * np.exp(1.5 * mean / eq) / 1.65


BRITTLE_TAGS = {"brittle_damage_initial_threshold": 57.0, "brittle_damage_fracture_energy": 11.2,
                "brittle_damage_constant_D": 0.1, "brittle_damage_max_damage_increment": 0.1,
                "brittle_damage_recoveryCoeff": 1.0}


def read(material, cm):
    """The material's damage model (None without a <damage_model>) and its erosion, Uintah's
    defaults."""
    dm = material.child("damage_model")
    if dm is None:
        return None
    kind = dm.attr("type", choices=TYPES)
    er = material.child("erosion")
    if er is None:
        raise dm.error(f'a <damage_model type="{kind}"> needs an <erosion algorithm="..."> in its material '
                       "(Uintah: an erosion model must be specified when a damage model is used)")
    erosion, char_time = read_erosion(er)
    if kind in ("Threshold", "ThresholdVar"):
        return read_threshold_var(dm, erosion, char_time, kind == "ThresholdVar")
    v = {t: dm.get(t, "float", d) for t, d in BRITTLE_TAGS.items()}
    for t in ("brittle_damage_fracture_energy", "brittle_damage_constant_D"):
        if v[t] <= 0.0:
            raise dm.child(t).error(f"<{t}> must be positive")
    if not 0.0 <= v["brittle_damage_recoveryCoeff"] <= 1.0:
        raise dm.child("brittle_damage_recoveryCoeff").error("<brittle_damage_recoveryCoeff> must lie in [0, 1]")
    if not cm.has("bulk_modulus") or not cm.has("shear_modulus"):
        raise dm.error("Brittle damage reads the constitutive model's <bulk_modulus> and <shear_modulus>, "
                       "which this one does not have")
    K, G = cm.get("bulk_modulus", above=0.0), cm.get("shear_modulus", at_least=0.0)
    return Brittle(v["brittle_damage_initial_threshold"], v["brittle_damage_fracture_energy"],
                   v["brittle_damage_constant_D"], v["brittle_damage_max_damage_increment"],
                   dm.get("brittle_damage_allowRecovery", "bool", False), v["brittle_damage_recoveryCoeff"],
                   dm.get("brittle_damage_printDamage", "bool", False), 9.0 * K * G / (3.0 * K + G))


def read_erosion(er):
    """<erosion algorithm="..."> and its <char_time>: (EROSION code, char_time)."""
    return (EROSION[er.attr("algorithm", default="none", choices=tuple(EROSION))],
            er.get("char_time", default=1.0e-99, above=0.0))


def read_threshold_var(dm, erosion, char_time, by_color):
    """<damage_model type="ThresholdVar"> (the entries) or "Threshold" (one <failure_mean>): the
    criterion and the distribution of the thresholds."""
    crit = dm.get("failure_criteria", "str", choices=tuple(CRITERIA))
    mohr = (dm.get("friction_angle", "float"), dm.get("tensile_cutoff_fraction_of_cohesion", "float")) \
        if crit == "MohrCoulomb" else (0.0, 0.0)
    dist = dm.get("failure_distrib", "str", "constant", choices=tuple(DISTRIBUTIONS) + ("uniform",))
    for tag, what in (("failure_distrib", "uniform"), ("scaling", None), ("reference_volume", None),
                      ("exponent", None)):
        c = dm.child(tag)
        if c is not None and (what is None or c.text().strip() == what):
            raise c.error(f"<{tag}>{c.text().strip()} is refused by Uintah's input specification (sus does not run "
                          "it); accepted: <failure_distrib> constant, gauss, weibull, without volume scaling")
    seed = dm.get("failure_seed", "int", 0)
    if by_color:
        vp = dm.child("variable_properties", required=True)
        rows = [(e.get("color"), e.get("mean"), e.get("std", at_least=0.0)) for e in vp.children("entry")]
        if not rows:
            raise vp.error("<variable_properties> needs at least one <entry> (<color>, <mean>, <std>)")
        if any(b[0] <= a[0] for a, b in zip(rows, rows[1:])):
            raise vp.error("the <entry>s' <color>s must increase")
    else:
        rows = [(0.0, dm.get("failure_mean"),
                 dm.get("failure_std", at_least=0.0) if dist != "constant" else dm.get("failure_std", "float", 0.0))]
    if dist == "weibull" and min(r[2] for r in rows) <= 0.0:
        raise (dm.child("variable_properties") or dm.child("failure_std") or dm).error(
            "a weibull draw needs a positive Weibull modulus (<std>, <failure_std>)")
    return ThresholdVar(tuple(r[0] for r in rows), tuple(r[1] for r in rows), CRITERIA[crit],
                        dm.get("LocalizeParticles", "bool", True), erosion, char_time, tuple(r[2] for r in rows),
                        DISTRIBUTIONS[dist], seed, by_color, *mohr)


@njit(cache=True, inline="always")
def extreme_eigenvalues_sym(a00, a11, a22, a01, a02, a12):
    """The largest and the smallest eigenvalue of a symmetric 3x3 matrix (the trigonometric solution of its
    cubic)."""
    q = (a00 + a11 + a22) / 3.0
    p1 = a01 * a01 + a02 * a02 + a12 * a12
    b00, b11, b22 = a00 - q, a11 - q, a22 - q
    p2 = b00 * b00 + b11 * b11 + b22 * b22 + 2.0 * p1
    if p2 <= 1e-300:
        return q, q
    p = np.sqrt(p2 / 6.0)
    ip = 1.0 / p
    c00, c11, c22, c01, c02, c12 = b00 * ip, b11 * ip, b22 * ip, a01 * ip, a02 * ip, a12 * ip
    r = 0.5 * (c00 * (c11 * c22 - c12 * c12) - c01 * (c01 * c22 - c12 * c02) + c02 * (c01 * c12 - c11 * c02))
    r = min(1.0, max(-1.0, r))
    a = np.arccos(r) / 3.0
    return q + 2.0 * p * np.cos(a), q + 2.0 * p * np.cos(a + 2.0 * np.pi / 3.0)


@njit(cache=True, inline="always")
def max_eigenvalue_sym(a00, a11, a22, a01, a02, a12):
    """The largest eigenvalue of a symmetric 3x3 matrix."""
    return extreme_eigenvalues_sym(a00, a11, a22, a01, a02, a12)[0]


@njit(cache=True)
def brittle_kernel(r0, Gf, D, max_inc, recovery, rc, printing, E, F, vol, stress, r_old, d_old, r_new, d_new):
    """Brittle damage of every particle (module docstring); scales stress in place."""
    for p in range(F.shape[0]):
        r_new[p] = r_old[p]
        d = d_old[p]
        d_new[p] = d
        if stress[p, 0, 0] + stress[p, 1, 1] + stress[p, 2, 2] < 0.0:      # compression
            if d <= 0.0:
                continue
            if recovery:
                stress[p] *= rc
                d_new[p] = -d
            if not printing:
                stress[p] *= 1.0 - d
            continue
        eps = almansi_max(F, p)                   # the largest Almansi strain
        tau = np.sqrt(E * eps * eps)
        if tau > r_old[p]:
            C = r0 * np.cbrt(vol[p]) * (1.0 + D) / (Gf * D) * np.log(1.0 + D)
            dn = 0.999 / D * ((1.0 + D) / (1.0 + D * np.exp(-C * (tau - r0))) - 1.0)
            if dn - d > max_inc:
                dn = d + max_inc
            r_new[p] = tau
            d_new[p] = dn
            stress[p] *= 1.0 - dn
        elif d != 0.0:
            if recovery:
                stress[p] *= rc
                d_new[p] = -d
            else:
                stress[p] *= 1.0 - d


# the constitutive models a damage model may follow: their stress needs no temperature, and
# their state (if any) is what their own update takes
MODELS = ("comp_neo_hook", "comp_mooney_rivlin", "hypo_elastic", "comp_neo_hook_plastic", "UCNH", "UCNHVar")
# those that leave a particle localized at the step's start out of the strain energy (Uintah's UCNH)
NO_ENERGY_WHEN_LOCALIZED = ("comp_neo_hook", "comp_neo_hook_plastic", "UCNH", "UCNHVar")


class Damaged:
    """A constitutive model module followed by a damage model: the erosion of F and L (the
    particles localized at the step's start), the model's update, the damage's on the new
    stress; the state is the model's (n_model arrays) then the damage's."""

    def __init__(self, model, n_model, damage, no_localized_energy):
        self.model, self.n_model, self.damage = model, n_model, damage
        self.no_localized_energy = no_localized_energy and isinstance(damage, ThresholdVar)

    def __getattr__(self, name):           # the model's constants (ENERGY_IS_INCREMENT, Params ...)
        if name in ("state_of", "STATE", "read_params"):
            raise AttributeError(name)
        return getattr(self.model, name)

    def initial_state(self, params, n, temperature=None, color=None, draw=None):
        """The model's state, then the damage's (draw: what a random threshold needs,
        ThresholdVar.initial_state)."""
        own = ()
        if self.n_model:
            if getattr(params, "yield_uniform", False):      # UCNH's drawn p.yieldStress
                own = self.model.initial_state(params, n, temperature, draw=draw)
            else:
                own = self.model.initial_state(params, n, temperature)
            own = own if isinstance(own, tuple) else (own,)
        color = np.zeros(n) if color is None else color
        if isinstance(self.damage, ThresholdVar):
            return own + self.damage.initial_state(n, color, draw)
        return own + self.damage.initial_state(n, color)

    def update(self, params, L, F_old, F_new, vol, mass, vel, dt, stress_old, stress_new, energy, old, new,
               time=0.0, color=None, **stabilized):
        k = self.n_model
        dold, dnew = old[k:], new[k:]
        if isinstance(self.damage, ThresholdVar):
            L = self.damage.erode_kinematics(dold[1], F_old, F_new, L)
        extra = dict({"color": color} if getattr(self.model, "USES_COLOR", False) else {}, **stabilized)
        if k == 0:
            ws = self.model.update(params, L, F_old, F_new, vol, mass, vel, dt, stress_old, stress_new, energy,
                                   **extra)
        else:
            mo, mn = (old[0], new[0]) if k == 1 else (old[:k], new[:k])
            ws = self.model.update(params, L, F_old, F_new, vol, mass, vel, dt, stress_old, stress_new, energy,
                                   mo, mn, **extra)
        if self.no_localized_energy:
            energy[dold[1] != 0.0] = 0.0
        self.damage.apply(F_new, vol, stress_new, dold, dnew, color, time)
        return ws
