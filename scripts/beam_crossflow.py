"""Flexible beam in a crossflow (paper 001 sec. 4.2): tip deflection and beam temperature
over time from a run of inputs/MPMICE/beam_crossflow.ups.

The tip is the particles within 0.1 m of the beam's initial top (y = 1.5 m); its
deflection is their mean x displacement. The beam's temperature is the mass-weighted
mean of p.temperature; ThermalEnergy is its heat sum m cv T. Prints one row per output
and the tip's turning points, and the period of its oscillation from them.

  .venv/bin/pysus inputs/MPMICE/beam_crossflow.ups          (about 5 minutes)
  .venv/bin/python scripts/beam_crossflow.py beam_crossflow.uda [--json out.json]
"""
from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from framework.archiver import DataArchive  # noqa: E402

TOP = 1.5


def history(uda):
    """Per output: time, tip x displacement, tip y displacement, mean beam T, min/max T, gas mass."""
    da = DataArchive(uda)
    p0 = da.particles(0, 0)
    ids0 = p0["p.particleID"]
    tip_ids = ids0[p0["p.x"][:, 1] > TOP - 0.1]
    x0 = dict(zip(ids0.tolist(), p0["p.x"].tolist()))
    rows = []
    for i, t in enumerate(da.times):
        p = da.particles(0, i)
        sel = np.isin(p["p.particleID"], tip_ids)
        ref = np.array([x0[k] for k in p["p.particleID"][sel].tolist()])
        d = (p["p.x"][sel] - ref).mean(axis=0)
        m, T = p["p.mass"], p["p.temperature"]
        rows.append(dict(t=float(t), tip_dx=float(d[0]), tip_dy=float(d[1]), T_mean=float(np.dot(m, T) / m.sum()),
                         T_min=float(T.min()), T_max=float(T.max()), beam_mass=float(m.sum())))
    return rows


def extrema(rows):
    """(time, tip_dx) of the tip's turning points: local maxima and minima of tip_dx."""
    t = np.array([r["t"] for r in rows])
    d = np.array([r["tip_dx"] for r in rows])
    return [(float(t[i]), float(d[i])) for i in range(1, len(d) - 1)
            if (d[i] - d[i - 1]) * (d[i + 1] - d[i]) < 0]


def period(rows):
    """Twice the mean time between successive turning points of the tip (s), or None."""
    ext = extrema(rows)
    return 2.0 * float(np.mean(np.diff([e[0] for e in ext]))) if len(ext) > 1 else None


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("uda")
    ap.add_argument("--json")
    a = ap.parse_args(argv)
    rows = history(a.uda)
    print(f"{'t (s)':>9} {'tip dx (mm)':>12} {'tip dy (mm)':>12} {'T mean (K)':>11} {'T min':>8} {'T max':>8}")
    for r in rows:
        print(f"{r['t']:9.4f} {1e3 * r['tip_dx']:12.3f} {1e3 * r['tip_dy']:12.3f} {r['T_mean']:11.3f} "
              f"{r['T_min']:8.2f} {r['T_max']:8.2f}")
    ext = extrema(rows)
    print("tip turning points (t s, dx mm): " + ", ".join(f"({t:.4f}, {1e3 * d:.1f})" for t, d in ext))
    T = period(rows)
    print(f"oscillation period of the tip: {T:.4f} s" if T else "oscillation period: fewer than two turning points")
    if a.json:
        Path(a.json).write_text(json.dumps(dict(rows=rows, period=T), indent=1))


if __name__ == "__main__":
    main()
