#!/usr/bin/env python
"""Semi-implicit ICE: PCG iterations to converge and the solve's share of the step time.

    .venv/bin/python scripts/bench/implicit_ice.py [--res 64 128 256 512] [--precond pfmg jacobi]
                                                   [--steps 3] [--patch 64] [--json implicit_ice.json]

Scene (components/ice/scene_lowmach.py: blob_deck): a closed 2D box of air (symmetry
walls) at rest with a hot cylinder (3x the temperature, so 1/3 the density: variable
coefficients) moving at --mach; one material, second-order advection, delT from the flow speed (CFL 0.4). Patches of
--patch^2 cells (the patch count grows with the resolution), one rank. The first
step (numba compilation, the acoustic first delT) is not timed. With delT from the
flow speed the acoustic CFL is 0.4 / Mach at every resolution, so eq. P's condition
number is about 1 + 8 (0.4 / Mach)^2 until that exceeds the Laplacian's own (~ n^2):
at Mach 0.05 the operator is resolution-independent (Jacobi stays flat too); at Mach
0.001 it is the Poisson limit and Jacobi's count grows like n. Printed per
resolution and preconditioner: mean and max inner PCG iterations per solve (relative
L2 tolerance 1e-10), outer iterations per step, seconds per step and the share of the
step spent in the PCG loop.
"""
from __future__ import annotations

import argparse
import json
import os
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))

from components.ice.scene_lowmach import blob_deck  # noqa: E402
from framework.controller import Controller  # noqa: E402


def deck(n, precond, steps, patch, mach):
    return blob_deck(n, mach=mach, steps=steps, implicit=True, precond=precond,
                     patches=f"[{max(1, n // patch)},{max(1, n // patch)},1]")


def run(n, precond, steps, patch, mach):
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "bench.ups")
        with open(path, "w") as f:
            f.write(deck(n, precond, steps + 1, patch, mach))
        c = Controller(path, quiet=True, filebase=os.path.join(d, "b.uda"))
        execute, seen = c.sched.execute, []

        def execute_marking(graph, old_dw, new_dw, **kw):    # solve time of the first step left out
            if old_dw is not None and kw.get("parents") is None:
                seen.append(c.sched.timing.get("ICE::implicitPressureSolve", 0.0))
            return execute(graph, old_dw, new_dw, **kw)
        c.sched.execute = execute_marking
        c.run()
    comp, sched = c.component, c.sched
    its = comp.pcg.iterations
    first = len(its) - sum(comp.outer_iterations[1:])          # solves of the untimed first step
    timed = its[first:]
    step_s = sum(c.step_times[1:]) / steps
    solve = sched.timing.get("ICE::implicitPressureSolve", 0.0) - seen[1]
    share = solve / (step_s * steps)
    return {"cells": n * n, "n": n, "mach": mach, "precond": precond, "patches": max(1, n // patch) ** 2,
            "running": comp.pcg.precond, "iterations_mean": sum(timed) / len(timed), "iterations_max": max(timed),
            "outer_per_step": sum(comp.outer_iterations[1:]) / steps, "step_s": step_s, "solve_share": share}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--res", type=int, nargs="+", default=[64, 128, 256, 512])
    ap.add_argument("--precond", nargs="+", default=["pfmg", "jacobi"])
    ap.add_argument("--steps", type=int, default=3)
    ap.add_argument("--patch", type=int, default=64)
    ap.add_argument("--mach", type=float, nargs="+", default=[0.05, 0.001],
                    help="flow Mach number(s); lower = stiffer (acoustic CFL = 0.4 / Mach)")
    ap.add_argument("--json", default="implicit_ice.json")
    args = ap.parse_args()
    rows = []
    print(f"{'Mach':>6s} {'cells':>8s} {'patches':>7s} {'preconditioner':>22s} {'PCG its (mean/max)':>19s} {'outer':>6s} "
          f"{'s/step':>8s} {'solve share':>11s}")
    for mach, pre, n in ((m, p, n) for m in args.mach for p in args.precond for n in args.res):
        if True:
            r = run(n, pre, args.steps, args.patch, mach)
            rows.append(r)
            print(f"{mach:6g} {n:>4d}^2   {r['patches']:7d} {pre + ' -> ' + r['running']:>22s} "
                  f"{r['iterations_mean']:11.1f}/{r['iterations_max']:<7d} {r['outer_per_step']:6.1f} "
                  f"{r['step_s']:8.3f} {100 * r['solve_share']:10.0f}%", flush=True)
    with open(args.json, "w") as f:
        json.dump(rows, f, indent=1)


if __name__ == "__main__":
    main()
