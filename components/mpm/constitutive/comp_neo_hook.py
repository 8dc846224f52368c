"""Compressible neo-Hookean solid, Uintah's CompNeoHook.

Uintah ``<constitutive_model type="comp_neo_hook">`` tags: ``bulk_modulus``
(K), ``shear_modulus`` (mu).  With J = det F, b = F F^T, bbar = J^(-2/3) b:

    sigma = K/2 (J - 1/J) I + mu/J dev(bbar)   (= mu J^(-5/3) dev(b))
    W     = K/2 (1/2 (J^2 - 1) - ln J) + mu/2 (tr bbar - 3)   per unit
            reference volume; ``energy`` receives the TOTAL W * V/J.
    c     = sqrt((K + 4 mu/3) V/m), or sqrt((K + 4 mu/3) J/rho0) under <DoPressureStabilization>
            (Uintah's UCNH: J of the stabilized F, whose volume follows the unstabilized J)
"""
from dataclasses import dataclass

import numpy as np
from numba import njit

from ._common import _get

ENERGY_IS_INCREMENT = False
STABILIZED_WAVE_SPEED = True      # update takes rho0 (tasks._constitutive)


@dataclass(frozen=True)
class Params:
    bulk_modulus: float
    shear_modulus: float

    @classmethod
    def from_ups(cls, d):
        return cls(_get(d, "bulk_modulus"), _get(d, "shear_modulus"))


@njit(cache=True, fastmath={'contract'}, inline="always")
def point(K, mu, cK, F00, F01, F02, F10, F11, F12, F20, F21, F22, vol, mass, p, stress_new):
    """The stress of one particle from its F (written to stress_new[p]); returns its strain
    energy W V/J and wave speed c. Scalar locals only (no scratch arrays that could alias
    the outputs). The transfer kernels call it in the pass that computes F (transfer.py)."""
    J = (F00 * (F11 * F22 - F12 * F21) - F01 * (F10 * F22 - F12 * F20)
         + F02 * (F10 * F21 - F11 * F20))
    b00 = F00 * F00 + F01 * F01 + F02 * F02
    b11 = F10 * F10 + F11 * F11 + F12 * F12
    b22 = F20 * F20 + F21 * F21 + F22 * F22
    b01 = F00 * F10 + F01 * F11 + F02 * F12
    b02 = F00 * F20 + F01 * F21 + F02 * F22
    b12 = F10 * F20 + F11 * F21 + F12 * F22
    lnJ = np.log(J)
    Jm23 = np.exp(-2.0 / 3.0 * lnJ)         # J^(-2/3), from the log the energy needs anyway
    trbb = Jm23 * (b00 + b11 + b22)
    iJ = 1.0 / J
    pr = 0.5 * K * (J - iJ)
    c = mu * iJ * Jm23
    d = pr - mu * iJ * trbb / 3.0
    stress_new[p, 0, 0] = c * b00 + d
    stress_new[p, 1, 1] = c * b11 + d
    stress_new[p, 2, 2] = c * b22 + d
    stress_new[p, 0, 1] = stress_new[p, 1, 0] = c * b01
    stress_new[p, 0, 2] = stress_new[p, 2, 0] = c * b02
    stress_new[p, 1, 2] = stress_new[p, 2, 1] = c * b12
    U = 0.5 * K * (0.5 * (J * J - 1.0) - lnJ)
    W = 0.5 * mu * (trbb - 3.0)
    return (U + W) * vol * iJ, np.sqrt(cK * vol / mass)


@njit(cache=True, fastmath={'contract'})
def kernel(K, mu, F_new, vol, mass, vel, stress_new, energy, rho0=0.0):
    """Every particle's stress, energy and the wave speed (3,); rho0 > 0: c from J/rho0
    (pressure stabilization), else from V/m."""
    w0 = w1 = w2 = 0.0
    cK = K + 4.0 * mu / 3.0
    for p in range(F_new.shape[0]):
        energy[p], cs = point(K, mu, cK, F_new[p, 0, 0], F_new[p, 0, 1], F_new[p, 0, 2], F_new[p, 1, 0],
                              F_new[p, 1, 1], F_new[p, 1, 2], F_new[p, 2, 0], F_new[p, 2, 1], F_new[p, 2, 2],
                              vol[p], mass[p], p, stress_new)
        if rho0 > 0.0:
            J = (F_new[p, 0, 0] * (F_new[p, 1, 1] * F_new[p, 2, 2] - F_new[p, 1, 2] * F_new[p, 2, 1])
                 - F_new[p, 0, 1] * (F_new[p, 1, 0] * F_new[p, 2, 2] - F_new[p, 1, 2] * F_new[p, 2, 0])
                 + F_new[p, 0, 2] * (F_new[p, 1, 0] * F_new[p, 2, 1] - F_new[p, 1, 1] * F_new[p, 2, 0]))
            cs = np.sqrt(cK * J / rho0)
        w0 = max(w0, cs + abs(vel[p, 0]))
        w1 = max(w1, cs + abs(vel[p, 1]))
        w2 = max(w2, cs + abs(vel[p, 2]))
    return np.array([w0, w1, w2])


def update(params, L, F_old, F_new, vol, mass, vel, dt, stress_old, stress_new, energy, rho0=0.0):
    """Stress from F_new (L, F_old, dt, stress_old unused); returns wave speed (3,); rho0 > 0:
    the wave speed of a pressure-stabilized F (kernel)."""
    return kernel(params.bulk_modulus, params.shear_modulus, F_new, vol, mass, vel,
                  stress_new, energy, rho0)
