"""Faster numba variable liveness: the same live map, with sets of variables held as bit masks.

numba's analysis.compute_live_map finds the variables live at the entry of each block in two
fix-point passes over Python sets: the variables defined or used in some block that reaches
each block (def_reach), then liveness pushed backward through the predecessors. In a kernel
whose helpers are inlined (inline="always") the IR has thousands of blocks and tens of
thousands of variables, and the reaching sets of the late blocks hold nearly all of them:
each pass unions sets of that size per block, and numba runs the analysis after every
inlining and rewrite pass (PostProcessor). For MPM's transfer kernels that was a fifth of the
compile. Here each set is one Python int (bit i: the i-th variable), unions and differences
are integer operations, and the same fix points are reached: the least solutions of the
same equations, so the live map, and everything numba derives from it, does not change.
Importing this module installs it once.
"""
from __future__ import annotations

from numba.core import analysis as _analysis
from numba.core import ir_utils as _ir_utils
from numba.core import postproc as _postproc

ENABLED = True      # False: numba's own sets (for comparison in tests)


def _masks(var_maps, order, index):
    """{block: bit mask} of one use or def map, numbering new variable names in `index`."""
    out = {}
    for label in order:
        m = 0
        for name in var_maps[label]:
            bit = index.get(name)
            if bit is None:
                bit = index[name] = len(index)
            m |= 1 << bit
        out[label] = m
    return out


def _names(mask, names):
    """The set of variable names of a bit mask."""
    out = set()
    while mask:
        low = mask & -mask
        out.add(names[low.bit_length() - 1])
        mask ^= low
    return out


def compute_live_map(cfg, blocks, var_use_map, var_def_map):
    """Variables that must be alive at the entry of each block: numba's compute_live_map
    (same arguments, same result) on bit masks."""
    if not ENABLED:
        return _numba_compute_live_map(cfg, blocks, var_use_map, var_def_map)
    topo = list(cfg.topo_order())
    labels = list(blocks.keys())
    every = list(dict.fromkeys(labels + topo))
    index = {}
    use = _masks(var_use_map, every, index)
    defs = _masks(var_def_map, every, index)
    succs = {label: [s for s, _ in cfg.successors(label)] for label in topo}
    preds = {label: [p for p, _ in cfg.predecessors(label)] for label in topo}

    # variables defined or used in a block that reaches each block (itself included)
    reach = {}
    changed = True
    while changed:
        changed = False
        for label in topo:
            r = reach.get(label, 0) | defs[label] | use[label]
            if r != reach.get(label, 0):
                reach[label] = r
                changed = True
            for s in succs[label]:
                old = reach.get(s, 0)
                new = old | r
                if new != old:
                    reach[s] = new
                    changed = True

    # live at entry: used before defined here, or live at a successor, reached here and not defined here
    live = {label: use[label] for label in labels}
    changed = True
    while changed:
        changed = False
        for label in reversed(topo):
            lv = live[label]
            for p in preds[label]:
                old = live[p]
                new = old | (lv & reach.get(p, 0) & ~defs[p])
                if new != old:
                    live[p] = new
                    changed = True
    names = [None] * len(index)
    for name, bit in index.items():
        names[bit] = name
    return {label: _names(live[label], names) for label in labels}


def _numba_as_expected():
    import inspect
    try:
        params = list(inspect.signature(_analysis.compute_live_map).parameters)
    except (TypeError, ValueError):
        return False
    return params == ["cfg", "blocks", "var_use_map", "var_def_map"] \
        and getattr(_ir_utils, "compute_live_map", None) is _analysis.compute_live_map \
        and getattr(_postproc, "analysis", None) is _analysis


_numba_compute_live_map = _analysis.compute_live_map
if getattr(_numba_compute_live_map, "__module__", "") != __name__ and _numba_as_expected():
    _analysis.compute_live_map = compute_live_map
    _ir_utils.compute_live_map = compute_live_map
