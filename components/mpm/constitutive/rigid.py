"""Rigid material: stress stays zero (Uintah ``type="rigid"``).

Optional tags ``shear_modulus``, ``bulk_modulus`` (default 0) and
``coeff_thermal_expansion`` are accepted and, as by Uintah's rigid model, not used: a
rigid material has no wave speed, so it bounds the timestep at 1 s only (Uintah's
RigidMaterial puts delT = 1; a piston moving at 40 m/s would otherwise shorten every step
of adiCuJC4000s696K.ups by 1 %).
"""
from dataclasses import dataclass

import numpy as np

from ._common import _get

ENERGY_IS_INCREMENT = True
MAX_DELT = 1.0          # s, Uintah's RigidMaterial::carryForward


@dataclass(frozen=True)
class Params:
    shear_modulus: float = 0.0
    bulk_modulus: float = 0.0
    coeff_thermal_expansion: float = 0.0

    @classmethod
    def from_ups(cls, d):
        return cls(_get(d, "shear_modulus", 0.0), _get(d, "bulk_modulus", 0.0))


def update(params, L, F_old, F_new, vol, mass, vel, dt, stress_old, stress_new, energy):
    """Zero stress and energy; no wave speed (zeros (3,))."""
    stress_new[...] = 0.0
    energy[...] = 0.0
    return np.zeros(3)
