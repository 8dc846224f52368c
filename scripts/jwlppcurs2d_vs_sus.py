#!/usr/bin/env python
"""Uintah's JWLppCuRS2d.ups (tests/mpmice/uintah_reference/) step by step against sus: writes
the deck with every step saved (pysus's copy with <stress_update>usl, Uintah's update), runs
sus (when given) and pysus, and prints per step the largest difference relative to sus's
largest value of the copper particles' velocity and stress (matched by their place on the
particle lattice; sus's z layer at 6.25e-5) and of press_CC and F, with the cell or particle.

    .venv/bin/python scripts/jwlppcurs2d_vs_sus.py --steps 60 --sus PATH/TO/sus --dir OUT
    .venv/bin/python scripts/jwlppcurs2d_vs_sus.py --steps 60 --dir OUT      # sus's run in OUT kept
"""
import argparse
import os
import subprocess
from pathlib import Path

import numpy as np

DECK = Path(__file__).resolve().parent.parent / "tests" / "mpmice" / "uintah_reference" / "JWLppCuRS2d.ups"


def write_deck(out, steps, usl):
    text = DECK.read_text(encoding="iso-8859-1")
    edits = [("<max_Timesteps>      250       </max_Timesteps>", f"<max_Timesteps>{steps}</max_Timesteps>"),
             ("<outputInterval>2.00e-7</outputInterval>", "<outputTimestepInterval>1</outputTimestepInterval>"),
             ('<checkpoint cycle = "1" timestepInterval = "100"/>', ""),
             ("<filebase>JWLppCuRS2d.uda</filebase>", f"<filebase>{out.with_suffix('.uda').name}</filebase>")]
    if usl:
        edits.append(("<interpolator>                  gimp        </interpolator>",
                      "<interpolator>gimp</interpolator><stress_update>usl</stress_update>"))
    for old, new in edits:
        text = text.replace(old, new)
    out.write_text(text.replace('href="inputs/', f'href="{DECK.parent}/inputs/'), encoding="iso-8859-1")


def keyed(x, values, layer):
    """Particles in the order of their place on the particle lattice (x, y)."""
    k = np.round((x[:, :2] - np.array([-1e-2, 0.0])) / 1.25e-4 - 0.5).astype(np.int64)
    key = k[:, 0] * 1000 + k[:, 1]
    o = np.argsort(key[layer])
    return key[layer][o], [v[layer][o] for v in values]


def rel(a, b):
    """The largest |a - b| over the largest |b| (the difference itself where b is all zero)."""
    d = np.abs(a - b)
    m = np.abs(b).max()
    return d.max() / (m if m > 0 else 1.0), np.unravel_index(np.argmax(d), d.shape)


def compare(py_uda, sus_uda):
    from framework.archiver import DataArchive
    from framework.uintah_uda import UintahArchive
    py, su = DataArchive(py_uda), UintahArchive(sus_uda)
    for s in range(1, min(len(py.times) - 1, len(su.times)) + 1):
        p = py.particles(0, s)
        kp, (vp, sp) = keyed(p["p.x"], (p["p.velocity"], p["p.stress"]), slice(None))
        xs = su.particles("p.x", 0, s - 1)
        ks, (vs, ss) = keyed(xs, (su.particles("p.velocity", 0, s - 1), su.particles("p.stress", 0, s - 1)),
                             xs[:, 2] < 1.25e-4)
        line = f"step {s:3d} t {py.times[s]:.6e} (sus {su.times[s - 1]:.6e})"
        if np.array_equal(kp, ks):
            for name, a, b in (("p.velocity", vp, vs), ("p.stress", sp, ss)):
                r, i = rel(a, b)
                line += f"  {name} {r:.2e} ({kp[i[0]]})"
        for name, m in (("press_CC", 0), ("F", 1)):
            r, i = rel(np.squeeze(py.read(name, m, s)[0]), np.squeeze(su.read(name, m, s - 1)[0]))
            line += f"  {name} {r:.2e} {tuple(int(j) for j in i)}"
        print(line, flush=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--steps", type=int, default=60)
    ap.add_argument("--sus", help="sus executable (else the sus run already in --dir is compared)")
    ap.add_argument("--dir", default="jwlppcurs2d_vs_sus")
    a = ap.parse_args()
    out = Path(a.dir).resolve()
    out.mkdir(exist_ok=True)
    if a.sus:
        write_deck(out / "sus.ups", a.steps, usl=False)
        env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
        subprocess.run([a.sus, "sus.ups"], cwd=out, env=env, check=True, stdout=subprocess.DEVNULL)
    write_deck(out / "pysus.ups", a.steps, usl=True)
    from framework.controller import Controller
    ctl = Controller(str(out / "pysus.ups"), quiet=True, filebase=str(out / "pysus.uda"))
    ctl.run()
    compare(ctl.archiver.dir, out / "sus.uda")


if __name__ == "__main__":
    main()
