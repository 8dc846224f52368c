"""framework/numba_typing_memo.py: scalar calls typed from the memo, the same machine code as
numba's own typing, overloads (compiled for the caller's flags) left to numba."""
import math
import re

import numpy as np
from numba import njit

from framework import numba_typing_memo


def _kernel():
    """A new function each call: operators, math, NumPy ufuncs on scalars, and max and min
    (numba @overloads) on scalars."""
    def kernel(a, n):
        s = 0.0
        k = 0
        for i in range(a.shape[0]):
            x = a[i] * 2.0 + 1.0
            y = math.sqrt(abs(x)) - np.exp(-x) / (1.0 + x * x)
            s += max(x, y) - min(x, 0.5) * np.sin(y)
            k += i % n + (i > 3)
        return s + k
    return kernel


def _asm(fastmath):
    f = njit(fastmath=fastmath)(_kernel())
    a = np.linspace(-1.0, 2.0, 7)
    value = f(a, 3)
    asm = f.inspect_asm(f.signatures[0])
    # unique ids and addresses in symbol names (and so the sizes of the strings that hold
    # them) differ between any two compiles
    asm = re.sub(r"0x[0-9a-f]+", "0x", re.sub(r"B\d+v\d+", "Bv", asm))
    return value, re.sub(r"(\.size\t[^,\n]*), \d+", r"\1, n", asm)


def test_same_machine_code_with_and_without_the_memo():
    try:
        numba_typing_memo.ENABLED = False
        plain = [_asm(fm) for fm in (False, {"contract"}, True)]
        numba_typing_memo.ENABLED = True
        hits = numba_typing_memo.hits
        memo = [_asm(fm) for fm in (False, {"contract"}, True)]
        assert numba_typing_memo.hits > hits + 20          # the kernel's scalar operators and math
    finally:
        numba_typing_memo.ENABLED = True
    for (v0, a0), (v1, a1) in zip(plain, memo):
        assert v0 == v1 and a0 == a1
    # max and min are overloads compiled with the caller's flags: not from the memo, so that the
    # fastmath kernel's differ from the plain one's (as numba's own)
    assert memo[0][1] != memo[2][1]


def test_overloads_stay_out_of_the_memo():
    from numba.core.registry import cpu_target
    _asm(False)
    memo = cpu_target.typing_context.__dict__.get("_pysus_typing_memo", {})
    assert memo and all(func.typing_key not in (max, min) for func, _ in memo)
    assert any(func.typing_key is math.sqrt for func, _ in memo)
