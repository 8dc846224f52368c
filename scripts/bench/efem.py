#!/usr/bin/env python
"""EFEM (components/efem) speed: element-steps per second per core and the share of the
step spent in the pressure Poisson solve.

    .venv/bin/python scripts/bench/efem.py [--res 40 80 160] [--steps 20] [--patch 40] [--json efem.json]

Scene: inputs/EFEM/floating_block.ups (block and water in a 1 m box) at n x n elements,
patches of --patch^2 elements, one rank (one core). The first step (numba compilation)
is not timed. Printed per resolution: seconds per step, element-steps per second, mean
PCG iterations per solve (multigrid-preconditioned, relative tolerance 1e-10), and the
share of the step in the tasks of EFEM::pressureSolve (the PCG loop's body, ghost exchange
excluded) and in its set-up tasks.
"""
from __future__ import annotations

import argparse
import json
import os
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))

from components.efem import scene_float as S  # noqa: E402
from framework.controller import Controller  # noqa: E402

SOLVE = "EFEM::pressureSolve::"            # the PCG loop's body tasks
SETUP = ("EFEM::setupPressureSystem", "EFEM::pressureSolveSetup")


def run(n, steps, patch):
    p = max(1, n // patch)
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "bench.ups")
        text = S.deck_text(n, patches=(p, p), max_time=100.0, filebase=os.path.join(d, "b.uda"))
        text = text.replace("<timestep_multiplier>", f"<max_Timesteps> {steps + 1} </max_Timesteps>"
                            "<timestep_multiplier>")
        text = text.replace("<outputInterval> 0.1 </outputInterval>", "<outputInterval> 1000 </outputInterval>")
        with open(path, "w") as f:
            f.write(text)
        c = Controller(path, quiet=True)
        execute, marks = c.sched.execute, []

        def execute_marking(graph, old_dw, new_dw, **kw):      # task times of the first step left out
            if old_dw is not None and kw.get("parents") is None:
                marks.append(dict(c.sched.timing))
            return execute(graph, old_dw, new_dw, **kw)
        c.sched.execute = execute_marking
        c.run()
    step_s = sum(c.step_times[1:]) / steps
    first = marks[1]

    def spent(names):
        return sum(c.sched.timing.get(k, 0.0) - first.get(k, 0.0) for k in names)
    solve = [k for k in c.sched.timing if k.startswith(SOLVE)]
    its = c.component.pcg.iterations[1:]
    return {"n": n, "elements": n * n, "patches": p * p, "steps": steps, "step_s": step_s,
            "element_steps_per_s": n * n / step_s, "pcg_iterations": sum(its) / max(1, len(its)),
            "solve_share": spent(solve) / (step_s * steps), "setup_share": spent(SETUP) / (step_s * steps)}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--res", type=int, nargs="+", default=[40, 80, 160])
    ap.add_argument("--steps", type=int, default=20)
    ap.add_argument("--patch", type=int, default=40)
    ap.add_argument("--json", default=None)
    args = ap.parse_args(argv)
    rows = []
    print(f"{'n':>5} {'patches':>7} {'s/step':>8} {'elem-steps/s':>13} {'PCG its':>8} {'solve':>6} {'set-up':>6}")
    for n in args.res:
        r = run(n, args.steps, args.patch)
        rows.append(r)
        print(f"{n:5d} {r['patches']:7d} {r['step_s']:8.4f} {r['element_steps_per_s']:13.0f} "
              f"{r['pcg_iterations']:8.1f} {100 * r['solve_share']:5.1f}% {100 * r['setup_share']:5.1f}%", flush=True)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f, indent=1)


if __name__ == "__main__":
    main()
