#!/usr/bin/env python
"""ICE throughput and memory: cell-steps per second per core and bytes per cell.

    .venv/bin/python scripts/bench/ice.py [--cells 1000000] [--steps 5] [--json ice_bench.json]
                                          [--only 2D1] [--tasks] [--cpu]

Scenes: an explosion (high-pressure circle/sphere in a closed box, second-order
advection) in 2D and 3D with one material, and with two materials (the charge a second
ideal gas, momentum and heat exchange 1e10). One rank, one thread. Timings exclude
the first step (numba compilation) and initialization. Memory: the peak of numpy
allocations during the timed steps (tracemalloc) and the state carried between steps,
both per cell. Goal (DESIGN.md): 3e6 cell-steps/s/core for one material in 2D, < 0.5 KB
per cell (Uintah needs about 1.8 KB). --tasks prints each task's seconds per step;
--cpu measures CPU seconds of the process instead of wall time (steps and tasks), which
on a machine shared with other jobs is close to what an idle machine gives.
"""
from __future__ import annotations

import argparse
import json
import os
import sys
import tempfile
import time
import tracemalloc

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))

from framework.controller import Controller  # noqa: E402

FACES = "".join(f'<Face side="{s}"><BCType id="all" label="Symmetric" var="symmetry"/></Face>'
                for s in ("x-", "x+", "y-", "y+", "z-", "z+"))

MATERIAL = """<material><EOS type="ideal_gas"/><dynamic_viscosity>0</dynamic_viscosity>
<thermal_conductivity>0</thermal_conductivity><specific_heat>{cv}</specific_heat><gamma>1.4</gamma>
{objects}</material>"""
OBJ = """<geom_object>{piece}<res>[2,2,2]</res><velocity>[0.5,0.3,{w}]</velocity><temperature>{T}</temperature>
<density>{rho}</density><pressure>{p}</pressure></geom_object>"""

DECK = """<Uintah_specification><SimulationComponent type="ice"/>
<Time><maxTime>100</maxTime><max_Timesteps>{steps}</max_Timesteps><delt_init>1e-4</delt_init></Time>
<Grid><BoundaryConditions>{faces}</BoundaryConditions><Level><Box label="1"><lower>[0,0,0]</lower>
<upper>[2,2,{zup}]</upper><extraCells>[1,1,1]</extraCells><patches>{patches}</patches><resolution>{res}</resolution>
</Box></Level></Grid>
<CFD><cfl>0.4</cfl><ICE><advection type="SecondOrder"/></ICE></CFD>
<PhysicalConstants><gravity>[0,0,0]</gravity></PhysicalConstants>
<MaterialProperties><ICE>{materials}</ICE>{exchange}</MaterialProperties></Uintah_specification>"""


def deck(dim, nmat, n, steps):
    """A blast plus a uniform drift, so every face carries a flux (advection costs what it costs)."""
    zup = 2 if dim == 3 else 0.01
    charge = f'<sphere label="c"><origin>[1,1,{1 if dim == 3 else 0.005}]</origin><radius>0.4</radius></sphere>'
    if dim == 2:
        charge = '<cylinder label="c"><bottom>[1,1,-1]</bottom><top>[1,1,1]</top><radius>0.4</radius></cylinder>'
    rest = f'<difference><box><min>[-1,-1,-1]</min><max>[3,3,3]</max></box><{charge.split()[0][1:]} label="c"/>' \
           '</difference>'
    inside = OBJ.format(piece=charge, T=1.0, rho=1.0, p=1.0, w=0.2 if dim == 3 else 0)
    outside = OBJ.format(piece=rest, T=0.8, rho=0.125, p=0.1, w=0.2 if dim == 3 else 0)
    if nmat == 1:
        mats = MATERIAL.format(cv=2.5, objects=inside + outside)
        exch = ""
    else:   # the labelled piece is defined where it first appears (the outer gas)
        tag = charge.split()[0][1:]
        outside = OBJ.format(piece=f'<difference><box><min>[-1,-1,-1]</min><max>[3,3,3]</max></box>{charge}'
                                   '</difference>', T=0.8, rho=0.125, p=0.1, w=0.2 if dim == 3 else 0)
        inside = OBJ.format(piece=f'<{tag} label="c"/>', T=1.0, rho=1.0, p=1.0, w=0.2 if dim == 3 else 0)
        mats = MATERIAL.format(cv=2.5, objects=outside) + MATERIAL.format(cv=2.0, objects=inside)
        exch = ("<exchange_properties><exchange_coefficients><momentum>[1e10]</momentum><heat>[1e10]</heat>"
                "</exchange_coefficients></exchange_properties>")
    res = f"[{n},{n},{n if dim == 3 else 1}]"
    patches = "[2,2,2]" if dim == 3 else "[4,4,1]"
    return DECK.format(steps=steps, faces=FACES, zup=zup, patches=patches, res=res, materials=mats, exchange=exch)


class _CpuClock:
    """Stands in for the scheduler's `time` module so that task timings are CPU seconds."""
    perf_counter = staticmethod(time.process_time)


def bench(dim, nmat, cells, steps, cpu=False):
    n = round(cells ** (1 / dim))
    sched_mod = sys.modules["framework.scheduler.scheduler"]
    sched_mod.time = _CpuClock if cpu else time
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "bench.ups")
        with open(path, "w") as f:
            f.write(deck(dim, nmat, n, steps + 1))
        c = Controller(path, quiet=True)
        tracemalloc.start()
        execute = c.sched.execute

        state = {"steps": 0, "cpu": 0.0}

        def execute_and_reset(graph, old_dw, new_dw, **kw):   # peak of the steps, not of initialization
            if old_dw is not None:
                state["steps"] += 1
                if state["steps"] == 2:          # task timings and peak of steps 2.. (no compilation)
                    tracemalloc.reset_peak()
                    c.sched.timing.clear()
                    c.sched.overhead.clear()
            t0 = time.process_time()
            out = execute(graph, old_dw, new_dw, **kw)
            if state["steps"] >= 2:
                state["cpu"] += time.process_time() - t0
            return out
        c.sched.execute = execute_and_reset
        c.run()
        _, peak = tracemalloc.get_traced_memory()
        tracemalloc.stop()
    ncell = n ** dim
    t = state["cpu"] if cpu else sum(c.step_times[1:])
    return {"dim": dim, "materials": nmat, "cells": ncell, "steps": steps, "step_s": t / steps,
            "cell_steps_per_s": ncell * steps / t, "peak_bytes_per_cell": peak / ncell,
            "task_s_per_step": {k: v / steps for k, v in sorted(c.sched.timing.items(), key=lambda kv: -kv[1])}}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cells", type=int, default=1_000_000)
    ap.add_argument("--steps", type=int, default=5)
    ap.add_argument("--json", default="ice_bench.json")
    ap.add_argument("--only", default=None, help="e.g. 2D1 or 3D2")
    ap.add_argument("--tasks", action="store_true", help="print seconds per step of every task")
    ap.add_argument("--cpu", action="store_true",
                    help="time in CPU seconds of this process, not wall seconds (on a loaded machine)")
    args = ap.parse_args()
    rows = []
    if args.cpu:
        print("CPU seconds of this process (--cpu)")
    print(f"{'case':8s} {'cells':>9s} {'s/step':>8s} {'Mcell-steps/s/core':>19s} {'peak B/cell':>12s}")
    for dim in (2, 3):
        for nmat in (1, 2):
            name = f"{dim}D{nmat}"
            if args.only and name != args.only:
                continue
            r = bench(dim, nmat, args.cells, args.steps, args.cpu)
            rows.append(r)
            print(f"{name:8s} {r['cells']:9d} {r['step_s']:8.3f} {r['cell_steps_per_s'] / 1e6:19.2f} "
                  f"{r['peak_bytes_per_cell']:12.0f}", flush=True)
            if args.tasks:
                for k, v in r["task_s_per_step"].items():
                    print(f"    {k:40s} {v:8.4f} s/step  {v / r['step_s']:5.1%}")
    with open(args.json, "w") as f:
        json.dump(rows, f, indent=1)


if __name__ == "__main__":
    main()
