"""Numba kernels of the example component."""
from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True)
def diffuse(T, Tn, lo, hi, c):
    """Explicit heat equation: Tn = T + c . (second differences of T) over cells [lo, hi)."""
    cx, cy, cz = c[0], c[1], c[2]
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                t = T[i, j, k]
                lap = cx * (T[i - 1, j, k] - 2.0 * t + T[i + 1, j, k])
                if cy != 0.0:
                    lap += cy * (T[i, j - 1, k] - 2.0 * t + T[i, j + 1, k])
                if cz != 0.0:
                    lap += cz * (T[i, j, k - 1] - 2.0 * t + T[i, j, k + 1])
                Tn[i, j, k] = t + lap


@njit(cache=True)
def neumann_face(T, lo, hi, d, side):
    """Copy the first interior layer into the extra cells of one face (zero gradient)."""
    a0 = np.zeros(3, np.int64)
    a1 = np.array(T.shape, dtype=np.int64)
    if side == 0:
        a1[d] = lo[d]
        src = lo[d]
    else:
        a0[d] = hi[d]
        src = hi[d] - 1
    for i in range(a0[0], a1[0]):
        for j in range(a0[1], a1[1]):
            for k in range(a0[2], a1[2]):
                si = src if d == 0 else i
                sj = src if d == 1 else j
                sk = src if d == 2 else k
                T[i, j, k] = T[si, sj, sk]


@njit(cache=True)
def velocity_at(x, u0, omega, center):
    """Given velocity field: uniform u0 plus solid-body rotation omega about center (z axis)."""
    vx = u0[0] - omega * (x[1] - center[1])
    vy = u0[1] + omega * (x[0] - center[0])
    return vx, vy, u0[2]


@njit(cache=True)
def advect(px, pxn, dt, u0, omega, center):
    """Midpoint (RK2) step of dx/dt = v(x) for every particle."""
    h = np.empty(3)
    for p in range(px.shape[0]):
        vx, vy, vz = velocity_at(px[p], u0, omega, center)
        h[0] = px[p, 0] + 0.5 * dt * vx
        h[1] = px[p, 1] + 0.5 * dt * vy
        h[2] = px[p, 2] + 0.5 * dt * vz
        vx, vy, vz = velocity_at(h, u0, omega, center)
        pxn[p, 0] = px[p, 0] + dt * vx
        pxn[p, 1] = px[p, 1] + dt * vy
        pxn[p, 2] = px[p, 2] + dt * vz


@njit(cache=True)
def mass_to_nodes(px, pm, gm, anchor, dx, low, own_lo, own_hi, dims):
    """Linear (tent) interpolation of particle mass onto the nodes a patch owns."""
    for p in range(px.shape[0]):
        base = np.empty(3, np.int64)
        fx = np.empty(3)
        for d in range(3):
            if dims[d]:
                s = (px[p, d] - anchor[d]) / dx[d]
                b = int(np.floor(s))
                base[d] = b
                fx[d] = s - b
            else:
                base[d] = 0
                fx[d] = 0.0
        for a in range(2 if dims[0] else 1):
            wx = (fx[0] if a else 1.0 - fx[0]) if dims[0] else 1.0
            I = base[0] + a - low[0]
            if I < own_lo[0] or I >= own_hi[0]:
                continue
            for b in range(2 if dims[1] else 1):
                wy = (fx[1] if b else 1.0 - fx[1]) if dims[1] else 1.0
                J = base[1] + b - low[1]
                if J < own_lo[1] or J >= own_hi[1]:
                    continue
                for c in range(2 if dims[2] else 1):
                    wz = (fx[2] if c else 1.0 - fx[2]) if dims[2] else 1.0
                    K = base[2] + c - low[2]
                    if K < own_lo[2] or K >= own_hi[2]:
                        continue
                    gm[I, J, K] += pm[p] * wx * wy * wz


@njit(cache=True)
def helmholtz(p, q, lo, hi, c):
    """q = (I - c . second differences) p over [lo, hi): backward-Euler heat operator."""
    s = 0.0
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                t = p[i, j, k]
                lap = c[0] * (p[i - 1, j, k] - 2.0 * t + p[i + 1, j, k])
                if c[1] != 0.0:
                    lap += c[1] * (p[i, j - 1, k] - 2.0 * t + p[i, j + 1, k])
                if c[2] != 0.0:
                    lap += c[2] * (p[i, j, k - 1] - 2.0 * t + p[i, j, k + 1])
                q[i, j, k] = t - lap
                s += t * q[i, j, k]
    return s


@njit(cache=True)
def cg_update(x, r, p, q, xn, rn, zn, alpha, diag, lo, hi):
    """x += alpha p, r -= alpha q, z = r / diag (Jacobi); returns (r.z, r.r)."""
    rz = 0.0
    rr = 0.0
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                xn[i, j, k] = x[i, j, k] + alpha * p[i, j, k]
                rv = r[i, j, k] - alpha * q[i, j, k]
                rn[i, j, k] = rv
                zn[i, j, k] = rv / diag
                rz += rv * zn[i, j, k]
                rr += rv * rv
    return rz, rr


@njit(cache=True)
def cg_direction(z, p, pn, beta, lo, hi):
    """p_new = z + beta p."""
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                pn[i, j, k] = z[i, j, k] + beta * p[i, j, k]
