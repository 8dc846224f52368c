"""The ghost exchange's merge of owned and ghost IDs gives exactly the stable argsort of
their concatenation (and its runs), and runs() answers the remembered runs of an order."""
import numpy as np

from framework.scheduler.particle_kernels import KNOWN_RUNS, _runs, merge_ids, runs


def test_merge_ids_is_stable_argsort():
    rng = np.random.default_rng(1)
    for _ in range(2000):
        n_own, n_gh, hi = rng.integers(0, 40), rng.integers(0, 15), rng.integers(1, 60)
        own = np.sort(rng.integers(0, hi, n_own)).astype(np.int64)
        gh = rng.integers(0, hi, n_gh).astype(np.int64)
        ok, order, mask, r = merge_ids(own, gh, np.argsort(gh, kind="stable"), True)
        ref = np.argsort(np.concatenate([own, gh]), kind="stable")
        assert ok and np.array_equal(order, ref) and np.array_equal(mask, ref < n_own)
        assert np.array_equal(r, _runs(ref, n_own))
        if n_own > 1 and own[0] != own[-1]:
            assert not merge_ids(own[::-1].copy(), gh, np.argsort(gh, kind="stable"), True)[0]


def test_runs_remembered_per_array():
    order = np.array([0, 3, 1, 2], np.int64)
    fake = np.zeros((1, 3), np.int64)
    KNOWN_RUNS.put(order, (3, fake))
    assert runs(order, 3) is fake
    assert np.array_equal(runs(order.copy(), 3), _runs(order, 3))
    assert np.array_equal(runs(order, 2), _runs(order, 2))
