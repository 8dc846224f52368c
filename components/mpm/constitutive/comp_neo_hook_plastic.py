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
    c = sqrt((K + 4 mu/3) V/m)

As in Uintah, the yield stress is the same for every particle (``yield_distrib``
"constant"; its random "uniform" distribution is not read), the thermal part of J
(p.JThermal) is 1 and the stress needs F only (not the velocity gradient).  Without
plasticity the stress is comp_neo_hook's (the same formula) and there is no state.
"""
from dataclasses import dataclass

import numpy as np
from numba import njit

from . import comp_neo_hook
from ._common import _get, det3, inv3, max_wavespeed

ENERGY_IS_INCREMENT = False
SQ23 = np.sqrt(2.0 / 3.0)


@dataclass(frozen=True)
class Params:
    bulk_modulus: float
    shear_modulus: float
    yield_stress: float = 0.0
    hardening_modulus: float = 0.0
    alpha: float = 0.0                    # initial equivalent plastic strain
    usePlasticity: bool = True

    @classmethod
    def from_ups(cls, d):
        plastic = str(d.get("usePlasticity", cls.usePlasticity)) == "True"
        if not plastic:
            return cls(_get(d, "bulk_modulus"), _get(d, "shear_modulus"), usePlasticity=False)
        return cls(_get(d, "bulk_modulus"), _get(d, "shear_modulus"), _get(d, "yield_stress"),
                   _get(d, "hardening_modulus"), _get(d, "alpha", 0.0), True)


def initial_state(params, n):
    """p.plasticStrain = alpha, p.bElBar = I (Uintah's initializeCMData)."""
    be = np.zeros((n, 3, 3))
    be[:, 0, 0] = be[:, 1, 1] = be[:, 2, 2] = 1.0
    return np.full(n, params.alpha), be


@njit(cache=True)
def kernel(K, mu, sy, H, F_old, F_new, vol, mass, vel, alpha_old, be_old, alpha_new, be_new,
           stress_new, energy):
    """Every particle's stress, plastic strain, bElBar and energy; the wave speed (3,)."""
    ws = np.zeros(3)
    cK = K + 4.0 * mu / 3.0
    Fi = np.empty((3, 3))
    f = np.empty((3, 3))
    fb = np.empty((3, 3))
    bt = np.empty((3, 3))
    for p in range(F_new.shape[0]):
        inv3(F_old[p], Fi)                       # f = F_new F_old^-1
        for i in range(3):
            for j in range(3):
                f[i, j] = F_new[p, i, 0] * Fi[0, j] + F_new[p, i, 1] * Fi[1, j] + F_new[p, i, 2] * Fi[2, j]
        c3 = 1.0 / np.cbrt(det3(f))
        for i in range(3):                       # fbar bbar_old
            for j in range(3):
                fb[i, j] = c3 * (f[i, 0] * be_old[p, 0, j] + f[i, 1] * be_old[p, 1, j] + f[i, 2] * be_old[p, 2, j])
        for i in range(3):                       # bbar_trial = fbar bbar_old fbar^T
            for j in range(3):
                bt[i, j] = c3 * (fb[i, 0] * f[j, 0] + fb[i, 1] * f[j, 1] + fb[i, 2] * f[j, 2])
        Ie = (bt[0, 0] + bt[1, 1] + bt[2, 2]) / 3.0
        ss = 0.0                                 # |s_trial|^2, s_trial = mu dev(bbar_trial)
        for i in range(3):
            for j in range(3):
                s = mu * (bt[i, j] - (Ie if i == j else 0.0))
                ss += s * s
        snorm = np.sqrt(ss)
        a = alpha_old[p]
        ftrial = snorm - SQ23 * (H * a + sy)
        plastic = ftrial > 0.0
        scale = 1.0                               # s = scale * s_trial
        if plastic:                               # radial return
            mubar = Ie * mu
            dgamma = (ftrial / (2.0 * mubar)) / (1.0 + H / (3.0 * mubar))
            scale = 1.0 - 2.0 * mubar * dgamma / snorm
            a += SQ23 * dgamma
        alpha_new[p] = a
        J = det3(F_new[p])
        iJ = 1.0 / J
        pr = 0.5 * K * (J - iJ)
        tr = 0.0
        for i in range(3):
            for j in range(3):
                s = scale * mu * (bt[i, j] - (Ie if i == j else 0.0))
                be_new[p, i, j] = (s / mu + (Ie if i == j else 0.0)) if plastic else bt[i, j]
                stress_new[p, i, j] = s * iJ + (pr if i == j else 0.0)
            tr += be_new[p, i, i]
        U = 0.5 * K * (0.5 * (J * J - 1.0) - np.log(J))
        W = 0.5 * mu * (tr - 3.0)
        energy[p] = (U + W) * vol[p] * iJ
        max_wavespeed(ws, np.sqrt(cK * vol[p] / mass[p]), vel, p)
    return ws


def update(params, L, F_old, F_new, vol, mass, vel, dt, stress_old, stress_new, energy, *state):
    """Stress from F_old, F_new and the state (alpha_old, bElBar_old, alpha_new, bElBar_new);
    returns the wave speed (3,). L, dt, stress_old unused."""
    if not params.usePlasticity:
        return comp_neo_hook.update(params, L, F_old, F_new, vol, mass, vel, dt, stress_old, stress_new,
                                    energy)
    alpha_old, be_old, alpha_new, be_new = state
    return kernel(params.bulk_modulus, params.shear_modulus, params.yield_stress, params.hardening_modulus,
                  F_old, F_new, vol, mass, vel, alpha_old, be_old, alpha_new, be_new, stress_new, energy)
