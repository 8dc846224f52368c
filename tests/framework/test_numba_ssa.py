"""framework.numba_ssa: SSA reconstruction rewriting only the blocks that mention each variable
gives numba's own IR, statement for statement and name for name, for every reconstruction of
a kernel with inlined helpers, loops and variables reassigned across blocks."""
import copy

import numpy as np
from numba import njit
from numba.core import ssa

import framework.numba_ssa as numba_ssa


def _kernel():
    @njit(inline="always")
    def leaf(x, k):
        y = x
        if x > k:
            y = x - k
        elif x < -k:
            y = x + k
        return y

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


def _dump(blocks):
    return [(label, type(b).__name__, [str(s) for s in b.body]) for label, b in blocks.items()]


def test_same_ir_and_kernel(monkeypatch):
    import components  # noqa: F401  (installs the patch as every run does)
    assert ssa._run_ssa is numba_ssa.run_ssa
    numba_own = numba_ssa._numba_run_ssa
    compared = []

    def both(blocks):
        theirs_in = copy.deepcopy(blocks)
        theirs = numba_own(theirs_in)
        ours = numba_ssa.run_ssa(blocks)
        assert _dump(ours) == _dump(theirs)
        ours_scope, theirs_scope = ssa._get_scope(ours), ssa._get_scope(theirs)
        assert list(ours_scope.localvars._con) == list(theirs_scope.localvars._con)
        assert not set(map(id, ours.values())) & set(map(id, blocks.values()))
        compared.append(sum(len(b.body) for b in theirs.values()))
        return ours

    monkeypatch.setattr(ssa, "_run_ssa", both)
    kernel = _kernel()
    a = np.linspace(-4.0, 4.0, 21)
    value = kernel(a)
    monkeypatch.undo()
    assert compared and max(compared) > 200, compared
    fresh = _kernel()
    assert fresh(a) == value
