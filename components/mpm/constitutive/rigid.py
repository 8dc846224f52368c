"""Rigid material: stress stays zero (Uintah ``type="rigid"``).

Optional tags ``shear_modulus``, ``bulk_modulus`` (default 0) only enter the
wave speed c = sqrt((K + 4G/3) V/m) used for the stable timestep;
``coeff_thermal_expansion`` is accepted and, as by Uintah's rigid model, not used.
"""
from dataclasses import dataclass

import numpy as np
from numba import njit

from ._common import _get, max_wavespeed

ENERGY_IS_INCREMENT = True


@dataclass(frozen=True)
class Params:
    shear_modulus: float = 0.0
    bulk_modulus: float = 0.0
    coeff_thermal_expansion: float = 0.0

    @classmethod
    def from_ups(cls, d):
        return cls(_get(d, "shear_modulus", 0.0), _get(d, "bulk_modulus", 0.0))


@njit(cache=True)
def kernel(G, K, vol, mass, vel, stress_new, energy):
    ws = np.zeros(3)
    for p in range(vol.shape[0]):
        for i in range(3):
            for j in range(3):
                stress_new[p, i, j] = 0.0
        energy[p] = 0.0
        max_wavespeed(ws, np.sqrt((K + 4.0 * G / 3.0) * vol[p] / mass[p]), vel, p)
    return ws


def update(params, L, F_old, F_new, vol, mass, vel, dt, stress_old, stress_new, energy):
    """Zero stress and energy; returns wave speed (3,)."""
    return kernel(params.shear_modulus, params.bulk_modulus, vol, mass, vel, stress_new, energy)
