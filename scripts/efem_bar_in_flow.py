#!/usr/bin/env python
"""The bar in a stream of paper 003 (sec. 7.2, Fig. 7) to the paper's 2.4 s (components/efem).

Runs inputs/EFEM/bar_in_flow.ups (an elastic bar 0.1 m x 0.8 m fixed at the bottom of a
1 m x 1 m box, water entering at 0.2 m/s through the x- face), prints the wall time, and
at each output:
  top     the downstream displacement of the bar's top: the x-centroid of its volume
          fraction in the rows above 0.6 m, less its initial 0.5 m (smeared solid counts);
  core    the same from the midpoint of the bar's phi = 1/2 crossings in the row at 0.7 m;
  width   the smeared width of its faces: the mean over the rows from 0.1 m to 0.6 m of
          the distance between the 0.1 and 0.9 crossings of phi on each face, in elements;
  trace   the share of the bar's volume in elements below <solid_min> (stress-free traces);
  fill    the range of the sum of the volume fractions (the box stays full);
then the change of top and core over the last 0.4 s, beam theory's tip under the run's own
pressure load (its mean over those outputs), and draws the paper's panels, 0 to
2.4 s, with scripts/efem_snapshots.py.

Beam and drag estimate: the bar blocks 0.8 m of the 1 m channel, the 0.2 m/s stream goes
over its top at about 1 m/s and expands behind it; the pressure drop across the bar lies
between Borda-Carnot's 0.5 rho (1 - 0.2)^2 = 320 Pa and, with a vena contracta of 0.6,
0.5 rho (1.67 - 0.2)^2 = 1080 Pa. As a uniform load q on the 0.8 m cantilever (plane
strain E' = E / (1 - nu^2) = 5.49 MPa, I = 0.1^3 / 12): tip q L^4 / (8 E' I) = 36 to
121 mm. Dry first mode 1.9 Hz; the water it pushes adds several times its mass.

    .venv/bin/python scripts/efem_bar_in_flow.py                        # 50 x 50, about 18 min
    .venv/bin/python scripts/efem_bar_in_flow.py -n 24 --max-time 1.2   # coarser, shorter
    .venv/bin/python scripts/efem_bar_in_flow.py --uda bar_in_flow.uda  # an existing run
"""
from __future__ import annotations

import argparse
import os
import re
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, ".."))

from framework.archiver import DataArchive  # noqa: E402

DECK = os.path.join(HERE, "..", "inputs", "EFEM", "bar_in_flow.ups")
TIMES = (0.0, 0.3, 0.6, 0.9, 1.2, 1.5, 1.8, 2.1, 2.4)       # Fig. 7's panels
SOLID_MIN = 0.1


def top_displacement(da, k):
    """x-centroid of the bar's volume fraction above y = 0.6 m, less the bar's axis 0.5 m."""
    f, (x, y, _) = da.read("vol_frac_CC", 0, k)
    w = f[:, y > 0.6, 0]
    return float((w.sum(axis=1) * x).sum() / w.sum()) - 0.5


def crossings(row, x, level):
    """x of the first upward and the last downward crossing of `level` along a row (linear)."""
    above = np.nonzero(row >= level)[0]
    if len(above) == 0:
        return np.nan, np.nan
    i, j = above[0], above[-1]
    lo = x[i] if i == 0 else x[i - 1] + (level - row[i - 1]) / (row[i] - row[i - 1]) * (x[i] - x[i - 1])
    hi = x[j] if j == len(x) - 1 else x[j] + (row[j] - level) / (row[j] - row[j + 1]) * (x[j + 1] - x[j])
    return lo, hi


def core_displacement(da, k, height=0.7):
    """Midpoint of the bar's phi = 1/2 crossings in the row nearest `height`, less 0.5 m."""
    f, (x, y, _) = da.read("vol_frac_CC", 0, k)
    lo, hi = crossings(f[:, int(np.argmin(np.abs(y - height))), 0], x, 0.5)
    return 0.5 * (lo + hi) - 0.5


def smeared_width(da, k):
    """Mean 0.1-to-0.9 distance of phi across the bar's two faces, rows 0.1 m to 0.6 m, in elements."""
    f, (x, y, _) = da.read("vol_frac_CC", 0, k)
    dx = x[1] - x[0]
    w = []
    for j in np.nonzero((y > 0.1) & (y < 0.6))[0]:
        a10, b10 = crossings(f[:, j, 0], x, 0.1)
        a90, b90 = crossings(f[:, j, 0], x, 0.9)
        if np.isfinite(a90):
            w += [a90 - a10, b10 - b90]
    return float(np.mean(w) / dx) if w else np.nan


def trace_share(da, k):
    """Share of the bar's volume in elements where its fraction is below solid_min."""
    f = da.read("vol_frac_CC", 0, k)[0]
    return float(f[f < SOLID_MIN].sum() / f.sum())


def beam_tip_from_load(da, k, E=5e6, nu=0.3, t=0.1, L=0.8):
    """Tip deflection of the straight cantilever (Euler-Bernoulli, plane strain E' = E / (1 - nu^2))
    under the run's own load at output k: in each row below L where the bar's fraction reaches
    1/2, the pressure one element beyond the first element upstream of the bar with phi < 0.05
    (the solid's own pressure reaches into that one) less that downstream, times dy;
    w(L) = sum q(s) s^2 (3 L - s) / (6 E' I) ds. (load per metre of height, N/m; tip m)."""
    f, (x, y, _) = da.read("vol_frac_CC", 0, k)
    p = da.read("press_CC", 0, k)[0][:, :, 0]
    dy = y[1] - y[0]
    EI = E / (1.0 - nu * nu) * t ** 3 / 12.0
    tip = 0.0
    total = 0.0
    for j in np.nonzero(y < L)[0]:
        row = f[:, j, 0]
        a = b = int(np.argmax(row))
        if row[a] < 0.5:
            continue
        while a > 0 and row[a] >= 0.05:
            a -= 1
        while b < len(x) - 1 and row[b] >= 0.05:
            b += 1
        q = p[max(a - 1, 0), j] - p[min(b + 1, len(x) - 1), j]
        total += q * dy
        tip += q * y[j] ** 2 * (3.0 * L - y[j]) / (6.0 * EI) * dy
    return total, tip


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--uda", default=None, help="read this run instead of running the deck")
    ap.add_argument("-n", type=int, default=None, help="elements per direction (default the deck's 50)")
    ap.add_argument("--max-time", type=float, default=None, help="end time (default the deck's 2.4 s)")
    ap.add_argument("--set", action="append", default=[], metavar="TAG=VALUE",
                    help="an <EFEM> setting, e.g. --set slide_condition=false (repeatable)")
    ap.add_argument("--png", default="bar_in_flow.png")
    args = ap.parse_args(argv)
    uda = args.uda
    if uda is None:
        from framework.controller import Controller
        with open(DECK) as f:
            text = f.read()
        if args.max_time is not None:
            text = re.sub(r"<maxTime>.*?</maxTime>", f"<maxTime> {args.max_time} </maxTime>", text)
        if args.n is not None:
            text = re.sub(r"<resolution>.*?</resolution>", f"<resolution> [{args.n}, {args.n}, 1] </resolution>", text)
        for s in args.set:
            tag, value = s.split("=", 1)
            if f"<{tag}>" in text:
                text = re.sub(rf"<{tag}>.*?</{tag}>", f"<{tag}> {value} </{tag}>", text)
            else:
                text = text.replace("<EFEM>\n", f"<EFEM>\n    <{tag}> {value} </{tag}>\n", 1)
        t0 = time.perf_counter()
        ctl = Controller(DECK, quiet=True, filebase="bar_in_flow.uda", deck_text=text)
        ctl.run()
        wall = time.perf_counter() - t0
        n = args.n or 50
        print(f"wall {wall:.0f} s, {ctl.timestep} steps, {n * n * ctl.timestep / wall:,.0f} element-steps/s", flush=True)
        uda = ctl.archiver.dir
    da = DataArchive(uda)
    hist = []
    for k, t in enumerate(da.times):
        fill = sum(da.read("vol_frac_CC", m, k)[0] for m in range(len(da.materials)))
        top, core = top_displacement(da, k), core_displacement(da, k)
        hist.append((t, top, core))
        print(f"t = {t:5.2f} s  top {1000 * top:7.1f} mm  core {1000 * core:7.1f} mm  "
              f"width {smeared_width(da, k):5.2f} el  trace {trace_share(da, k):.4f}  "
              f"fill {fill.min():.5f} to {fill.max():.5f}", flush=True)
    t_end = hist[-1][0]
    k0 = int(np.argmin([abs(t - (t_end - 0.4)) for t, _, _ in hist]))
    print(f"change over the last {t_end - hist[k0][0]:.2f} s: top {1000 * (hist[-1][1] - hist[k0][1]):+.1f} mm, "
          f"core {1000 * (hist[-1][2] - hist[k0][2]):+.1f} mm")
    last = [k for k in range(max(k0, 1), len(da.times))]      # the initial output holds no pressure
    if last:
        force, tip = np.mean([beam_tip_from_load(da, k) for k in last], axis=0)
        print(f"the run's pressure load on the bar, mean over the outputs from {da.times[last[0]]:.2f} s: "
              f"{force:.1f} N per metre of depth; beam theory's tip under it {1000 * tip:.1f} mm")
    from efem_snapshots import main as snapshots
    snapshots([uda, *[str(t) for t in TIMES if t <= da.times[-1] + 1e-9], "--png", args.png])


if __name__ == "__main__":
    main()
