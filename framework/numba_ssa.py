"""Faster numba SSA reconstruction: each variable fixed in the blocks that hold it only.

numba's ssa._run_ssa gives every variable assigned more than once (every `s += ...` of a
loop, every variable of a helper inlined at several places) fresh names and phi nodes, one
variable at a time, and for each one rewrites every block of the function: a kernel whose
helpers are inlined (inline="always") has thousands of blocks and hundreds of such
variables, and MPMICE's pressure force spent seconds there. A block that neither defines nor
uses the variable comes out of that rewrite unchanged, so here each variable's two rewrites
run over the blocks that mention it, in the same order, with the function's scope: the same
fresh names, the same phi nodes in the same places, the same IR. Importing this module
installs it once.
"""
from __future__ import annotations

import collections
import inspect

from numba.core import ir
from numba.core import ssa as _ssa
from numba.core.analysis import compute_cfg_from_blocks

ENABLED = True      # False: numba's own reconstruction (for comparison in tests)


def _labels_by_variable(blocks, names):
    """{variable name: [labels of the blocks that define or use it]} for `names`, in block order."""
    out = collections.defaultdict(list)
    for label, block in blocks.items():
        seen = set()
        for stmt in block.body:
            for var in stmt.list_vars():
                name = var.name
                if name in names and name not in seen:
                    seen.add(name)
                    out[name].append(label)
    return out


def run_ssa(blocks):
    """numba's ssa._run_ssa (same argument, same result), each variable rewritten only in
    the blocks that mention it (and given phi nodes where numba puts them)."""
    if not ENABLED:
        return _numba_run_ssa(blocks)
    if not blocks:
        return {}
    cfg = compute_cfg_from_blocks(blocks)
    df_plus = _ssa._iterated_domfronts(cfg)
    violators = _ssa._find_defs_violators(blocks, cfg)
    cache_list_vars = _ssa._CacheListVars()
    scope = _ssa._get_scope(blocks)
    where = _labels_by_variable(blocks, set(violators))
    blocks = dict(blocks)
    fresh = set()                    # labels whose Block is already a new object
    for varname in violators:
        part = {label: blocks[label] for label in where[varname]}
        defmap = collections.defaultdict(list)
        states = {"scope": scope, "varname": varname, "defmap": defmap}
        part = _ssa._run_block_rewrite(part, states, _ssa._FreshVarHandler())
        phimap = collections.defaultdict(list)
        states = {"scope": scope, "varname": varname, "defmap": defmap, "phimap": phimap, "cfg": cfg,
                  "phi_locations": _ssa._compute_phi_locations(df_plus, defmap)}
        part = _ssa._run_block_rewrite(part, states, _ssa._FixSSAVars(cache_list_vars))
        blocks.update(part)
        fresh.update(part)
        for label, philist in phimap.items():
            block = blocks[label]
            if label not in fresh:
                block = blocks[label] = _copy_block(block)
                fresh.add(label)
            block.body = philist + block.body
    for label in blocks.keys() - fresh:
        blocks[label] = _copy_block(blocks[label])
    if compute_cfg_from_blocks(blocks) != cfg:
        raise _ssa.errors.CompilerError("CFG mutated in SSA pass")
    return blocks


def _copy_block(block):
    """A new Block holding the same statements (numba's rewrite returns new Blocks throughout)."""
    out = ir.Block(scope=block.scope, loc=block.loc)
    out.body = list(block.body)
    return out


def _numba_as_expected():
    """The internals used here, as numba 0.59-0.68 has them; otherwise numba's own pass."""
    names = ("_run_ssa", "_iterated_domfronts", "_find_defs_violators", "_CacheListVars", "_get_scope",
             "_run_block_rewrite", "_FreshVarHandler", "_FixSSAVars", "_compute_phi_locations")
    if not all(hasattr(_ssa, n) for n in names):
        return False
    try:
        fix = inspect.signature(_ssa._fix_ssa_vars).parameters
        rewrite = inspect.signature(_ssa._run_block_rewrite).parameters
    except (AttributeError, TypeError, ValueError):
        return False
    return list(fix) == ["blocks", "varname", "defmap", "cfg", "df_plus", "cache_list_vars"] \
        and list(rewrite) == ["blocks", "states", "handler"]


_numba_run_ssa = _ssa._run_ssa
if getattr(_numba_run_ssa, "__module__", "") != __name__ and _numba_as_expected():
    _ssa._run_ssa = run_ssa
