"""Uintah's slip exchange model: the momentum and heat exchange of a gas with a solid surface
slowed by the gas's mean free path (Maxwell's slip and temperature-jump boundary conditions
written as exchange coefficients; Uintah's ExchangeModels::SlipExch).

    <exchange_properties>
      <Model type="slip">
        <fluidMatlIndex> 1 </fluidMatlIndex>   <solidMatlIndex> 0 </solidMatlIndex>
        <momentum_accommodation_coeff> a_v </momentum_accommodation_coeff>
        <thermal_accommodation_coeff>  a_t </thermal_accommodation_coeff>
        <useSlipCoeffs> true </useSlipCoeffs>          (default false)
      </Model>
      <exchange_coefficients> <momentum> [K] </momentum> <heat> [H] </heat> </exchange_coefficients>
    </exchange_properties>

The solid's surface cells are those where, of the solid's eight node masses around the cell,
at least one is zero and the largest exceeds 1e-12 V (Uintah's ComputeSurfaceNormal); the
surface normal n is the direction of minus the gradient of those masses, the rotation Q has n
as its second row. lambda = v / sqrt(2 cv (gamma - 1) T / pi) (the gas's mean free path over
its viscosity, from the start of the step). With useSlipCoeffs, in a surface cell:

    K_slip = A_V / (beta_v lambda theta_s),    beta_v = (2 - a_v) / a_v,
    H_slip = A_V / (beta_t lambda theta_s),    beta_t = (2 - a_t) / a_t  2 / (1 + gamma) / cv,
    A_V = 1 / (dx |n_x| + dy |n_y| + dz |n_z|),

each at most the deck's coefficient (1e15 on faces). Faces: the exchange of eq. 28+38 with
theta_n K on a face the mean of theta_n K_slip of its two cells (K = 1e15 in cells that are not
surface cells, and everywhere without useSlipCoeffs: the face exchange then ignores <momentum>).
Cells: eq. 38 in the frame of Q, K_slip along the two tangential directions and K along the
normal, and eq. 39 with H_slip. Without useSlipCoeffs the cell exchange is the scalar one.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numba import njit

from framework import labels as L
from framework.variables import VarType

from .kernels import _exchange_matrix, solve_small

CC = VarType.CC
K_FACE = 1e15           # Uintah's face coefficient of the slip model outside surface cells
TINY_RHO = 1e-12        # surface cell: largest node mass above TINY_RHO * V

surfaceNorm = L.create("surfaceNorm", CC, (3,))                     # the solid's outward surface normal
isSurfaceCell = L.create("isSurfaceCell", CC, dtype=np.int64)       # 1 in the solid's surface cells
meanFreePath = L.create("meanFreePath", CC)                         # the gas's lambda / viscosity
vel_CCTransposed = L.create("vel_CCTransposed", CC, (3,))           # Q u before the exchange (surface cells)
slipK_CC = L.create("slipK_CC", CC)                                 # the face exchange's K of each cell


@dataclass
class Slip:
    """The <Model type="slip"> of <exchange_properties>."""
    fluid: int
    solid: int
    a_v: float
    a_t: float
    use_coeffs: bool


def read_slip(exch, n_all, n_before, mpm_matls=()):
    """The slip model of <exchange_properties> (None without a <Model>); only MPMICE has the
    solid's node masses it needs."""
    node = exch.child("Model") if exch is not None else None
    if node is None:
        return None
    node.attr("type", choices=("slip",))
    if not n_before:
        raise node.error('the slip exchange model needs an MPM solid (its surface comes from the node masses); '
                         'accepted in MPMICE')
    out = Slip(node.get("fluidMatlIndex", "int"), node.get("solidMatlIndex", "int"),
               node.get("momentum_accommodation_coeff", "float", above=0.0),
               node.get("thermal_accommodation_coeff", "float", above=0.0),
               node.get("useSlipCoeffs", "bool", False))
    if not n_before <= out.fluid < n_all:
        raise node.child("fluidMatlIndex").error(f"{out.fluid} is not an ICE material; accepted: "
                                                 f"{n_before} to {n_all - 1} (MPM materials first)")
    if not 0 <= out.solid < n_before:
        raise node.child("solidMatlIndex").error(f"{out.solid} is not an MPM material; accepted: 0 to {n_before - 1}")
    return out


@njit(cache=True, inline="always")
def _normal_row(nx, ny, nz):
    """Row 1 of Uintah's surface rotation Q (the normal, or y when n is within 1e-4 of it)."""
    if abs(ny) > 0.9999:
        return 0.0, 1.0, 0.0
    return nx, ny, nz


@njit(cache=True)
def rotation(nx, ny, nz, Q):
    """Uintah's computeSurfaceRotationMatrix: Q with the normal as row 1 (identity if n ~ +-y)."""
    Q[:, :] = 0.0
    if abs(ny) > 0.9999:
        for d in range(3):
            Q[d, d] = 1.0
        return
    s = 1.0 / np.sqrt(1.0 - ny * ny)
    Q[1, 0], Q[1, 1], Q[1, 2] = nx, ny, nz
    Q[0, 0], Q[0, 1], Q[0, 2] = ny, -nx, ny * nz * s
    Q[2, 0], Q[2, 1], Q[2, 2] = -nz * s, 0.0, nx * s


@njit(cache=True, inline="always")
def _area_per_volume(n, dx):
    r0, r1, r2 = _normal_row(n[0], n[1], n[2])
    return 1.0 / (dx[0] * abs(r0) + dx[1] * abs(r1) + dx[2] * abs(r2))


@njit(cache=True)
def surface_cells(gmass, node_low, cc_low, lo, hi, dims, n_lo, n_hi, dx, norm, surf):
    """The solid's surface cells and normals (Uintah's ComputeSurfaceNormal): of the eight node
    masses around a cell (NC_CCweight: 1/8, doubled per domain face the node lies on) at least
    one zero and the largest above TINY_RHO V; n = -grad m / |grad m| (minus side minus plus side)."""
    vol = dx[0] * dx[1] * dx[2]
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                gi, gj, gk = i + cc_low[0], j + cc_low[1], k + cc_low[2]
                mx = 1e-100
                mn = 1e100
                g = np.zeros(3)
                for a in range(2):
                    for b in range(2):
                        for c in range(2):
                            x = gi + a - node_low[0] if dims[0] else 0
                            y = gj + b - node_low[1] if dims[1] else 0
                            z = gk + c - node_low[2] if dims[2] else 0
                            w = 0.125
                            if gi + a == n_lo[0] or gi + a == n_hi[0]:
                                w *= 2.0
                            if gj + b == n_lo[1] or gj + b == n_hi[1]:
                                w *= 2.0
                            if gk + c == n_lo[2] or gk + c == n_hi[2]:
                                w *= 2.0
                            m = w * gmass[x, y, z]
                            mx = max(mx, m)
                            mn = min(mn, m)
                            g[0] += m * (1 - 2 * a)
                            g[1] += m * (1 - 2 * b)
                            g[2] += m * (1 - 2 * c)
                if (mx - mn) / mx == 1.0 and mx > TINY_RHO * vol:
                    gn = np.sqrt((g[0] / dx[0]) ** 2 + (g[1] / dx[1]) ** 2 + (g[2] / dx[2]) ** 2)
                    if gn > 0.0:
                        for d in range(3):
                            norm[i, j, k, d] = g[d] / dx[d] / gn
                        surf[i, j, k] = 1


@njit(cache=True, error_model="numpy")
def mean_free_path(sp_vol, temp, cv, gamma, out):
    """lambda / mu = v / sqrt(2 cv (gamma - 1) T / pi) in every cell of the arrays."""
    c = 2.0 * cv * (gamma - 1.0) / np.pi
    for i in range(out.shape[0]):
        for j in range(out.shape[1]):
            for k in range(out.shape[2]):
                out[i, j, k] = sp_vol[i, j, k] / np.sqrt(c * temp[i, j, k])


@njit(cache=True, error_model="numpy")
def face_coefficients(surf, norm, mfp, vf_s, dx, a_v, use, lo, hi, out):
    """K of every cell lo..hi for the face exchange: K_FACE, or in a surface cell with
    useSlipCoeffs min(A_V / (beta_v lambda theta_s), K_FACE)."""
    beta = (2.0 - a_v) / a_v
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                out[i, j, k] = K_FACE
                if use and surf[i, j, k]:
                    kv = _area_per_volume(norm[i, j, k], dx) / (beta * mfp[i, j, k] * vf_s[i, j, k])
                    out[i, j, k] = min(kv, K_FACE)


@njit(cache=True, error_model="numpy")
def exchange_surface_cells(masses, moms, engs, vfs, sps, cvs, surf, norm, mfp, gamma_g, dx, gm, sm, a_v, a_t,
                           mom_out, eng_out, lo, hi, dt, K, H):
    """Eqs. 38-39 again in the surface cells (the other cells keep the scalar exchange): the
    momentum's change along each row of Q with K_slip along the tangents, taken back with
    Q^T (Uintah's SlipExch vel_CC_exchange; Q is not orthogonal off the axes, so the change,
    not the rotated velocity, goes back), and the heat with H_slip. As exchange_cells, each
    system is solved for the deviation from the conserved mass- (m cv-) weighted mean."""
    n = len(masses)
    a = np.empty((n, n))
    b = np.empty(n)
    th = np.empty(n)
    sv = np.empty(n)
    cvv = np.empty(n)
    Kt = np.empty((n, n))
    Ht = np.empty((n, n))
    Q = np.empty((3, 3))
    uT = np.empty((n, 3))
    ub = np.empty(3)
    for m in range(n):
        cvv[m] = cvs[m]
    beta_v = (2.0 - a_v) / a_v
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                if not surf[i, j, k]:
                    continue
                nrm = norm[i, j, k]
                rotation(nrm[0], nrm[1], nrm[2], Q)
                av_ = _area_per_volume(nrm, dx)
                lam_th = mfp[i, j, k] * vfs[sm][i, j, k]
                Kt[:, :] = K
                Kt[gm, sm] = Kt[sm, gm] = min(av_ / (beta_v * lam_th), K[gm, sm])
                beta_t = (2.0 - a_t) / a_t * (2.0 / (1.0 + gamma_g)) / cvv[gm]
                Ht[:, :] = H
                Ht[gm, sm] = Ht[sm, gm] = min(av_ / (beta_t * lam_th), H[gm, sm])
                msum = 0.0
                esum = 0.0
                for m in range(n):
                    th[m] = vfs[m][i, j, k]
                    sv[m] = sps[m][i, j, k]
                    msum += masses[m][i, j, k]
                    esum += masses[m][i, j, k] * cvv[m]
                for d in range(3):
                    ub[d] = 0.0
                    for m in range(n):
                        ub[d] += moms[m][i, j, k, d]
                    ub[d] /= msum
                for m in range(n):
                    for r in range(3):
                        s = 0.0
                        for d in range(3):
                            s += Q[r, d] * moms[m][i, j, k, d] / masses[m][i, j, k]
                        uT[m, r] = s
                for r in range(3):          # r = 1: along the normal, the deck's K
                    ubr = Q[r, 0] * ub[0] + Q[r, 1] * ub[1] + Q[r, 2] * ub[2]
                    for m in range(n):
                        b[m] = uT[m, r] - ubr
                    _exchange_matrix(a, th, sv, K if r == 1 else Kt, dt, n, None)
                    dev = b.copy()
                    solve_small(a, b, n)
                    for m in range(n):
                        uT[m, r] = b[m] - dev[m]        # the exchange's change along row r
                for m in range(n):
                    for d in range(3):
                        du = Q[0, d] * uT[m, 0] + Q[1, d] * uT[m, 1] + Q[2, d] * uT[m, 2]
                        mom_out[m][i, j, k, d] = (moms[m][i, j, k, d] / masses[m][i, j, k] + du) * masses[m][i, j, k]
                tbar = 0.0
                for m in range(n):
                    tbar += engs[m][i, j, k]
                tbar /= esum
                for m in range(n):
                    b[m] = engs[m][i, j, k] / (masses[m][i, j, k] * cvv[m]) - tbar
                _exchange_matrix(a, th, sv, Ht, dt, n, cvv)
                solve_small(a, b, n)
                for m in range(n):
                    eng_out[m][i, j, k] = (tbar + b[m]) * masses[m][i, j, k] * cvv[m]


@njit(cache=True, error_model="numpy")
def transposed_velocity(mass, mom, surf, norm, out):
    """Q u of one material in the surface cells, zero elsewhere (Uintah's vel_CCTransposed)."""
    Q = np.empty((3, 3))
    for i in range(out.shape[0]):
        for j in range(out.shape[1]):
            for k in range(out.shape[2]):
                if not surf[i, j, k]:
                    continue
                nrm = norm[i, j, k]
                rotation(nrm[0], nrm[1], nrm[2], Q)
                for r in range(3):
                    s = 0.0
                    for d in range(3):
                        s += Q[r, d] * mom[i, j, k, d] / mass[i, j, k]
                    out[i, j, k, r] = s
