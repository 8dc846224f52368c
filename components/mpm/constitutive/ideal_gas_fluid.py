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
``artificial_viscosity_coeff2`` (c2), ``density_from_grid`` (pysus, default false: the
points' volumes from the nodal mass each step, ``grid_volumes``; MUSL, linear
interpolation), ``reference_pressure`` (p_ref, default 0:
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
    density_from_grid: bool = False

    @classmethod
    def from_ups(cls, d):
        def flag(key):
            return str(d.get(key, "false")).strip().lower() in ("true", "1")
        return cls(_get(d, "gamma", 1.4), _get(d, "viscosity", 0.0),
                   _get(d, "specific_heat", 0.0), flag("artificial_viscosity"), _get(d, "av_g", 0.0),
                   _get(d, "av_lambda", 0.75), _get(d, "artificial_viscosity_coeff1", 1.0),
                   _get(d, "artificial_viscosity_coeff2", 1.0), _get(d, "reference_pressure", 0.0),
                   flag("density_from_grid"))


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


FULL = 0.9   # a node whose support the points claim to >= 90 % counts as full


@njit(cache=True)
def grid_volumes(px, anchor, dx, ncells, periodic, node_low, gmass, gvol, gvol_all, mass, vol, axi=False):
    """Fluid point volumes V_p = m_p / rho_p from the nodal densities (linear shape
    functions), in place: rho_p = sum_i S_ip rho_i over the nodes that carry this fluid.
    rho_i = m_i / (V_i f_i) at a node whose support is full (the points of all materials
    claim at least FULL V_i, V_i the integral of S_i over the domain: dx dy dz, halved per
    domain face it lies on), f_i = this fluid's share of the claimed volume; a node only
    partly covered (a free or membrane boundary) contributes the point's own V0 det F
    density instead.
    Why: V = V0 det F drifts point by point (the grid sees neither how a node's volume is
    split among the points nor by how much their sum exceeds it), so Sigma V outgrows the
    region the fluid fills; the nodal mass says where the points are, as the density of
    PIC/FLIP. For an ideal gas V p = (gamma-1) m e is unchanged, so are the step's forces.
    Collapsed directions (ncells 1) carry one node layer of weight 1.
    axi (axisymmetric, x = r, volumes and masses per radian): V_i = the integral of S_i r dr dy,
    r_i dx dy, and r_i dx/2 +- dx^2/6 (times dy) on the lower / upper r face; no z factor. A node
    on the axis is skipped (its ring has no volume, and the points' sum S_ip m_p over-weights it
    by 1/(2 n^2) for n points per cell in r, where elsewhere the sum is exact for a uniform
    fill): the points of the first cell take the density of the nodes at r = dx."""
    idx = np.zeros(3, np.int64)
    frac = np.zeros(3)
    node = np.zeros(3, np.int64)
    for p in range(px.shape[0]):
        for d in range(3):
            if ncells[d] > 1:
                s = (px[p, d] - anchor[d]) / dx[d]
                idx[d] = int(np.floor(s))
                frac[d] = s - idx[d]
        rho = 0.0
        wsum = 0.0
        for c in range(8):
            w = 1.0
            vi = 1.0
            skip = False
            for d in range(3):
                hi = (c >> d) & 1
                if ncells[d] == 1:
                    if hi:
                        skip = True
                    if not (axi and d == 2):
                        vi *= dx[d]
                    continue
                node[d] = idx[d] + hi
                w *= frac[d] if hi else 1.0 - frac[d]
                lower = not periodic[d] and node[d] == 0
                upper = not periodic[d] and node[d] == ncells[d]
                if axi and d == 0:
                    r = anchor[0] + node[0] * dx[0]
                    if r <= 0.5 * dx[0]:            # on the axis
                        skip = True
                    elif lower or upper:
                        vi *= 0.5 * r * dx[0] + (dx[0] * dx[0] / 6.0 if lower else -dx[0] * dx[0] / 6.0)
                    else:
                        vi *= r * dx[0]
                else:
                    vi *= 0.5 * dx[d] if lower or upper else dx[d]
            if skip or w <= 0.0:
                continue
            a, b, k = node[0] - node_low[0], node[1] - node_low[1], node[2] - node_low[2]
            gm = gmass[a, b, k]
            if gm <= 0.0:
                continue
            va = gvol_all[a, b, k]
            if va >= FULL * vi:
                rho += w * gm * va / (vi * gvol[a, b, k])
            else:
                rho += w * mass[p] / vol[p]
            wsum += w
        if rho > 0.0:
            vol[p] = mass[p] * wsum / rho


def update(params, L, F_old, F_new, vol, mass, vel, dt, stress_old, stress_new, energy,
           e_old, e_new, scale=None):
    """Update stress and specific internal energy; returns wave speed (3,). `scale`:
    the level-wide (c_max, max|div v|) of this material, else taken from these particles."""
    P = params
    cm, dm = scale if scale is not None else (-1.0, -1.0)
    return kernel(P.gamma, P.viscosity, bool(P.artificial_viscosity), P.av_g, P.av_lambda,
                  P.artificial_viscosity_coeff1, P.artificial_viscosity_coeff2, L, vol,
                  mass, vel, dt, e_old, e_new, stress_new, energy, P.reference_pressure, cm, dm)
