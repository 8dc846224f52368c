"""Prescribed deformation (Uintah's `<UsePrescribedDeformation>`, SerialMPM::setPrescribedMotion).

`<PrescribedDeformationFile>` lists lines `t F11 F12 F13 F21 F22 F23 F31 F32 F33 theta a1 a2 a3`
(times increasing): the deformation gradient at t, and a rotation by theta degrees about the
axis a superposed on it relative to the previous line.  Each step, after the grid boundary
conditions, every node gets v*_i = Fdot* F*^-1 x_i at the step's start time t (F linear in
time between the lines, the rotation's angle too; Fdot* = Qdot P F + Q P Fdot, F* = Q P F,
P the product of the earlier lines' rotations) and a_i = 0, so every particle's velocity
gradient is that of the prescribed motion.  The file name is taken as given (relative to
the working directory, as Uintah does), else relative to the deck's folder or its parents,
else the file of that name beside the deck.
"""
from __future__ import annotations

import os

import numpy as np
from numba import njit

from .constitutive._common import det3, matmul3


def find_file(name, deck):
    """The prescribed-deformation file: as given, then under the deck's folder and its
    parents, then beside the deck by its base name; None if none exists."""
    if os.path.isfile(name):
        return name
    d = os.path.dirname(os.path.abspath(deck))
    while True:
        cand = os.path.join(d, name)
        if os.path.isfile(cand):
            return cand
        up = os.path.dirname(d)
        if up == d:
            break
        d = up
    cand = os.path.join(os.path.dirname(os.path.abspath(deck)), os.path.basename(name))
    return cand if os.path.isfile(cand) else None


def read(node, deck):
    """(times, F (n, 3, 3), angle (degrees), axes (n, 3), the products of the rotations up to
    each line (n, 3, 3)) from the file named by `node`."""
    name = node.text().strip()
    path = find_file(name, deck)
    if path is None:
        raise node.error(f"prescribed deformation file '{name}' not found (looked in the working directory, "
                         "under the deck's folder and its parents, and beside the deck)")
    try:
        vals = np.array(open(path).read().split(), float)
    except ValueError:
        raise node.error(f"{path}: not a table of numbers (14 a line: t, F by rows, theta, axis)") from None
    rows = vals[:len(vals) // 14 * 14].reshape(-1, 14)
    if len(rows) < 2:
        raise node.error(f"{path}: needs at least two lines of 14 numbers")
    if np.any(np.diff(rows[:, 0]) <= 0):
        raise node.error(f"{path}: the times must increase")
    angle, axis = rows[:, 10].copy(), rows[:, 11:14].copy()
    before = np.empty((len(rows), 3, 3))       # Q_s ... Q_1 Q_0: the rotations up to line s
    P = np.eye(3)
    for i in range(len(rows)):
        P = _rot(angle[i] * np.pi / 180.0, axis[i]) @ P
        before[i] = P
    return rows[:, 0].copy(), rows[:, 1:10].reshape(-1, 3, 3).copy(), angle, axis, before


def _rot(theta, a):
    """Q = (I - a a) cos theta + A sin theta + a a, A the cross-product matrix of a."""
    aa = np.outer(a, a)
    A = np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])
    return (np.eye(3) - aa) * np.cos(theta) + A * np.sin(theta) + aa


def velocity_gradient(table, t):
    """M with v* = M x at time t (Uintah's Fdot* F^-1 P^-1 Q^T)."""
    times, F, angle, axis, before = table
    n = len(times)
    if t <= times[0]:
        s = 0
    elif t >= times[-1]:
        s = n - 2
    else:
        s = int(np.searchsorted(times, t, side="left")) - 1
    t1, t2 = times[s], times[s + 1]
    Ft = F[s] * (t2 - t) / (t2 - t1) + F[s + 1] * (t - t1) / (t2 - t1)
    Fdot = (F[s + 1] - F[s]) / (t2 - t1)
    deg = np.pi / 180.0
    theta = angle[s + 1] * deg * (t - t1) / (t2 - t1)
    a = axis[s + 1]
    Qt = _rot(theta, a)
    thetadot = angle[s + 1] * deg / (t2 - t1)
    aa = np.outer(a, a)
    A = np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])
    Qdot = (np.eye(3) - aa) * (-np.sin(theta) * thetadot) + A * np.cos(theta) * thetadot
    P = before[s]
    Fdot_star = Qdot @ P @ Ft + Qt @ P @ Fdot
    return Fdot_star @ np.linalg.inv(Ft) @ np.linalg.inv(P) @ Qt.T


@njit(cache=True)
def set_nodes(M, anchor, dx, low, gvs, ga):
    """v*_i = M x_i, a_i = 0 on every node of the patch's arrays."""
    nx, ny, nz = gvs.shape[0], gvs.shape[1], gvs.shape[2]
    for i in range(nx):
        x0 = anchor[0] + (low[0] + i) * dx[0]
        for j in range(ny):
            x1 = anchor[1] + (low[1] + j) * dx[1]
            for k in range(nz):
                x2 = anchor[2] + (low[2] + k) * dx[2]
                for d in range(3):
                    gvs[i, j, k, d] = M[d, 0] * x0 + M[d, 1] * x1 + M[d, 2] * x2
                    ga[i, j, k, d] = 0.0


@njit(cache=True)
def deform_series(L, F_old, dt, terms, F_new, vol_new):
    """F^{n+1} = exp(L dt) F^n by its Taylor series to `terms` terms (Uintah's
    minimum_subcycles_for_F < 0), or (I + L dt/n)^n F^n with n = max(terms, 2 int(|L| dt))
    substeps (> 0); V scales with det F."""
    for p in range(F_old.shape[0]):
        A = L[p] * dt
        if terms < 0:
            E = np.eye(3)
            T = np.eye(3)
            for k in range(-terms):
                T = matmul3(T, A) * (1.0 / (k + 1))
                E = E + T
            F = matmul3(E, F_old[p])
        else:
            n = min(max(terms, 2 * int(np.sqrt(np.sum(A * A)))), 10000)
            Op = np.eye(3) + L[p] * (dt / n)
            F = F_old[p].copy()
            for _ in range(n):
                F = matmul3(Op, F)
        vol_new[p] *= det3(F) / det3(F_new[p])
        F_new[p] = F
