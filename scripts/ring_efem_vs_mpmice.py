#!/usr/bin/env python
"""The elastic ring falling onto a liquid (paper 003 sec. 7.1, Fig. 6) by two methods on the
same cells: EFEM (inputs/EFEM/ring_falling.ups: incompressible fluid, void above it, the ring
as a volume fraction) and MPMICE (inputs/MPMICE/ring_on_fluid.ups: the ring as MPM particles,
a weakly compressible liquid and a light gas in ICE).

Runs both decks at -n cells along x (2/3 of it along y, one patch), then prints a table
(wall time, steps, mean time step) and, at each output, the ring's centroid height, its
ovalisation (the rms width of its area about the centroid over its rms height: 1 for the
circle, above 1 when it flattens), its area, and the liquid's volume; and draws the
materials side by side at the paper's times (EFEM top row, MPMICE bottom row: ring red,
liquid blue, void or gas white). About 2 min (EFEM) and 3 min (MPMICE) on one core at 60.

    .venv/bin/python scripts/ring_efem_vs_mpmice.py                    # 60 x 40, run both
    .venv/bin/python scripts/ring_efem_vs_mpmice.py -n 90 --json ring.json
    .venv/bin/python scripts/ring_efem_vs_mpmice.py --efem-uda A.uda --mpmice-uda B.uda
"""
from __future__ import annotations

import argparse
import json
import os
import re
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, ".."))

from framework.archiver import DataArchive  # noqa: E402

EFEM_DECK = os.path.join(HERE, "..", "inputs", "EFEM", "ring_falling.ups")
MPMICE_DECK = os.path.join(HERE, "..", "inputs", "MPMICE", "ring_on_fluid.ups")
TIMES = (0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9)      # Fig. 6's panels
SOLID, FLUID = np.array([0.85, 0.15, 0.1]), np.array([0.2, 0.45, 0.9])


def deck_text(path, n, max_time):
    """The deck at n x (2 n / 3) cells on one patch, to max_time."""
    with open(path) as f:
        text = f.read()
    text = re.sub(r"<resolution>[^<]*</resolution>", f"<resolution> [{n}, {2 * n // 3}, 1] </resolution>", text)
    text = re.sub(r"<patches>[^<]*</patches>", "<patches> [1, 1, 1] </patches>", text)
    return re.sub(r"<maxTime>[^<]*</maxTime>", f"<maxTime> {max_time} </maxTime>", text)


def run_deck(path, n, max_time, filebase):
    from framework.controller import Controller
    t0 = time.perf_counter()
    ctl = Controller(path, quiet=True, filebase=filebase, deck_text=deck_text(path, n, max_time))
    ctl.run()
    return ctl.archiver.dir, time.perf_counter() - t0, ctl.timestep


def moments(x, y, w):
    """(centroid x, centroid y, rms width / rms height, area) of weights w at points (x, y)."""
    a = w.sum()
    cx, cy = (w * x).sum() / a, (w * y).sum() / a
    return cx, cy, float(np.sqrt((w * (x - cx) ** 2).sum() / (w * (y - cy) ** 2).sum())), a


class Efem:
    """Ring (material 0) and fluid (material 1) volume fractions of an EFEM run."""

    name = "EFEM"

    def __init__(self, uda):
        self.da = DataArchive(uda)
        self.area = float(np.prod(self.da.dx[:2]))

    def fields(self, k):
        ring, (x, y, _) = self.da.read("vol_frac_CC", 0, k)
        fluid, _ = self.da.read("vol_frac_CC", 1, k)
        return ring[:, :, 0], fluid[:, :, 0], x, y

    def ring(self, k):
        ring, _, x, y = self.fields(k)
        X, Y = np.meshgrid(x, y, indexing="ij")
        return moments(X, Y, ring * self.area)

    def liquid_volume(self, k):
        return float(self.fields(k)[1].sum()) * self.area


class Mpmice:
    """Ring particles (material 0) and the liquid (ICE material 1) of an MPMICE run; volumes per
    unit thickness (area) as EFEM's."""

    name = "MPMICE"

    def __init__(self, uda):
        self.da = DataArchive(uda)
        self.dx = np.asarray(self.da.dx)
        self.area = float(self.dx[0] * self.dx[1])

    def fields(self, k):
        p = self.da.particles(0, k)
        try:
            liquid, (x, y, _) = self.da.read("vol_frac_CC", 1, k)
        except KeyError:        # the first output holds no ICE volume fraction yet: rho_CC sp_vol_CC
            rho, (x, y, _) = self.da.read("rho_CC", 1, k)
            liquid = rho * self.da.read("sp_vol_CC", 1, k)[0]
        edges = [np.append(c - 0.5 * h, c[-1] + 0.5 * h) for c, h in ((x, self.dx[0]), (y, self.dx[1]))]
        ring, _, _ = np.histogram2d(p["p.x"][:, 0], p["p.x"][:, 1], bins=edges,
                                    weights=p["p.volume"] / (self.area * self.dx[2]))
        return ring, liquid[:, :, 0], x, y

    def ring(self, k):
        p = self.da.particles(0, k)
        return moments(p["p.x"][:, 0], p["p.x"][:, 1], p["p.volume"] / self.dx[2])

    def liquid_volume(self, k):
        return float(self.fields(k)[1].sum()) * self.area


def image(run, k):
    """RGB (ny, nx, 3): white minus the ring's and the liquid's shares of their colours."""
    ring, liquid, x, y = run.fields(k)
    rgb = np.ones(ring.T.shape + (3,))
    for f, col in ((ring, SOLID), (liquid, FLUID)):
        rgb -= np.clip(f.T, 0.0, 1.0)[..., None] * (1.0 - col)[None, None, :]
    ext = [x[0] - (x[1] - x[0]) / 2, x[-1] + (x[1] - x[0]) / 2, y[0] - (y[1] - y[0]) / 2, y[-1] + (y[1] - y[0]) / 2]
    return np.clip(rgb, 0.0, 1.0), ext


def draw(runs, times, png, columns=5):
    """Panels at the given times, `columns` to a row: per row of times an EFEM row above an
    MPMICE row."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    chunks = [times[i:i + columns] for i in range(0, len(times), columns)]
    ncol = min(columns, len(times))
    fig, axes = plt.subplots(len(runs) * len(chunks), ncol, figsize=(2.4 * ncol, 1.75 * len(runs) * len(chunks)),
                             squeeze=False)
    for ax in axes.ravel():
        ax.axis("off")
    for g, chunk in enumerate(chunks):
        for r, run in enumerate(runs):
            for c, t in enumerate(chunk):
                k = int(np.argmin(np.abs(run.da.times - t)))
                rgb, ext = image(run, k)
                ax = axes[g * len(runs) + r, c]
                ax.imshow(rgb, origin="lower", extent=ext, interpolation="nearest")
                ax.set_title(f"{run.name} t = {run.da.times[k]:.2f} s", fontsize=8)
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    print(png)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("-n", type=int, default=60, help="cells along x (2/3 of it along y)")
    ap.add_argument("--max-time", type=float, default=0.9)
    ap.add_argument("--efem-uda", default=None, help="read this EFEM run instead of running the deck")
    ap.add_argument("--mpmice-uda", default=None, help="read this MPMICE run instead of running the deck")
    ap.add_argument("--png", default="ring_efem_vs_mpmice.png")
    ap.add_argument("--json", default=None)
    args = ap.parse_args(argv)
    cost = {}
    udas = {}
    for name, deck, given in (("EFEM", EFEM_DECK, args.efem_uda), ("MPMICE", MPMICE_DECK, args.mpmice_uda)):
        if given is not None:
            udas[name] = given
            continue
        udas[name], wall, steps = run_deck(deck, args.n, args.max_time, f"ring_{name.lower()}_{args.n}.uda")
        cost[name] = dict(wall_s=wall, steps=steps)
    runs = [Efem(udas["EFEM"]), Mpmice(udas["MPMICE"])]
    rows = {}
    for run in runs:
        t_end = float(run.da.times[-1])
        c = cost.get(run.name, {})
        if c:
            c["mean_dt"] = t_end / c["steps"]
            print(f"{run.name:7s} wall {c['wall_s']:7.1f} s  steps {c['steps']:6d}  mean delT {c['mean_dt']:.2e} s  "
                  f"to t = {t_end:.3f} s", flush=True)
        hist = []
        v0 = run.liquid_volume(0)
        for k, t in enumerate(run.da.times):
            cx, cy, ov, area = run.ring(k)
            hist.append(dict(t=float(t), centroid_y=cy, centroid_x=cx, ovalisation=ov, ring_area=area,
                             liquid_volume=run.liquid_volume(k) / v0))
        rows[run.name] = dict(cost=c, history=hist)
    print(f"{'t (s)':>6s} | {'centroid y (m)':>17s} | {'ovalisation':>15s} | {'ring area (m^2)':>19s} | "
          f"{'liquid volume / t=0':>21s}")
    print(f"{'':6s} | {'EFEM':>8s} {'MPMICE':>8s} | {'EFEM':>7s} {'MPMICE':>7s} | {'EFEM':>9s} {'MPMICE':>9s} | "
          f"{'EFEM':>10s} {'MPMICE':>10s}")
    a, b = rows["EFEM"]["history"], rows["MPMICE"]["history"]
    for ha in a:
        hb = min(b, key=lambda h: abs(h["t"] - ha["t"]))
        print(f"{ha['t']:6.2f} | {ha['centroid_y']:8.4f} {hb['centroid_y']:8.4f} | {ha['ovalisation']:7.3f} "
              f"{hb['ovalisation']:7.3f} | {ha['ring_area']:9.6f} {hb['ring_area']:9.6f} | "
              f"{ha['liquid_volume']:10.6f} {hb['liquid_volume']:10.6f}")
    for name, r in rows.items():
        h = r["history"]
        k = int(np.argmax([x["ovalisation"] for x in h]))
        print(f"{name}: largest ovalisation {h[k]['ovalisation']:.3f} at t = {h[k]['t']:.2f} s; lowest centroid "
              f"{min(x['centroid_y'] for x in h):.4f} m; liquid volume {min(x['liquid_volume'] for x in h):.6f} to "
              f"{max(x['liquid_volume'] for x in h):.6f} of its start")
    draw(runs, [t for t in TIMES if t <= args.max_time + 1e-9], args.png)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f, indent=1)


if __name__ == "__main__":
    main()
