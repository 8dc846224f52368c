#!/usr/bin/env python
"""A block floating in water comes to rest at the Archimedes draught (components/efem, paper 003).

Runs inputs/EFEM/floating_block.ups (block 0.2 m x 0.2 m, density 500, in water: exact
draught 0.1 m) at several resolutions and prints the draught at the end, its error, the
steps and the wall time side by side; and the block's volume below the hydrostatic surface
(the pressure head far from the block) against Archimedes' displaced volume. About 8 min on one core for 20, 30 and 40 elements.

    .venv/bin/python scripts/efem_archimedes.py                 # 20 30 40
    .venv/bin/python scripts/efem_archimedes.py -n 20 40 --json archimedes.json
"""
from __future__ import annotations

import argparse
import json
import os
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))

from components.efem import scene_float as S  # noqa: E402
from framework.archiver import DataArchive  # noqa: E402
from framework.controller import Controller  # noqa: E402


def run(n, max_time, workdir):
    deck = os.path.join(workdir, f"float{n}.ups")
    with open(deck, "w") as f:
        # patches of even extent, so that the pressure solve keeps its multigrid preconditioner
        p = 2 if n % 4 == 0 else 1
        f.write(S.deck_text(n, patches=(p, p), max_time=max_time, filebase=os.path.join(workdir, f"float{n}.uda")))
    t0 = time.perf_counter()
    ctl = Controller(deck, quiet=True)
    ctl.run()
    wall = time.perf_counter() - t0
    da = DataArchive(ctl.archiver.dir)
    d, surface, under = S.draught(da)
    head, displaced = S.displaced(da)
    return dict(n=n, draught=d, error=d / S.EXACT - 1.0, surface=surface, head=head, displaced=displaced,
                steps=ctl.timestep, wall_s=wall,
                history=[(float(t), S.draught(da, k)[0]) for k, t in enumerate(da.times)])


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("-n", type=int, nargs="+", default=[20, 30, 40], help="elements per direction")
    ap.add_argument("--max-time", type=float, default=2.0)
    ap.add_argument("--json", default=None)
    args = ap.parse_args(argv)
    rows = []
    with tempfile.TemporaryDirectory() as wd:
        for n in args.n:
            rows.append(run(n, args.max_time, wd))
            r = rows[-1]
            print(f"n={n:4d}  draught {r['draught']:.5f} m (exact {S.EXACT:.3f})  error {100 * r['error']:+.2f} %  "
                  f"displaced below the hydrostatic surface {100 * (r['displaced'] - 1):+.2f} %  "
                  f"steps {r['steps']:6d}  wall {r['wall_s']:7.1f} s", flush=True)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f, indent=1)


if __name__ == "__main__":
    main()
