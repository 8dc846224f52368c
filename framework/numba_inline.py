"""Faster numba IR inlining: a callee's untyped IR built once, copied with one deepcopy memo.

numba's InlineWorker.inline_ir copies the callee's IR block by block, each block with a fresh
deepcopy memo, so every block copies the callee's whole Scope (every variable of the callee,
its own inlined callees' included) again. For MPM's transfer kernels, whose helpers are
inlined several levels deep (inline="always"), that is most of the compile time and memory.
Sharing the memo between the blocks of one copy makes one Scope copy per inlined call; the
copied IR is the same IR (the blocks shared one Scope before and share one copy after). numba
also runs a callee's untyped passes (its own inlining included) again at every call site; the
result depends only on the callee and the compile flags, and inline_ir never mutates it (it
copies it first), so it is built once per (callee, flags) and handed out under a fresh function
identity, as numba's own would be. inline_ir also copies its copy once more, for a return value
that numba's callers (up to 0.68) discard: that copy is skipped. The typed IR and the machine
code do not change. Importing this module installs it once.
"""
from __future__ import annotations

import contextvars
import copy as _copy
import inspect

import numba

from numba.core import bytecode as _bytecode
from numba.core import inline_closurecall as _icc
from numba.core import ir as _ir

_memos = contextvars.ContextVar("pysus_inline_memos", default=None)
ENABLED = True          # False: numba's own copies and untyped passes (for comparison in tests)
_untyped = {}           # callee function -> [(flags, locals, its untyped IR)]
_SKIP_UNUSED_COPY = tuple(int(v) for v in numba.__version__.split(".")[:2]) <= (0, 68)


class _SharedMemoCopy:
    """Stands in for the `copy` module inside numba's inline_closurecall: a Block copied
    while inline_ir runs shares the memo of the other blocks of the same source IR (same
    Scope object); everything else is the copy module's own."""

    def __getattr__(self, name):
        return getattr(_copy, name)

    @staticmethod
    def deepcopy(x, memo=None):
        state = _memos.get()
        if memo is None and state is not None and isinstance(x, _ir.Block):
            memos, produced = state
            if _SKIP_UNUSED_COPY and id(x.scope) in produced:
                # inline_ir's second copy (of its own first copy) is returned as
                # callee_ir_original, which every caller in numba <= 0.68 discards
                return x
            memo = memos.setdefault(id(x.scope), ({}, x.scope))[0]
            out = _copy.deepcopy(x, memo)
            produced[id(out.scope)] = out.scope
            return out
        return _copy.deepcopy(x, memo)


def _callee_untyped_ir(worker, function):
    """The callee's untyped IR as numba's run_untyped_passes gives it, built once per (callee,
    compile flags, locals); a shallow copy under a fresh FunctionIdentity (inline_ir names the
    inlined variables after it and deep-copies the blocks before changing anything)."""
    worker.flags.enable_ssa = False             # what run_untyped_passes does to the flags
    entries = _untyped.setdefault(function, [])
    for flags, local_types, func_ir in entries:
        if flags == worker.flags and local_types == worker.locals:
            out = func_ir.copy()
            out.func_id = _bytecode.FunctionIdentity.from_function(function)
            return out
    func_ir = worker.run_untyped_passes(function)
    entries.append((type(worker.flags)(copy_from=worker.flags), dict(worker.locals or {}), func_ir))
    return func_ir


def _numba_as_expected():
    """The internals patched here, as numba 0.59-0.68 has them; otherwise numba's own inliner."""
    worker = getattr(_icc, "InlineWorker", None)
    try:
        params = list(inspect.signature(worker.inline_function).parameters)
        ir_params = list(inspect.signature(worker.inline_ir).parameters)
    except (AttributeError, TypeError, ValueError):
        return False
    return (isinstance(getattr(_icc, "copy", None), type(_copy)) or isinstance(_icc.copy, _SharedMemoCopy)) \
        and params == ["self", "caller_ir", "block", "i", "function", "arg_typs"] \
        and ir_params[:6] == ["self", "caller_ir", "block", "i", "callee_ir", "callee_freevars"] \
        and hasattr(worker, "run_untyped_passes")


def _install():
    worker = _icc.InlineWorker
    if getattr(worker.inline_ir, "_pysus_shared_memo", False) or not _numba_as_expected():
        return
    original = worker.inline_ir

    def inline_ir(self, *args, **kwargs):
        # one memo per source Scope for this call, and the Scopes its copies made
        token = _memos.set(({}, {}) if ENABLED else None)
        try:
            return original(self, *args, **kwargs)
        finally:
            _memos.reset(token)

    def inline_function(self, caller_ir, block, i, function, arg_typs=None):
        if not ENABLED:
            return original_inline_function(self, caller_ir, block, i, function, arg_typs=arg_typs)
        callee_ir = _callee_untyped_ir(self, function)
        return self.inline_ir(caller_ir, block, i, callee_ir, function.__code__.co_freevars,
                              arg_typs=arg_typs)

    original_inline_function = worker.inline_function
    inline_ir._pysus_shared_memo = True
    worker.inline_ir = inline_ir
    worker.inline_function = inline_function
    _icc.copy = _SharedMemoCopy()


_install()
