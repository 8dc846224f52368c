"""Burning explosive in a notched steel ring that ruptures (paper 000 sec. 5, 001 sec. 4.3):
the measurements of inputs/MPMICE/burning_container_rupture2D.ups from its output.

    history(da)  per output: t, timestep, total mass of all materials and its relative
                 change, explosive mass, failed steel particles, the opening (the widest
                 angular gap between intact steel particles, times their mean radius), the
                 product gas mass outside the ring and how much of it came from inside
                 (escaped), the mean gap and outside pressures, and the gas mass in cells
                 that were solid explosive at the first output (gas where there was none)
    rupture(h)   the first output where the opening is wider than OPEN_CELLS cells
    escape(h)    the first output where the escaped gas exceeds ESCAPED of the gas that was
                 outside the ring at t = 0
The deck's heat exchange between each solid and the gas is what keeps this run affordable:
the trace product gas inside the solids (volume fraction < 1e-4) takes the solids'
temperature instead of being squeezed adiabatically to 1e5-1e6 K, so delT is set by the
steel's wave speed (1.2e-7 to 1.8e-7 s) instead of that gas's sound speed (2e-8 to 3e-8 s in
burning_container2D.ups, which has no heat exchange). This is how Uintah's container decks
treat the vanishing phase; ICE's CFL itself is unchanged (Uintah's: every cell, every fluid).
Used by scripts/container_rupture.py and tests/mpmice/test_container_rupture.py.
"""
from __future__ import annotations

import os

import numpy as np

DECK = os.path.join(os.path.dirname(__file__), "..", "..", "inputs", "MPMICE", "burning_container_rupture2D.ups")
STEEL, HE, GAS = 0, 1, 2           # material indices (deck)
FAIL_STRAIN = 0.05                 # critical_scalar_damage * D1 (deck): failed at eps_p >= this
R_HE, R_IN, R_OUT = 0.040, 0.050, 0.056   # explosive radius, ring radii at t = 0 (deck)
OPEN_CELLS = 2.0                   # a rupture: an opening wider than this many cells
BINS = 30                          # angular bins for the ring's local outer radius
ESCAPED = 0.05                     # gas has escaped: more than this fraction of the initial outside gas


def cells(da):
    """Cell-centre radius and angle (2D, one cell deep) and the cell volume."""
    x = da.anchor[0] + (np.arange(da.ncells[0]) + 0.5) * da.dx[0]
    y = da.anchor[1] + (np.arange(da.ncells[1]) + 0.5) * da.dx[1]
    X, Y = np.meshgrid(x, y, indexing="ij")
    return np.hypot(X, Y), np.arctan2(Y, X), float(np.prod(da.dx))


def opening(px, ok):
    """Widest angular gap between intact particles (and the symmetry planes are not gaps),
    times the intact particles' mean radius (m)."""
    a = np.sort(np.arctan2(px[ok, 1], px[ok, 0]))
    r = np.hypot(px[ok, 0], px[ok, 1]).mean()
    return float(np.diff(a).max() * r) if len(a) > 1 else np.inf


def outer_radius(px, ok, ang):
    """The intact ring's outer radius at each angle `ang`: the largest particle radius in each
    of BINS angular bins, interpolated across bins with no intact particle (the crack)."""
    pa = np.arctan2(px[ok, 1], px[ok, 0])
    pr = np.hypot(px[ok, 0], px[ok, 1])
    edges = np.linspace(0.0, 0.5 * np.pi, BINS + 1)
    k = np.clip(np.digitize(pa, edges) - 1, 0, BINS - 1)
    rmax = np.full(BINS, np.nan)
    for b in range(BINS):
        if np.any(k == b):
            rmax[b] = pr[k == b].max()
    mid = 0.5 * (edges[1:] + edges[:-1])
    have = ~np.isnan(rmax)
    return np.interp(ang, mid[have], rmax[have])


def history(da):
    r, ang, V = cells(da)
    out = {k: [] for k in ("t", "step", "mass", "dmass", "he_mass", "failed", "opening", "gas_out",
                           "escaped", "p_gap", "p_out", "gas_new")}
    solid = None
    for i, step in enumerate(da.timesteps):
        steel, he = da.particles(STEEL, i), da.particles(HE, i)
        rho = da.read("rho_CC", GAS, i)[0][..., 0]
        p = da.read("press_CC", 0, i)[0][..., 0]
        eps = steel.get("p.plasticStrain", np.zeros(len(steel["p.mass"])))
        ok = eps < FAIL_STRAIN
        gas = rho * V
        mass = float(steel["p.mass"].sum() + he["p.mass"].sum() + gas.sum())
        r_o = outer_radius(steel["p.x"], ok, ang)
        out["t"].append(da.times[i])
        out["step"].append(step)
        out["mass"].append(mass)
        out["dmass"].append((mass - out["mass"][0]) / out["mass"][0])
        out["he_mass"].append(float(he["p.mass"].sum()))
        out["failed"].append(int((~ok).sum()))
        out["opening"].append(opening(steel["p.x"], ok))
        out["gas_out"].append(float(gas[r > r_o + da.dx[0]].sum()))
        out["escaped"].append(out["gas_out"][-1] - out["gas_out"][0])
        out["p_gap"].append(float(p[(r > R_HE + da.dx[0]) & (r < R_IN - da.dx[0])].mean()))
        out["p_out"].append(float(p[r > r_o + 2 * da.dx[0]].mean()))
        if solid is None and i > 0:          # vol_frac_CC is not saved at initialization
            vf = da.read("vol_frac_CC", GAS, i)[0][..., 0]
            solid = (vf < 1e-3) & (r < R_HE)
        out["gas_new"].append(float(gas[solid].sum()) if solid is not None else np.nan)
    return {k: np.array(v) for k, v in out.items()}


def rupture(h, dx):
    """Index of the first output with an opening wider than OPEN_CELLS cells, or None."""
    k = np.nonzero(h["opening"] > OPEN_CELLS * dx)[0]
    return int(k[0]) if len(k) else None


def escape(h):
    """Index of the first output where more than ESCAPED of the initial outside gas escaped."""
    k = np.nonzero(h["escaped"] > ESCAPED * h["gas_out"][0])[0]
    return int(k[0]) if len(k) else None
