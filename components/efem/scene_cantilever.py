"""The cantilever of inputs/EFEM/cantilever.ups: its deflection from a run and beam theory, for
scripts/efem_cantilever.py and tests/efem/test_cantilever.py.

A bar of length L and depth h, clamped at x = 0, under its weight q = rho g h per length.
The pressure projection makes the solid incompressible, so its plane-strain modulus is
E' = 4 mu; Timoshenko's beam with the shear correction (kappa = 5/6, G = mu):
    w(x) = q x^2 (6 L^2 - 4 L x + x^2) / (24 E' I) + q (L x - x^2 / 2) / (kappa G h),  I = h^3 / 12.
Measured: the drop of the centroid of the bar's volume fraction in an element column.
"""
from __future__ import annotations

import os

import numpy as np

DECK = os.path.join(os.path.dirname(__file__), "..", "..", "inputs", "EFEM", "cantilever.ups")
L, H, RHO, E, NU, G = 0.8, 0.1, 1000.0, 1.5e7, 0.0, 9.81
MU = E / (2.0 * (1.0 + NU))


def deck_text(nx=40, ny=16, max_time=None, filebase=None, cfl=None):
    with open(DECK) as f:
        text = f.read()
    if cfl is not None:
        text = text.replace("<cfl> 0.1 </cfl>", f"<cfl> {cfl} </cfl>")
    text = text.replace("<resolution> [40, 16, 1] </resolution>", f"<resolution> [{nx}, {ny}, 1] </resolution>")
    if max_time is not None:
        text = text.replace("<maxTime> 0.3 </maxTime>", f"<maxTime> {max_time} </maxTime>")
    if filebase is not None:
        text = text.replace("<filebase>cantilever.uda</filebase>", f"<filebase>{filebase}</filebase>")
    return text


def beam(x):
    """Static deflection (positive down) of the Timoshenko cantilever at x."""
    q = RHO * G * H
    Ep, I = 4.0 * MU, H ** 3 / 12.0
    return q * x ** 2 * (6 * L ** 2 - 4 * L * x + x ** 2) / (24 * Ep * I) + q * (L * x - x * x / 2) / (5.0 / 6.0 * MU * H)


def period():
    """First bending period 2 pi / omega_1 of the clamped-free beam (Euler-Bernoulli):
    omega_1 = 1.8751^2 sqrt(E' I / (rho h L^4))."""
    Ep, I = 4.0 * MU, H ** 3 / 12.0
    return 2.0 * np.pi / (1.8751 ** 2 * np.sqrt(Ep * I / (RHO * H * L ** 4)))


def deflection(da, timestep=-1):
    """(x of the element columns under the bar, their centroid drop) at an output."""
    f0, (x, y, z) = da.read("vol_frac_CC", 0, 0)
    f1, _ = da.read("vol_frac_CC", 0, timestep)
    cols = np.nonzero(x < L)[0]

    def centroid(f):
        w = f[cols, :, 0]
        return (w * y[None, :]).sum(axis=1) / w.sum(axis=1)
    return x[cols], centroid(f0) - centroid(f1)
