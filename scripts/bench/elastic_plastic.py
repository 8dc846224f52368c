"""Throughput of elastic_plastic's stress update: particle-steps per second per core.

    .venv/bin/python scripts/bench/elastic_plastic.py [--particles 200000] [--steps 5]

The constitutive kernel alone (no grid), one thread, on the copper of Uintah's adiCu*4000s696K
decks (Mie-Gruneisen EOS) with each flow-stress model of tests/mpm/test_elastic_plastic_hp.py,
and pysus's linear-hardening elastic_plastic beside them. Every particle is stretched at
4000/s with a small random shear, so every step yields and runs the radial return. The first
step (JIT, warm-up) is not timed; the table shows the median over the timed steps.
"""
from __future__ import annotations

import argparse
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))

from components.mpm.constitutive import elastic_plastic as ep_linear  # noqa: E402
from components.mpm.constitutive import elastic_plastic_hp as hp  # noqa: E402
from tests.mpm.test_elastic_plastic_hp import params  # noqa: E402


def case(P, n, steps, dt=1.0e-6):
    rng = np.random.default_rng(1)
    L = np.zeros((n, 3, 3))
    L[:, 2, 2], L[:, 0, 0], L[:, 1, 1] = 4000.0, -2000.0, -2000.0
    L[:, 0, 1] = rng.uniform(-200.0, 200.0, n)
    mass = np.full(n, 8.93e-3)
    F = np.tile(np.eye(3), (n, 1, 1))
    s = np.zeros((n, 3, 3))
    s2 = np.empty_like(s)
    vel = np.zeros((n, 3))
    energy = np.empty(n)
    state = [np.zeros(n) for _ in range(4)] + [np.full(n, 696.0)]
    new = [np.empty(n) for _ in range(5)]
    rates = []
    for k in range(steps + 1):
        F2 = np.ascontiguousarray(np.einsum("pij,pjk->pik", np.eye(3) + L * dt, F))
        vol = mass / 8930.0 * np.linalg.det(F2)
        t = time.perf_counter()
        if P is None:
            ep_linear.update(LINEAR, L, F, F2, vol, mass, vel, dt, s, s2, energy, state[0], new[0])
        else:
            hp.update(P, L, F, F2, vol, mass, vel, dt, s, s2, energy, tuple(state), tuple(new))
        if k:
            rates.append(n / (time.perf_counter() - t))
        F, s, s2 = F2, s2, s
        state[:4] = [new[i].copy() for i in range(4)]
    return float(np.median(rates))


LINEAR = ep_linear.Params(46.0e9, 129.0e9, 90.0e6, 1.0e9)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--particles", type=int, default=200_000)
    ap.add_argument("--steps", type=int, default=5)
    a = ap.parse_args(argv)
    print(f"{'model':<34} particle-steps/s")
    print(f"{'elastic_plastic (linear hardening)':<34} {case(None, a.particles, a.steps):14.3e}")
    for model in ("JC", "ZA", "MTS", "SCG"):
        print(f"{'elastic_plastic ' + model + ' + Mie-Gruneisen':<34} {case(params(model), a.particles, a.steps):14.3e}")


if __name__ == "__main__":
    main()
