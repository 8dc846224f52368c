"""Compressible viscous ideal-gas fluid material points (004 sec. 3.3).

    sigma = 2 mu D - 2/3 mu tr(D) I - (p + q) I              (004 eq. 21)
    p     = (gamma - 1) rho e                                (004 eq. 22)
    e^{k+1} = e^k + dt sigma^{k+1} : D / rho^{k+1}           (004 eq. 23)
    q     = c_max g rho lambda~ |D_v| (c1 + c2 |div v| / max|div v|),
            only where div v < 0                              (004 eqs. 24-25)

Eq. 23 is solved exactly for e^{k+1} (p is linear in e):
    e^{k+1} = (e^k + dt/rho (2 mu D':D' - q div v)) / (1 + (gamma-1) dt div v).
q is taken with the sign that raises the pressure in compression; c_max is
the largest sound speed sqrt(gamma (gamma-1) e) and max|div v| the largest
over the material on the whole level (the component reduces them before the stress
update: MPM::artificialViscosityScale); without them, over the particles passed in.

Tags: ``gamma``, ``viscosity`` (mu), optional ``specific_heat`` (not used
here), ``artificial_viscosity`` (bool), ``av_g`` (g, e.g. sqrt(2) dx),
``av_lambda`` (lambda~, 0.75 in 004), ``artificial_viscosity_coeff1`` (c1),
``artificial_viscosity_coeff2`` (c2), ``reference_pressure`` (p_ref, default 0:
pysus): the stress the grid sees is taken relative to an ambient p_ref, as for a gas
whose container and pistons carry p_ref on their outer faces (004 eq. 26 uses the
perturbation pressure); e and p stay absolute.  State: specific internal energy e.
``energy`` receives the internal energy INCREMENT m (e^{k+1} - e^k).
Wave speed c = sqrt(gamma p / rho) (viscous limit not included).
"""
from dataclasses import dataclass

import numpy as np
from numba import njit

from ._common import _get, max_wavespeed

ENERGY_IS_INCREMENT = True


@dataclass(frozen=True)
class Params:
    gamma: float = 1.4
    viscosity: float = 0.0
    specific_heat: float = 0.0
    artificial_viscosity: bool = False
    av_g: float = 0.0
    av_lambda: float = 0.75
    artificial_viscosity_coeff1: float = 1.0
    artificial_viscosity_coeff2: float = 1.0
    reference_pressure: float = 0.0
    density_from_cells: bool = False

    @classmethod
    def from_ups(cls, d):
        def flag(key):
            return str(d.get(key, "false")).strip().lower() in ("true", "1")
        return cls(_get(d, "gamma", 1.4), _get(d, "viscosity", 0.0),
                   _get(d, "specific_heat", 0.0), flag("artificial_viscosity"), _get(d, "av_g", 0.0),
                   _get(d, "av_lambda", 0.75), _get(d, "artificial_viscosity_coeff1", 1.0),
                   _get(d, "artificial_viscosity_coeff2", 1.0), _get(d, "reference_pressure", 0.0),
                   flag("density_from_cells"))


@njit(cache=True)
def kernel(gamma, mu, use_av, g, lam, c1, c2, L, vol, mass, vel, dt, e_old, e_new,
           stress_new, energy, p_ref=0.0, cmax_in=-1.0, dmax_in=-1.0):
    n = L.shape[0]
    cmax = 0.0
    dmax = 0.0
    if use_av and cmax_in >= 0.0:
        cmax = cmax_in
        dmax = dmax_in
    elif use_av:
        for p in range(n):
            cmax = max(cmax, np.sqrt(max(gamma * (gamma - 1.0) * e_old[p], 0.0)))
            dmax = max(dmax, abs(L[p, 0, 0] + L[p, 1, 1] + L[p, 2, 2]))
    ws = np.zeros(3)
    for p in range(n):
        rho = mass[p] / vol[p]
        div = L[p, 0, 0] + L[p, 1, 1] + L[p, 2, 2]
        q = 0.0
        if use_av and div < 0.0:  # eqs. 24-25
            q = cmax * g * rho * lam * (-div) * (c1 + c2 * abs(div) / dmax)
        visc = 0.0  # 2 mu D':D'
        for i in range(3):
            for j in range(3):
                Dij = 0.5 * (L[p, i, j] + L[p, j, i]) - (div / 3.0 if i == j else 0.0)
                visc += Dij * Dij
        visc *= 2.0 * mu
        en = (e_old[p] + dt / rho * (visc - q * div)) / (1.0 + (gamma - 1.0) * dt * div)  # eq. 23
        e_new[p] = en
        pr = (gamma - 1.0) * rho * en  # eq. 22
        for i in range(3):
            for j in range(3):
                Dij = 0.5 * (L[p, i, j] + L[p, j, i]) - (div / 3.0 if i == j else 0.0)
                stress_new[p, i, j] = 2.0 * mu * Dij - (pr + q - p_ref if i == j else 0.0)  # eq. 21
        energy[p] = mass[p] * (en - e_old[p])
        max_wavespeed(ws, np.sqrt(max(gamma * pr / rho, 0.0)), vel, p)
    return ws


@njit(cache=True)
def av_scale(gamma, L, e_old):
    """(largest sound speed, largest |div v|) of these particles (eq. 24's scales)."""
    cmax = 0.0
    dmax = 0.0
    for p in range(L.shape[0]):
        cmax = max(cmax, np.sqrt(max(gamma * (gamma - 1.0) * e_old[p], 0.0)))
        dmax = max(dmax, abs(L[p, 0, 0] + L[p, 1, 1] + L[p, 2, 2]))
    return cmax, dmax


@njit(cache=True)
def _cell_keys(px, anchor, dx, lo, ext, out):
    """Flat index of each point's cell in the box lo + [0, ext); -1 outside it."""
    for p in range(px.shape[0]):
        k = 0
        for d in range(3):
            c = int(np.floor((px[p, d] - anchor[d]) / dx[d])) - lo[d]
            if c < 0 or c >= ext[d]:
                k = -1
                break
            k = k * ext[d] + c
        out[p] = k


@njit(cache=True)
def cell_volumes(px, pid, anchor, dx, mass, vol, other_px):
    """Fluid point volumes from the cells they lie in, in place. A cell that holds no point
    of another material is full of this fluid: its points get the density (their mass) /
    (cell volume). A cell shared with another material (a membrane through it) keeps the
    sum of its points' V0 det F and shares it at one density. V = V0 det F drifts point by
    point (the grid sees neither how a cell's volume is split among its points nor the
    excess of their sum over the cell, so nothing restores it) until Sigma V outgrows the
    region the fluid fills; taking the density from the mass in the cell, as PIC/FLIP do
    on their grid, ties it to where the points are. For an ideal gas V p = (gamma-1) m e
    is unchanged, so the grid forces of the step are too. Sums in particle-ID order within
    a cell: the same on any patch layout (a cell's points all live on one patch)."""
    n = px.shape[0]
    if n == 0:
        return
    lo = np.full(3, np.iinfo(np.int64).max)
    hi = np.full(3, np.iinfo(np.int64).min)
    for p in range(n):
        for d in range(3):
            c = int(np.floor((px[p, d] - anchor[d]) / dx[d]))
            lo[d] = min(lo[d], c)
            hi[d] = max(hi[d], c)
    ext = hi - lo + 1
    key = np.empty(n, np.int64)
    _cell_keys(px, anchor, dx, lo, ext, key)
    okey = np.empty(other_px.shape[0], np.int64)
    _cell_keys(other_px, anchor, dx, lo, ext, okey)
    okey = np.sort(okey)
    vcell = dx[0] * dx[1] * dx[2]
    by_id = np.argsort(pid, kind="mergesort")
    order = by_id[np.argsort(key[by_id], kind="mergesort")]
    a = 0
    while a < n:
        kk = key[order[a]]
        b = a
        sm = 0.0
        sv = 0.0
        while b < n and key[order[b]] == kk:
            sm += mass[order[b]]
            sv += vol[order[b]]
            b += 1
        j = np.searchsorted(okey, kk)
        if j >= okey.shape[0] or okey[j] != kk:
            sv = vcell
        for i in range(a, b):
            vol[order[i]] = mass[order[i]] * sv / sm
        a = b


def update(params, L, F_old, F_new, vol, mass, vel, dt, stress_old, stress_new, energy,
           e_old, e_new, scale=None):
    """Update stress and specific internal energy; returns wave speed (3,). `scale`:
    the level-wide (c_max, max|div v|) of this material, else taken from these particles."""
    P = params
    cm, dm = scale if scale is not None else (-1.0, -1.0)
    return kernel(P.gamma, P.viscosity, bool(P.artificial_viscosity), P.av_g, P.av_lambda,
                  P.artificial_viscosity_coeff1, P.artificial_viscosity_coeff2, L, vol,
                  mass, vel, dt, e_old, e_new, stress_new, energy, P.reference_pressure, cm, dm)
