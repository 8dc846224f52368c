#!/usr/bin/env python
"""Adiabatic piston compression (paper 000 sec. 4.2, Fig. 4): the gas pressure at the bottom
of the column against the adiabatic law P2 = P1 (V1/V2)^gamma (eq. 44), over time.

Reads a finished run (framework DataArchive) of inputs/MPMICE/piston_validation.ups or of
Uintah's MPMICE/pistonValidation.ups (both save press_CC, vol_frac_CC and p.x); V1/V2 is
y_b(0) / y_b(t), y_b the piston's bottom from its particles. Prints, per output, t, V1/V2,
P at the bottom cell, the exact P and the relative error (and the error against the ratio
of the trapped gas's own volume, the sum of its volume fractions), then the error at the
highest compression; writes a PNG of P and the exact curve against t.

    ./pysus inputs/MPMICE/piston_validation.ups                  # ~3 min, one core
    .venv/bin/python scripts/piston_validation.py piston_validation.uda --png piston.png

    ./pysus UINTAH_SRC/StandAlone/inputs/MPMICE/pistonValidation.ups   # Uintah's deck, ratio 5.0
    .venv/bin/python scripts/piston_validation.py imp_pistonVal_cgs.uda
"""
from __future__ import annotations

import argparse
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))

from components.mpmice import scene_piston as S  # noqa: E402
from framework.archiver import DataArchive  # noqa: E402


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("uda")
    ap.add_argument("--png", default=None, help="plot of P(t) and P1 (V1/V2)^gamma")
    ap.add_argument("--every", type=int, default=5, help="print every n-th output (default 5)")
    args = ap.parse_args(argv)
    da = DataArchive(args.uda)
    h = S.history(da)
    e = S.errors(da)
    print(f"{'t (s)':>8} {'V1/V2':>7} {'P bottom':>10} {'P1(V1/V2)^g':>12} {'rel err':>9} {'gas V1/V2':>9} "
          f"{'rel err':>9}")
    n = len(h["t"])
    for i in range(n):
        if i % args.every and i != n - 1:
            continue
        print(f"{h['t'][i]:8.4f} {h['ratio'][i]:7.3f} {h['P'][i]:10.5f} {h['exact'][i]:12.5f} {h['err'][i]:+9.4f} "
              f"{h['ratio_gas'][i]:9.3f} {h['err_gas'][i]:+9.4f}")
    print(f"highest compression V1/V2 = {e['ratio']:.3f}: relative error {e['end']:+.4f} "
          f"(gas-volume ratio: {e['end_gas']:+.4f}); while the piston moves: max |err| {e['max']:.4f}, "
          f"mean |err| {e['mean']:.4f}")
    if args.png:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(1, 2, figsize=(10, 4))
        ax[0].plot(h["t"], h["exact"], "k-", label="P1 (V1/V2)^gamma (eq. 44)")
        ax[0].plot(h["t"], h["P"], "o", ms=3, label="pysus, bottom cell")
        ax[0].set_xlabel("t (s)")
        ax[0].set_ylabel("pressure")
        ax[0].legend()
        ax[1].plot(h["t"][1:], h["err"][1:], "o-", ms=3, label="vs piston position")
        ax[1].plot(h["t"][1:], h["err_gas"][1:], "s-", ms=3, label="vs trapped-gas volume")
        ax[1].axhline(0.0, color="k", lw=0.5)
        ax[1].set_xlabel("t (s)")
        ax[1].set_ylabel("relative error")
        ax[1].legend()
        fig.suptitle(os.path.basename(os.path.normpath(args.uda)))
        fig.tight_layout()
        fig.savefig(args.png, dpi=120)
        print(f"wrote {args.png}")
    return h


if __name__ == "__main__":
    main()
