"""The floating block of inputs/EFEM/floating_block.ups: its deck at other resolutions and the
draught measured from a run, for scripts/efem_archimedes.py and tests/efem/test_archimedes.py.

Archimedes: a block of height H and density rho_s floats in a liquid of density rho_w at the
draught d = H rho_s / rho_w (here 0.2 m x 500 / 1000 = 0.1 m). Measured as the free surface
far from the block (the liquid's height in the two columns next to the x- wall) minus the
liquid's height in the block's middle column (the liquid below the block).
"""
from __future__ import annotations

import os

import numpy as np

DECK = os.path.join(os.path.dirname(__file__), "..", "..", "inputs", "EFEM", "floating_block.ups")
H, WIDTH, RHO_S, RHO_W = 0.2, 0.2, 500.0, 1000.0
EXACT = H * RHO_S / RHO_W


def deck_text(n=20, patches=(2, 2), max_time=None, damping=None, filebase=None):
    """The deck with n x n elements (and optionally another end time, damping or filebase)."""
    with open(DECK) as f:
        text = f.read()
    text = text.replace("<resolution> [20, 20, 1] </resolution>", f"<resolution> [{n}, {n}, 1] </resolution>")
    text = text.replace("<patches> [2, 2, 1] </patches>", f"<patches> [{patches[0]}, {patches[1]}, 1] </patches>")
    if max_time is not None:
        text = text.replace("<maxTime> 2.0 </maxTime>", f"<maxTime> {max_time} </maxTime>")
    if damping is not None:
        text = text.replace("<damping> 5 </damping>", f"<damping> {damping} </damping>")
    if filebase is not None:
        text = text.replace("<filebase>floating_block.uda</filebase>", f"<filebase>{filebase}</filebase>")
    return text


def draught(da, timestep=-1):
    """(draught, far surface height, liquid height under the block) at an output."""
    fw, (x, y, z) = da.read("vol_frac_CC", 1, timestep)
    dy = y[1] - y[0]
    surface = float(fw[:2, :, 0].sum(axis=1).mean() * dy)
    mid = fw.shape[0] // 2
    under = float(fw[mid - 1:mid + 1, :, 0].sum(axis=1).mean() * dy)
    return surface - under, surface, under


def displaced(da, timestep=-1):
    """(hydrostatic surface, the block's volume below it over the Archimedes volume H W rho_s /
    rho_w): the surface is the pressure head deep in the column next to the x- wall, p / (rho_w g)
    + y, which a film of water thinner than fill_min lying on top does not raise; the volume
    counts the block's smeared edges wherever they lie."""
    fs, (x, y, _) = da.read("vol_frac_CC", 0, timestep)
    p, _ = da.read("press_CC", 0, timestep)
    dx, dy = x[1] - x[0], y[1] - y[0]
    j = len(y) // 4
    surface = float(p[0, j, 0] / (RHO_W * 9.81) + y[j])
    below = np.clip((surface - (y - dy / 2)) / dy, 0.0, 1.0)
    volume = float((fs[:, :, 0] * below[None, :]).sum() * dx * dy)
    return surface, volume / (EXACT * WIDTH)
