"""framework.numba_fold: branches on compile-time constants (closure constants passed to inlined
helpers, tested through &, <<, !=, not) are taken before typing, and the kernel computes
the same numbers as with numba's own pruning."""
import numpy as np
from numba import njit

import framework.numba_fold as numba_fold
import framework.numba_inline as numba_inline

LINEAR, GIMP = 0, 1


@njit(inline="always")
def _weight(kind, active, x):
    if not active:
        return 1.0
    if kind == LINEAR:
        return 1.0 - abs(x)
    return 0.75 - x * x


@njit(inline="always")
def _axis(kind, act, d, x):
    return _weight(kind, act & (1 << d) != 0, x)


def _kernel(kind, act):
    @njit
    def kernel(xs):
        s = 0.0
        for x in xs:
            s += _axis(kind, act, 0, x) * _axis(kind, act, 1, 0.5 * x) * _axis(kind, act, 2, 0.25 * x)
            if act & 4 and kind != LINEAR:
                s += 1.0
        return s
    return kernel


def test_folded_branches_same_numbers(monkeypatch):
    import components  # noqa: F401  (installs the pass as every run does)
    counts = []
    fold = numba_fold.fold_constant_branches

    def counting(func_ir):
        counts.append(fold(func_ir))
        return counts[-1]

    xs = np.linspace(-0.4, 0.4, 9)
    for kind, act in ((LINEAR, 3), (GIMP, 3), (GIMP, 7), (LINEAR, 1)):
        monkeypatch.setattr(numba_fold, "fold_constant_branches", counting)
        counts.clear()
        numba_inline._untyped.clear()      # the helpers built anew (not from an earlier case's constants)
        folded = _kernel(kind, act)(xs)
        assert sum(counts) >= 2, counts      # _weight's tests of its axis bit and of kind
        monkeypatch.setattr(numba_fold, "ENABLED", False)
        plain = _kernel(kind, act)(xs)
        monkeypatch.undo()
        expected = sum((1.0 - abs(x) if kind == LINEAR else 0.75 - x * x)
                       * ((1.0 - abs(0.5 * x) if kind == LINEAR else 0.75 - 0.25 * x * x) if act & 2 else 1.0)
                       * ((0.75 - x * x / 16.0) if act & 4 else 1.0) + (1.0 if act & 4 and kind != LINEAR else 0.0)
                       for x in xs)
        assert folded == plain
        assert np.isclose(folded, expected, rtol=1e-14)
