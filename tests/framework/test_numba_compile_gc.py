"""framework/numba_compile_gc.py: no cyclic garbage collection while numba compiles, the
collector as it was afterwards (after a failed compile too)."""
import gc
import sys

import numpy as np
import pytest
from numba import njit
from numba.core.errors import TypingError

from framework import numba_compile_gc


def _fresh_kernel():
    """A new function each call (no cache), big enough that compiling it allocates past the
    collector's thresholds many times over."""
    def kernel(a, b):
        s = 0.0
        for i in range(a.shape[0]):
            x = a[i] * b[i]
            if x > 0.5:
                s += np.sqrt(x) + np.exp(-x) * np.sin(x)
            elif x > 0.25:
                s -= np.cos(x) / (1.0 + x * x)
            else:
                s += np.log1p(x) * np.tanh(x)
        return s
    return njit(kernel)


def _collections_in_compile(f):
    """The collections that start while numba compiles (its Dispatcher's _compile_core is on the
    stack) during f()."""
    count = [0]

    def callback(phase, info):
        frame = sys._getframe(1)
        while frame is not None and phase == "start":
            if frame.f_code.co_name == "_compile_core" and frame.f_code.co_filename.endswith("dispatcher.py"):
                count[0] += 1
                break
            frame = frame.f_back
    gc.callbacks.append(callback)
    try:
        f()
    finally:
        gc.callbacks.remove(callback)
    return count[0]


def test_no_collection_while_compiling_and_collector_back_on():
    a = np.random.default_rng(0).random(8)
    assert gc.isenabled()
    assert _collections_in_compile(lambda: _fresh_kernel()(a, a)) == 0
    assert gc.isenabled()
    # the same compile as if it were nested in another (no pause of its own): the collector runs,
    # so the count above could have failed
    numba_compile_gc._state.depth = 1
    try:
        assert _collections_in_compile(lambda: _fresh_kernel()(a, a)) > 0
    finally:
        numba_compile_gc._state.depth = 0


def test_failed_compile_and_disabled_collector_left_as_they_were():
    @njit
    def bad(x):
        return x.no_such_attribute
    with pytest.raises(TypingError):
        bad(1.0)
    assert gc.isenabled() and numba_compile_gc._state.depth == 0
    gc.disable()
    try:
        _fresh_kernel()(np.ones(3), np.ones(3))
        assert not gc.isenabled()
    finally:
        gc.enable()
