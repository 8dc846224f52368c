"""Faster numba IR inlining: copy a callee's IR with one deepcopy memo for all its blocks.

numba's InlineWorker.inline_ir copies the callee's IR block by block, each block with a fresh
deepcopy memo, so every block copies the callee's whole Scope (every variable of the callee,
its own inlined callees' included) again. For MPM's transfer kernels, whose helpers are
inlined several levels deep (inline="always"), that is most of the compile time and memory.
Sharing the memo between the blocks of one copy makes one Scope copy per inlined call; the
copied IR is the same IR (the blocks shared one Scope before and share one copy after), so the
typed IR and the machine code do not change. Importing this module installs it once.
"""
from __future__ import annotations

import contextvars
import copy as _copy

from numba.core import inline_closurecall as _icc
from numba.core import ir as _ir

_memos = contextvars.ContextVar("pysus_inline_memos", default=None)
ENABLED = True          # False: numba's own per-block copies (for comparison in tests)


class _SharedMemoCopy:
    """Stands in for the `copy` module inside numba's inline_closurecall: a Block copied
    while inline_ir runs shares the memo of the other blocks of the same source IR (same
    Scope object); everything else is the copy module's own."""

    def __getattr__(self, name):
        return getattr(_copy, name)

    @staticmethod
    def deepcopy(x, memo=None):
        memos = _memos.get()
        if memo is None and memos is not None and isinstance(x, _ir.Block):
            memo = memos.setdefault(id(x.scope), ({}, x.scope))[0]
        return _copy.deepcopy(x, memo)


def _install():
    worker = _icc.InlineWorker
    if getattr(worker.inline_ir, "_pysus_shared_memo", False):
        return
    original = worker.inline_ir

    def inline_ir(self, *args, **kwargs):
        # one memo per source Scope for this call: its two copies (the callee's IR, then the
        # copy kept unmutated) each copy a different source once
        token = _memos.set({} if ENABLED else None)
        try:
            return original(self, *args, **kwargs)
        finally:
            _memos.reset(token)

    inline_ir._pysus_shared_memo = True
    worker.inline_ir = inline_ir
    _icc.copy = _SharedMemoCopy()


_install()
