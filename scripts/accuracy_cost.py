#!/usr/bin/env python
"""What accuracy costs: run a scene at several resolutions and options; print cells,
steps, wall time, error and observed order side by side; write JSON (and a PNG of
error vs cells and vs wall time when matplotlib is importable).

    .venv/bin/python scripts/accuracy_cost.py sod --res 50 100 200 400 \
        --opt order=FirstOrder,SecondOrder --json sod.json --png sod.png

    .venv/bin/python scripts/accuracy_cost.py toro3 --res 100 200 400 --opt energy=internal,total
    .venv/bin/python scripts/accuracy_cost.py toro3 --res 100 200 400 \
        --opt limiter=vanLeer,BarthJespersen --opt heating=true,false --uintah PATH/TO/sus
    .venv/bin/python scripts/accuracy_cost.py wave1d --res 25 50 100 200 400 \
        --opt order=FirstOrder,SecondOrder --json wave1d.json --png wave1d.png
    .venv/bin/python scripts/accuracy_cost.py wave2d --res 16 32 64 \
        --opt transverse=false,true --opt cfl=0.4,0.1
    .venv/bin/python scripts/accuracy_cost.py vortex --res 16 32 64 --opt scheme=explicit,implicit \
        --opt mach=0.05
    .venv/bin/python scripts/accuracy_cost.py cylinder --res 12 18 24 36 48 72 --json cylinder.json
    .venv/bin/python scripts/accuracy_cost.py cylinder --res 12 18 24 36 --opt dz=dx --opt ri=0.4 --opt ro=0.9
    .venv/bin/python scripts/accuracy_cost.py piston --res 50 100 200 400 --opt heat=1,0 --json piston.json
    .venv/bin/python scripts/accuracy_cost.py piston --res 40 100 200 --opt gamma=1.4,1.67 --opt speed=0.001,0.002
    .venv/bin/python scripts/accuracy_cost.py piston --res 100 200 --opt heat=0 --opt stroke=0.3,0.5,0.83
    .venv/bin/python scripts/accuracy_cost.py piston --res 40 80 --uintah PATH/TO/sus
    .venv/bin/python scripts/accuracy_cost.py cylinder --res 12 18 --uintah PATH/TO/sus
    .venv/bin/python scripts/accuracy_cost.py bar --res 25 50 100 200 --opt interpolator=linear,gimp
    .venv/bin/python scripts/accuracy_cost.py lame --res 11 22 44 --opt interpolator=linear,gimp
    .venv/bin/python scripts/accuracy_cost.py disks --res 20 50 --opt interpolator=linear,gimp --opt update=musl,usl
    .venv/bin/python scripts/accuracy_cost.py stretch --res 25 50 100 200 --interpolators linear,gimp,cpdi,fast_cpdi
    .venv/bin/python scripts/accuracy_cost.py twist --res 8 16 32 --interpolators linear,gimp,cpdi,fast_cpdi

A scene is a name -> (deck template taking the resolution and options, error function
of the finished run's DataArchive). Components add theirs to SCENES below (ICE: Sod and
Toro's tests 1-5, and the smooth periodic entropy wave in 1D and along the diagonal in
2D, from components/ice/scenes.py; the low-Mach Taylor-Green vortex, explicit against
semi-implicit ICE, from components/ice/scene_lowmach.py; MPM's bar, Lame cylinder,
colliding disks and the manufactured large deformations (a bar stretched to twice its
length, a twisted ring) with each interpolator and stress update, from
components/mpm/scene_accuracy.py); nothing else here is component-specific.
--interpolators LIST is --opt interpolator=LIST. A run that breaks down (a blown-up
particle, particles beyond the patch's nodes) prints a FAILED row and the table goes on.
--uintah SUS runs each resolution's deck on Uintah's sus too, once for each option
combination that gives sus a deck of its own (pysus-only options are dropped, see
uintah_deck: `--opt limiter=vanLeer,BarthJespersen` is one sus run, `--opt ri=0.5,0.6` two) and reads its .uda (framework/uintah_uda.py):
its error and wall time (sus's start-up included) join the table, the JSON and the PNG.
An implicit deck runs on sus's own CGSolver unless --uintah-solver names another (deck: the
deck's own, hypre where sus has it).
Wall time is the whole run (initialisation included: the 2D wave's per-cell geometry
takes a noticeable part of it); step_s in the JSON is the time-stepping alone.
"""
from __future__ import annotations

import argparse
import itertools
import json
import math
import os
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))

from framework.archiver import DataArchive  # noqa: E402
from framework.controller import Controller  # noqa: E402
from framework.errors import RunStopped  # noqa: E402


def _ice_scene(name):
    from components.ice import scenes

    def deck(n, order="SecondOrder", cfl="0.4", energy="internal", limiter=None, heating=None):
        """energy=internal (Uintah's ICE) or total (<conserveTotalEnergy>); limiter=vanLeer or
        BarthJespersen (Uintah's); heating=true/false (<advection dissipationHeating>)."""
        return scenes.shock_tube_deck(name, n=n, order=order, cfl=float(cfl), conserve=energy == "total",
                                      limiter=limiter, heating=None if heating is None else heating == "true")

    def error(da):
        err, num, ex, _ = scenes.shock_tube_errors(da, name)
        return {**err, "peak": float(num["rho"].max() / ex["rho"].max())}
    return {"deck": deck, "error": error, "key": "rho",
            "what": f"ICE {name}: L1 error of density, velocity, pressure vs the exact Riemann solution; "
                    "peak: the largest density over the exact one (the overshoot at a blast wave's contact)"}


def _wave_scene(dim):
    from components.ice import scenes

    def deck(n, order="SecondOrder", cfl="0.4", transverse="false", periods="1"):
        return scenes.smooth_wave_deck(n, order=order, cfl=float(cfl), dim=dim, periods=float(periods),
                                       transverse=transverse.lower() in ("1", "true", "yes"))
    return {"deck": deck, "error": scenes.smooth_wave_errors, "key": "rho",
            "what": f"ICE smooth entropy wave, periodic {dim}D{' (diagonal)' if dim == 2 else ''}: L1 error of "
                    "density vs the translated exact cell averages (order of accuracy on a smooth problem)"}


def _vortex_scene():
    from components.ice import scene_lowmach as V
    state = {"mach": 0.05}

    def deck(n, scheme="explicit", cfl="0.4", mach="0.05", precond="pfmg"):
        """scheme=explicit or implicit (<ImplicitSolver>: delT from the flow speed)."""
        state["mach"] = float(mach)
        return V.vortex_deck(n, mach=float(mach), implicit=scheme == "implicit", cfl=float(cfl), precond=precond)

    def error(da):
        return V.vortex_errors(da, mach=state["mach"])
    return {"deck": deck, "error": error, "key": "u",
            "what": "ICE Taylor-Green vortex at low Mach (steady Euler solution), periodic 2D, to 0.2 turnover "
                    "times: L1 error of velocity and of p - mean(p); explicit vs semi-implicit ICE"}


SCENES = {name: (lambda n=name: _ice_scene(n)) for name in ("sod", "toro1", "toro2", "toro3", "toro4", "toro5")}
SCENES["wave1d"] = lambda: _wave_scene(1)
SCENES["wave2d"] = lambda: _wave_scene(2)
SCENES["vortex"] = _vortex_scene


def _cylinder_scene():
    from components.mpmice import scene_cylinder as C

    state = {"ri": C.RI, "ro": C.RO}

    def deck(n, damping=None, patches="1,1,1", ri=None, ro=None, t_end=None, dz=None, stab=None, ppc=None,
             fill=None, interpolator=None, geom=None, cut=None, heat=None, trace=None):
        """n cells across the 1.2 m domain (dx = 1.2/n; the paper's 0.025 m: n = 48); ri, ro: the
        annulus's radii in m (0.5, 1.0); t_end: the end time in s (5e-3); dz: the one z
        cell's thickness in m (0.025), or dx; stab: the MPM <DoPressureStabilization> (true);
        ppc: the steel's particles per cell per direction (2); fill: its
        <numLevelsParticleFilling>; interpolator (gimp); geom=smooth: the steel in rings; cut: its
        <cut_cell_particles> (true; pysus only: sus runs the deck without it); heat: the steel's
        heat exchange coefficient with the airs (0); trace: ICE's <delT_traceVolFrac> (none; pysus
        only)."""
        state["ri"] = C.RI if ri is None else float(ri)
        state["ro"] = C.RO if ro is None else float(ro)
        return C.deck(n, damping=damping, patches=patches, t_end=t_end, ri=state["ri"], ro=state["ro"], dz=dz,
                      stab=stab, ppc=ppc, fill=fill, interpolator=interpolator, geom=geom, cut=cut, heat=heat,
                      trace=trace)

    def error(da):
        return C.errors(da, state["ri"], state["ro"])
    return {"deck": deck, "error": error, "key": "eq43",
            "what": "MPMICE pressurized cylinder (paper 000 sec. 4.1): eq. 43 error of s_r + s_t over all particles, "
                    "radial/hoop L1 error vs Lame (eq. 42) relative to the inner gauge pressure P"}


SCENES["cylinder"] = _cylinder_scene


def _piston_scene():
    from components.mpmice import scene_piston as P

    state = {"gamma": P.GAMMA}

    def deck(n, heat=None, stop=None, gamma=None, speed=None, ratio=None, stroke=None, open=None, dtmax=None):
        """n cells along the 2.5 mm column (dy = 2.5e-3 / n; the deck's 200 cells: n = 200);
        heat: the heat-exchange coefficient (the deck's 1); stop: the piston's stop_time;
        gamma: the gases' gamma (1.4); speed: the piston's speed in m/s (1e-3); ratio: V1/V2
        where the piston stops (5.9); stroke: the piston's travel as a fraction of the trapped
        gas's initial height (ratio = 1 / (1 - stroke); the deck's 0.83); open: false for
        Uintah's advection next to the piston (openFaceTransfers, docs/MPMICE.md); dtmax: the
        deck's delt_max in s (0.006 at the deck's speed)."""
        state["gamma"] = P.GAMMA if gamma is None else float(gamma)
        if stroke is not None:
            ratio = 1.0 / (1.0 - float(stroke))
        return P.deck(n, heat=heat, stop=stop, gamma=gamma, speed=speed, ratio=ratio, open_faces=open,
                      delt_max=dtmax)

    def error(da):
        return P.errors(da, state["gamma"])
    return {"deck": deck, "error": error, "key": "max",
            "what": "MPMICE adiabatic piston (paper 000 sec. 4.2, rmpmice + implicit ICE): bottom pressure vs "
                    "P1 (V1/V2)^gamma (eq. 44); end = relative error at the highest compression (V1/V2 = ratio), "
                    "max / mean = |error| while the piston moves, late = max |error| from V1/V2 = 2 to the stop, "
                    "end_gas with the trapped gas's own volume ratio"}


SCENES["piston"] = _piston_scene


def _mpm_scene(name):
    from components.mpm import scene_accuracy as A
    deck, error, key, what = A.SCENES[name]
    return {"deck": deck, "error": error, "key": key, "what": what}


for _name in ("bar", "lame", "disks", "stretch", "twist"):
    SCENES[_name] = (lambda n=_name: _mpm_scene(n))


def run_case(scene, n, opts, workdir):
    """Run one deck; returns a result row (cells, steps, wall time, errors)."""
    text = scene["deck"](n, **opts)
    path = os.path.join(workdir, "deck.ups")
    with open(path, "w") as f:
        f.write(text)
    c = Controller(path, quiet=True, filebase=os.path.join(workdir, "run.uda"))
    t0 = time.perf_counter()
    c.run()
    wall = time.perf_counter() - t0
    err = scene["error"](DataArchive(c.archiver.dir))
    cells = int(math.prod(c.level.ncells))
    return {"n": n, "cells": cells, "steps": c.timestep, "wall_s": wall,
            "step_s": sum(c.step_times), "errors": err, **{f"opt_{k}": v for k, v in opts.items()}}


PYSUS_ONLY_ATTRS = ("limiter", "dissipationHeating", "transverseTerms", "openFaceTransfers")


def uintah_deck(text, solver="CGSolver"):
    """The deck as Uintah's sus takes it: pysus-only options dropped (sus's own scheme runs),
    one material's boundary conditions under id "0" (sus refuses "all" then), symmetry
    on faces the deck leaves open (a 1D tube: y and z), the output at t = 0 written (the
    piston's V1/V2 starts from it), and an implicit deck's <Solver> set to `solver` (sus's
    own CGSolver by default: it needs no hypre, and solves the pressure system to the
    deck's relative <tolerance> as hypre's cg does, in the max norm of the residual per
    cell volume: with its default L2 norm CGSolver tests the unscaled squared residual
    against tolerance^2 before its first iteration, and a deck in small units, such as the
    piston's (residual^2 ~ 1e-22), is never solved; None keeps the deck's solver)."""
    from lxml import etree
    root = etree.fromstring(text.encode())
    sol = root.find("Solver")
    if sol is not None and solver:
        sol.set("type", solver)
        if solver == "CGSolver":
            for par in root.iter("Parameters"):
                if par.find("norm") is None:
                    etree.SubElement(par, "norm").text = "LInfinity"
    da = root.find("DataArchiver")
    if da is not None and da.find("outputInitTimestep") is None:
        etree.SubElement(da, "outputInitTimestep")
    for a in root.iter("advection"):
        for name in PYSUS_ONLY_ATTRS:
            a.attrib.pop(name, None)
    for tag in ("conserveTotalEnergy", "delT_activeDirectionsOnly", "delT_traceVolFrac", "cut_cell_particles"):
        for e in list(root.iter(tag)):
            e.getparent().remove(e)
    if len(root.findall("MaterialProperties/ICE/material")) == 1:
        for bc in root.iter("BCType"):
            if bc.get("id") == "all":
                bc.set("id", "0")
    tm = root.find("Time")
    if tm is not None and tm.find("timestep_multiplier") is None:      # required by sus, 1 by default here
        etree.SubElement(tm, "timestep_multiplier").text = "1.0"
    bcs = root.find("Grid/BoundaryConditions")
    if bcs is not None:
        have = {f.get("side") for f in bcs.findall("Face")}
        for side in ("x-", "x+", "y-", "y+", "z-", "z+"):
            if side not in have:
                face = etree.SubElement(bcs, "Face", side=side)
                etree.SubElement(face, "BCType", id="0", label="Symmetric", var="symmetry")
    return etree.tostring(root, encoding="unicode")


def run_uintah(sus, scene, n, workdir, solver="CGSolver", opts=None):
    """Run the scene's deck with these options (pysus-only ones dropped by uintah_deck) on
    Uintah's sus; the same row as run_case."""
    import glob
    import subprocess
    from framework.uintah_uda import UintahArchive
    path = os.path.join(workdir, "deck.ups")
    with open(path, "w") as f:
        f.write(uintah_deck(scene["deck"](n, **(opts or {})), solver))
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    t0 = time.perf_counter()
    out = subprocess.run([sus, path], cwd=workdir, env=env, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    udas = glob.glob(os.path.join(workdir, "*.uda.[0-9][0-9][0-9]"))
    if out.returncode != 0 or not udas:         # sus can exit 0 after a ProblemSetupException
        raise RuntimeError(f"sus failed ({out.returncode}): {(out.stdout + out.stderr).strip()[-400:]}")
    uda = max(udas, key=os.path.getmtime)
    da = UintahArchive(uda)
    steps = int(os.path.basename(da.steps[-1])[1:])
    press, _ = da.read("press_CC", 0, -1)
    return {"n": n, "cells": int(press.size), "steps": steps, "wall_s": wall, "step_s": None,
            "errors": scene["error"](da), "opt_code": "uintah",
            **{f"opt_{k}": v for k, v in (opts or {}).items()}}


def uintah_combos(scene, res, combos, solver):
    """The option combinations that give sus a deck of its own (a geometry, an end time), one
    each: combinations differing only in pysus-only options (a limiter) give sus one deck."""
    seen, keep = set(), []
    for opts in combos:
        decks = tuple(uintah_deck(scene["deck"](n, **opts), solver) for n in res)
        if decks not in seen:
            seen.add(decks)
            keep.append(opts)
    return keep


def _report_row(row, prev, n, key, label, step_column):
    """Adds the observed order against the previous resolution (prev: (n, error) or None) to
    row, prints the row's line and returns (n, error) for the next one."""
    e = row["errors"][key]
    row["order"] = math.log(prev[1] / e) / math.log(n / prev[0]) if prev and e > 0 else None
    o = f"{row['order']:.2f}" if row["order"] is not None else "  - "
    errs = "  ".join(f"{k}={v:.3e}" for k, v in row["errors"].items())
    print(f"{label:24s} cells={row['cells']:8d} steps={row['steps']:6d} "
          f"wall={row['wall_s']:8.3f}s {step_column}  L1 {errs}  order({key})={o}", flush=True)
    return n, e


def _run_or_fail(scene, n, opts, workdir, label):
    """run_case, or a row saying why the run stopped (a scheme that breaks down under large
    deformation may send its particles beyond the patch's nodes): the table goes on."""
    try:
        return run_case(scene, n, opts, workdir)
    except (ArithmeticError, IndexError, RuntimeError, ValueError, RunStopped) as e:
        print(f"{label:24s} n={n:<5d} FAILED ({type(e).__name__}: {str(e)[:110]})", flush=True)
        return {"n": n, "failed": f"{type(e).__name__}: {e}", **{f"opt_{k}": v for k, v in opts.items()}}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene", choices=sorted(SCENES))
    ap.add_argument("--res", type=int, nargs="+", default=[50, 100, 200, 400])
    ap.add_argument("--opt", action="append", default=[], help="name=v1,v2 (an option of the deck template)")
    ap.add_argument("--interpolators", metavar="LIST", default=None,
                    help="the same as --opt interpolator=LIST (MPM scenes: linear,gimp,cpdi,fast_cpdi)")
    ap.add_argument("--json", default=None)
    ap.add_argument("--png", default=None)
    ap.add_argument("--uintah", metavar="SUS", default=None,
                    help="also run each resolution's deck on Uintah's sus (path to the executable)")
    ap.add_argument("--uintah-solver", metavar="NAME", default="CGSolver",
                    help="the <Solver> sus uses for an implicit deck (CGSolver: sus's own; 'deck' keeps the deck's)")
    args = ap.parse_args(argv)
    scene = SCENES[args.scene]()
    if args.interpolators:
        args.opt.append(f"interpolator={args.interpolators}")
    names = [o.split("=")[0] for o in args.opt]
    values = [o.split("=")[1].split(",") for o in args.opt]
    rows = []
    key = scene["key"]
    print(scene["what"])
    for combo in itertools.product(*values) if values else [()]:
        opts = dict(zip(names, combo))
        label = " ".join(f"{k}={v}" for k, v in opts.items())
        with tempfile.TemporaryDirectory() as d:      # warm-up: numba compiles outside the timings
            _run_or_fail(scene, args.res[0], opts, d, label)
        prev = None
        for n in args.res:
            with tempfile.TemporaryDirectory() as d:
                row = _run_or_fail(scene, n, opts, d, label)
            if "failed" in row:
                prev = None
            else:
                prev = _report_row(row, prev, n, key, label, f"step={row['step_s']:8.3f}s")
            rows.append(row)
    uintah_labels = []
    if args.uintah:
        solver = None if args.uintah_solver == "deck" else args.uintah_solver
        combos = [dict(zip(names, c)) for c in (itertools.product(*values) if values else [()])]
        sus_combos = uintah_combos(scene, args.res, combos, solver)
        for opts in sus_combos:
            label = "Uintah sus" + ("" if len(sus_combos) == 1 else " " + " ".join(f"{k}={v}" for k, v in opts.items()))
            uintah_labels.append((label, opts))
            prev = None
            for n in args.res:
                with tempfile.TemporaryDirectory() as d:
                    try:
                        row = run_uintah(args.uintah, scene, n, d, solver, opts)
                    except RuntimeError as e:
                        print(f"{label:24s} n={n:<5d} FAILED ({str(e)[:110]})", flush=True)
                        prev = None
                        continue
                prev = _report_row(row, prev, n, key, label, " " * 14)
                rows.append(row)
    out = {"scene": args.scene, "what": scene["what"], "rows": rows}
    if args.json:
        with open(args.json, "w") as f:
            json.dump(out, f, indent=1)
    if args.png:
        try:
            import matplotlib
            matplotlib.use("Agg")
            import matplotlib.pyplot as plt
        except ImportError:
            print("matplotlib not importable: no PNG", file=sys.stderr)
        else:
            fig, axes = plt.subplots(1, 2, figsize=(10, 4))
            pysus_rows = [r for r in rows if r.get("opt_code") != "uintah" and "failed" not in r]
            groups = [(" ".join(combo) or args.scene,
                       [r for r in pysus_rows if all(r.get(f"opt_{k}") == v for k, v in zip(names, combo))])
                      for combo in (itertools.product(*values) if values else [()])]
            for label, opts in uintah_labels:
                groups.append((label, [r for r in rows if r.get("opt_code") == "uintah"
                                       and all(r.get(f"opt_{k}") == v for k, v in opts.items())]))
            for label, sel in groups:
                for ax, x in zip(axes, ("cells", "wall_s")):
                    ax.loglog([r[x] for r in sel], [r["errors"][key] for r in sel], "o-", label=label)
            for ax, xlabel in zip(axes, ("cells", "wall time (s)")):
                ax.set_xlabel(xlabel)
                ax.set_ylabel(f"error ({key})")
                ax.set_title(args.scene)
                ax.legend()
            fig.tight_layout()
            fig.savefig(args.png, dpi=120)
    return rows


if __name__ == "__main__":
    main()
