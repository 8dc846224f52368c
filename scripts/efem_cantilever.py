#!/usr/bin/env python
"""An elastic cantilever under its weight against beam theory (components/efem, paper 003).

Runs inputs/EFEM/cantilever.ups (bar 0.8 m x 0.1 m, clamped at the x- wall) at one or more
resolutions and prints the deflection of the tip and mid-span element columns against
Timoshenko's static deflection (components/efem/scene_cantilever.py), with the wall time.
About 3 min on one core at 25 x 10, 10 min at 40 x 16.

    .venv/bin/python scripts/efem_cantilever.py                 # 25 x 10 and 40 x 16
    .venv/bin/python scripts/efem_cantilever.py -n 25 --json cantilever.json
    .venv/bin/python scripts/efem_cantilever.py -n 20 --cfl 0.25     # 20 x 8, faces on element edges
"""
from __future__ import annotations

import argparse
import json
import os
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))

from components.efem import scene_cantilever as S  # noqa: E402
from framework.archiver import DataArchive  # noqa: E402
from framework.controller import Controller  # noqa: E402


def run(nx, max_time, workdir, cfl=None):
    ny = int(round(nx * 0.4))
    deck = os.path.join(workdir, f"cantilever{nx}.ups")
    with open(deck, "w") as f:
        f.write(S.deck_text(nx, ny, max_time=max_time, filebase=os.path.join(workdir, f"cantilever{nx}.uda"), cfl=cfl))
    t0 = time.perf_counter()
    ctl = Controller(deck, quiet=True)
    ctl.run()
    wall = time.perf_counter() - t0
    da = DataArchive(ctl.archiver.dir)
    x, w = S.deflection(da)
    out = dict(nx=nx, ny=ny, steps=ctl.timestep, wall_s=wall)
    for name, k in (("tip", len(x) - 1), ("mid", len(x) // 2)):
        exact = S.beam(x[k])
        out[name] = dict(x=float(x[k]), w=float(w[k]), beam=float(exact), error=float(w[k] / exact - 1.0))
    out["history"] = [(float(t), float(S.deflection(da, k)[1][-1])) for k, t in enumerate(da.times)]
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("-n", type=int, nargs="+", default=[25, 40], help="elements along x (0.4 n along y)")
    ap.add_argument("--max-time", type=float, default=0.3)
    ap.add_argument("--cfl", type=float, default=None, help="the deck's <cfl> (0.1) replaced")
    ap.add_argument("--json", default=None)
    args = ap.parse_args(argv)
    rows = []
    with tempfile.TemporaryDirectory() as wd:
        for n in args.n:
            r = run(n, args.max_time, wd, args.cfl)
            rows.append(r)
            for name in ("tip", "mid"):
                c = r[name]
                print(f"{r['nx']:4d} x {r['ny']:3d}  {name} x={c['x']:.3f}: deflection {c['w']:.5f} m, beam "
                      f"{c['beam']:.5f} m, error {100 * c['error']:+.1f} %", flush=True)
            print(f"          steps {r['steps']}  wall {r['wall_s']:.1f} s", flush=True)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f, indent=1)


if __name__ == "__main__":
    main()
