"""CPU seconds numba spends compiling MPM's transfer kernels from an empty cache, variant by variant.

    .venv/bin/python scripts/bench/transfer_compile.py g2p linear 3 [musl] [xpic] [, p2g gimp 3 [fext], ...]

A variant is PASS INTERPOLATOR AXES [FLAGS]: PASS g2p (flags musl, xpic), p2g (fext: with the
external force; always with g.volume), p2g_projected (the gradient-enhanced one, with fext) or
grad; AXES the active-axis mask (3: xy, 7: xyz, 11: axisymmetric). Each is called once on 50
particles with the tasks' argument types, its compile timed with the process's CPU clock, in a
fresh NUMBA_CACHE_DIR (numba's own start-up is paid before the first). The first variant of a
process also builds the helpers the later ones share: run one per process for the cost of a
kernel compiled alone (a test worker's first), several for the cost of each after it.
"""
import os
import sys
import tempfile
import time

os.environ["NUMBA_CACHE_DIR"] = tempfile.mkdtemp(prefix="pysus_transfer_compile_")
sys.path.insert(0, os.getcwd())

import numpy as np  # noqa: E402
from numba import njit  # noqa: E402


@njit
def _start_up(x):
    return x + 1


def compile_once(transfer, zeros3, pas, interp, act, flags):
    """CPU seconds of the first call of one variant."""
    on = np.array([bool(act >> d & 1) for d in range(3)])
    dx = np.where(on, [0.5, 0.25, 0.4], 1.0)
    anchor = np.array([0.1, -0.3, 0.7])
    lo = np.where(on, -2, 0).astype(np.int64)
    shape = tuple(int(s) for s in np.where(on, 11, 1))
    n = 50
    rng = np.random.default_rng(0)
    px = np.ascontiguousarray(np.tile(anchor, (n, 1)) + np.where(on, rng.random((n, 3)) * 6 * dx, 0.0))
    lp = zeros3(n) if interp == "linear" else np.tile(dx / 4, (n, 1))
    pv, pm = rng.random((n, 3)), rng.random(n) + 0.5
    F = np.tile(np.eye(3), (n, 1, 1))
    t0 = time.process_time()
    if pas == "g2p":
        g2p = transfer._g2p_entry(interp, act, "musl" in flags, "xpic" in flags)
        own = (px, pv, pm, lp)
        gv = rng.random(shape + (3,))
        g2p(own, own, transfer.one_run(n), anchor, dx, lo, gv, gv.copy(), 0.01, np.empty((n, 3)), np.empty((n, 3)),
            np.empty((n, 3, 3)), np.zeros(shape + (3,)), np.zeros(8), 0.0, np.inf, True, F, np.empty((n, 3, 3)),
            np.empty(n), 1.0, gv, gv)
    elif pas in ("p2g", "p2g_projected"):
        part = (px, pm, pv, pm.copy(), rng.random((n, 3, 3)), rng.random((n, 3)), lp)
        grid = (np.zeros(shape), np.zeros(shape + (3,)), np.zeros(shape), np.zeros(shape + (3,)),
                np.zeros(shape + (3,)))
        projection = pas == "p2g_projected"
        L = (rng.random((n, 3, 3)),) * 2 if projection else ()
        transfer._p2g_entry(interp, act, projection)(part, part, transfer.one_run(n), "fext" in flags, True, anchor,
                                                     dx, lo, *grid, *L)
    elif pas == "grad":
        transfer._grad_entry(interp, act)(px, lp, anchor, dx, lo, np.zeros(shape + (3,)), np.empty((n, 3, 3)), True,
                                          0.01, pm, 1.0, F, np.empty((n, 3, 3)), np.empty(n), 0, 1.0, 1.0, pv,
                                          np.empty((n, 3, 3)), np.empty(n))
    else:
        raise SystemExit(f"unknown pass {pas}; accepted: g2p, p2g, p2g_projected, grad")
    return time.process_time() - t0


def main():
    specs = [s.split() for s in " ".join(sys.argv[1:]).split(",") if s.strip()]
    if not specs:
        raise SystemExit(__doc__)
    _start_up(1)
    from components.mpm import transfer
    from components.mpm.tasks import _zeros3
    total = 0.0
    for pas, interp, act, *flags in specs:
        t = compile_once(transfer, _zeros3, pas, interp, int(act), set(flags))
        total += t
        print(f"{pas} {interp} {act} {' '.join(sorted(flags))}: {t:.2f} CPU s", flush=True)
    print(f"total {total:.2f} CPU s")


if __name__ == "__main__":
    main()
