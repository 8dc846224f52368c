"""numba's typing of built-in functions on scalars, resolved once per argument types.

Type inference asks the typing context for the signature of every operator and math call in a
kernel: `a * b` on two float64 goes through every template numba has for operator.mul (NumPy's
array operators, which type the ufunc loops before they find no array, among them) each time
it appears, and MPM's inlined transfer kernels have thousands such calls. Where the function
is a built-in (numba.types.Function), every argument is a number or a bool, and the template
that matched is a plain one (its implementation key is the function itself: operators, math,
NumPy ufuncs), the answer depends on the argument types alone: it is kept per typing context
and handed out again (MPM's g2p, GIMP, 3D, MUSL: 3.2 -> 2.9 CPU s of compile). Overloads
(numba's @overload, e.g. max) compile an implementation for the caller's flags and are
always resolved by numba. The machine code is the same (tests/framework/test_numba_typing_memo.py
compares it). Importing this module installs it once.
"""
from __future__ import annotations

from numba.core import types
from numba.core.typing import context as _context

ENABLED = True          # False: numba resolves every call (for comparison in tests)
_SCALARS = (types.Number, types.Boolean)
hits = 0                # calls answered from the memo in this process (for tests)


def _install():
    cls = _context.BaseContext
    if getattr(cls.resolve_function_type, "_pysus_typing_memo", False):
        return
    original = cls.resolve_function_type

    def resolve_function_type(self, func, args, kws):
        global hits
        if not ENABLED or kws or type(func) is not types.Function \
                or not all(isinstance(a, _SCALARS) for a in args):
            return original(self, func, args, kws)
        memo = self.__dict__.get("_pysus_typing_memo")
        if memo is None:
            memo = self._pysus_typing_memo = {}
        key = (func, tuple(args))
        sig = memo.get(key)
        if sig is not None:
            # the key get_call_type records for lowering, should this Function be a new copy
            func._impl_keys.setdefault(sig.args, func.typing_key)
            hits += 1
            return sig
        sig = original(self, func, args, kws)
        if sig is not None and func._impl_keys.get(sig.args) is func.typing_key:
            memo[key] = sig
        return sig

    resolve_function_type._pysus_typing_memo = True
    cls.resolve_function_type = resolve_function_type


_install()
