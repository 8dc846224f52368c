"""`pysus info | extract | plot RUN.uda`: look into a `.uda` as Uintah's puda, lineextract
and partextract do, and draw it with matplotlib (an optional extra: pip install pysus[plot]).

    pysus info RUN.uda [-t N]                               labels, centring, materials, min/max
    pysus extract RUN.uda --var press_CC --line X0 X1 [-o f.csv]   cells along a line ("x,y,z" points;
                                                                  "x" or "x,y": the rest at the domain's centre)
    pysus extract RUN.uda --particles [--var p.mass ...] [-o f.csv] one row per particle
    pysus plot RUN.uda --var temp_CC [-t N] [-m M] -o out.png       1D profile or 2D field + particles
    pysus plot RUN.uda --var KineticEnergy TotalMass -o out.png      saved sums against time
"""
from __future__ import annotations

import argparse
import csv
import os
import sys

import numpy as np

from .archiver import DataArchive
from .variables import VarType

COMMANDS = ("info", "extract", "plot")


class ToolError(Exception):
    """Bad arguments or a label/timestep the uda lacks: one line, exit 2."""


def parser():
    p = argparse.ArgumentParser(prog="pysus", description="Inspect a .uda (like Uintah's puda/lineextract/partextract).")
    sub = p.add_subparsers(dest="command", required=True)
    for name, text in (("info", "labels, centring, materials, timesteps and min/max"),
                       ("extract", "values along a line, or particles, as CSV"),
                       ("plot", "a PNG: 1D profiles, 2D field with particles (needs matplotlib)")):
        s = sub.add_parser(name, help=text)
        s.add_argument("uda")
        s.add_argument("-t", dest="t", type=int, default=-1, help="output index (negative from the end; default last)")
        s.add_argument("-m", "--mat", dest="mat", type=int, default=0, help="material (default 0)")
        if name != "info":
            s.add_argument("--var", nargs="+", default=[], help="label(s)")
            s.add_argument("-o", dest="out", help="output file (extract: default stdout, also '-o -')")
        if name == "extract":
            s.add_argument("--line", nargs=2, metavar=("X0", "X1"), help='end points "x,y,z" ("x" or "x,y": the other coordinates at the domain\'s centre)')
            s.add_argument("--particles", action="store_true", help="one CSV row per particle")
    return p


def main(argv):
    args = parser().parse_args(argv)
    try:
        if not os.path.isfile(os.path.join(args.uda, "index.json")):
            raise ToolError(f"{args.uda}: not a .uda (no index.json)")
        da = DataArchive(args.uda)
        if not da.timesteps:
            raise ToolError(f"{args.uda}: no output timesteps")
        if not -len(da.timesteps) <= args.t < len(da.timesteps):
            raise ToolError(f"-t {args.t}: the uda has outputs 0..{len(da.timesteps) - 1}")
        {"info": info, "extract": extract, "plot": plot}[args.command](da, args)
        return 0
    except BrokenPipeError:             # `pysus extract ... | head`: the reader has what it wants
        sys.stderr.close()
        return 0
    except (ToolError, KeyError) as e:
        msg = e.args[0] if e.args else str(e)
        print(f"pysus: error: {msg}", file=sys.stderr)
        return 2


def _check_labels(da, names):
    for n in names:
        if n not in da.index["labels"]:
            raise ToolError(f"--var {n}: not saved in {da.path}; saved: {', '.join(da.labels)}")


def info(da, args, out=None):
    """puda: every saved label with its centring, materials and min/max at one output."""
    out = out or sys.stdout
    e = da.index["timesteps"][args.t]
    t = da.times
    print(f"{da.path}: {da.index.get('component', '')} {da.ncells[0]}x{da.ncells[1]}x{da.ncells[2]} cells, "
          f"[{', '.join(f'{v:g}' for v in da.anchor)}] .. [{', '.join(f'{v:g}' for v in da.upper)}] m", file=out)
    print(f"timesteps: {len(t)} outputs, timestep {da.timesteps[0]} .. {da.timesteps[-1]}, "
          f"t = {t[0]:.6g} .. {t[-1]:.6g} s", file=out)
    print(f"values at output {args.t} (timestep {e['timestep']}, t = {float(e['time']):.6g} s):", file=out)
    print(f"  {'label':24s} {'centring':9s} {'type':8s} {'mat':>3s} {'min':>14s} {'max':>14s}  units"
          "   (Vector, Matrix3: of the magnitude)", file=out)
    for name in da.labels:
        li = da.label_info(name)
        units = li["units"] or ""
        if li["centring"] == VarType.REDUCTION.value:
            try:
                t, v = da.reduction(name)
                v = _magnitude(np.asarray(v).reshape((len(t),) + tuple(li["shape"])), li["shape"])
                kind = _type_name(v.dtype, li["shape"])
                print(f"  {name:24s} {li['centring']:9s} {kind:8s} {'-':>3s} {np.min(v):14.6g} {np.max(v):14.6g}  {units}",
                      file=out)
            except OSError:
                print(f"  {name:24s} {li['centring']:9s}", file=out)
            continue
        for m in li["materials"]:
            if li["centring"] == VarType.PARTICLE.value:
                a = da.particles(m, args.t).get(name)
            else:
                try:
                    a, _ = da.read(name, m, args.t)
                except KeyError:
                    a = None
            if a is None or a.size == 0:
                continue
            a = _magnitude(a, li["shape"])
            kind = _type_name(a.dtype, li["shape"])
            print(f"  {name:24s} {li['centring']:9s} {kind:8s} {m:3d} {a.min():14.6g} {a.max():14.6g}  {units}", file=out)


def _magnitude(a, shape):
    """Scalars as they are; a Vector's length and a tensor's Frobenius norm per entry (puda's
    -varsummary gives a Vector's min and max magnitude)."""
    if not shape:
        return a
    return np.sqrt((np.asarray(a, float).reshape(a.shape[:a.ndim - len(shape)] + (-1,)) ** 2).sum(axis=-1))


def _type_name(dtype, shape):
    """Uintah's name for what one entry holds (puda's CCVariable<double>, ParticleVariable<Vector>)."""
    if np.issubdtype(dtype, np.integer):
        return "long64"
    return {(): "double", (3,): "Vector", (3, 3): "Matrix3"}.get(tuple(shape), "x".join(map(str, shape)))


def _point(text, da):
    """A point "x,y,z"; "x" or "x,y" takes the other coordinates at the domain's centre (a 1D or
    2D run's line)."""
    try:
        v = [float(x) for x in text.split(",")]
    except ValueError:
        v = []
    if not 1 <= len(v) <= 3 or not all(np.isfinite(v)):
        raise ToolError(f'--line {text}: a point is "x,y,z" (or "x", "x,y": the rest at the domain\'s centre)')
    centre = 0.5 * (np.asarray(da.anchor, float) + np.asarray(da.upper, float))
    return np.concatenate([v, centre[len(v):]])


def line_cells(da, vt, x0, x1):
    """Indices (i, j, k) of the cells (or nodes/faces along node-like directions) that the
    segment x0-x1 passes through, in order, each once (lineextract's cell list)."""
    shift = np.array([0.0 if vt.node_like(d) and da.ncells[d] > 1 else 0.5 for d in range(3)])
    n = int(np.ceil(np.max(np.abs(x1 - x0) / da.dx))) * 4 + 1
    out = []
    for s in np.linspace(0.0, 1.0, n):
        p = x0 + s * (x1 - x0)
        ijk = tuple(int(v) for v in np.rint((p - da.anchor) / da.dx - shift))    # nearest centre/node
        if not out or out[-1] != ijk:
            out.append(ijk)
    return out


def extract(da, args):
    """lineextract (--line) or partextract (--particles) to CSV."""
    if args.particles == bool(args.line):
        raise ToolError("extract: give --line X0 X1 or --particles")
    _check_labels(da, args.var)
    to_file = args.out not in (None, "-")
    if args.particles:
        table = da.particles_table(args.mat, args.t)
        if not table:
            raise ToolError(f"no particles of material {args.mat} at output {args.t}")
        keep = [c for c in table if not args.var or c.split("[")[0] in args.var or c.startswith("p.x")]
    else:
        if not args.var:
            raise ToolError("extract --line: give --var LABEL")
        x0, x1 = _point(args.line[0], da), _point(args.line[1], da)
        fields, header = [], ["x", "y", "z"]
        for name in args.var:
            vt = VarType(da.index["labels"][name]["type"])
            if not vt.is_grid:
                raise ToolError(f"--var {name}: a {vt.value} label; --line takes grid labels (CC, NC, SFC)")
            data, coords = da.read(name, args.mat, args.t)
            flat = data.reshape(data.shape[:3] + (-1,))
            header += [name] if flat.shape[3] == 1 else [f"{name}[{k}]" for k in range(flat.shape[3])]
            fields.append((vt, flat, coords))
        vt0, _, coords0 = fields[0]
        lo = [int(np.rint((c[0] - a) / h - (0.0 if vt0.node_like(d) and da.ncells[d] > 1 else 0.5)))
              for d, (c, a, h) in enumerate(zip(coords0, da.anchor, da.dx))]
        rows = []
        for ijk in line_cells(da, vt0, x0, x1):
            local = [ijk[d] - lo[d] for d in range(3)]
            if any(not 0 <= local[d] < len(coords0[d]) for d in range(3)):
                continue
            rows.append([coords0[d][local[d]] for d in range(3)] + [v for _, flat, _ in fields for v in flat[tuple(local)]])
        if not rows:
            raise ToolError(f"--line {args.line[0]} {args.line[1]} misses the domain "
                            f"[{', '.join(f'{v:g}' for v in da.anchor)}] .. [{', '.join(f'{v:g}' for v in da.upper)}]")
    # opened once the arguments are known good: an error leaves no empty file behind
    f = open(args.out, "w", newline="") if to_file else sys.stdout
    try:
        w = csv.writer(f)
        if args.particles:
            w.writerow(keep)
            for row in zip(*(table[c] for c in keep)):
                w.writerow([_number(v) for v in row])
            return
        w.writerow(header)
        for row in rows:
            w.writerow([_number(v) for v in row])
    finally:
        if to_file:
            f.close()


def _number(v):
    """A CSV cell: integers (particle IDs) as integers, floats with all their digits."""
    return str(int(v)) if isinstance(v, (int, np.integer)) else repr(float(v))


def plot(da, args):
    """A PNG of one output: profiles along the one long axis (1D), else the field in the
    x-y plane (mid z) with the particles on top."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        raise ToolError("plot needs matplotlib: pip install matplotlib (or pip install pysus[plot])") from None
    if not args.var:
        raise ToolError("plot: give --var LABEL [LABEL ...]")
    if not args.out:
        raise ToolError("plot: give -o FILE.png")
    _check_labels(da, args.var)
    kinds = {n: VarType(da.index["labels"][n]["type"]) for n in args.var}
    sums = [n for n in args.var if kinds[n] == VarType.REDUCTION]
    if sums:
        if len(sums) < len(args.var):
            raise ToolError(f"plot: {', '.join(sums)} are sums over time; plot them apart from the fields "
                            f"({', '.join(n for n in args.var if n not in sums)})")
        return _plot_sums(da, sums, args.out, plt)
    e = da.index["timesteps"][args.t]
    title = f"{os.path.basename(os.path.normpath(da.path))}  timestep {e['timestep']}, t = {float(e['time']):.4g} s"
    long_axes = [d for d in range(3) if da.ncells[d] > 1]
    grid_vars = [n for n in args.var if VarType(da.index["labels"][n]["type"]).is_grid]
    if len(long_axes) == 1 and grid_vars:
        d = long_axes[0]
        fig, axes = plt.subplots(len(grid_vars), 1, figsize=(6, 2.2 * len(grid_vars)), sharex=True, squeeze=False)
        for ax, name in zip(axes[:, 0], grid_vars):
            data, coords = da.read(name, args.mat, args.t)
            ax.plot(coords[d], data.reshape(data.shape[:3] + (-1,))[:, :, :, 0].squeeze(), ".-", ms=3)
            ax.set_ylabel(name + (f" [{da.label_info(name)['units']}]" if da.label_info(name)["units"] else ""))
        axes[-1, 0].set_xlabel("xyz"[d] + " [m]")
        axes[0, 0].set_title(title, fontsize=9)
    else:
        fig, ax = plt.subplots(figsize=(6, 5))
        mappable = None
        for name in grid_vars[:1]:
            data, coords = da.read(name, args.mat, args.t)
            data = data.reshape(data.shape[:3] + (-1,))
            field = data[:, :, data.shape[2] // 2, 0] if data.shape[3] == 1 else \
                np.linalg.norm(data[:, :, data.shape[2] // 2, :], axis=-1)
            mappable = ax.pcolormesh(coords[0], coords[1], field.T, shading="nearest", cmap="viridis")
            fig.colorbar(mappable, ax=ax, label=name)
        pvar = next((n for n in args.var if not VarType(da.index["labels"][n]["type"]).is_grid), None)
        coloured = False
        for m in sorted({int(m) for pm in e["patches"].values() for m in pm["particles"]}):
            parts = da.particles(m, args.t)
            if "p.x" not in parts:
                continue
            shape = tuple(da.index["labels"][pvar]["shape"]) if pvar else ()
            c = _magnitude(parts[pvar], shape) if pvar in parts else None     # |p.stress|, |p.velocity|
            sc = ax.scatter(parts["p.x"][:, 0], parts["p.x"][:, 1], s=2, c=c if c is not None else "k",
                            cmap="plasma" if c is not None else None, linewidths=0)
            if c is not None and not coloured:
                coloured = True
                fig.colorbar(sc, ax=ax, label=f"|{pvar}|" if shape else pvar)
        ax.set_xlim(da.anchor[0], da.upper[0])
        ax.set_ylim(da.anchor[1], da.upper[1])
        ax.set_aspect("equal")
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        ax.set_title(title, fontsize=9)
    fig.tight_layout()
    fig.savefig(args.out, dpi=100)
    plt.close(fig)


def _plot_sums(da, names, out, plt):
    """Saved sums (TotalMass, KineticEnergy, ...) against time, one panel each; a vector's
    components as three lines."""
    fig, axes = plt.subplots(len(names), 1, figsize=(6, 2.2 * len(names)), sharex=True, squeeze=False)
    for ax, name in zip(axes[:, 0], names):
        t, v = da.reduction(name)
        v = np.asarray(v).reshape(len(t), -1)
        for k in range(v.shape[1]):
            ax.plot(t, v[:, k], "-", label="xyz"[k] if v.shape[1] == 3 else None)
        if v.shape[1] == 3:
            ax.legend(fontsize=8)
        units = da.label_info(name)["units"]
        ax.set_ylabel(name + (f" [{units}]" if units else ""))
    axes[-1, 0].set_xlabel("t [s]")
    axes[0, 0].set_title(os.path.basename(os.path.normpath(da.path)), fontsize=9)
    fig.tight_layout()
    fig.savefig(out, dpi=100)
    plt.close(fig)
