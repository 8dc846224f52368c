"""Compressible neo-Hookean solid with J2 plasticity: Uintah's UCNH with plasticity.

Uintah builds both ``<constitutive_model type="comp_neo_hook_plastic">`` and
``type="UCNH"`` (ucnh.py) as its class UCNH; this is its explicit update (Simo and
Hughes 1998, box 9.1: multiplicative plasticity in the elastic left Cauchy-Green
tensor).  Tags: ``bulk_modulus`` (K), ``shear_modulus`` (mu), ``yield_stress``
(sigma_y), ``hardening_modulus`` (H, linear isotropic hardening), ``alpha`` (the
initial equivalent plastic strain, default 0), ``usePlasticity`` (default true here).
State per particle: p.plasticStrain (alpha) and p.bElBar (the volume-preserving
elastic left Cauchy-Green tensor, I at the start).  One step, with f = F_new F_old^-1:

    fbar = f / det(f)^(1/3),  bbar_trial = fbar bbar_old fbar^T,  I_e = tr(bbar_trial)/3
    s_trial = mu dev(bbar_trial),  f_trial = |s_trial| - sqrt(2/3) (H alpha + sigma_y)
    plastic (f_trial > 0): dgamma = f_trial / (2 mu I_e) / (1 + H / (3 mu I_e)),
        s = s_trial - 2 mu I_e dgamma s_trial/|s_trial|,  alpha += sqrt(2/3) dgamma,
        bbar = s/mu + I_e I
    sigma = K/2 (J - 1/J) I + s/J
    W = K/2 (1/2 (J^2 - 1) - ln J) + mu/2 (tr bbar - 3); ``energy`` gets W V/J
    c = sqrt((K + 4 mu/3) V/m), or sqrt((K + 4 mu/3) J/rho0) under <DoPressureStabilization> (as Uintah's UCNH)

The yield stress is the same for every particle (``yield_distrib`` "constant"), or, with
``yield_distrib`` "uniform", ``yield_range`` r and ``yield_seed`` (0), each particle's
p.yieldStress is sigma_y + (2 u - 1) r with u from Uintah's MusilRNG, one stream per patch
seeded as Uintah's UCNH (uintah_random.py), drawn in Uintah's order of particle creation, so
that it is sus's on the same patch layout.  As in Uintah, the thermal part of J
(p.JThermal) is 1 and the stress needs F only (not the velocity gradient).  Without
plasticity the stress is comp_neo_hook's (the same formula) and there is no state.
"""
from dataclasses import dataclass

import numpy as np
from numba import njit

from . import comp_neo_hook
from ._common import _get, max_wavespeed
from .uintah_random import STATE_SIZE, musil_next, musil_start, patch_seed

ENERGY_IS_INCREMENT = False
STABILIZED_WAVE_SPEED = True      # update takes rho0 (tasks._constitutive)
UINTAH_UNREAD = ("strain_limit", "reduction_factor")     # in Uintah's decks, read by no Uintah model
SQ23 = np.sqrt(2.0 / 3.0)


@dataclass(frozen=True)
class Params:
    bulk_modulus: float
    shear_modulus: float
    yield_stress: float = 0.0
    hardening_modulus: float = 0.0
    alpha: float = 0.0                    # initial equivalent plastic strain
    usePlasticity: bool = True
    yield_uniform: bool = False           # yield_distrib uniform: p.yieldStress drawn per particle
    yield_range: float = 0.0
    yield_seed: int = 0

    @classmethod
    def from_ups(cls, d):
        plastic = str(d.get("usePlasticity", cls.usePlasticity)) == "True"
        if not plastic:
            return cls(_get(d, "bulk_modulus"), _get(d, "shear_modulus"), usePlasticity=False)
        return cls(_get(d, "bulk_modulus"), _get(d, "shear_modulus"), _get(d, "yield_stress"),
                   _get(d, "hardening_modulus"), _get(d, "alpha", 0.0), True)


def state_of(params):
    """p.plasticStrain, p.bElBar (and p.yieldStress, drawn)."""
    return ("p.plasticStrain", "p.bElBar") + (("p.yieldStress",) if getattr(params, "yield_uniform", False) else ())


def initial_state(params, n, temperature=None, draw=None):
    """p.plasticStrain = alpha, p.bElBar = I (Uintah's initializeCMData); p.yieldStress drawn
    (draw = (the particles' order of creation in Uintah, the patch's Uintah ID))."""
    be = np.zeros((n, 3, 3))
    be[:, 0, 0] = be[:, 1, 1] = be[:, 2, 2] = 1.0
    if not getattr(params, "yield_uniform", False):        # (UCNHVar's params have no draw)
        return np.full(n, params.alpha), be
    ys = np.empty(n)
    order, patch_id = draw
    draw_uniform(patch_seed(params.yield_seed, patch_id), params.yield_stress, params.yield_range, order, ys)
    return np.full(n, params.alpha), be, ys


@njit(cache=True)
def draw_uniform(seed, mean, half_range, order, out):
    """out[order[k]] = mean + (2 u_k - 1) half_range, u_k the k-th value of one generator."""
    st = np.zeros(STATE_SIZE, np.int64)
    musil_start(seed, st)
    for k in range(order.shape[0]):
        out[order[k]] = mean + (2.0 * musil_next(st) - 1.0) * half_range


@njit(cache=True, inline="always")
def _load(A, p):
    """Row-major 9-tuple of A[p]."""
    return (A[p, 0, 0], A[p, 0, 1], A[p, 0, 2], A[p, 1, 0], A[p, 1, 1], A[p, 1, 2], A[p, 2, 0], A[p, 2, 1],
            A[p, 2, 2])


@njit(cache=True, inline="always")
def _mul(a, b):
    """a b of row-major 9-tuples."""
    return (a[0] * b[0] + a[1] * b[3] + a[2] * b[6], a[0] * b[1] + a[1] * b[4] + a[2] * b[7],
            a[0] * b[2] + a[1] * b[5] + a[2] * b[8], a[3] * b[0] + a[4] * b[3] + a[5] * b[6],
            a[3] * b[1] + a[4] * b[4] + a[5] * b[7], a[3] * b[2] + a[4] * b[5] + a[5] * b[8],
            a[6] * b[0] + a[7] * b[3] + a[8] * b[6], a[6] * b[1] + a[7] * b[4] + a[8] * b[7],
            a[6] * b[2] + a[7] * b[5] + a[8] * b[8])


@njit(cache=True, inline="always")
def _det(a):
    return a[0] * (a[4] * a[8] - a[5] * a[7]) - a[1] * (a[3] * a[8] - a[5] * a[6]) + a[2] * (a[3] * a[7] - a[4] * a[6])


@njit(cache=True, inline="always")
def _inv(a):
    d = 1.0 / _det(a)
    return ((a[4] * a[8] - a[5] * a[7]) * d, (a[2] * a[7] - a[1] * a[8]) * d, (a[1] * a[5] - a[2] * a[4]) * d,
            (a[5] * a[6] - a[3] * a[8]) * d, (a[0] * a[8] - a[2] * a[6]) * d, (a[2] * a[3] - a[0] * a[5]) * d,
            (a[3] * a[7] - a[4] * a[6]) * d, (a[1] * a[6] - a[0] * a[7]) * d, (a[0] * a[4] - a[1] * a[3]) * d)


@njit(cache=True, inline="always")
def _abt(a, b):
    """a b^T of row-major 9-tuples."""
    return _mul(a, (b[0], b[3], b[6], b[1], b[4], b[7], b[2], b[5], b[8]))


@njit(cache=True, fastmath={'contract'})
def kernel(K, mu, sy, H, F_old, F_new, vol, mass, vel, alpha_old, be_old, alpha_new, be_new,
           stress_new, energy, yields, rho0=0.0):
    """Every particle's stress, plastic strain, bElBar and energy; the wave speed (3,).
    Scalar locals (9-tuples) only. yields: each particle's yield stress (empty: sy); rho0 > 0:
    c from J/rho0 (pressure stabilization, comp_neo_hook.kernel), else from V/m."""
    ws = np.zeros(3)
    cK = K + 4.0 * mu / 3.0
    for p in range(F_new.shape[0]):
        Fn = _load(F_new, p)
        f = _mul(Fn, _inv(_load(F_old, p)))      # f = F_new F_old^-1
        c3 = 1.0 / np.cbrt(_det(f))
        fb = (c3 * f[0], c3 * f[1], c3 * f[2], c3 * f[3], c3 * f[4], c3 * f[5], c3 * f[6], c3 * f[7], c3 * f[8])
        bt = _abt(_mul(fb, _load(be_old, p)), fb)   # bbar_trial = fbar bbar_old fbar^T
        Ie = (bt[0] + bt[4] + bt[8]) / 3.0
        d0, d4, d8 = bt[0] - Ie, bt[4] - Ie, bt[8] - Ie     # s_trial = mu dev(bbar_trial)
        snorm = mu * np.sqrt(d0 * d0 + d4 * d4 + d8 * d8 + bt[1] * bt[1] + bt[2] * bt[2] + bt[3] * bt[3]
                             + bt[5] * bt[5] + bt[6] * bt[6] + bt[7] * bt[7])
        a = alpha_old[p]
        ftrial = snorm - SQ23 * (H * a + (yields[p] if yields.shape[0] else sy))
        scale = 1.0                               # s = scale * s_trial
        if ftrial > 0.0:                          # radial return
            mubar = Ie * mu
            dgamma = (ftrial / (2.0 * mubar)) / (1.0 + H / (3.0 * mubar))
            scale = 1.0 - 2.0 * mubar * dgamma / snorm
            a += SQ23 * dgamma
        alpha_new[p] = a
        J = _det(Fn)
        iJ = 1.0 / J
        pr = 0.5 * K * (J - iJ)
        c = mu * iJ * scale
        stress_new[p, 0, 0] = c * d0 + pr
        stress_new[p, 1, 1] = c * d4 + pr
        stress_new[p, 2, 2] = c * d8 + pr
        stress_new[p, 0, 1] = c * bt[1]
        stress_new[p, 1, 0] = c * bt[3]
        stress_new[p, 0, 2] = c * bt[2]
        stress_new[p, 2, 0] = c * bt[6]
        stress_new[p, 1, 2] = c * bt[5]
        stress_new[p, 2, 1] = c * bt[7]
        if ftrial > 0.0:                          # bbar = s/mu + I_e I
            bt = (scale * d0 + Ie, scale * bt[1], scale * bt[2], scale * bt[3], scale * d4 + Ie, scale * bt[5],
                  scale * bt[6], scale * bt[7], scale * d8 + Ie)
        for i in range(3):
            for j in range(3):
                be_new[p, i, j] = bt[3 * i + j]
        U = 0.5 * K * (0.5 * (J * J - 1.0) - np.log(J))
        W = 0.5 * mu * (bt[0] + bt[4] + bt[8] - 3.0)
        energy[p] = (U + W) * vol[p] * iJ
        max_wavespeed(ws, np.sqrt(cK * J / rho0) if rho0 > 0.0 else np.sqrt(cK * vol[p] / mass[p]), vel, p)
    return ws


def update(params, L, F_old, F_new, vol, mass, vel, dt, stress_old, stress_new, energy, old=None, new=None,
           rho0=0.0):
    """Stress from F_old, F_new and the state, old = (alpha, bElBar) -> new; returns the wave
    speed (3,). L, dt, stress_old unused; rho0 > 0: pressure stabilization's wave speed (kernel)."""
    if not params.usePlasticity:
        return comp_neo_hook.update(params, L, F_old, F_new, vol, mass, vel, dt, stress_old, stress_new,
                                    energy, rho0)
    if params.yield_uniform:
        (alpha_old, be_old, yields), (alpha_new, be_new, y_new) = old, new
        y_new[:] = yields
    else:
        (alpha_old, be_old), (alpha_new, be_new) = old, new
        yields = np.empty(0)
    return kernel(params.bulk_modulus, params.shear_modulus, params.yield_stress, params.hardening_modulus,
                  F_old, F_new, vol, mass, vel, alpha_old, be_old, alpha_new, be_new, stress_new, energy, yields,
                  rho0)
