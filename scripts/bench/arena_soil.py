"""Throughput of ArenaSoil's stress update: particle-steps per second per core.

    .venv/bin/python scripts/bench/arena_soil.py [--particles 20000] [--steps 10]

The constitutive kernel alone (no grid), one thread, with the parameters of Uintah's three
ArenaSoil decks (tests/mpm/uintah_reference/) and their loading: hydrostatic compression of
the saturated soil at 0.5/s (plastic every step), the dry soil's first, elastic, steps at
0.0094/s, the clay's uniaxial strain at 30/s (plastic, damage and rate dependence). The
first two steps (JIT, warm-up) are not timed; CPU time of this process.
"""
from __future__ import annotations

import argparse
import os
import sys
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, ROOT)

from components.mpm.constitutive import arena_soil as A  # noqa: E402
from framework.problemspec import ProblemSpec  # noqa: E402

REF = os.path.join(ROOT, "tests", "mpm", "uintah_reference")
CASES = (("HydrostaticCompressionSaturated", np.eye(3) * -0.5, 1.2e-4),
         ("MultiaxialStrainLoadUnload", np.eye(3) * -0.0094, 6.0e-4),
         ("BoulderClaySHPB072213-014", np.diag([-30.0, 0.0, 0.0]), 1.0e-6))


def rate(deck, Lr, dt, n, steps):
    """(particle-steps per CPU second, the plastic volume strain reached)."""
    root = ProblemSpec.from_string(open(os.path.join(REF, deck + ".ups")).read())
    mat = root.child("MaterialProperties").child("MPM").child("material")
    P = A.read_params(mat.child("constitutive_model"), mat, {})
    old = A.initial_state(P, n)
    F = np.tile(np.eye(3), (n, 1, 1))
    vol, mass, vel = np.ones(n), np.full(n, 1000.0), np.zeros((n, 3))
    s_old, energy = np.zeros((n, 3, 3)), np.zeros(n)
    A.update(P, np.zeros((n, 3, 3)), F, F, vol, mass, vel, 0.0, s_old, s_old, energy, old, old)
    L = np.tile(Lr, (n, 1, 1))
    spent = 0.0
    for k in range(steps + 2):
        F_new = np.einsum("ij,pjk->pik", np.eye(3) + Lr * dt, F)
        new = tuple(np.empty_like(a) for a in old)
        s_new = np.empty_like(s_old)
        t = time.process_time()
        A.update(P, L, F, F_new, vol, mass, vel, dt, s_old, s_new, energy, old, new)
        if k >= 2:
            spent += time.process_time() - t
        F, old, s_old = F_new, new, s_new
    return n * steps / spent, old[2][0]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--particles", type=int, default=20000)
    ap.add_argument("--steps", type=int, default=10)
    a = ap.parse_args()
    for deck, Lr, dt in CASES:
        r, ev = rate(deck, Lr, dt, a.particles, a.steps)
        print(f"{deck:34s} {r:10.3g} particle-steps/s   (plastic volume strain {ev:.3g})")


if __name__ == "__main__":
    main()
