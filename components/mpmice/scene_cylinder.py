"""Pressurized cylinder (paper 000 sec. 4.1): deck at a chosen resolution and the errors
against Lame's solution (eq. 42) and the paper's error measure (eq. 43).

    deck(n)  inputs/MPMICE/pressurized_cylinder.ups with n cells across the 1.2 m domain
             (dx = 1.2 / n; the paper's 0.025 m is n = 48)
    errors(da)  (a pysus DataArchive or a sus UintahArchive) at the last output: P = mean gauge pressure of the inner air (cells with
             r < 0.4 m); over all particles, eq. 43
                 mean | |s_r + s_t| - 2/3 P | / (2/3 P)      (ri^2 / (ro^2 - ri^2) = 1/3)
             and the L1 errors of s_r and s_t against eq. 42, relative to P.
Used by scripts/accuracy_cost.py (scene "cylinder") and tests/mpmice/test_cylinder.py.
"""
from __future__ import annotations

import os

import numpy as np

from framework.uintah_uda import particle_var

DECK = os.path.join(os.path.dirname(__file__), "..", "..", "inputs", "MPMICE", "pressurized_cylinder.ups")
RI, RO, L, P_REF = 0.5, 1.0, 1.2, 101325.0


def deck(n, damping=None, patches="1,1,1", t_end=None):
    text = open(DECK, encoding="iso-8859-1").read()
    dx = L / int(n)
    reps = [("<spacing> [0.025,0.025,0.025] </spacing>", f"<spacing> [{dx!r},{dx!r},0.025] </spacing>"),
            ("<patches> [2,2,1] </patches>", f"<patches> [{patches}] </patches>")]
    if damping is not None:
        reps.append(("<artificial_damping_coeff> 4000.0 </artificial_damping_coeff>",
                     f"<artificial_damping_coeff> {float(damping)!r} </artificial_damping_coeff>"))
    if t_end is not None:
        reps += [("<maxTime> 2.5e-3 </maxTime>", f"<maxTime> {float(t_end)!r} </maxTime>"),
                 ("<outputInterval> 2.5e-3 </outputInterval>", f"<outputInterval> {float(t_end)!r} </outputInterval>")]
    for old, new in reps:
        assert old in text, old
        text = text.replace(old, new)
    return text


def stresses(da, i=-1):
    """(r, s_r, s_t, P) at output i: particle radius, radial and hoop stress, inner gauge pressure."""
    x, s = particle_var(da, "p.x", 0, i), particle_var(da, "p.stress", 0, i)
    r = np.hypot(x[:, 0], x[:, 1])
    n = np.stack([x[:, 0] / r, x[:, 1] / r], axis=1)
    t = np.stack([-n[:, 1], n[:, 0]], axis=1)
    s_r = np.einsum("pi,pij,pj->p", n, s[:, :2, :2], n)
    s_t = np.einsum("pi,pij,pj->p", t, s[:, :2, :2], t)
    p, _ = da.read("press_CC", 0, i)
    nx, ny = p.shape[:2]
    dx, dy = L / nx, L / ny
    xc = (np.arange(nx) + 0.5) * dx
    yc = (np.arange(ny) + 0.5) * dy
    rc = np.hypot(xc[:, None], yc[None, :])
    P = float(p[..., 0][rc < 0.8 * RI].mean()) - P_REF
    return r, s_r, s_t, P


def lame(r, P):
    a = P * RI ** 2 / (RO ** 2 - RI ** 2)
    return a * (1 - RO ** 2 / r ** 2), a * (1 + RO ** 2 / r ** 2)


def errors(da):
    r, s_r, s_t, P = stresses(da)
    er, et = lame(r, P)
    two3 = 2.0 / 3.0 * P
    return {"eq43": float(np.mean(np.abs(np.abs(s_r + s_t) - two3)) / two3),
            "radial": float(np.mean(np.abs(s_r - er)) / P),
            "hoop": float(np.mean(np.abs(s_t - et)) / P),
            "P_MPa": P / 1e6}
