"""Numba kernels of the ICE Eulerian phase (paper 000 sec. 3.3 step 12): advection.

Mass is fluxed through each face with the face velocity u*: the flux volume is the
slab u* dt A next to the face in the donor cell. First order takes the donor cell's
value; second order adds the van Leer limited slope along the face normal evaluated
at the slab's centroid (a distance (1 - |u* dt/dx|) dx/2 from the donor's centre).
Momentum, internal energy and material volume are fluxed *compatibly*: the mass flux
times the reconstructed specific value (velocity, e, v), so a uniform velocity or
temperature stays exactly uniform and every flux leaves one cell and enters the
other (mass, momentum and energy are conserved to round-off).

One kernel call advects one material of one patch: the specific values q = Q/m are
computed once per cell into a scratch array (not three times per face), then each
direction's faces are swept in turn; the order of the sums per cell (x faces, then
y, then z, each in increasing index) is what makes the result independent of the
patch layout.
"""
from __future__ import annotations

import numpy as np
from numba import njit

NQ = 7  # mass, velocity x/y/z, specific internal energy, specific volume, specific total energy


@njit(cache=True, error_model="numpy")
def _van_leer(a, b):
    if a * b <= 0.0:
        return 0.0
    return 2.0 * a * b / (a + b)


@njit(cache=True, error_model="numpy")
def _specific_values(mass, mom, eng, volm, tot, with_e, q):
    """q = (m, (mu)/m, (me)/m, (mv)/m, E/m) in every stored cell (unused halo corners may hold garbage)."""
    nx, ny, nz = mass.shape
    for i in range(nx):
        for j in range(ny):
            for k in range(nz):
                m = mass[i, j, k]
                q[i, j, k, 0] = m
                q[i, j, k, 1] = mom[i, j, k, 0] / m
                q[i, j, k, 2] = mom[i, j, k, 1] / m
                q[i, j, k, 3] = mom[i, j, k, 2] / m
                q[i, j, k, 4] = eng[i, j, k] / m
                q[i, j, k, 5] = volm[i, j, k] / m
                q[i, j, k, 6] = tot[i, j, k] / m if with_e else 0.0


@njit(cache=True, error_model="numpy")
def _sweep(q, uf, d, sh, flo, fhi, lo, hi, dt, dxs, dims, second, transverse, nq,
           rho_o, vel_o, temp_o, spv_o, tot_o):
    """Add the fluxes through the d-faces [flo, fhi) to the cells [lo, hi).

    `transverse` (second order only): the face value is also moved half a step back
    along the donor cell's velocity in the other directions, q -= dt/2 v_t dq/dx_t
    (limited slopes), which supplies the cross terms u v dt d2q/dxdy that a purely
    normal reconstruction lacks; without them oblique flow is first order in time.
    """
    face = np.empty(NQ)
    n = q.shape[d]
    e0, e1, e2 = (1, 0, 0) if d == 0 else ((0, 1, 0) if d == 1 else (0, 0, 1))
    dx = dxs[d]
    for i in range(flo[0], fhi[0]):
        for j in range(flo[1], fhi[1]):
            for k in range(flo[2], fhi[2]):
                u = uf[i, j, k]
                if u == 0.0:
                    continue
                r0, r1, r2 = i + sh[0], j + sh[1], k + sh[2]
                l0, l1, l2 = r0 - e0, r1 - e1, r2 - e2
                if u > 0.0:
                    d0, d1, d2, s = l0, l1, l2, 1.0
                else:
                    d0, d1, d2, s = r0, r1, r2, -1.0
                cfl = abs(u) * dt / dx
                for c in range(nq):
                    face[c] = q[d0, d1, d2, c]
                if second:
                    dn = d0 * e0 + d1 * e1 + d2 * e2          # the donor's index along d
                    if dn >= 1 and dn + 1 < n:
                        w = 0.5 * s * (1.0 - cfl)
                        for c in range(nq):
                            qd = q[d0, d1, d2, c]
                            face[c] += w * _van_leer(qd - q[d0 - e0, d1 - e1, d2 - e2, c],
                                                     q[d0 + e0, d1 + e1, d2 + e2, c] - qd)
                    if transverse:
                        for t in range(3):
                            if not dims[t] or t == d:
                                continue
                            f0, f1, f2 = (1, 0, 0) if t == 0 else ((0, 1, 0) if t == 1 else (0, 0, 1))
                            tn = d0 * f0 + d1 * f1 + d2 * f2
                            if tn >= 1 and tn + 1 < q.shape[t]:
                                wt = -0.5 * dt * q[d0, d1, d2, 1 + t] / dxs[t]
                                for c in range(nq):
                                    qd = q[d0, d1, d2, c]
                                    face[c] += wt * _van_leer(qd - q[d0 - f0, d1 - f1, d2 - f2, c],
                                                              q[d0 + f0, d1 + f1, d2 + f2, c] - qd)
                fm = cfl * s * face[0]              # signed mass leaving L for R
                if l0 * e0 + l1 * e1 + l2 * e2 >= lo[d]:
                    rho_o[l0, l1, l2] -= fm
                    vel_o[l0, l1, l2, 0] -= fm * face[1]
                    vel_o[l0, l1, l2, 1] -= fm * face[2]
                    vel_o[l0, l1, l2, 2] -= fm * face[3]
                    temp_o[l0, l1, l2] -= fm * face[4]
                    spv_o[l0, l1, l2] -= fm * face[5]
                    if nq == NQ:
                        tot_o[l0, l1, l2] -= fm * face[6]
                if r0 * e0 + r1 * e1 + r2 * e2 < hi[d]:
                    rho_o[r0, r1, r2] += fm
                    vel_o[r0, r1, r2, 0] += fm * face[1]
                    vel_o[r0, r1, r2, 1] += fm * face[2]
                    vel_o[r0, r1, r2, 2] += fm * face[3]
                    temp_o[r0, r1, r2] += fm * face[4]
                    spv_o[r0, r1, r2] += fm * face[5]
                    if nq == NQ:
                        tot_o[r0, r1, r2] += fm * face[6]


@njit(cache=True, error_model="numpy")
def advect(mass, mom, eng, volm, tot, with_e, ux, uy, uz, shx, shy, shz, flo, fhi, lo, hi, dt, dxs, dims,
           second, transverse, q, rho_o, vel_o, temp_o, spv_o, tot_o):
    """Advect one material's Lagrangian totals (m, m u, m e, m v, E) over one step into the cells [lo, hi).

    flo, fhi: (3, 3) face ranges per direction; q: scratch of shape mass.shape + (NQ,).
    The outputs hold the advected totals (advect_finish turns them into primitives).
    """
    _specific_values(mass, mom, eng, volm, tot, with_e, q)
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                if with_e:
                    tot_o[i, j, k] = tot[i, j, k]
                rho_o[i, j, k] = mass[i, j, k]
                temp_o[i, j, k] = eng[i, j, k]
                spv_o[i, j, k] = volm[i, j, k]
                for c in range(3):
                    vel_o[i, j, k, c] = mom[i, j, k, c]
    nq = NQ if with_e else NQ - 1
    if dims[0]:
        _sweep(q, ux, 0, shx, flo[0], fhi[0], lo, hi, dt, dxs, dims, second, transverse, nq,
               rho_o, vel_o, temp_o, spv_o, tot_o)
    if dims[1]:
        _sweep(q, uy, 1, shy, flo[1], fhi[1], lo, hi, dt, dxs, dims, second, transverse, nq,
               rho_o, vel_o, temp_o, spv_o, tot_o)
    if dims[2]:
        _sweep(q, uz, 2, shz, flo[2], fhi[2], lo, hi, dt, dxs, dims, second, transverse, nq,
               rho_o, vel_o, temp_o, spv_o, tot_o)


@njit(cache=True)
def advect_finish(rho_o, vel_o, temp_o, spv_o, lo, hi, vol, cv):
    """Advected totals -> primitives: rho = m/V, u = (mu)/m, T = (me)/(m cv), v = (mv)/m."""
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                m = max(rho_o[i, j, k], 1e-300)
                rho_o[i, j, k] = m / vol
                temp_o[i, j, k] = temp_o[i, j, k] / (m * cv)
                spv_o[i, j, k] = spv_o[i, j, k] / m
                for c in range(3):
                    vel_o[i, j, k, c] = vel_o[i, j, k, c] / m


@njit(cache=True)
def energy_finish(rho_o, vel_o, temp_o, tot_o, lo, hi, vol, cv):
    """Conservative total energy -> temperature: e = E/m - |u|^2/2 where that is positive
    (elsewhere the advected internal energy stays). Returns the number of such cells."""
    bad = 0
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                m = rho_o[i, j, k] * vol
                u0, u1, u2 = vel_o[i, j, k, 0], vel_o[i, j, k, 1], vel_o[i, j, k, 2]
                e = tot_o[i, j, k] / m - 0.5 * (u0 * u0 + u1 * u1 + u2 * u2)
                if e > 0.0:
                    temp_o[i, j, k] = e / cv
                else:
                    bad += 1
    return bad
