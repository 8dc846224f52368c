#!/usr/bin/env python
"""Oblique shock angle of the Mach 3 wedge (paper 000 sec. 4.3) from the pressure field.

    .venv/bin/pysus inputs/MPMICE/wedge_mach3.ups --filebase wedge_mach3.uda
    .venv/bin/python scripts/wedge_shock_angle.py wedge_mach3.uda [--json out.json]

At the last output, in each column over the wedge's face (x from tip + 0.1 to tip + 0.45 m)
the shock is where the pressure, scanned down from the top, first passes halfway between
the free stream and the post-shock plateau (the median pressure of the air cells within
three cells above the face), linearly interpolated between cells. A least-squares line
through those points gives the shock angle, which theory puts at 37.76 deg for M = 3,
a 20 deg deflection and gamma = 1.4 (post-shock p2 / p1 = 3.771).
"""
from __future__ import annotations

import argparse
import json
import math
import os
import re
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))

from framework.archiver import DataArchive  # noqa: E402

TIP, LENGTH, HALF_ANGLE, GAMMA, MACH = 0.2, 0.5, 20.0, 1.4, 3.0


def theory(mach=MACH, theta_deg=HALF_ANGLE, g=GAMMA):
    """Weak oblique-shock angle (deg) and pressure ratio from the theta-beta-M relation."""
    th = math.radians(theta_deg)
    f = lambda b: math.tan(th) - 2 / math.tan(b) * (mach ** 2 * math.sin(b) ** 2 - 1) / (mach ** 2 * (g + math.cos(2 * b)) + 2)
    lo, hi = math.asin(1 / mach) + 1e-9, math.radians(64.0)     # weak branch below max deflection
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if f(lo) * f(mid) <= 0:
            hi = mid
        else:
            lo = mid
    b = 0.5 * (lo + hi)
    return math.degrees(b), 1 + 2 * g / (g + 1) * (mach ** 2 * math.sin(b) ** 2 - 1)


def _box(uda):
    text = open(os.path.join(uda, "input.ups"), encoding="iso-8859-1").read()
    vec = lambda tag: np.array([float(v) for v in re.search(rf"<{tag}>\s*\[([^\]]*)\]", text).group(1).split(",")])
    return vec("lower"), vec("upper")


def measure(uda, i=-1):
    da = DataArchive(uda)
    p, _ = da.read("press_CC", 0, i)
    p = p[..., 0]
    lo, hi = _box(uda)
    nx, ny = p.shape
    dx, dy = (hi[0] - lo[0]) / nx, (hi[1] - lo[1]) / ny
    xc = lo[0] + (np.arange(nx) + 0.5) * dx
    yc = lo[1] + (np.arange(ny) + 0.5) * dy
    p1 = float(np.median(p[:, -1]))                       # free stream: the top row
    tan = math.tan(math.radians(HALF_ANGLE))
    xs, ys, plateau = [], [], []
    for ix in np.nonzero((xc > TIP + 0.1) & (xc < TIP + 0.45))[0]:
        face = tan * (xc[ix] - TIP)
        near = (yc > face + dy) & (yc < face + 4 * dy)
        p2 = float(np.median(p[ix, near]))
        thr = 0.5 * (p1 + p2)
        col = p[ix]
        above = np.nonzero(col[::-1] > thr)[0]
        if len(above) == 0 or above[0] == 0:
            continue
        j = ny - 1 - above[0]                             # first cell from the top above thr
        y = yc[j] + (col[j] - thr) / (col[j] - col[j + 1]) * dy
        if y > face + 2 * dy and y < yc[-1] - 2 * dy:
            xs.append(xc[ix])
            ys.append(y)
            plateau.append(p2 / p1)
    slope, icpt = np.polyfit(xs, ys, 1)
    beta, ratio = theory()
    angle = math.degrees(math.atan(slope))
    return {"time": float(da.times[i]), "dx": dx, "columns": len(xs), "angle_deg": angle, "theory_deg": beta,
            "error_deg": angle - beta, "x_at_y0": float(-icpt / slope), "tip_x": TIP,
            "p2_over_p1": float(np.mean(plateau)), "p2_over_p1_theory": ratio}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("uda")
    ap.add_argument("--json", default=None)
    args = ap.parse_args(argv)
    r = measure(args.uda)
    print(f"t = {r['time']:.3e} s, dx = {r['dx']:.4f} m, {r['columns']} columns: shock angle "
          f"{r['angle_deg']:.2f} deg (theory {r['theory_deg']:.2f}, off {r['error_deg']:+.2f}); line meets y = 0 "
          f"at x = {r['x_at_y0']:.3f} (tip {r['tip_x']}); p2/p1 = {r['p2_over_p1']:.3f} (theory {r['p2_over_p1_theory']:.3f})")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(r, f, indent=1)
    return r


if __name__ == "__main__":
    main()
