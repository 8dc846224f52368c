#!/usr/bin/env python
"""MPMICE cost: time per step split by task, and the coupling overhead over ICE and MPM alone.

    .venv/bin/python scripts/bench/mpmice.py [--n 256] [--steps 10] [--repeat 3] [--cpu] [--json mpmice_bench.json]

Scene (2D, n x n cells, 4 x 4 patches, closed box): a steel block (comp_neo_hook, 2 x 2
particles per cell, the middle third of the box in each direction) moving at 10 m/s in
air at 1 atm, K = 1e15 momentum exchange, second-order advection. Three runs on the same
grid and particles, one rank, one thread, fixed delT so all take the same steps:

  mpmice   steel + air, <SimulationComponent type="mpmice">
  ice      the air alone filling the box (one ICE material)
  mpm      the steel alone (the same particles, MPM only)

The coupling overhead is t(mpmice) - t(ice) - t(mpm) per step, and the ratio
t(mpmice) / (t(ice) + t(mpm)); inside the MPMICE step the tasks are grouped by owner
(ICE::, MPM::, MPMICE::, framework). The first step (numba compilation) is not timed;
with --repeat R each run is repeated and the median time per step is reported. --cpu
times with the process's CPU time instead of the wall clock (a machine shared with other
jobs).
"""
from __future__ import annotations

import argparse
import json
import os
import statistics
import sys
import time
import types

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))

FACES = "".join(f'<Face side="{s}"><BCType id="all" label="Symmetric" var="symmetry"/></Face>'
                for s in ("x-", "x+", "y-", "y+"))

STEEL = """<material name="steel"><density>8900.0</density>
  <constitutive_model type="comp_neo_hook"><bulk_modulus>117.0e9</bulk_modulus><shear_modulus>43.8e9</shear_modulus>
  </constitutive_model><thermal_conductivity>0.0</thermal_conductivity><specific_heat>452.0</specific_heat>
  <geom_object><box label="block"><min>[0.333,0.333,-1]</min><max>[0.667,0.667,1]</max></box>
  <res>[2,2,1]</res><velocity>[10,5,0]</velocity><temperature>300</temperature></geom_object></material>"""

AIR = """<material name="air"><EOS type="ideal_gas"/><dynamic_viscosity>0.0</dynamic_viscosity>
  <thermal_conductivity>0.0</thermal_conductivity><specific_heat>716.0</specific_heat><gamma>1.4</gamma>
  <geom_object>{piece}<res>[2,2,1]</res><velocity>[0,0,0]</velocity><temperature>300.0</temperature>
  <density>1.1792946927374306</density><pressure>101325.0</pressure></geom_object></material>"""

AROUND = ('<difference><box label="all"><min>[-1,-1,-1]</min><max>[2,2,1]</max></box>'
          '<box label="block"/></difference>')
EVERYWHERE = '<box label="all"><min>[-1,-1,-1]</min><max>[2,2,1]</max></box>'

DECK = """<?xml version="1.0"?>
<Uintah_specification><SimulationComponent type="{component}"/>
<Time><maxTime>1.0</maxTime><max_Timesteps>{steps}</max_Timesteps><delt_init>{dt}</delt_init>
  <delt_max>{dt}</delt_max><delt_min>0</delt_min><timestep_multiplier>1.0</timestep_multiplier></Time>
<Grid><BoundaryConditions>{faces}</BoundaryConditions><Level><Box label="1"><lower>[0,0,0]</lower>
  <upper>[1,1,{dz}]</upper><extraCells>[1,1,0]</extraCells><patches>[4,4,1]</patches>
  <resolution>[{n},{n},1]</resolution></Box></Level></Grid>
{cfd}{mpm_flags}
<PhysicalConstants><gravity>[0,0,0]</gravity><reference_pressure>101325.0</reference_pressure></PhysicalConstants>
<MaterialProperties>{mpm}{ice}{exchange}</MaterialProperties></Uintah_specification>"""

EXCHANGE = ("<exchange_properties><exchange_coefficients><momentum>[1e15]</momentum><heat>[0]</heat>"
            "</exchange_coefficients></exchange_properties>")


def deck(kind, n, steps):
    """The deck of one of the three runs; delT is a fixed fraction of the steel's CFL step."""
    dx = 1.0 / n
    dt = 0.3 * dx / 4700.0
    mpm = f"<MPM>{STEEL}</MPM>" if kind in ("mpmice", "mpm") else ""
    ice = {"mpmice": f"<ICE>{AIR.format(piece=AROUND)}</ICE>", "ice": f"<ICE>{AIR.format(piece=EVERYWHERE)}</ICE>",
           "mpm": ""}[kind]
    cfd = '<CFD><cfl>0.4</cfl><ICE><advection type="SecondOrder"/></ICE></CFD>' if kind != "mpm" else ""
    flags = ("<MPM><time_integrator>explicit</time_integrator><interpolator>linear</interpolator></MPM>"
             if kind != "ice" else "")
    return DECK.format(component=kind, steps=steps, dt=dt, faces=FACES, dz=dx, n=n, mpm=mpm, ice=ice,
                       exchange=EXCHANGE if kind == "mpmice" else "", cfd=cfd, mpm_flags=flags)


def owner(task_name):
    """ICE, MPM, MPMICE or framework: who a task belongs to, from its Uintah-style name."""
    for prefix in ("MPMICE", "ICE", "MPM"):
        if task_name.startswith(prefix + "::"):
            return prefix
    return "framework"


def run(kind, n, steps):
    """Seconds per step (steps 2..), seconds per step of every task, and the particle count."""
    from framework.controller import Controller
    ctl = Controller("bench.ups", deck_text=deck(kind, n, 1 + steps), quiet=True)
    execute, seen = ctl.sched.execute, {"steps": 0}

    def execute_timed(graph, old_dw, new_dw, **kw):      # task timings of steps 2.. (no compilation)
        if old_dw is not None:
            seen["steps"] += 1
            if seen["steps"] == 2:
                ctl.sched.timing.clear()
                ctl.sched.overhead.clear()
        return execute(graph, old_dw, new_dw, **kw)
    ctl.sched.execute = execute_timed
    dw = ctl.run()
    npart = sum(len(a) for (name, _, _), a in dw.particles.items() if name == "p.x")
    return sum(ctl.step_times[1:]) / steps, {k: v / steps for k, v in ctl.sched.timing.items()}, npart


def use_cpu_time():
    """Make the controller's step times and the scheduler's task times CPU seconds of this process."""
    import framework.controller as C
    import framework.scheduler.scheduler as S
    clock = types.SimpleNamespace(perf_counter=time.process_time)
    C.time = S.time = clock


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, default=256, help="cells per direction")
    ap.add_argument("--steps", type=int, default=10)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--json", default="mpmice_bench.json")
    ap.add_argument("--cpu", action="store_true", help="CPU time of this process instead of wall time")
    args = ap.parse_args()
    if args.cpu:
        use_cpu_time()
    out = {}
    for kind in ("mpmice", "ice", "mpm"):
        runs = [run(kind, args.n, args.steps) for _ in range(args.repeat)]
        med = statistics.median(r[0] for r in runs)
        best = min(runs, key=lambda r: abs(r[0] - med))
        out[kind] = {"step_s": med, "all_step_s": [r[0] for r in runs], "tasks": best[1], "particles": best[2]}
    cells = args.n * args.n
    t_m, t_i, t_p = (out[k]["step_s"] for k in ("mpmice", "ice", "mpm"))
    print(f"2D, {cells} cells, {out['mpm']['particles']} steel particles, {args.steps} steps x {args.repeat} "
          "runs (median), one core, "
          f"{'CPU' if args.cpu else 'wall'} time")
    print(f"{'run':8s} {'s/step':>9s}")
    for k in ("mpmice", "ice", "mpm"):
        print(f"{k:8s} {out[k]['step_s']:9.4f}")
    print(f"coupling overhead: {t_m - t_i - t_p:.4f} s/step; mpmice / (ice + mpm) = {t_m / (t_i + t_p):.2f}")
    groups = {}
    for name, t in out["mpmice"]["tasks"].items():
        groups[owner(name)] = groups.get(owner(name), 0.0) + t
    total = sum(out["mpmice"]["tasks"].values()) or 1.0
    print("MPMICE step by owner: " + ", ".join(f"{g} {t / total:.0%}" for g, t in sorted(groups.items(),
                                                                                           key=lambda kv: -kv[1])))
    print("MPMICE tasks (s/step, share of the task time):")
    for name, t in sorted(out["mpmice"]["tasks"].items(), key=lambda kv: -kv[1]):
        print(f"  {name:45s} {t:8.4f}  {t / total:5.1%}")
    out["summary"] = {"cells": cells, "coupling_overhead_s": t_m - t_i - t_p, "ratio": t_m / (t_i + t_p),
                      "by_owner": groups}
    with open(args.json, "w") as f:
        json.dump(out, f, indent=1)


if __name__ == "__main__":
    main()
