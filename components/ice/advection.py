"""Numba kernels of the ICE Eulerian phase (paper 000 sec. 3.3 step 12): advection.

Mass is fluxed through each face with the face velocity u*: the flux volume is the
slab u* dt A next to the face in the donor cell. First order takes the donor cell's
value; second order adds the van Leer limited slope along the face normal evaluated
at the slab's centroid (a distance (1 - |u* dt/dx|) dx/2 from the donor's centre).
Momentum, internal energy and material volume are fluxed *compatibly*: the mass flux
times the reconstructed specific value (velocity, e, v), so a uniform velocity or
temperature stays exactly uniform and every flux leaves one cell and enters the
other (mass, momentum and energy are conserved to round-off).
"""
from __future__ import annotations

import numpy as np
from numba import njit

NQ = 7  # mass, velocity x/y/z, specific internal energy, specific volume, specific total energy


@njit(cache=True)
def advect_start(mass, mom, eng, volm, rho_o, vel_o, temp_o, spv_o, lo, hi, tot, tot_o, with_e):
    """Copy the Lagrangian totals into the output arrays, which then accumulate fluxes."""
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


@njit(cache=True)
def _specific(mass, mom, eng, volm, a, b, c, q, tot, with_e):
    m = mass[a, b, c]
    q[6] = tot[a, b, c] / m if with_e else 0.0
    q[0] = m
    q[1] = mom[a, b, c, 0] / m
    q[2] = mom[a, b, c, 1] / m
    q[3] = mom[a, b, c, 2] / m
    q[4] = eng[a, b, c] / m
    q[5] = volm[a, b, c] / m


@njit(cache=True)
def _van_leer(a, b):
    if a * b <= 0.0:
        return 0.0
    return 2.0 * a * b / (a + b)


@njit(cache=True)
def advect_dir(mass, mom, eng, volm, uf, sh, dd, flo, fhi, lo, hi, dt, dx, second,
               rho_o, vel_o, temp_o, spv_o, transverse, dims, dxs, tot, tot_o, with_e):
    """Add the fluxes through the faces [flo, fhi) of one direction to the cells [lo, hi).

    `transverse` (second order only): the face value is also moved half a step back
    along the donor cell's velocity in the other directions, q -= dt/2 v_t dq/dx_t
    (limited slopes), which supplies the cross terms u v dt d2q/dxdy that a purely
    normal reconstruction lacks; without them oblique flow is first order in time.
    """
    qd = np.empty(NQ)
    qa = np.empty(NQ)
    qm = np.empty(NQ)
    qp = np.empty(NQ)
    face = np.empty(NQ)
    nx, ny, nz = mass.shape
    for i in range(flo[0], fhi[0]):
        for j in range(flo[1], fhi[1]):
            for k in range(flo[2], fhi[2]):
                u = uf[i, j, k]
                if u == 0.0:
                    continue
                r0, r1, r2 = i + sh[0], j + sh[1], k + sh[2]
                l0, l1, l2 = r0 - dd[0], r1 - dd[1], r2 - dd[2]
                if u > 0.0:
                    d0, d1, d2, s = l0, l1, l2, 1.0
                else:
                    d0, d1, d2, s = r0, r1, r2, -1.0
                cfl = abs(u) * dt / dx
                _specific(mass, mom, eng, volm, d0, d1, d2, qd, tot, with_e)
                for q in range(NQ):
                    face[q] = qd[q]
                if second:
                    a0, a1, a2 = d0 - dd[0], d1 - dd[1], d2 - dd[2]
                    b0, b1, b2 = d0 + dd[0], d1 + dd[1], d2 + dd[2]
                    if a0 >= 0 and a1 >= 0 and a2 >= 0 and b0 < nx and b1 < ny and b2 < nz:
                        _specific(mass, mom, eng, volm, a0, a1, a2, qm, tot, with_e)
                        _specific(mass, mom, eng, volm, b0, b1, b2, qp, tot, with_e)
                        w = 0.5 * s * (1.0 - cfl)
                        for q in range(NQ):
                            face[q] += w * _van_leer(qd[q] - qm[q], qp[q] - qd[q])
                    if transverse:
                        for t in range(3):
                            if not dims[t] or dd[t] == 1:
                                continue
                            e0, e1, e2 = (1, 0, 0) if t == 0 else ((0, 1, 0) if t == 1 else (0, 0, 1))
                            a0, a1, a2 = d0 - e0, d1 - e1, d2 - e2
                            b0, b1, b2 = d0 + e0, d1 + e1, d2 + e2
                            if a0 >= 0 and a1 >= 0 and a2 >= 0 and b0 < nx and b1 < ny and b2 < nz:
                                _specific(mass, mom, eng, volm, a0, a1, a2, qa, tot, with_e)
                                _specific(mass, mom, eng, volm, b0, b1, b2, qp, tot, with_e)
                                wt = -0.5 * dt * qd[1 + t] / dxs[t]
                                for q in range(NQ):
                                    face[q] += wt * _van_leer(qd[q] - qa[q], qp[q] - qd[q])
                fm = cfl * s * face[0]              # signed mass leaving L for R
                inL = lo[0] <= l0 < hi[0] and lo[1] <= l1 < hi[1] and lo[2] <= l2 < hi[2]
                inR = lo[0] <= r0 < hi[0] and lo[1] <= r1 < hi[1] and lo[2] <= r2 < hi[2]
                if inL:
                    rho_o[l0, l1, l2] -= fm
                    vel_o[l0, l1, l2, 0] -= fm * face[1]
                    vel_o[l0, l1, l2, 1] -= fm * face[2]
                    vel_o[l0, l1, l2, 2] -= fm * face[3]
                    temp_o[l0, l1, l2] -= fm * face[4]
                    spv_o[l0, l1, l2] -= fm * face[5]
                    if with_e:
                        tot_o[l0, l1, l2] -= fm * face[6]
                if inR:
                    rho_o[r0, r1, r2] += fm
                    vel_o[r0, r1, r2, 0] += fm * face[1]
                    vel_o[r0, r1, r2, 1] += fm * face[2]
                    vel_o[r0, r1, r2, 2] += fm * face[3]
                    temp_o[r0, r1, r2] += fm * face[4]
                    spv_o[r0, r1, r2] += fm * face[5]
                    if with_e:
                        tot_o[r0, r1, r2] += fm * face[6]


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
