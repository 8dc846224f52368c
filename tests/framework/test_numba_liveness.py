"""framework.numba_liveness: numba's live map computed on bit masks is numba's own live map,
block for block, for every analysis of a kernel with inlined helpers and loops."""
import numpy as np
from numba import njit
from numba.core import analysis, ir_utils

import framework.numba_liveness as numba_liveness


def _kernel():
    @njit(inline="always")
    def leaf(x, k):
        if x > k:
            return x - k
        elif x < -k:
            return x + k
        return 0.0

    @njit(inline="always")
    def mid(x, n):
        s = 0.0
        for i in range(n):
            s += leaf(x + i, 1.0) * leaf(x - i, 2.0)
            if s > 100.0:
                break
        return s

    @njit
    def kernel(a):
        s = 0.0
        t = 0.0
        for v in a:
            s += mid(v, 3) + mid(-v, 2) * mid(0.5 * v, 4)
            while t < s:
                t += 1.0 + leaf(t, 0.5)
        return s, t
    return kernel


def test_same_live_map_and_kernel(monkeypatch):
    import components  # noqa: F401  (installs the patch as every run does)
    assert analysis.compute_live_map is numba_liveness.compute_live_map
    assert ir_utils.compute_live_map is numba_liveness.compute_live_map
    numba_own = numba_liveness._numba_compute_live_map
    compared = []

    def both(cfg, blocks, var_use_map, var_def_map):
        own = numba_own(cfg, blocks, var_use_map, var_def_map)
        masks = numba_liveness.compute_live_map(cfg, blocks, var_use_map, var_def_map)
        assert masks == own
        assert list(masks) == list(own)
        compared.append(sum(len(v) for v in own.values()))
        return own

    monkeypatch.setattr(analysis, "compute_live_map", both)
    monkeypatch.setattr(ir_utils, "compute_live_map", both)
    kernel = _kernel()
    a = np.linspace(-4.0, 4.0, 21)
    value = kernel(a)
    monkeypatch.undo()
    assert len(compared) > 3 and max(compared) > 50, compared
    fresh = _kernel()
    assert fresh(a) == value
