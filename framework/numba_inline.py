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
code do not change. A helper whose arguments include compile-time constants of the caller (a
kernel factory's interpolator kind, its active axes) is built once per set of such constants:
its parameters are bound to them and the branches on them folded (the code they leave
unreachable dropped) before its own helpers are inlined, so those are inlined for the same
constants in turn (numba_fold would fold the same branches in the caller after the copy): each
call site builds and copies only its own interpolator's and axes' code, never every
interpolator's (MPM's first g2p variant in a process: 6.2 -> 3.2 CPU s of compile, the same
machine code). Importing this module installs it once.
"""
from __future__ import annotations

import contextvars
import copy as _copy
import inspect

import numba

from numba.core import bytecode as _bytecode
from numba.core import inline_closurecall as _icc
from numba.core import ir as _ir
from numba.core import untyped_passes as _up
from numba.core.ir_utils import build_definitions

from framework import numba_fold

_memos = contextvars.ContextVar("pysus_inline_memos", default=None)
_exact_definitions = contextvars.ContextVar("pysus_inline_exact_definitions", default=None)
_binding = contextvars.ContextVar("pysus_inline_binding", default=None)     # (callee being built, constants)
ENABLED = True          # False: numba's own copies and untyped passes (for comparison in tests)
FOLD_AT_CALL = True     # False: callees copied whole, folded in the caller only (for comparison in tests)
_untyped = {}           # callee function -> [(flags, locals, its untyped IR, constant arguments)]
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


def _callee_entry(worker, function, constants=()):
    """(flags, locals, the callee's untyped IR as numba's run_untyped_passes gives it, constants),
    built once per (callee, compile flags, locals, constant arguments). With constants (by
    position, _constant_arguments) the callee's parameters are bound to them and the branches on
    them folded before the callee's own inlining runs (_bind_constants), so its helpers are
    inlined, and copied, for those constants only. A call site gets a shallow copy under a fresh
    FunctionIdentity (inline_ir names the inlined variables after it and deep-copies the blocks
    before changing anything)."""
    worker.flags.enable_ssa = False             # what run_untyped_passes does to the flags
    entries = _untyped.setdefault(function, [])
    for entry in entries:
        if entry[0] == worker.flags and entry[1] == worker.locals and entry[3] == constants:
            return entry
    token = _binding.set((function, constants) if constants else None)
    try:
        func_ir = worker.run_untyped_passes(function)
    finally:
        _binding.reset(token)
    entry = (type(worker.flags)(copy_from=worker.flags), dict(worker.locals or {}), func_ir, constants)
    entries.append(entry)
    return entry


def _bind_constants(func_ir, constants):
    """Give the parameters at `constants` (by position) their values in the callee's own IR,
    each where it has one definition (its argument), and fold the branches on them."""
    by_position = {position: value for position, _, value in constants}
    definitions = build_definitions(func_ir.blocks)
    for block in func_ir.blocks.values():
        for stmt in block.body:
            if isinstance(stmt, _ir.Assign) and isinstance(stmt.value, _ir.Arg) \
                    and stmt.value.index in by_position and len(definitions.get(stmt.target.name, ())) == 1:
                stmt.value = _ir.Const(by_position[stmt.value.index], stmt.value.loc)
    numba_fold.fold_constant_branches(func_ir)
    func_ir._definitions = build_definitions(func_ir.blocks)


def _fresh_identity(func_ir, function):
    """A shallow copy of func_ir under a new FunctionIdentity of `function`."""
    out = func_ir.copy()
    out.func_id = _bytecode.FunctionIdentity.from_function(function)
    return out


def _constant_arguments(caller_ir, call):
    """((position, type, value), ...) of the call's positional arguments that are int or bool
    constants of the caller (numba_fold's rules, on definitions kept exact in this pass)."""
    memo = {}
    out = []
    for position, var in enumerate(call.args):
        try:
            value = numba_fold._value(caller_ir, var, memo)
        except (numba_fold._NotConstant, ArithmeticError, ValueError):
            continue
        out.append((position, type(value), value))
    return tuple(out)


def _callee_for_call(worker, caller_ir, call, function):
    """The callee's untyped IR for this call site: built for the caller's constant arguments
    where the caller's definitions are exact (numba's untyped inlining pass)."""
    constants = ()
    if FOLD_AT_CALL and numba_fold.ENABLED and _exact_definitions.get() is caller_ir \
            and not worker._permit_update_type_and_call_maps and isinstance(call, _ir.Expr) and call.op == "call" \
            and not function.__code__.co_flags & inspect.CO_VARARGS:
        constants = _constant_arguments(caller_ir, call)
    return _fresh_identity(_callee_entry(worker, function, constants)[2], function)


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
        callee_ir = _callee_for_call(self, caller_ir, block.body[i].value, function)
        return self.inline_ir(caller_ir, block, i, callee_ir, function.__code__.co_freevars,
                              arg_typs=arg_typs)

    def run_pass(self, state):
        binding = _binding.get()
        if binding is not None and binding[0] is state.func_id.func:
            _bind_constants(state.func_ir, binding[1])
        # the caller's definitions, rebuilt here, are kept exact by inline_ir for the pass
        exact = ENABLED and FOLD_AT_CALL
        if exact:
            state.func_ir._definitions = build_definitions(state.func_ir.blocks)
        token = _exact_definitions.set(state.func_ir if exact else None)
        try:
            return original_run_pass(self, state)
        finally:
            _exact_definitions.reset(token)

    original_inline_function = worker.inline_function
    original_run_pass = _up.InlineInlinables.run_pass
    inline_ir._pysus_shared_memo = True
    worker.inline_ir = inline_ir
    worker.inline_function = inline_function
    _up.InlineInlinables.run_pass = run_pass
    _icc.copy = _SharedMemoCopy()


_install()
