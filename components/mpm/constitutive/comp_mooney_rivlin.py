"""Compressible Mooney-Rivlin solid, Uintah's CompMooneyRivlin.

Uintah ``<constitutive_model type="comp_mooney_rivlin">`` tags:
``he_constant_1`` (C1), ``he_constant_2`` (C2), ``he_PR`` (Poisson ratio nu).
With B = F F^T, invariants I1, I2, I3 = J^2 and

    C3 = C1/2 + C2,  C4 = (C1 (5 nu - 2) + C2 (11 nu - 5)) / (2 (1 - 2 nu))
    W  = C1 (I1 - 3) + C2 (I2 - 3) + C3 (I3^-2 - 1) + C4 (I3 - 1)^2
    sigma = 2/J [ (W1 + I1 W2) B - W2 B^2 + I3 W3 I ],
            W1 = C1, W2 = C2, W3 = -2 C3 I3^-3 + 2 C4 (I3 - 1)

which is stress free at F = I with small-strain shear modulus 2 (C1 + C2)
and Poisson ratio nu.  ``energy`` receives the TOTAL W * V/J.  Wave speed
uses Uintah's expression
    c^2 = (4 (C1 + C2 I2)/J + 8 (2 C3 I3^-3 + C4 (2 I3 - 1)) - min_i sigma_ii/J) V/m.
The artificial viscosity's sound speed takes K = 4 (C1 + C2 I2)/J (viscosity_bulk_modulus).
"""
from dataclasses import dataclass

import numpy as np
from numba import njit

from ._common import _get, det3, max_wavespeed

ENERGY_IS_INCREMENT = False


@dataclass(frozen=True)
class Params:
    he_constant_1: float
    he_constant_2: float
    he_PR: float

    @classmethod
    def from_ups(cls, d):
        return cls(_get(d, "he_constant_1"), _get(d, "he_constant_2"), _get(d, "he_PR"))

    @property
    def shear_modulus(self):
        return 2.0 * (self.he_constant_1 + self.he_constant_2)


@njit(cache=True)
def kernel(C1, C2, PR, F_new, vol, mass, vel, stress_new, energy):
    C3 = 0.5 * C1 + C2
    C4 = 0.5 * (C1 * (5.0 * PR - 2.0) + C2 * (11.0 * PR - 5.0)) / (1.0 - 2.0 * PR)
    ws = np.zeros(3)
    B = np.empty((3, 3))
    for p in range(F_new.shape[0]):
        F = F_new[p]
        J = det3(F)
        for i in range(3):
            for j in range(3):
                B[i, j] = F[i, 0] * F[j, 0] + F[i, 1] * F[j, 1] + F[i, 2] * F[j, 2]
        I1 = B[0, 0] + B[1, 1] + B[2, 2]
        trBB = 0.0
        for i in range(3):
            for j in range(3):
                trBB += B[i, j] * B[j, i]
        I2 = 0.5 * (I1 * I1 - trBB)
        I3 = J * J
        W3 = -2.0 * C3 / (I3 * I3 * I3) + 2.0 * C4 * (I3 - 1.0)
        a = C1 + I1 * C2
        smin = 1e300
        for i in range(3):
            for j in range(3):
                BB = B[i, 0] * B[0, j] + B[i, 1] * B[1, j] + B[i, 2] * B[2, j]
                s = a * B[i, j] - C2 * BB
                if i == j:
                    s += I3 * W3
                s *= 2.0 / J
                stress_new[p, i, j] = s
                if i == j and s < smin:
                    smin = s
        W = (C1 * (I1 - 3.0) + C2 * (I2 - 3.0) + C3 * (1.0 / (I3 * I3) - 1.0)
             + C4 * (I3 - 1.0) ** 2)
        energy[p] = W * vol[p] / J
        c2 = (4.0 * (C1 + C2 * I2) / J + 8.0 * (2.0 * C3 / (I3 * I3 * I3) + C4 * (2.0 * I3 - 1.0))
              - smin / J) * vol[p] / mass[p]
        max_wavespeed(ws, np.sqrt(max(c2, 0.0)), vel, p)
    return ws


@njit(cache=True)
def viscosity_bulk_modulus(C1, C2, F_new, out):
    """The bulk modulus of the artificial viscosity's sound speed, 4 (C1 + C2 I2)/J of the
    current B = F F^T (Uintah's CompMooneyRivlin, which calls its choice tentative)."""
    for p in range(F_new.shape[0]):
        F = F_new[p]
        trB = 0.0
        trBB = 0.0
        for i in range(3):
            trB += F[i, 0] * F[i, 0] + F[i, 1] * F[i, 1] + F[i, 2] * F[i, 2]
        for i in range(3):
            for j in range(3):
                Bij = F[i, 0] * F[j, 0] + F[i, 1] * F[j, 1] + F[i, 2] * F[j, 2]
                trBB += Bij * Bij
        I2 = 0.5 * (trB * trB - trBB)
        out[p] = 4.0 * (C1 + C2 * I2) / det3(F)


def update(params, L, F_old, F_new, vol, mass, vel, dt, stress_old, stress_new, energy):
    """Stress from F_new (L, F_old, stress_old unused); returns wave speed (3,). At the
    initialization (dt = 0) the wave speed is that of Uintah's computeStableTimestep there,
    c^2 = 2 mu (1 - nu) V / ((1 - 2 nu) m), mu = 2 (C1 + C2), which differs from the step's."""
    ws = kernel(params.he_constant_1, params.he_constant_2, params.he_PR, F_new, vol,
                mass, vel, stress_new, energy)
    if dt == 0.0 and len(vol):
        nu = params.he_PR
        c = np.sqrt(2.0 * params.shear_modulus * (1.0 - nu) * vol / ((1.0 - 2.0 * nu) * mass))
        ws = (c[:, None] + np.abs(vel)).max(axis=0)
    return ws
