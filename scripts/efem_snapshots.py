#!/usr/bin/env python
"""PNG snapshots of an EFEM run (components/efem): the materials' volume fractions at given
times, solids in red, fluids in blue (void white), one panel per time, as the paper's
Figs. 6-8.

    pysus inputs/EFEM/ring_falling.ups
    .venv/bin/python scripts/efem_snapshots.py ring_falling.uda 0 0.1 0.2 0.3 0.4 0.5 0.6 0.7 0.8 0.9
    .venv/bin/python scripts/efem_snapshots.py pontoon_falling.uda 0 0.6 1.2 1.8 --png pontoon.png

Each time is drawn from the nearest output.
"""
from __future__ import annotations

import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))

from framework.archiver import DataArchive  # noqa: E402

SOLID, FLUID = np.array([0.85, 0.15, 0.1]), np.array([0.2, 0.45, 0.9])


def image(da, k, solids):
    """RGB (ny, nx, 3) of output k: white minus each material's share of its colour."""
    rgb = None
    for m, name in enumerate(da.materials):
        f, _ = da.read("vol_frac_CC", m, k)
        f = np.clip(f[:, :, 0].T, 0.0, 1.0)
        if rgb is None:
            rgb = np.ones(f.shape + (3,))
        col = SOLID if m in solids else FLUID
        rgb -= f[..., None] * (1.0 - col)[None, None, :]
    return np.clip(rgb, 0.0, 1.0)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("uda")
    ap.add_argument("times", type=float, nargs="+", help="times (s) to draw")
    ap.add_argument("--png", default=None, help="output file (default: <uda>.png next to the uda)")
    ap.add_argument("--solids", type=int, nargs="*", default=None,
                    help="material indices drawn as solids (default: every material but the last)")
    ap.add_argument("--columns", type=int, default=5)
    args = ap.parse_args(argv)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    da = DataArchive(args.uda)
    times = np.asarray(da.times)
    solids = set(args.solids) if args.solids is not None else set(range(len(da.materials) - 1))
    f0, (x, y, _) = da.read("vol_frac_CC", 0, 0)
    ext = [x[0] - (x[1] - x[0]) / 2, x[-1] + (x[1] - x[0]) / 2, y[0] - (y[1] - y[0]) / 2, y[-1] + (y[1] - y[0]) / 2]
    n = len(args.times)
    cols = min(args.columns, n)
    rows = (n + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(3.2 * cols, 2.4 * rows), squeeze=False)
    for ax in axes.ravel():
        ax.axis("off")
    for i, t in enumerate(args.times):
        k = int(np.argmin(np.abs(times - t)))
        ax = axes.ravel()[i]
        ax.imshow(image(da, k, solids), origin="lower", extent=ext, interpolation="nearest")
        ax.set_title(f"t = {times[k]:.2f} s", fontsize=9)
    fig.tight_layout()
    out = args.png or os.path.abspath(args.uda).rstrip("/").removesuffix(".uda") + ".png"
    fig.savefig(out, dpi=110)
    print(out)


if __name__ == "__main__":
    main()
