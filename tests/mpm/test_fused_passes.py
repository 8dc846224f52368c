"""The fused particle passes give bitwise the numbers of the separate ones: the grad pass
with the comp_neo_hook stress (MUSL) against grad, then comp_neo_hook.kernel; p2g without
g.volume against p2g with it; relocation's block gather against the row-by-row one.

The kernels allow multiply-adds to be contracted (fastmath 'contract'), so "bitwise" holds for
two kernels compiled at one optimisation level, as every run's are. The suite compiles what the
shipped decks' warm-up did not at NUMBA_OPT=2 (scripts/test), so one of a pair may be the warm-up's
(full level) and the other the suite's: below the full level the pair must agree to 1e-14 of the
largest value instead (a contraction's rounding), which a wrong sum still fails."""
import numpy as np
import pytest

from components.mpm.constitutive import comp_neo_hook
from components.mpm.transfer import NEO_HOOKE, kernels, one_run
from framework.numba_cache_opt import FULL_LEVEL, opt_level
from framework.scheduler.particle_kernels import gather_merged, gather_runs, runs

from .test_shape import P2G_CASES, make_grid, make_particles


def _state(kind, on, anchor, dx, shape, seed=5):
    px, lp = make_particles(on, anchor, dx, 6, seed=seed, kind=kind)
    n = len(px)
    rng = np.random.default_rng(seed)
    F = np.tile(np.eye(3), (n, 1, 1)) + 0.05 * rng.standard_normal((n, 3, 3))
    gvel = rng.standard_normal(shape + (3,))
    return px, lp, rng.random(n) + 0.5, F, gvel, rng.standard_normal((n, 3))


def same(a, b):
    """Bitwise at numba's full optimisation level; within contraction's rounding below it."""
    a, b = np.asarray(a), np.asarray(b)
    if opt_level() >= FULL_LEVEL:
        return np.array_equal(a, b)
    return a.shape == b.shape and np.allclose(a, b, rtol=0.0, atol=1e-14 * max(np.abs(a).max(initial=0.0), 1e-300))


# P2G_CASES: the shipped decks' combinations with the tasks' argument types (test_shape; these
# compilations are made by scripts/warm_kernels anyway); PYSUS_TEST_VARIANTS=all: every one
@pytest.mark.parametrize("kind,act", P2G_CASES)
def test_grad_with_neo_hooke_stress_equals_separate_passes(kind, act):
    on, anchor, dx, lo, shape = make_grid(act)
    px, lp, pm, F, gvel, vel = _state(kind, on, anchor, dx, shape)
    n = len(px)
    grad = kernels(kind, act)[2]
    K, mu, rho0, dt = 833.3, 384.6, 1000.0, 1e-3
    none = (np.zeros((1, 3)), np.zeros((1, 3, 3)), np.zeros(1))
    L, F1, V1 = np.empty((n, 3, 3)), np.empty((n, 3, 3)), np.empty(n)
    assert grad(px, lp, anchor, dx, lo, gvel, L, True, dt, pm, rho0, F, F1, V1, 0, 0.0, 0.0, *none) == (0, 0, 0)
    s1, e1 = np.empty((n, 3, 3)), np.empty(n)
    w1 = comp_neo_hook.kernel(K, mu, F1, V1, pm, vel, s1, e1)
    F2, V2, s2, e2 = np.empty((n, 3, 3)), np.empty(n), np.empty((n, 3, 3)), np.empty(n)
    w2 = grad(px, lp, anchor, dx, lo, gvel, L, False, dt, pm, rho0, F, F2, V2, NEO_HOOKE, K, mu, vel, s2, e2)
    for a, b in ((F1, F2), (V1, V2), (s1, s2), (e1, e2), (w1, np.array(w2))):
        assert same(a, b)


@pytest.mark.parametrize("kind,act", P2G_CASES)
def test_p2g_without_volume_same_other_sums(kind, act):
    on, anchor, dx, lo, shape = make_grid(act)
    px, lp = make_particles(on, anchor, dx, 6, seed=7, kind=kind)
    n = len(px)
    rng = np.random.default_rng(8)
    part = (px, rng.random(n) + 0.5, rng.random((n, 3)), rng.random(n) + 0.1, rng.random((n, 3, 3)),
            np.zeros((1, 3)), lp)
    p2g = kernels(kind, act)[0]
    out = []
    for hv in (True, False):
        g = [np.zeros(shape), np.zeros(shape + (3,)), np.zeros(shape) if hv else np.zeros((1, 1, 1)),
             np.zeros(shape + (3,)), np.zeros(shape + (3,))]
        p2g(part, part, one_run(n), False, hv, anchor, dx, lo, *g)
        out.append(g)
    assert out[0][2].sum() > 0.0 and not out[1][2].any()
    for k in (0, 1, 3, 4):
        assert same(out[0][k], out[1][k])


@pytest.mark.parametrize("cols,dtype", [(9, np.float64), (3, np.float64), (1, np.int64)])
def test_gather_runs_equals_gather_merged(cols, dtype):
    rng = np.random.default_rng(cols)
    n_src, n_arr = 500, 40
    src = (rng.random((n_src, cols)) * 1e6).astype(dtype)
    arrived = (rng.random((n_arr, cols)) * 1e6).astype(dtype)
    index = np.sort(rng.permutation(n_src + n_arr)[: n_src - 25]).astype(np.int64)
    index[:10] = index[:10][::-1]                      # not sorted everywhere: runs still cover it
    a, b = np.empty((len(index), cols), dtype), np.empty((len(index), cols), dtype)
    gather_merged(src, arrived, index, a)
    gather_runs(src, arrived, runs(index, n_src), b)
    assert np.array_equal(a, b)
