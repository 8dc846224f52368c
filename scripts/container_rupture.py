#!/usr/bin/env python
"""A notched steel ring around burning HMX pressurizes, bulges and ruptures (paper 000
sec. 5, 001 sec. 4.3): runs inputs/MPMICE/burning_container_rupture2D.ups (or reads a
finished run) and reports what components/mpmice/scene_container.py measures.

Per output: t, timestep, explosive burned (% of its initial mass), failed steel particles,
the opening (widest angular gap between intact steel particles times their mean radius),
the mean gap pressure and the mean pressure outside the ring, the product gas mass that
has left the ring (escaped) and the gas mass in cells that were solid explosive. Then:
the first failure, the rupture (first output with an opening wider than two cells), when
the gas starts to escape (more than 5 % of the gas outside at t = 0), the peak gap pressure, the largest relative change of the total mass of all materials, the
steps and the wall time.

    .venv/bin/python scripts/container_rupture.py                # 1500 steps, ~30 s
    .venv/bin/python scripts/container_rupture.py --steps 1800 --every 50
    .venv/bin/python scripts/container_rupture.py --uda burning_container_rupture2D.uda
"""
from __future__ import annotations

import argparse
import os
import re
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))

import numpy as np  # noqa: E402

from components.mpmice import scene_container as S  # noqa: E402
from framework.archiver import DataArchive  # noqa: E402


def run(steps, every, filebase):
    """Run the deck for `steps` steps with an output every `every`; (archive, wall s, steps)."""
    from framework.controller import Controller
    text = open(S.DECK, encoding="iso-8859-1").read()
    text = re.sub(r"<outputTimestepInterval>.*?</outputTimestepInterval>",
                  f"<outputTimestepInterval> {every} </outputTimestepInterval>", text)
    c = Controller(S.DECK, deck_text=text, quiet=True, filebase=filebase, max_timesteps=steps)
    t0 = time.perf_counter()
    c.run()
    return DataArchive(c.archiver.dir), time.perf_counter() - t0, c.timestep


def report(da, wall=None, steps=None):
    h = S.history(da)
    dx = da.dx[0]
    burned = 100.0 * (1.0 - h["he_mass"] / h["he_mass"][0])
    print(f"{'t (us)':>8} {'step':>5} {'burned %':>8} {'failed':>6} {'open mm':>8} {'p gap':>9} "
          f"{'p out':>9} {'escaped kg/m':>12} {'gas in HE':>10} {'dm/m':>9}")
    for i in range(len(h["t"])):
        print(f"{h['t'][i] * 1e6:8.1f} {h['step'][i]:5d} {burned[i]:8.3f} {h['failed'][i]:6d} "
              f"{h['opening'][i] * 1e3:8.2f} {h['p_gap'][i]:9.3e} {h['p_out'][i]:9.3e} "
              f"{h['escaped'][i] / da.dx[2]:12.4e} {h['gas_new'][i] / da.dx[2]:10.3e} {h['dmass'][i]:+9.1e}")
    f = np.nonzero(h["failed"] > 0)[0]
    if len(f):
        print(f"first failed steel particles: by t = {h['t'][f[0]] * 1e6:.1f} us (step {h['step'][f[0]]}), "
              f"gap pressure {h['p_gap'][f[0]]:.3e} Pa")
    k = S.rupture(h, dx)
    if k is None:
        print(f"no rupture: widest opening {h['opening'].max() * 1e3:.2f} mm (a rupture: > {S.OPEN_CELLS * dx * 1e3:.1f} mm)")
    else:
        print(f"rupture: opening {h['opening'][k] * 1e3:.2f} mm > {S.OPEN_CELLS:.0f} cells by t = {h['t'][k] * 1e6:.1f} us "
              f"(step {h['step'][k]}); at the end: opening {h['opening'][-1] * 1e3:.1f} mm, product gas escaped "
              f"{h['escaped'][-1] / da.dx[2]:.3e} kg/m ({h['escaped'][-1] / h['gas_out'][0]:.2f} x the gas "
              f"outside at t = 0), outside pressure {h['p_out'][0]:.3e} -> {h['p_out'][-1]:.3e} Pa")
    e = S.escape(h)
    if e is not None:
        print(f"gas escaping: more than {100 * S.ESCAPED:.0f} % of the initial outside gas by t = {h['t'][e] * 1e6:.1f} us "
              f"(step {h['step'][e]})")
    j = int(np.argmax(h["p_gap"]))
    print(f"peak gap pressure {h['p_gap'][j]:.3e} Pa at t = {h['t'][j] * 1e6:.1f} us (step {h['step'][j]}); "
          f"explosive burned {burned[-1]:.2f} %; gas in former explosive cells {h['gas_new'][1] / da.dx[2]:.2e} -> "
          f"{h['gas_new'][-1] / da.dx[2]:.2e} kg/m")
    print(f"total mass of all materials: largest relative change {np.abs(h['dmass']).max():.1e}")
    if wall is not None:
        print(f"{steps} steps to t = {h['t'][-1] * 1e6:.1f} us in {wall:.1f} s wall ({1e3 * wall / steps:.1f} ms/step)")
    return h


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--uda", default=None, help="report a finished run instead of running")
    ap.add_argument("--steps", type=int, default=1500)
    ap.add_argument("--every", type=int, default=100, help="output interval in steps")
    args = ap.parse_args(argv)
    if args.uda:
        report(DataArchive(args.uda))
        return
    with tempfile.TemporaryDirectory() as tmp:
        da, wall, steps = run(args.steps, args.every, os.path.join(tmp, "rupture.uda"))
        report(da, wall, steps)


if __name__ == "__main__":
    main()
