#!/usr/bin/env python
"""The bar in a stream of paper 003 (sec. 7.2, Fig. 7) to the paper's 2.4 s (components/efem).

Runs inputs/EFEM/bar_in_flow.ups (an elastic bar 0.1 m x 0.8 m fixed at the bottom of a
1 m x 1 m box, water entering at 0.2 m/s through the x- face), prints the wall time, and
at each output the downstream displacement of the bar's top (the x-centroid of its
volume fraction in the rows above 0.6 m, less its initial 0.5 m) and the range of the sum
of the volume fractions (the box stays full); then draws the paper's panels, 0 to 2.4 s,
with scripts/efem_snapshots.py. About 20 min on one idle core.

    .venv/bin/python scripts/efem_bar_in_flow.py                        # run and draw
    .venv/bin/python scripts/efem_bar_in_flow.py --uda bar_in_flow.uda  # an existing run
"""
from __future__ import annotations

import argparse
import os
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, ".."))

from framework.archiver import DataArchive  # noqa: E402

DECK = os.path.join(HERE, "..", "inputs", "EFEM", "bar_in_flow.ups")
TIMES = (0.0, 0.3, 0.6, 0.9, 1.2, 1.5, 1.8, 2.1, 2.4)       # Fig. 7's panels


def top_displacement(da, k):
    """x-centroid of the bar's volume fraction above y = 0.6 m, less the bar's axis 0.5 m."""
    f, (x, y, _) = da.read("vol_frac_CC", 0, k)
    w = f[:, y > 0.6, 0]
    return float((w.sum(axis=1) * x).sum() / w.sum()) - 0.5


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--uda", default=None, help="read this run instead of running the deck")
    ap.add_argument("--max-time", type=float, default=None, help="end time (default the deck's 2.4 s)")
    ap.add_argument("--png", default="bar_in_flow.png")
    args = ap.parse_args(argv)
    uda = args.uda
    if uda is None:
        from framework.controller import Controller
        kw = {}
        if args.max_time is not None:
            with open(DECK) as f:
                kw["deck_text"] = f.read().replace("<maxTime> 2.4 </maxTime>", f"<maxTime> {args.max_time} </maxTime>")
        t0 = time.perf_counter()
        ctl = Controller(DECK, quiet=True, filebase="bar_in_flow.uda", **kw)
        ctl.run()
        print(f"wall {time.perf_counter() - t0:.0f} s, {ctl.timestep} steps", flush=True)
        uda = ctl.archiver.dir
    da = DataArchive(uda)
    for k, t in enumerate(da.times):
        fill = sum(da.read("vol_frac_CC", m, k)[0] for m in range(len(da.materials)))
        print(f"t = {t:5.2f} s  top of the bar {1000 * top_displacement(da, k):7.1f} mm downstream  "
              f"sum of volume fractions {fill.min():.5f} to {fill.max():.5f}")
    from efem_snapshots import main as snapshots
    snapshots([uda, *[str(t) for t in TIMES if t <= da.times[-1] + 1e-9], "--png", args.png])


if __name__ == "__main__":
    main()
