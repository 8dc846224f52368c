"""Compressible neo-Hookean solid, Uintah's CompNeoHook.

Uintah ``<constitutive_model type="comp_neo_hook">`` tags: ``bulk_modulus``
(K), ``shear_modulus`` (mu).  With J = det F, b = F F^T, bbar = J^(-2/3) b:

    sigma = K/2 (J - 1/J) I + mu/J dev(bbar)   (= mu J^(-5/3) dev(b))
    W     = K/2 (1/2 (J^2 - 1) - ln J) + mu/2 (tr bbar - 3)   per unit
            reference volume; ``energy`` receives the TOTAL W * V/J.
    c     = sqrt((K + 4 mu/3) V/m)
"""
from dataclasses import dataclass

import numpy as np
from numba import njit

from ._common import _get, det3, max_wavespeed

ENERGY_IS_INCREMENT = False


@dataclass(frozen=True)
class Params:
    bulk_modulus: float
    shear_modulus: float

    @classmethod
    def from_ups(cls, d):
        return cls(_get(d, "bulk_modulus"), _get(d, "shear_modulus"))


@njit(cache=True)
def kernel(K, mu, F_new, vol, mass, vel, stress_new, energy):
    ws = np.zeros(3)
    b = np.empty((3, 3))
    for p in range(F_new.shape[0]):
        F = F_new[p]
        J = det3(F)
        for i in range(3):
            for j in range(3):
                b[i, j] = F[i, 0] * F[j, 0] + F[i, 1] * F[j, 1] + F[i, 2] * F[j, 2]
        Jm23 = J ** (-2.0 / 3.0)
        trbb = Jm23 * (b[0, 0] + b[1, 1] + b[2, 2])
        pr = 0.5 * K * (J - 1.0 / J)
        for i in range(3):
            for j in range(3):
                s = mu / J * Jm23 * b[i, j]
                if i == j:
                    s += pr - mu / J * trbb / 3.0
                stress_new[p, i, j] = s
        U = 0.5 * K * (0.5 * (J * J - 1.0) - np.log(J))
        W = 0.5 * mu * (trbb - 3.0)
        energy[p] = (U + W) * vol[p] / J
        c = np.sqrt((K + 4.0 * mu / 3.0) * vol[p] / mass[p])
        max_wavespeed(ws, c, vel, p)
    return ws


def update(params, L, F_old, F_new, vol, mass, vel, dt, stress_old, stress_new, energy):
    """Stress from F_new (L, F_old, dt, stress_old unused); returns wave speed (3,)."""
    return kernel(params.bulk_modulus, params.shear_modulus, F_new, vol, mass, vel,
                  stress_new, energy)
