"""J2 (von Mises) plasticity, linear isotropic hardening, radial return.

Hypoelastic trial stress with the Jaumann rate (004 eq. 19) followed by the
classical radial return:  q = sqrt(3/2 s:s),  sigma_y = yield_stress +
hardening_modulus * eps_p,  d_eps_p = (q_trial - sigma_y) / (3G + H).

Deck tags (``<constitutive_model type="elastic_plastic">``): ``shear_modulus``,
``bulk_modulus``, ``yield_stress``, ``hardening_modulus``.  State: equivalent
plastic strain per particle.  ``energy`` receives the stress-work INCREMENT.
"""
from dataclasses import dataclass

import numpy as np
from numba import njit

from ._common import _get, max_wavespeed
from .hypo_elastic import jaumann_trial, work_increment

ENERGY_IS_INCREMENT = True


@dataclass(frozen=True)
class Params:
    shear_modulus: float
    bulk_modulus: float
    yield_stress: float
    hardening_modulus: float = 0.0

    @classmethod
    def from_ups(cls, d):
        return cls(_get(d, "shear_modulus"), _get(d, "bulk_modulus"),
                   _get(d, "yield_stress"), _get(d, "hardening_modulus", 0.0))


@njit(cache=True)
def kernel(G, K, sy0, H, L, vol, mass, vel, dt, stress_old, stress_new, eps_p_old,
           eps_p_new, energy):
    ws = np.zeros(3)
    for p in range(L.shape[0]):
        jaumann_trial(G, K, L, p, dt, stress_old, stress_new)
        pr = (stress_new[p, 0, 0] + stress_new[p, 1, 1] + stress_new[p, 2, 2]) / 3.0
        ss = 0.0
        for i in range(3):
            for j in range(3):
                sij = stress_new[p, i, j] - (pr if i == j else 0.0)
                ss += sij * sij
        q = np.sqrt(1.5 * ss)
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
        energy[p] = work_increment(L, p, stress_old, stress_new, vol, dt)
        c = np.sqrt((K + 4.0 * G / 3.0) * vol[p] / mass[p])
        max_wavespeed(ws, c, vel, p)
    return ws


def update(params, L, F_old, F_new, vol, mass, vel, dt, stress_old, stress_new, energy,
           eps_p_old, eps_p_new):
    """Update stress and plastic strain; returns wave speed (3,)."""
    return kernel(params.shear_modulus, params.bulk_modulus, params.yield_stress,
                  params.hardening_modulus, L, vol, mass, vel, dt, stress_old, stress_new,
                  eps_p_old, eps_p_new, energy)
