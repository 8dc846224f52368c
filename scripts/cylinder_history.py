#!/usr/bin/env python
"""The pressurized cylinder's way to its quasi-static state: run the scene's deck
(components/mpmice/scene_cylinder.py, the accuracy_cost.py scene "cylinder") with an output
every --every seconds and print, at each, the inner air's gauge pressure P, the mean of
s_r + s_t over Lame's (level) and the hoop force the steel carries over P ri (load; 1 when the
steel carries the inner pressure).

    .venv/bin/python scripts/cylinder_history.py 24 --opt ri=0.4 --opt dz=dx --every 1e-4
    .venv/bin/python scripts/cylinder_history.py 24 --opt dz=dx --opt heat=1e6 --every 5e-4
"""
from __future__ import annotations

import argparse
import os
import re
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))

from components.mpmice import scene_cylinder as C  # noqa: E402
from framework.archiver import DataArchive  # noqa: E402
from framework.controller import Controller  # noqa: E402


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("n", type=int, help="cells across the 1.2 m domain (the paper's 0.025 m: 48)")
    ap.add_argument("--opt", action="append", default=[], metavar="KEY=VALUE",
                    help="a scene_cylinder.deck option: ri, ro, dz, t_end, stab, cut, heat, damping, ...")
    ap.add_argument("--every", type=float, default=1e-4, help="seconds between outputs (1e-4)")
    args = ap.parse_args(argv)
    opts = {}
    for kv in args.opt:
        key, sep, value = kv.partition("=")
        if not sep:
            ap.error(f"--opt {kv!r}: KEY=VALUE")
        opts[key] = value
    ri = float(opts.get("ri", C.RI))
    ro = float(opts.get("ro", C.RO))
    text = re.sub(r"<outputInterval>[^<]*</outputInterval>", f"<outputInterval> {args.every!r} </outputInterval>",
                  C.deck(args.n, **opts))
    with tempfile.TemporaryDirectory() as work:
        path = os.path.join(work, "deck.ups")
        with open(path, "w") as f:
            f.write(text)
        ctl = Controller(path, quiet=True, filebase=os.path.join(work, "run.uda"))
        ctl.run()
        print(f"{'t (ms)':>8} {'P (MPa)':>8} {'level':>8} {'load':>7}")
        for t, P, level, load in C.history(DataArchive(ctl.archiver.dir), ri, ro):
            print(f"{t * 1e3:8.3f} {P:8.3f} {level:+8.4f} {load:7.4f}")


if __name__ == "__main__":
    main()
