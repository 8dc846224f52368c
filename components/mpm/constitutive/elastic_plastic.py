"""J2 (von Mises) plasticity, linear isotropic hardening, radial return; optional failure.

Hypoelastic trial stress with the Jaumann rate (004 eq. 19) followed by the
classical radial return:  q = sqrt(3/2 s:s),  sigma_y = yield_stress +
hardening_modulus * eps_p,  d_eps_p = (q_trial - sigma_y) / (3G + H).

Deck tags (``<constitutive_model type="elastic_plastic">``): ``shear_modulus``,
``bulk_modulus``, ``yield_stress``, ``hardening_modulus``. (With a ``<flow_model>`` the
deck is Uintah's model with sub-models instead: elastic_plastic_hp.py.)  State: equivalent
plastic strain per particle.  ``energy`` receives the stress-work INCREMENT.

Failure (Uintah's tags, read by ``read_failure``): with ``<evolve_damage>true`` and a
``<damage_model type="johnson_cook">`` inside the constitutive model, the scalar damage
is D = sum d_eps_p / eps_f (Johnson and Cook 1985) with the failure strain
eps_f = D1 + D2 exp(D3 sigma*) ... ; only the constant part is implemented (D2 = D4 =
D5 = 0, so eps_f = D1 and D = eps_p / D1).  A particle has failed (Uintah: localized)
once D >= ``critical_scalar_damage`` (default 1), i.e. once eps_p >= Dc D1: the
plastic strain never decreases, so it is the whole failure state and no extra particle
variable is needed.  What a failed particle carries is the material's
``<erosion algorithm="...">`` (a sibling of the constitutive model, as in Uintah):
ZeroStress (no stress at all; and, as Uintah, the particle keeps the F and the volume
it had when it failed, so it does not swell to fill the crack that opens), AllowNoTension (hydrostatic compression only, nothing
when the mean stress is tensile), AllowNoShear (the mean stress only), none or
PreserveStress (failure changes nothing).  Uintah's char_time fade-out is not
implemented (its default 1e-99 s: the stress goes at once).  Without these tags the
model is bitwise the same as without failure.
"""
import dataclasses
from dataclasses import dataclass

import numpy as np
from numba import njit

from ._common import _get, det3, max_wavespeed
from .damage import _mean_and_von_mises
from .hypo_elastic import jaumann_trial, work_increment

ENERGY_IS_INCREMENT = True

# <erosion algorithm="..."> -> kernel code
EROSION = {"none": 0, "PreserveStress": 0, "ZeroStress": 1, "AllowNoTension": 2, "AllowNoShear": 3}
_NO_F = np.zeros((0, 3, 3))


@dataclass(frozen=True)
class Params:
    shear_modulus: float
    bulk_modulus: float
    yield_stress: float
    hardening_modulus: float = 0.0
    evolve_damage: bool = False
    critical_scalar_damage: float = 1.0
    failure_strain: float = np.inf       # Dc * D1: eps_p at which a particle fails (read_failure)
    erosion: int = 0                     # EROSION code of the material's <erosion> (read_failure)

    @classmethod
    def from_ups(cls, d):
        for k in ("failure_strain", "erosion"):
            if k in d:
                raise KeyError(f"<{k}> is not a deck tag (failure: <evolve_damage>, <damage_model>, "
                               "<critical_scalar_damage> and the material's <erosion>)")
        return cls(_get(d, "shear_modulus"), _get(d, "bulk_modulus"),
                   _get(d, "yield_stress"), _get(d, "hardening_modulus", 0.0),
                   str(d.get("evolve_damage", "False")) == "True",
                   _get(d, "critical_scalar_damage", 1.0))


def read_failure(params, material, cm):
    """Params with the failure strain and erosion code from the material node's
    <erosion algorithm> and the constitutive model's <damage_model type="johnson_cook">."""
    er = material.child("erosion")
    code = EROSION[er.attr("algorithm", choices=tuple(EROSION))] if er is not None else 0
    dm = cm.child("damage_model")
    eps_f = np.inf
    if dm is not None:
        dm.attr("type", choices=("johnson_cook",))
        D = {k: dm.get(k) for k in ("D1", "D2", "D3", "D4", "D5")}
        if D["D2"] != 0.0 or D["D4"] != 0.0 or D["D5"] != 0.0:
            raise dm.error("only a constant failure strain is implemented: <D2>, <D4> and <D5> must be 0 "
                           "(eps_f = D1)")
        if D["D1"] <= 0.0:
            raise dm.child("D1").error("<D1> (the failure strain) must be positive")
        if not params.evolve_damage:
            raise dm.error("<damage_model> needs <evolve_damage> true </evolve_damage> in the constitutive model")
        if params.critical_scalar_damage <= 0.0:
            raise cm.child("critical_scalar_damage").error("<critical_scalar_damage> must be positive")
        eps_f = params.critical_scalar_damage * D["D1"]
    elif params.evolve_damage:
        raise cm.error('<evolve_damage> true needs a <damage_model type="johnson_cook"> with <D1>...<D5>')
    return dataclasses.replace(params, failure_strain=eps_f, erosion=code)


@njit(cache=True, inline="always")
def erode(code, p, s):
    """The stress a failed particle keeps (Uintah's ErosionModel algorithms)."""
    pr = (s[p, 0, 0] + s[p, 1, 1] + s[p, 2, 2]) / 3.0
    for i in range(3):
        for j in range(3):
            if code == 1 or (code == 2 and pr > 0.0) or i != j:
                s[p, i, j] = 0.0
            else:
                s[p, i, j] = pr


@njit(cache=True, inline="always")
def freeze(p, F_old, F_new, vol):
    """ZeroStress (as Uintah's updateVariables_Erosion): a failed particle keeps its F, so its
    volume stays what it was (it does not swell and fill an opening crack)."""
    vol[p] *= det3(F_old[p]) / det3(F_new[p])
    for i in range(3):
        for j in range(3):
            F_new[p, i, j] = F_old[p, i, j]


@njit(cache=True)
def kernel(G, K, sy0, H, eps_f, erosion, L, F_old, F_new, vol, mass, vel, dt, stress_old, stress_new,
           eps_p_old, eps_p_new, energy):
    ws = np.zeros(3)
    for p in range(L.shape[0]):
        if erosion == 1 and eps_p_old[p] >= eps_f:
            freeze(p, F_old, F_new, vol)
        jaumann_trial(G, K, L, p, dt, stress_old, stress_new)
        pr, q = _mean_and_von_mises(stress_new, p)
        sy = sy0 + H * eps_p_old[p]
        eps_p_new[p] = eps_p_old[p]
        if q > sy:
            dg = (q - sy) / (3.0 * G + H)
            fac = 1.0 - 3.0 * G * dg / q
            for i in range(3):
                for j in range(3):
                    sij = stress_new[p, i, j] - (pr if i == j else 0.0)
                    stress_new[p, i, j] = fac * sij + (pr if i == j else 0.0)
            eps_p_new[p] = eps_p_old[p] + dg
        if erosion != 0 and eps_p_new[p] >= eps_f:       # failed: D = eps_p / D1 >= Dc
            erode(erosion, p, stress_new)
        energy[p] = work_increment(L, p, stress_old, stress_new, vol, dt)
        c = np.sqrt((K + 4.0 * G / 3.0) * vol[p] / mass[p])
        max_wavespeed(ws, c, vel, p)
    return ws


def update(params, L, F_old, F_new, vol, mass, vel, dt, stress_old, stress_new, energy,
           eps_p_old, eps_p_new):
    """Update stress and plastic strain; returns wave speed (3,). With ZeroStress erosion a
    particle failed at the start of the step gets F_new = F_old and its volume back (in place:
    under MUSL this task computes both; under USL they come from g2p and no task has read them
    yet)."""
    if params.erosion != 1:                 # F is read only by ZeroStress
        F_old = F_new = _NO_F
    return kernel(params.shear_modulus, params.bulk_modulus, params.yield_stress,
                  params.hardening_modulus, params.failure_strain, params.erosion, L, F_old, F_new,
                  vol, mass, vel, dt, stress_old, stress_new, eps_p_old, eps_p_new, energy)


def failed(params, eps_p):
    """Which particles have failed (for diagnostics: scripts, tests)."""
    return np.asarray(eps_p) >= params.failure_strain
