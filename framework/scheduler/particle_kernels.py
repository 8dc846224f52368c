"""Numba passes over a patch's particles for relocation and ghost selection.

Both only need to look closely at a few particles: those that left the patch, and
those close enough to its faces to be someone's ghost. One pass finds them, so the
per-step cost is one read of the positions rather than one per neighbour.
"""
from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True)
def leavers(x, anchor, dx, lo, hi, dims):
    """Indices of particles whose cell is outside [lo, hi) (NaN positions count as outside)."""
    n = x.shape[0]
    out = np.empty(n, np.int64)
    k = 0
    for p in range(n):
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
    for p in range(n):
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
