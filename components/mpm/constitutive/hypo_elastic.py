"""Hypoelastic solid with the Jaumann stress rate (004 eqs. 18-20).

Uintah ``<constitutive_model type="hypo_elastic">`` tags: ``G`` (shear
modulus), ``K`` (bulk modulus).  Rate form, so ``energy`` receives the strain
energy INCREMENT D:avg(sigma)*V*dt of the step (as Uintah's HypoElastic).
"""
from dataclasses import dataclass

import numpy as np
from numba import njit

from ._common import _get, max_wavespeed

ENERGY_IS_INCREMENT = True


@dataclass(frozen=True)
class Params:
    G: float
    K: float

    @classmethod
    def from_ups(cls, d):
        return cls(G=_get(d, "G"), K=_get(d, "K"))


@njit(cache=True, inline="always")
def jaumann_trial(G, K, L, p, dt, s_old, s_new):
    """s_new = s + dt (W s - s W) + dt (2G D' + K trD I)   (004 eq. 19).

    The paper writes sigma.W - W.sigma with W built from grad(v) = L^T;
    with W = (L - L^T)/2 (L_ij = dv_i/dx_j) the same update reads W.s - s.W."""
    trD = L[p, 0, 0] + L[p, 1, 1] + L[p, 2, 2]
    for i in range(3):
        for j in range(3):
            ws = 0.0
            for k in range(3):
                Wik = 0.5 * (L[p, i, k] - L[p, k, i])
                Wkj = 0.5 * (L[p, k, j] - L[p, j, k])
                ws += Wik * s_old[p, k, j] - s_old[p, i, k] * Wkj
            Dij = 0.5 * (L[p, i, j] + L[p, j, i])
            el = 2.0 * G * Dij
            if i == j:
                el += (K - 2.0 * G / 3.0) * trD
            s_new[p, i, j] = s_old[p, i, j] + dt * (ws + el)


@njit(cache=True, inline="always")
def work_increment(L, p, s_old, s_new, vol, dt):
    """D : (s_old + s_new)/2 * V * dt."""
    e = 0.0
    for i in range(3):
        for j in range(3):
            e += 0.5 * (L[p, i, j] + L[p, j, i]) * 0.5 * (s_old[p, i, j] + s_new[p, i, j])
    return e * vol[p] * dt


@njit(cache=True)
def kernel(G, K, L, vol, mass, vel, dt, stress_old, stress_new, energy):
    ws = np.zeros(3)
    for p in range(L.shape[0]):
        jaumann_trial(G, K, L, p, dt, stress_old, stress_new)
        energy[p] = work_increment(L, p, stress_old, stress_new, vol, dt)
        c = np.sqrt((K + 4.0 * G / 3.0) * vol[p] / mass[p])
        max_wavespeed(ws, c, vel, p)
    return ws


def update(params, L, F_old, F_new, vol, mass, vel, dt, stress_old, stress_new, energy):
    """Update stress of all particles; returns the wave speed vector (3,)."""
    return kernel(params.G, params.K, L, vol, mass, vel, dt, stress_old, stress_new, energy)
