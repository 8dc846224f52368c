#!/usr/bin/env python
"""gasCombustion (components/models/gas_kinetics.py) speed: the reaction-rate right-hand side per
call, and a closed hydrogen-air reactor through its ignition, beside Uintah's sus.

    .venv/bin/python scripts/bench/gas_chemistry.py [--cells 1 3] [--repeats 3] [--sus SUS]

Scene: tests/models/cv_hydrogen.ups (Uintah's cvHydrogen2: stoichiometric hydrogen-air at
1500 K, Burke's mechanism) on n^3 uniform cells, its 306 steps through the ignition to 2496 K.
Printed: the right-hand side's CPU microseconds per call (best of 5 x 200,000 calls inside
numba), then per n the CPU seconds of the whole run (median of --repeats, kernels compiled
beforehand; pysus in this process, sus as a child process) and cell-steps per CPU second.
"""
from __future__ import annotations

import argparse
import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
sys.path.insert(0, ROOT)

from components.models import gas_kinetics as GK  # noqa: E402
from components.models.gas_mechanism import read_mechanism  # noqa: E402
from framework.controller import Controller  # noqa: E402

DECK = os.path.join(ROOT, "tests", "models", "cv_hydrogen.ups")
MECH = os.path.join(ROOT, "tests", "models", "Burke2012Modified.xml")
STEPS = 306


def rhs_microseconds():
    """CPU microseconds per chem_rhs call, best of 5 loops of 200,000 calls compiled together."""
    from numba import njit
    kin = GK.kinetics(read_mechanism(MECH, "N2"))
    y = np.array([1e-4, 0.028, 1e-5, 1e-4, 0.01, 0.22, 1e-6, 1e-7, 0.0])
    y[-1] = 1.0 - y[:-1].sum()
    work = [np.empty(9) for _ in range(4)] + [np.empty(23), np.empty(8)]

    @njit(error_model="numpy")          # as the chemistry kernel, into which chem_rhs is inlined
    def loop(kin, y, conc, g, u, sdot, q, k1, n):
        s = 0.0
        for i in range(n):
            s += GK.chem_rhs(kin, 1500.0 + i * 1e-9, y, 0.17, 1.0, conc, g, q, u, sdot, k1)[0]
        return s

    loop(kin, y, *work, 10)
    best = np.inf
    for _ in range(5):
        t = time.process_time()
        loop(kin, y, *work, 200000)
        best = min(best, (time.process_time() - t) / 200000 * 1e6)
    return best


def deck(n, folder):
    text = open(DECK).read().replace("<resolution>   [1,1,1]         </resolution>",
                                     f"<resolution>   [{n},{n},{n}]         </resolution>")
    text = text.replace("<outputInterval>2e-6</outputInterval>", "<outputInterval>1</outputInterval>")
    path = os.path.join(folder, f"cv{n}.ups")
    with open(path, "w") as f:
        f.write(text)
    shutil.copy(MECH, folder)
    return path


def pysus_cpu(path, folder):
    t = time.process_time()
    c = Controller(path, quiet=True, filebase=os.path.join(folder, f"py{time.time_ns()}.uda"))
    c.run()
    assert c.timestep == STEPS
    return time.process_time() - t


def sus_cpu(sus, path, folder):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    subprocess.run([sus, os.path.basename(path)], cwd=folder, env=env, check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cells", type=int, nargs="+", default=[1, 3], help="cells per direction")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--sus", help="Uintah's sus: run it on the same decks")
    a = ap.parse_args()
    print(f"chem_rhs: {rhs_microseconds():.3f} CPU us per call (9 species, 23 reactions)")
    with tempfile.TemporaryDirectory() as d:
        for n in a.cells:
            path = deck(n, d)
            pysus_cpu(path, d)                  # compile and warm
            py = statistics.median(pysus_cpu(path, d) for _ in range(a.repeats))
            row = f"{n}^3 cells, {STEPS} steps: pysus {py:.2f} CPU s ({n ** 3 * STEPS / py:.0f} cell-steps/s)"
            if a.sus:
                su = statistics.median(sus_cpu(a.sus, path, d) for _ in range(a.repeats))
                row += f", sus {su:.2f} CPU s ({n ** 3 * STEPS / su:.0f} cell-steps/s), pysus/sus {py / su:.2f}"
            print(row, flush=True)


if __name__ == "__main__":
    main()
