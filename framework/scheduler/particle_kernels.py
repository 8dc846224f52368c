"""Numba passes over a patch's particles for relocation and ghost selection.

Both only need to look closely at a few particles: those that left the patch, and
those close enough to its faces to be someone's ghost. One pass finds them, so the
per-step cost is one read of the positions rather than one per neighbour. A particle
more than a cell away from the band in question is let through with two comparisons
per axis (_clear); only the others get the exact cell floor((x - anchor)/dx) that
every other particle test of the framework uses, so the answer is the same.
"""
from __future__ import annotations

import weakref

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
def leavers_near(x, anchor, dx, lo, hi, g, dims):
    """Indices of particles whose cell is outside [lo, hi) (NaN positions count as outside),
    and the indices and cells of the others that lie within g cells of the faces (near_faces
    of what stays). Relocation reads every position anyway; the ghost candidates it finds
    save the ghost exchange of the next step its own pass (g = 0: none)."""
    n = x.shape[0]
    out = np.empty(n, np.int64)
    idx = np.empty(n, np.int64)
    cells = np.empty((n, 3), np.int64)
    k = 0
    kn = 0
    b = _bounds(anchor, dx, lo + g, hi - g, dims)
    for p in range(n):
        if _clear(x, p, b):
            continue
        outside = False
        near = False
        for d in range(3):
            c = 0
            if dims[d]:
                v = x[p, d]
                if not (v == v):
                    outside = True
                    break
                cf = np.floor((v - anchor[d]) / dx[d])
                if cf < lo[d] or cf >= hi[d]:
                    outside = True
                    break
                c = int(cf)
                if c < lo[d] + g or c >= hi[d] - g:
                    near = True
            cells[kn, d] = c            # row kn is kept only if the particle is near
        if outside:
            out[k] = p
            k += 1
        elif near:
            idx[kn] = p
            kn += 1
    return out[:k], idx[:kn], cells[:kn]


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
def select_ghosts(x, anchor, dx, lo, hi, g, dims, boxes):
    """The particles of a patch that are ghosts in each cell box (k, 2, 3) in turn: their
    indices, box after box (particle order within a box), and the count per box. One
    read of the positions (near_faces) serves every neighbour."""
    idx, cells = near_faces(x, anchor, dx, lo, hi, g, dims)
    return in_boxes(idx, cells, dims, boxes)


@njit(cache=True)
def in_boxes(idx, cells, dims, boxes):
    """select_ghosts from the candidates (indices, cells) near the faces: box after box,
    the candidates whose cell is in the box, and the count per box."""
    nb = boxes.shape[0]
    counts = np.zeros(nb, np.int64)
    out = np.empty(nb * idx.shape[0], np.int64)
    k = 0
    for b in range(nb):
        k0 = k
        for i in range(idx.shape[0]):
            inside = True
            for d in range(3):
                if dims[d] and (cells[i, d] < boxes[b, 0, d] or cells[i, d] >= boxes[b, 1, d]):
                    inside = False
                    break
            if inside:
                out[k] = idx[i]
                k += 1
        counts[b] = k - k0
    return out[:k], counts


@njit(cache=True)
def gather_pieces(src, sel, counts, dst, out):
    """Rows src[sel] piece by piece (counts: rows per piece) into out at row dst[piece];
    pieces with dst < 0 are skipped (they go elsewhere)."""
    k = src.shape[1]
    s = 0
    for b in range(counts.shape[0]):
        o = dst[b]
        if o >= 0:
            for i in range(counts[b]):
                r = sel[s + i]
                for c in range(k):
                    out[o + i, c] = src[r, c]
        s += counts[b]


@njit(cache=True)
def _sorted(a):
    """a is in non-decreasing order (one branch-free pass)."""
    bad = False
    for i in range(1, a.shape[0]):
        bad |= a[i] < a[i - 1]
    return not bad


@njit(cache=True)
def _first_above(a, lo, v):
    """The first index >= lo of the sorted array a whose value exceeds v (binary search)."""
    hi = a.shape[0]
    while lo < hi:
        mid = (lo + hi) >> 1
        if a[mid] <= v:
            lo = mid + 1
        else:
            hi = mid
    return lo


@njit(cache=True)
def _first_not_below(a, lo, v):
    """The first index >= lo of the sorted array a whose value is not below v (binary search)."""
    hi = a.shape[0]
    while lo < hi:
        mid = (lo + hi) >> 1
        if a[mid] < v:
            lo = mid + 1
        else:
            hi = mid
    return lo


@njit(cache=True)
def relocation_runs(own, leave, arr, arr_order, arr_first, check):
    """The runs (see `runs`; source 0: the patch's own rows, 1: the arrivals) of a patch's
    particles after relocation, in ID order: its own rows (IDs `own`, sorted) but the
    leavers (sorted indices `leave`), merged with the arrivals (IDs `arr`, in stable ID
    order `arr_order`), an arrival going before own rows of equal ID where arr_first (it
    came from a patch of smaller id). This is the stable argsort of the IDs of [pieces in
    source-patch order], found by binary search, without a pass over the own rows.
    ok is False (nothing else valid) when `check` finds `own` not sorted."""
    n_own, n_arr, n_leave = own.shape[0], arr.shape[0], leave.shape[0]
    rs = np.empty((2 * n_arr + n_leave + 1, 3), np.int64)
    if check and not _sorted(own):
        return False, rs[:0]
    r = 0
    i = 0
    li = 0
    for jj in range(n_arr + 1):
        e = n_own
        if jj < n_arr:
            v = arr[arr_order[jj]]
            e = _first_not_below(own, i, v) if arr_first[arr_order[jj]] else _first_above(own, i, v)
        while i < e:                    # own rows [i, e) but the leavers
            if li < n_leave and leave[li] == i:
                i += 1
                li += 1
                continue
            stop = e if li == n_leave else min(e, leave[li])
            rs[r, 0], rs[r, 1], rs[r, 2] = 0, i, stop
            r += 1
            i = stop
        if jj == n_arr:
            break
        j = arr_order[jj]
        if r > 0 and rs[r - 1, 0] == 1 and rs[r - 1, 2] == j:
            rs[r - 1, 2] = j + 1
        else:
            rs[r, 0], rs[r, 1], rs[r, 2] = 1, j, j + 1
            r += 1
    return True, rs[:r]


@njit(cache=True)
def merge_ids(own, ghost, gorder, check):
    """The stable ID order of owned + ghost rows (np.argsort(concatenation, kind="stable")),
    the owned mask of the merged rows and the runs of the order (see `runs`): the ghost IDs,
    sorted by gorder, are placed among the sorted owned IDs by binary search and the owned
    rows between them copied as blocks. ok is False (nothing else valid) when `check` finds
    the owned IDs not sorted."""
    n_own, n_gh = own.shape[0], ghost.shape[0]
    n = n_own + n_gh
    order = np.empty(n, np.int64)
    mask = np.empty(n, np.bool_)
    rs = np.empty((2 * n_gh + 1, 3), np.int64)
    if check and not _sorted(own):
        return False, order, mask, rs[:0]
    i = 0
    k = 0
    r = 0
    for jj in range(n_gh + 1):
        e = n_own if jj == n_gh else _first_above(own, i, ghost[gorder[jj]])
        if e > i:                       # owned rows [i, e): IDs not above this ghost's
            for t in range(e - i):
                order[k + t] = i + t
            rs[r, 0], rs[r, 1], rs[r, 2] = 0, i, e
            r += 1
            k += e - i
            i = e
        if jj == n_gh:
            break
        row = gorder[jj]
        order[k] = n_own + row
        k += 1
        if r > 0 and rs[r - 1, 0] == 1 and rs[r - 1, 2] == row:
            rs[r - 1, 2] = row + 1
        else:
            rs[r, 0], rs[r, 1], rs[r, 2] = 1, row, row + 1
            r += 1
    for k in range(n):
        mask[k] = order[k] < n_own
    return True, order, mask, rs[:r]


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


class ArrayMemo:
    """Values attached to arrays, by identity, for as long as each array lives (particle
    arrays are not written in place once they are in a warehouse)."""

    def __init__(self):
        self._d = {}

    def put(self, a, value):
        key = id(a)

        def forget(ref):
            if self._d.get(key, (None,))[0] is ref:
                del self._d[key]
        self._d[key] = (weakref.ref(a, forget), value)

    def get(self, a):
        hit = self._d.get(id(a))
        return hit[1] if hit is not None and hit[0]() is a else None


KNOWN_RUNS = ArrayMemo()        # ghost order -> (n_own, its runs), found while merging IDs
KNOWN_SORTED = ArrayMemo()      # ID arrays found sorted (handed on from step to step unchanged)


def runs(order, n_own):
    """(source, first, end) rows of the runs of `order` that read one source consecutively:
    source 0 = owned rows [first, end), 1 = ghost rows (order over owned + ghost).
    A ghost order's runs were found when it was made (KNOWN_RUNS); tasks ask each step."""
    hit = KNOWN_RUNS.get(order)
    if hit is not None and hit[0] == n_own:
        return hit[1]
    return _runs(order, n_own)


@njit(cache=True)
def _runs(order, n_own):
    """runs(), one pass over order."""
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
