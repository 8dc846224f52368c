#!/usr/bin/env python
"""The ring and the pontoon falling onto water of paper 003 (sec. 7.1, 7.3; Figs. 6, 8) at
the paper's meshes and times (components/efem).

Runs inputs/EFEM/ring_falling.ups (paper: 100 x 66 elements, 0 to 0.9 s) or
pontoon_falling.ups (50 x 34, 0 to 1.8 s) with the resolution given, prints the wall time,
the steps and element-steps per second; at each output the body's centroid height beside
its Archimedes rest height, and each material's volume against its start; then draws the
paper's panels with scripts/efem_snapshots.py (PNG).

Archimedes rest heights (the pool's water conserved, the body's hollow parts dry):
ring centroid 0.446 m; pontoon bottom 0.428 m with the outside surface at 0.644 m
(draught 0.216 m = its 216 kg/m over 1000 kg/m^3 and its 1.0 m width), centroid 0.557 m.

    .venv/bin/python scripts/efem_falling.py ring                      # 100 x 66, to 0.9 s
    .venv/bin/python scripts/efem_falling.py pontoon                   # 50 x 34, to 1.8 s
    .venv/bin/python scripts/efem_falling.py ring -n 100 64 --max-time 0.3
    .venv/bin/python scripts/efem_falling.py ring -n 50 33 --set slide_condition=false
    .venv/bin/python scripts/efem_falling.py pontoon --uda pontoon_falling.uda   # an existing run
"""
from __future__ import annotations

import argparse
import os
import re
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, ".."))

from framework.archiver import DataArchive  # noqa: E402

SCENES = {
    # deck, the paper's mesh, its end time, Fig.'s panel times, rest centroid height
    "ring": ("ring_falling.ups", (100, 66), 0.9, tuple(0.1 * k for k in range(10)), 0.446),
    "pontoon": ("pontoon_falling.ups", (50, 34), 1.8, tuple(0.2 * k for k in range(10)), 0.557),
}
PONTOON_BOTTOM_REST = 0.428


def centroid_y(da, k):
    """y of the solid's (material 0) volume-fraction centroid."""
    f, (_, y, _) = da.read("vol_frac_CC", 0, k)
    f = f[:, :, 0]
    return float((f.sum(axis=0) * y).sum() / f.sum())


def ring_shape(da, k, r_in=0.075, r_out=0.125, sectors=16):
    """The ring's roundness at output k, from the solid's volume fractions about its centroid:
    (aspect, spread, hole, wall). aspect: sqrt of the ratio of the principal second moments
    (1 for a round ring, above 1 for an oval); spread: (max - min) / mean over `sectors`
    angular sectors of the phi-weighted mean radius (the centreline's radius); hole: the mean
    solid fraction within the inner radius less an element of the centroid (0 for a clean
    hole); wall: the phi-weighted rms distance from the mean centreline radius over the
    exact wall's (r_out - r_in) / sqrt(12) (1 for a sharp wall, above 1 as it smears)."""
    f, (x, y, _) = da.read("vol_frac_CC", 0, k)
    f = f[:, :, 0]
    X, Y = np.meshgrid(x, y, indexing="ij")
    w = f.sum()
    xc, yc = (f * X).sum() / w, (f * Y).sum() / w
    dx, dy = X - xc, Y - yc
    ixx, iyy, ixy = (f * dx * dx).sum() / w, (f * dy * dy).sum() / w, (f * dx * dy).sum() / w
    ev = np.linalg.eigvalsh(np.array([[ixx, ixy], [ixy, iyy]]))
    r = np.hypot(dx, dy)
    sector = ((np.arctan2(dy, dx) + np.pi) / (2.0 * np.pi) * sectors).astype(int) % sectors
    radii = np.array([(f * r)[sector == s].sum() / max(f[sector == s].sum(), 1e-300) for s in range(sectors)])
    inside = r < r_in - (x[1] - x[0])
    rc = (f * r).sum() / w
    wall = np.sqrt((f * (r - rc) ** 2).sum() / w) / ((r_out - r_in) / np.sqrt(12.0))
    return (float(np.sqrt(ev[1] / ev[0])), float((radii.max() - radii.min()) / radii.mean()),
            float(f[inside].mean()), float(wall))


def ring_moment(da, k, r_in=0.075, r_out=0.125):
    """The ring's n = 2 bending moment per metre of its n = 2 shape at output k: the cos 2 theta
    amplitude a2 of the solid's phi-weighted radius about its centroid (theta from the bottom),
    and M2 = (1/pi) sum phi (sigma_hoop - sigma_radial) (r - r_c) cos 2 theta dA of the solid's
    own stress (the pressure drops out of the difference). An elastic ring carries
    M2 / a2 = mu t^3 / R, 24 N m/m per metre here; a smaller ratio is a flattening its stress
    no longer pushes back. Returns (a2 in m, M2 / a2)."""
    f, (x, y, _) = da.read("vol_frac_CC", 0, k)
    s = da.read("stress_CC", 0, k)[0][:, :, 0, :]
    f = f[:, :, 0]
    X, Y = np.meshgrid(x, y, indexing="ij")
    w = f.sum()
    dx, dy = X - (f * X).sum() / w, Y - (f * Y).sum() / w
    r, th = np.hypot(dx, dy), np.arctan2(dx, -dy)
    wall = f * ((r > r_in - 0.035) & (r < r_out + 0.045))
    rc = (wall * r).sum() / wall.sum()
    c2, ct, st = np.cos(2.0 * th), np.cos(th), np.sin(th)
    hoop = s[..., 0] * ct * ct + s[..., 1] * st * st + 2.0 * s[..., 2] * ct * st
    radial = s[..., 0] * st * st + s[..., 1] * ct * ct - 2.0 * s[..., 2] * ct * st
    a2 = 2.0 * (wall * (r - rc) * c2).sum() / wall.sum()
    m2 = (wall * (hoop - radial) * (r - rc) * c2).sum() * (x[1] - x[0]) * (y[1] - y[0]) / np.pi
    return float(a2), float(m2 / a2) if abs(a2) > 1e-4 else float("nan")


def bottom_y(da, k):
    """The pontoon's lowest face: over its middle columns (|x - 0.75| < 0.3 m), the lowest y at
    which the solid's column profile reaches one half, interpolated between element centres."""
    f, (x, y, _) = da.read("vol_frac_CC", 0, k)
    cols = f[np.abs(x - 0.75) < 0.3, :, 0]
    out = []
    for c in cols:
        j = int(np.argmax(c >= 0.5))
        if c[j] < 0.5:
            continue
        if j == 0:
            out.append(y[0])
        else:
            out.append(y[j - 1] + (0.5 - c[j - 1]) / (c[j] - c[j - 1]) * (y[j] - y[j - 1]))
    return float(np.mean(out)) if out else float("nan")


def patches_for(nx, ny):
    """Two patches along x when both halves stay even (the multigrid restricts inside patches)."""
    return (2, 1) if nx % 4 == 0 and ny % 2 == 0 else (1, 1)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene", choices=sorted(SCENES))
    ap.add_argument("-n", type=int, nargs=2, default=None, metavar=("NX", "NY"),
                    help="elements (default the paper's: ring 100 66, pontoon 50 34)")
    ap.add_argument("--max-time", type=float, default=None, help="end time (default the paper's)")
    ap.add_argument("--set", action="append", default=[], metavar="TAG=VALUE",
                    help="an <EFEM> setting of the deck, e.g. slide_condition=false (repeatable)")
    ap.add_argument("--uda", default=None, help="read this run instead of running the deck")
    ap.add_argument("--png", default=None, help="snapshots (default <scene>_<nx>x<ny>.png)")
    args = ap.parse_args(argv)
    deck, mesh, t_end, panels, rest = SCENES[args.scene]
    nx, ny = args.n or mesh
    t_end = args.max_time if args.max_time is not None else t_end
    uda = args.uda
    if uda is None:
        from framework.controller import Controller
        path = os.path.join(HERE, "..", "inputs", "EFEM", deck)
        with open(path) as f:
            text = f.read()
        px, py = patches_for(nx, ny)
        text = re.sub(r"<resolution>.*?</resolution>", f"<resolution> [{nx}, {ny}, 1] </resolution>", text)
        text = re.sub(r"<patches>.*?</patches>", f"<patches> [{px}, {py}, 1] </patches>", text)
        text = re.sub(r"<maxTime>.*?</maxTime>", f"<maxTime> {t_end} </maxTime>", text)
        for item in args.set:
            tag, value = item.split("=", 1)
            text, n = re.subn(rf"<{tag}>.*?</{tag}>", f"<{tag}> {value} </{tag}>", text)
            if not n:
                text = text.replace("<EFEM>\n", f"<EFEM>\n    <{tag}> {value} </{tag}>\n", 1)
        t0 = time.perf_counter()
        ctl = Controller(path, quiet=True, filebase=f"{args.scene}_{nx}x{ny}.uda", deck_text=text)
        ctl.run()
        wall = time.perf_counter() - t0
        print(f"{args.scene} {nx} x {ny} to {t_end} s: wall {wall:.0f} s, {ctl.timestep} steps, "
              f"{nx * ny * ctl.timestep / wall:,.0f} element-steps/s", flush=True)
        uda = ctl.archiver.dir
    da = DataArchive(uda)
    nm = len(da.materials)
    vol0 = [float(da.read("vol_frac_CC", m, 0)[0].sum()) for m in range(nm)]
    for k, t in enumerate(da.times):
        vols = [float(da.read("vol_frac_CC", m, k)[0].sum()) for m in range(nm)]
        fill = sum(da.read("vol_frac_CC", m, k)[0] for m in range(nm))
        if args.scene == "pontoon":
            extra = f"  bottom {bottom_y(da, k):.4f} m (rest {PONTOON_BOTTOM_REST})"
        else:
            extra = "  aspect {:.3f} spread {:.3f} hole {:.3f} wall {:.2f}".format(*ring_shape(da, k))
            a2, ratio = ring_moment(da, k)
            extra += f"  a2 {1000 * a2:.1f} mm M2/a2 {ratio:.1f}"
        print(f"t = {t:5.2f} s  centroid {centroid_y(da, k):.4f} m (rest {rest}){extra}  volume change "
              + ", ".join(f"{da.materials[m]} {v / v0 - 1:+.1e}" for m, (v, v0) in enumerate(zip(vols, vol0)))
              + f"  fill max {fill.max():.5f}")
    from efem_snapshots import main as snapshots
    png = args.png or f"{args.scene}_{nx}x{ny}.png"
    snapshots([uda, *[f"{t:.2f}" for t in panels if t <= da.times[-1] + 1e-9], "--png", png])


if __name__ == "__main__":
    main()
