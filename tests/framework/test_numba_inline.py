"""framework.numba_inline: numba's IR inlining with one deepcopy memo per callee copy gives the
same kernels and copies far fewer IR variables; a callee folded to its call site's constant
arguments (bound before its own helpers are inlined) gives the same machine code as one folded in
the caller after the copy."""
import re

import numpy as np
from numba import njit
from numba.core import ir

import framework.numba_inline as numba_inline


def _helpers():
    @njit(inline="always")
    def leaf(x, k):
        if x > k:
            return x - k
        elif x < -k:
            return x + k
        return 0.0

    @njit(inline="always")
    def mid(x):
        return leaf(x, 1.0) + leaf(x, 2.0) * leaf(x, 3.0) - leaf(2 * x, 0.5)

    @njit
    def kernel(a):
        s = 0.0
        for v in a:
            s += mid(v) + mid(-v) * mid(0.5 * v)
        return s
    return kernel


def _compile_counting_var_copies(enabled, monkeypatch):
    count = [0]
    original = ir.Var.__deepcopy__

    def counting(self, memo):
        count[0] += 1
        return original(self, memo)

    monkeypatch.setattr(ir.Var, "__deepcopy__", counting)
    monkeypatch.setattr(numba_inline, "ENABLED", enabled)
    kernel = _helpers()
    a = np.linspace(-4.0, 4.0, 101)
    value = kernel(a)
    monkeypatch.undo()
    return value, count[0], kernel.inspect_asm(kernel.signatures[0])


def test_shared_memo_same_kernel_fewer_copies(monkeypatch):
    import components  # noqa: F401  (installs the patch as every run does)
    assert getattr(numba_inline._icc.InlineWorker.inline_ir, "_pysus_shared_memo", False)
    plain, plain_copies, plain_asm = _compile_counting_var_copies(False, monkeypatch)
    shared, shared_copies, shared_asm = _compile_counting_var_copies(True, monkeypatch)
    assert shared == plain
    # the same machine code but for the names numba numbers per compilation
    strip = lambda s: [ln for ln in s.splitlines() if "kernel" not in ln and "leaf" not in ln
                       and "mid" not in ln and ".file" not in ln and "_ZN" not in ln]
    assert strip(shared_asm) == strip(plain_asm)
    assert shared_copies * 3 < plain_copies, (shared_copies, plain_copies)


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


def _factory_kernel(kind, act):
    @njit
    def kernel(xs):
        s = 0.0
        for x in xs:
            s += _axis(kind, act, 0, x) * _axis(kind, act, 1, 0.5 * x) * _axis(kind, act, 2, 0.25 * x)
        return s
    return kernel


def test_callee_folded_at_call_same_machine_code(monkeypatch):
    import components  # noqa: F401
    xs = np.linspace(-0.4, 0.4, 9)
    for kind, act in ((LINEAR, 3), (GIMP, 7), (GIMP, 1)):
        out = []
        for at_call in (True, False):
            monkeypatch.setattr(numba_inline, "FOLD_AT_CALL", at_call)
            numba_inline._untyped.clear()
            kernel = _factory_kernel(kind, act)
            value = kernel(xs)
            folded = sum(1 for entries in numba_inline._untyped.values() for entry in entries if entry[3])
            # mangled names and the length of the string naming the kernel's environment (the
            # number of digits of numba's function counter, which the tests run before set) differ
            asm = re.sub(r"_ZN[0-9A-Za-z_$]+", "", kernel.inspect_asm(kernel.signatures[0]))
            asm = re.sub(r'(?<=Environment: ", )\d+', "", asm)
            out.append((value, asm, folded))
        monkeypatch.undo()
        (value, asm, folded), (plain_value, plain_asm, plain_folded) = out
        assert value == plain_value and asm == plain_asm
        assert folded >= 3 and plain_folded == 0, (folded, plain_folded)   # _axis at d = 0, 1, 2
