"""Rigid material: stress stays zero (Uintah ``type="rigid"``).

Optional tags ``shear_modulus``, ``bulk_modulus`` (default 0) and
``coeff_thermal_expansion`` are accepted and, as by Uintah's rigid model, not used: a rigid
material adds nothing to the wave speed, so it does not limit the timestep (Uintah's
RigidMaterial puts no stable-timestep bound of its own; a piston moving at 40 m/s would
otherwise shorten every step of adiCuJC4000s696K.ups by 1 %).
"""
from dataclasses import dataclass

import numpy as np
from numba import njit

from ._common import _get

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
def kernel(stress_new, energy):
    for p in range(stress_new.shape[0]):
        for i in range(3):
            for j in range(3):
                stress_new[p, i, j] = 0.0
        energy[p] = 0.0


def update(params, L, F_old, F_new, vol, mass, vel, dt, stress_old, stress_new, energy):
    """Zero stress and energy; returns the wave speed, zero (no timestep bound)."""
    kernel(stress_new, energy)
    return np.zeros(3)
