"""Strong and weak scaling on 1 and 2 ranks: the example component and ICE.

Strong: the same 1024 x 1024-cell problem (16 patches) on 1 and 2 ranks; weak:
1024 x 512 cells per rank. Scenes: `heat` (the example component's explicit heat
diffusion: a cheap, memory-bound kernel, the hardest case for scaling) and `ice`
(one-material 2D ICE blast with second-order advection, scripts/bench/ice.py). Reports median seconds per step, cell-steps
per second, parallel efficiency, and MPI messages and bytes per timestep (summed
over ranks). Writes JSON. About a minute:
    .venv/bin/python scripts/bench/scaling.py [--scene heat ice] [--steps 40] [--ranks 1 2]
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, ROOT)


def deck(nx, ny, px, py, steps, particles, scene="heat"):
    if scene == "ice":
        import importlib.util
        spec = importlib.util.spec_from_file_location("ice_bench", os.path.join(HERE, "ice.py"))
        mod = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(mod)
        text = mod.deck(2, 1, nx, steps)
        return text.replace(f"[{nx},{nx},1]", f"[{nx},{ny},1]").replace("[4,4,1]", f"[{px},{py},1]") \
            .replace("<upper>[2,2,", f"<upper>[2,{2 * ny / nx},")
    from tests.framework.decks import heat
    text = heat(n=nx, patches=f"[{px},{py},1]", maxTime=1e9, particles=particles, velocity="[1,0.5,0]", omega=0.0)
    text = text.replace(f"[{nx},{nx},1]", f"[{nx},{ny},1]")
    text = text.replace("<maxTime>1000000000.0</maxTime>", f"<maxTime>1e9</maxTime><max_Timesteps>{steps}</max_Timesteps>")
    return text


def worker(args):
    """Runs inside mpiexec: one measurement, JSON on stdout from rank 0."""
    import numpy as np
    from framework.cli import make_comm
    from framework.controller import Controller
    comm = make_comm()
    with tempfile.TemporaryDirectory() as tmp:
        text = deck(args.nx, args.ny, args.px, args.py, args.steps, args.particles, args.scene[0])
        text = text.replace("<DataArchiver>", "<!--").replace("</DataArchiver>", "-->")
        ctl = Controller(os.path.join(tmp, "d.ups"), comm=comm, deck_text=text, quiet=True)
        comm.messages = comm.bytes = 0
        ctl.run()
        steps = np.array(ctl.step_times[3:])
        msgs = comm.allreduce(comm.messages, "sum")
        nbytes = comm.allreduce(comm.bytes, "sum")
        if comm.rank == 0:
            nstep = len(ctl.step_times)
            print(json.dumps({"ranks": comm.size, "cells": args.nx * args.ny,
                              "median_step_s": float(np.median(steps)),
                              "messages_per_step": msgs / nstep, "bytes_per_step": nbytes / nstep}))


def measure(n, nx, ny, px, py, steps, particles, scene):
    mpiexec = os.path.join(os.path.dirname(sys.executable), "mpiexec")
    cmd = [mpiexec, "-n", str(n), sys.executable, __file__, "--worker", "--nx", str(nx), "--ny", str(ny),
           "--px", str(px), "--py", str(py), "--steps", str(steps), "--scene", scene] + (["--particles"] if particles else [])
    env = dict(os.environ, NUMBA_NUM_THREADS="1", OMP_NUM_THREADS="1")
    out = subprocess.run(cmd, capture_output=True, text=True, env=env, cwd=ROOT)
    if out.returncode != 0:
        raise SystemExit(out.stderr)
    return json.loads(out.stdout.strip().splitlines()[-1])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--worker", action="store_true")
    ap.add_argument("--nx", type=int, default=1024)
    ap.add_argument("--ny", type=int, default=1024)
    ap.add_argument("--px", type=int, default=4)
    ap.add_argument("--py", type=int, default=4)
    ap.add_argument("--steps", type=int, default=40)
    ap.add_argument("--particles", action="store_true")
    ap.add_argument("--scene", nargs="+", default=["heat", "ice"])
    ap.add_argument("--ranks", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--json", default="scaling.json")
    args = ap.parse_args()
    if args.worker:
        return worker(args)
    rows = []
    base = None
    print(f"{'scene':6s} {'kind':7s} {'ranks':>5s} {'cells':>10s} {'s/step':>9s} {'Mcell-steps/s':>14s} {'eff':>6s} "
          f"{'msgs/step':>10s} {'KB/step':>9s}")
    scenes = args.scene
    for scene, kind in ((sc, k) for sc in scenes for k in ("strong", "weak")):
        for n in args.ranks:
            ny = args.ny if kind == "strong" else args.ny // 2 * n
            r = measure(n, args.nx, ny, args.px, args.py if kind == "strong" else 2 * n, args.steps, args.particles,
                        scene)
            rate = r["cells"] / r["median_step_s"]
            if n == args.ranks[0]:
                base = r["median_step_s"]
            eff = base / r["median_step_s"] / (n / args.ranks[0]) if kind == "strong" else base / r["median_step_s"]
            r.update(scene=scene, kind=kind, efficiency=eff, cell_steps_per_s=rate)
            rows.append(r)
            print(f"{scene:6s} {kind:7s} {n:5d} {r['cells']:10d} {r['median_step_s']:9.4f} {rate / 1e6:14.2f} {eff:6.1%} "
                  f"{r['messages_per_step']:10.1f} {r['bytes_per_step'] / 1024:9.1f}")
    with open(args.json, "w") as f:
        json.dump(rows, f, indent=1)
    print(f"wrote {args.json}")


if __name__ == "__main__":
    main()
