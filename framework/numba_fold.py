"""Branches on compile-time constants removed before typing: numba's branch pruning, deeper.

The kernels take their interpolator and active-axis mask as closure constants (`kind`, `act`)
and pass them to their inlined helpers (inline="always"), whose branches test them through
expressions: ``act & (1 << d) != 0``, ``not active``, ``kind != LINEAR and ...``. numba's
DeadBranchPrune only folds a comparison of two constants, so most of these branches stay
in the IR: numba types and lowers every interpolator's and every axis' code of each helper
and LLVM deletes it afterwards. After inlining, this pass evaluates each branch condition
that is built only of integer and boolean constants (Const, Global, FreeVar, through
single-definition variables) with +, -, *, //, %, <<, >>, &, |, ^, comparisons, not, unary
minus and bool(), replaces the branch by a jump, and drops the blocks no longer reached.
The code that runs is the code that ran: only branches whose outcome is fixed at compile
time are taken early. Importing this module installs it once.
"""
from __future__ import annotations

import operator

from numba.core import ir, postproc
from numba.core import untyped_passes as _up
from numba.core.analysis import compute_cfg_from_blocks
from numba.core.ir_utils import build_definitions, simplify_CFG

ENABLED = True      # False: numba's own pruning only (for comparison in tests)

_BINOPS = {operator.add, operator.sub, operator.mul, operator.floordiv, operator.mod, operator.lshift,
           operator.rshift, operator.and_, operator.or_, operator.xor, operator.eq, operator.ne, operator.lt,
           operator.le, operator.gt, operator.ge}
_UNARY = {operator.not_, operator.neg, operator.pos, operator.invert}


class _NotConstant(Exception):
    pass


def _value(func_ir, var, memo, depth=0):
    """The compile-time value (int or bool) of variable `var`, or _NotConstant."""
    name = var.name
    if name in memo:
        v = memo[name]
        if v is _NotConstant:
            raise _NotConstant
        return v
    memo[name] = _NotConstant       # a cycle through this variable is not constant
    if depth > 64:
        raise _NotConstant
    defs = func_ir._definitions.get(name, ())
    if len(defs) != 1:
        raise _NotConstant
    d = defs[0]
    if isinstance(d, ir.Var):
        v = _value(func_ir, d, memo, depth + 1)
    elif isinstance(d, (ir.Const, ir.Global, ir.FreeVar)):
        v = d.value
        if type(v) not in (int, bool):
            raise _NotConstant
    elif isinstance(d, ir.Expr) and d.op == "binop" and d.fn in _BINOPS:
        v = d.fn(_value(func_ir, d.lhs, memo, depth + 1), _value(func_ir, d.rhs, memo, depth + 1))
    elif isinstance(d, ir.Expr) and d.op == "unary" and d.fn in _UNARY:
        v = d.fn(_value(func_ir, d.value, memo, depth + 1))
    elif isinstance(d, ir.Expr) and d.op == "call" and len(d.args) == 1 and not d.kws and d.vararg is None:
        fdefs = func_ir._definitions.get(d.func.name, ())
        if len(fdefs) != 1 or not isinstance(fdefs[0], ir.Global) or fdefs[0].value is not bool:
            raise _NotConstant
        v = bool(_value(func_ir, d.args[0], memo, depth + 1))
    else:
        raise _NotConstant
    if type(v) not in (int, bool):
        raise _NotConstant
    memo[name] = v
    return v


def fold_constant_branches(func_ir):
    """Replace each branch on a compile-time constant condition by a jump and delete the
    blocks no longer reached; returns the number of branches replaced."""
    total = 0
    while True:
        func_ir._definitions = build_definitions(func_ir.blocks)
        memo = {}
        folded = 0
        for block in func_ir.blocks.values():
            term = block.body[-1] if block.body else None
            if not isinstance(term, ir.Branch):
                continue
            try:
                taken = _value(func_ir, term.cond, memo)
            except (_NotConstant, ArithmeticError, ValueError):
                continue
            block.body[-1] = ir.Jump(term.truebr if taken else term.falsebr, loc=term.loc)
            folded += 1
        if not folded:
            break
        total += folded
        cfg = compute_cfg_from_blocks(func_ir.blocks)
        for dead in cfg.dead_nodes():
            del func_ir.blocks[dead]
    if total:
        func_ir._definitions = build_definitions(func_ir.blocks)
        postproc.PostProcessor(func_ir).run()
        func_ir.blocks = simplify_CFG(func_ir.blocks)
    return total


def _install():
    cls = _up.InlineInlinables
    if getattr(cls.run_pass, "_pysus_fold", False):
        return
    original = cls.run_pass

    def run_pass(self, state):
        out = original(self, state)
        if ENABLED:
            fold_constant_branches(state.func_ir)
        return out

    run_pass._pysus_fold = True
    cls.run_pass = run_pass


_install()
