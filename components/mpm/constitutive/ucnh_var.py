"""Uintah's UCNHVar: UCNH (comp_neo_hook_plastic.py) whose moduli vary with the particle's color.

``<constitutive_model type="UCNHVar">`` takes ``<variable_properties>`` with two or more
``<entry>``s, each a ``color`` and that color's ``bulk_modulus``, ``shear_modulus``,
``yield_stress`` and ``hardening_modulus``, in increasing color; a particle's properties
are interpolated linearly in its p.color between the entries around it (the last entry's at
or above the last color; below the first color the line of the first two entries extended,
as Uintah's findPropertiesFromColor).
``usePlasticity`` is false by default (then the stress is comp_neo_hook's with the
particle's moduli and there is no state), else the state and return map are UCNH's:
p.plasticStrain and p.bElBar.  The wave speed of a step is sqrt((K + 4 G/3) J/rho_0) with the
particle's moduli; that of the first step, as Uintah's, sqrt((K_max + 4/3 K_max) V/m) with
the largest bulk modulus of the entries for both moduli.  It needs <MPM><withColor>true.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numba import njit

from .comp_neo_hook_plastic import SQ23, _abt, _det, _inv, _load, _mul, initial_state as _ucnh_initial_state
from ._common import max_wavespeed

ENERGY_IS_INCREMENT = False
USES_COLOR = True
ENTRY = ("color", "bulk_modulus", "shear_modulus", "yield_stress", "hardening_modulus")


@dataclass(frozen=True)
class Params:
    colors: tuple
    bulk_modulus: tuple
    shear_modulus: tuple
    yield_stress: tuple
    hardening_modulus: tuple
    density: float
    usePlasticity: bool = False
    alpha: float = 0.0                    # the initial p.plasticStrain is 0, as Uintah's

    def table(self):
        """(colors, K, G, sigma_y, H) as arrays for the kernel."""
        return tuple(np.array(v, float) for v in (self.colors, self.bulk_modulus, self.shear_modulus,
                                                  self.yield_stress, self.hardening_modulus))


def read_params(cm, material, props):
    """The model's node: <variable_properties>, <usePlasticity>; <useInitialStress> false only."""
    vp = cm.child("variable_properties", required=True)
    rows = []
    for e in vp.children("entry"):
        rows.append((e.get("color"), e.get("bulk_modulus", above=0.0), e.get("shear_modulus", at_least=0.0),
                     e.get("yield_stress", at_least=0.0), e.get("hardening_modulus", at_least=0.0)))
    if len(rows) < 2:
        raise vp.error("<variable_properties> needs at least two <entry>s (Uintah: Need at least two entries "
                       "in Var model)")
    if any(b[0] <= a[0] for a, b in zip(rows, rows[1:])):
        raise vp.error("the <entry>s' <color>s must increase")
    if cm.get("useInitialStress", "bool", False):
        raise cm.child("useInitialStress").error("<useInitialStress> true is not implemented; accepted: false")
    cols = list(zip(*rows))
    return Params(*(tuple(c) for c in cols), density=props["density"],
                  usePlasticity=cm.get("usePlasticity", "bool", False))


def state_of(params):
    return ("p.plasticStrain", "p.bElBar") if params.usePlasticity else None


def initial_state(params, n, temperature=None):
    """p.plasticStrain = 0, p.bElBar = I."""
    return _ucnh_initial_state(params, n)


@njit(cache=True, inline="always")
def properties(color, C, K, G, Y, H):
    """(K, G, sigma_y, H) at this color: linear between the entries around it (extended below
    the first)."""
    n = C.shape[0]
    if color >= C[n - 1]:
        return K[n - 1], G[n - 1], Y[n - 1], H[n - 1]
    for i in range(1, n):
        if color <= C[i]:
            s = (C[i] - color) / (C[i] - C[i - 1])
            return (K[i - 1] * s + K[i] * (1.0 - s), G[i - 1] * s + G[i] * (1.0 - s),
                    Y[i - 1] * s + Y[i] * (1.0 - s), H[i - 1] * s + H[i] * (1.0 - s))
    return K[0], G[0], Y[0], H[0]            # not reached (C[n-1] > color)


def make_kernel(plastic):
    """The update of every particle, with the UCNH return map (plastic) or elastic."""

    @njit(cache=True, fastmath={'contract'})
    def kernel(C, Kt, Gt, Yt, Ht, rho0, first, F_old, F_new, vol, mass, vel, color, alpha_old, be_old,
               alpha_new, be_new, stress_new, energy):
        ws = np.zeros(3)
        Kmax = Kt.max()
        for p in range(F_new.shape[0]):
            K, mu, sy, H = properties(color[p], C, Kt, Gt, Yt, Ht)
            Fn = _load(F_new, p)
            J = _det(Fn)
            if plastic:                               # bbar_trial = fbar bbar_old fbar^T
                f = _mul(Fn, _inv(_load(F_old, p)))
                c3 = 1.0 / np.cbrt(_det(f))
                fb = (c3 * f[0], c3 * f[1], c3 * f[2], c3 * f[3], c3 * f[4], c3 * f[5], c3 * f[6], c3 * f[7],
                      c3 * f[8])
                bt = _abt(_mul(fb, _load(be_old, p)), fb)
            else:                                     # bbar = J^(-2/3) F F^T
                c2 = 1.0 / np.cbrt(J) ** 2
                b = _abt(Fn, Fn)
                bt = (c2 * b[0], c2 * b[1], c2 * b[2], c2 * b[3], c2 * b[4], c2 * b[5], c2 * b[6], c2 * b[7],
                      c2 * b[8])
            Ie = (bt[0] + bt[4] + bt[8]) / 3.0
            d0, d4, d8 = bt[0] - Ie, bt[4] - Ie, bt[8] - Ie
            scale = 1.0
            if plastic:
                snorm = mu * np.sqrt(d0 * d0 + d4 * d4 + d8 * d8 + bt[1] * bt[1] + bt[2] * bt[2]
                                     + bt[3] * bt[3] + bt[5] * bt[5] + bt[6] * bt[6] + bt[7] * bt[7])
                a = alpha_old[p]
                ftrial = snorm - SQ23 * (H * a + sy)
                if ftrial > 0.0:                      # radial return (Simo and Hughes box 9.1)
                    mubar = Ie * mu
                    dgamma = (ftrial / (2.0 * mubar)) / (1.0 + H / (3.0 * mubar))
                    scale = 1.0 - 2.0 * mubar * dgamma / snorm
                    a += SQ23 * dgamma
                    bt = (scale * d0 + Ie, scale * bt[1], scale * bt[2], scale * bt[3], scale * d4 + Ie,
                          scale * bt[5], scale * bt[6], scale * bt[7], scale * d8 + Ie)
                alpha_new[p] = a
                for i in range(3):
                    for j in range(3):
                        be_new[p, i, j] = bt[3 * i + j]
            iJ = 1.0 / J
            pr = 0.5 * K * (J - iJ)
            c = mu * iJ                               # sigma = p I + mu dev(bbar)/J
            stress_new[p, 0, 0] = c * scale * d0 + pr
            stress_new[p, 1, 1] = c * scale * d4 + pr
            stress_new[p, 2, 2] = c * scale * d8 + pr
            stress_new[p, 0, 1] = c * bt[1]
            stress_new[p, 1, 0] = c * bt[3]
            stress_new[p, 0, 2] = c * bt[2]
            stress_new[p, 2, 0] = c * bt[6]
            stress_new[p, 1, 2] = c * bt[5]
            stress_new[p, 2, 1] = c * bt[7]
            U = 0.5 * K * (0.5 * (J * J - 1.0) - np.log(J))
            W = 0.5 * mu * (bt[0] + bt[4] + bt[8] - 3.0)
            energy[p] = (U + W) * vol[p] * iJ
            if first:
                cs = np.sqrt((Kmax + 4.0 * Kmax / 3.0) * vol[p] / mass[p])
            else:
                cs = np.sqrt((K + 4.0 * mu / 3.0) * J / rho0)
            max_wavespeed(ws, cs, vel, p)
        return ws

    return kernel


KERNELS = {True: make_kernel(True), False: make_kernel(False)}


def update(params, L, F_old, F_new, vol, mass, vel, dt, stress_old, stress_new, energy, old=None, new=None,
           color=None):
    """Stress from F_old, F_new, p.color and the state (alpha, bElBar) old -> new (plastic);
    returns the wave speed (3,). L and stress_old unused; dt = 0 is the first step's."""
    C, K, G, Y, H = params.table()
    if params.usePlasticity:
        (a_old, be_old), (a_new, be_new) = old, new
    else:
        a_old = a_new = np.zeros(0)
        be_old = be_new = np.zeros((0, 3, 3))
    return KERNELS[params.usePlasticity](C, K, G, Y, H, params.density, dt == 0.0, F_old, F_new, vol, mass, vel,
                                         color, a_old, be_old, a_new, be_new, stress_new, energy)
