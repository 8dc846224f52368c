"""Numba passes over a patch's particles for relocation and ghost selection.

Both only need to look closely at a few particles: those that left the patch, and
those close enough to its faces to be someone's ghost. One pass finds them, so the
per-step cost is one read of the positions rather than one per neighbour. A particle
more than a cell away from the band in question is let through with two comparisons
per axis (_clear); only the others get the exact cell floor((x - anchor)/dx) that
every other particle test of the framework uses, so the answer is the same.
"""
from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True)
def _bounds(anchor, dx, lo, hi, dims):
    """Per axis, positions whose cell is surely in [lo, hi): [anchor + (lo+1) dx, anchor + (hi-1) dx)
    (one cell of margin for the rounding of the exact cell computation); inactive axes: all."""
    b = np.empty((3, 2))
    for d in range(3):
        if dims[d]:
            b[d, 0] = anchor[d] + (lo[d] + 1) * dx[d]
            b[d, 1] = anchor[d] + (hi[d] - 1) * dx[d]
        else:
            b[d, 0] = -np.inf
            b[d, 1] = np.inf
    return b


@njit(cache=True, inline="always")
def _clear(x, p, b):
    """Particle p lies within the bounds b on every axis (False for NaN)."""
    x0, x1, x2 = x[p, 0], x[p, 1], x[p, 2]
    return ((b[0, 0] <= x0) & (x0 < b[0, 1]) & (b[1, 0] <= x1) & (x1 < b[1, 1])
            & (b[2, 0] <= x2) & (x2 < b[2, 1]))


@njit(cache=True)
def leavers(x, anchor, dx, lo, hi, dims):
    """Indices of particles whose cell is outside [lo, hi) (NaN positions count as outside)."""
    n = x.shape[0]
    out = np.empty(n, np.int64)
    k = 0
    b = _bounds(anchor, dx, lo, hi, dims)
    for p in range(n):
        if _clear(x, p, b):
            continue
        outside = False
        for d in range(3):
            if not dims[d]:
                continue
            v = x[p, d]
            if not (v == v):
                outside = True
                break
            c = np.floor((v - anchor[d]) / dx[d])
            if c < lo[d] or c >= hi[d]:
                outside = True
                break
        if outside:
            out[k] = p
            k += 1
    return out[:k]


@njit(cache=True)
def complement(idx, n):
    """The indices in [0, n) that the sorted index array idx does not hold."""
    out = np.empty(n - idx.shape[0], np.int64)
    k = 0
    j = 0
    for p in range(n):
        if j < idx.shape[0] and idx[j] == p:
            j += 1
        else:
            out[k] = p
            k += 1
    return out


@njit(cache=True)
def near_faces(x, anchor, dx, lo, hi, g, dims):
    """Indices and cells of particles within g cells of the patch faces (ghost candidates)."""
    n = x.shape[0]
    idx = np.empty(n, np.int64)
    cells = np.empty((n, 3), np.int64)
    k = 0
    b = _bounds(anchor, dx, lo + g, hi - g, dims)
    for p in range(n):
        if _clear(x, p, b):
            continue
        near = False
        c0 = 0
        c1 = 0
        c2 = 0
        for d in range(3):
            c = 0
            if dims[d]:
                c = int(np.floor((x[p, d] - anchor[d]) / dx[d]))
                if c < lo[d] + g or c >= hi[d] - g:
                    near = True
            if d == 0:
                c0 = c
            elif d == 1:
                c1 = c
            else:
                c2 = c
        if near:
            idx[k] = p
            cells[k, 0] = c0
            cells[k, 1] = c1
            cells[k, 2] = c2
            k += 1
    return idx[:k], cells[:k]


@njit(cache=True)
def gather_merged(owned, ghost, order, out):
    """out[i] = (owned + ghost)[order[i]] without forming the concatenation (rows of 2D views)."""
    n_own = owned.shape[0]
    for i in range(order.shape[0]):
        j = order[i]
        if j < n_own:
            for c in range(owned.shape[1]):
                out[i, c] = owned[j, c]
        else:
            for c in range(owned.shape[1]):
                out[i, c] = ghost[j - n_own, c]


@njit(cache=True)
def gather_runs(owned, ghost, runs, out):
    """out = the row ranges `runs` (source 0: owned, 1: ghost; first, end) one after another:
    gather_merged for an order given as its runs (contiguous block copies, no per-row lookup;
    unsigned offsets, so the copy loops carry no negative-index handling)."""
    k = owned.shape[1]
    fo = owned.reshape(-1)
    fg = ghost.reshape(-1)
    fout = out.reshape(-1)
    o = np.uint64(0)
    for r in range(runs.shape[0]):
        a = np.uint64(runs[r, 1] * k)
        b = np.uint64(runs[r, 2] * k)
        src = fo if runs[r, 0] == 0 else fg
        for c in range(b - a):
            fout[o + np.uint64(c)] = src[a + np.uint64(c)]
        o += b - a


@njit(cache=True)
def runs(order, n_own):
    """(source, first, end) rows of the runs of `order` that read one source consecutively:
    source 0 = owned rows [first, end), 1 = ghost rows (order over owned + ghost)."""
    n = order.shape[0]
    out = np.empty((n, 3), np.int64)
    r = 0
    i = 0
    while i < n:
        j = order[i]
        src = 0 if j < n_own else 1
        e = i + 1
        while e < n and order[e] == j + (e - i) and (order[e] < n_own) == (src == 0):
            e += 1
        first = j if src == 0 else j - n_own
        out[r, 0] = src
        out[r, 1] = first
        out[r, 2] = first + e - i
        r += 1
        i = e
    return out[:r]


class GhostMerge:
    """One ghosted particle variable of a patch: its owned and ghost rows and their ID order.
    The merged array (owned + ghost)[order] is formed only when a task asks for it;
    kernels that can read the two parts run by run (`runs`) never need it."""

    __slots__ = ("owned", "ghost", "order", "_merged")

    def __init__(self, owned, ghost, order):
        self.owned, self.ghost, self.order = owned, ghost, order
        self._merged = None

    @property
    def nbytes(self):
        return self.ghost.nbytes + (0 if self._merged is None else self._merged.nbytes)

    def merged(self):
        if self._merged is None:
            n, k = len(self.order), int(np.prod(self.owned.shape[1:]))
            a = np.empty((n,) + self.owned.shape[1:], dtype=self.owned.dtype)
            gather_merged(np.ascontiguousarray(self.owned).reshape(len(self.owned), k),
                          self.ghost.reshape(len(self.ghost), k), self.order, a.reshape(n, k))
            self._merged = a
        return self._merged
