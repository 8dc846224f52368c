"""Level and Patch: index boxes, extra (boundary) cells, ghost regions and neighbours.

Cell (0,0,0) has its low corner at the level's anchor; extra cells carry indices -1
and N as in Uintah. A direction with a single cell is *collapsed*: it has no extra
or ghost cells and one node layer, so 1D and 2D scenes pay nothing for the unused
directions. Each cell, node and face is owned by exactly one patch: a patch owns the
nodes and faces at the low corners of its cells, plus the upper ones on the domain's
upper boundary.
"""
from __future__ import annotations

import itertools

import numpy as np

from .variables import GRID_TYPES, VarType

FACES = ("x-", "x+", "y-", "y+", "z-", "z+")


def box_intersect(a, b):
    lo = tuple(max(x, y) for x, y in zip(a[0], b[0]))
    hi = tuple(min(x, y) for x, y in zip(a[1], b[1]))
    if any(h <= l for l, h in zip(lo, hi)):
        return None
    return lo, hi


def box_shift(box, s):
    return tuple(l + d for l, d in zip(box[0], s)), tuple(h + d for h, d in zip(box[1], s))


def box_cells(box) -> int:
    return int(np.prod([h - l for l, h in zip(*box)]))


def split_points(n, p):
    """Cut n cells into p nearly equal parts."""
    return [n * i // p for i in range(p + 1)]


class Level:
    """A box of cells split into a tensor layout of patches."""

    def __init__(self, lower, upper, ncells, patches=(1, 1, 1), extra=(0, 0, 0),
                 periodic=(False, False, False), index=0, splits=None):
        """splits: the patch boundaries (cell indices from 0 to ncells) in each direction, in
        place of `patches` nearly equal parts (a level read from several <Box>es)."""
        self.index = index
        self.ncells = tuple(int(n) for n in ncells)
        self.anchor = np.asarray(lower, dtype=np.float64)
        self.upper = np.asarray(upper, dtype=np.float64)
        self.dx = (self.upper - self.anchor) / np.asarray(self.ncells, dtype=np.float64)
        self.collapsed = tuple(n == 1 for n in self.ncells)
        self.periodic = tuple(bool(p) and not c for p, c in zip(periodic, self.collapsed))
        self.extra = tuple(0 if (c or p) else int(e)
                           for e, c, p in zip(extra, self.collapsed, self.periodic))
        self.dim = sum(not c for c in self.collapsed)
        if splits is not None:
            patches = [len(sp) - 1 for sp in splits]
        self.layout = tuple(int(p) for p in patches)
        for d in range(3):
            if self.layout[d] > self.ncells[d]:
                raise ValueError(f"{self.layout[d]} patches along {'xyz'[d]} but only {self.ncells[d]} cells")
        if splits is None:
            splits = [split_points(self.ncells[d], self.layout[d]) for d in range(3)]
        self.splits = [[int(x) for x in sp] for sp in splits]
        for d, sp in enumerate(self.splits):
            if sp[0] != 0 or sp[-1] != self.ncells[d] or any(b <= a for a, b in zip(sp, sp[1:])):
                raise ValueError(f"patch boundaries {sp} along {'xyz'[d]} must rise from 0 to {self.ncells[d]}")
        self.halo = {vt: 0 for vt in GRID_TYPES}
        self.patches: list[Patch] = []
        for k, j, i in itertools.product(range(self.layout[2]), range(self.layout[1]), range(self.layout[0])):
            idx = (i, j, k)
            lo = tuple(self.splits[d][idx[d]] for d in range(3))
            hi = tuple(self.splits[d][idx[d] + 1] for d in range(3))
            self.patches.append(Patch(len(self.patches), self, idx, lo, hi))
        self._cache: dict = {}

    # -- index spaces ----------------------------------------------------------------
    def total_box(self, vt: VarType):
        """Every index of this type on the level, extra cells included."""
        lo, hi = [], []
        for d in range(3):
            if self.collapsed[d]:
                lo.append(0), hi.append(1)
                continue
            e = self.extra[d]
            top = self.ncells[d] + e + (1 if vt.node_like(d) and not self.periodic[d] else 0)
            lo.append(-e), hi.append(top)
        return tuple(lo), tuple(hi)

    def interior_box(self, vt: VarType = VarType.CC):
        """Indices of the physical domain: cells 0..N-1, nodes 0..N (0..N-1 if periodic)."""
        lo, hi = [], []
        for d in range(3):
            n = self.ncells[d]
            top = n + (1 if vt.node_like(d) and not self.periodic[d] and not self.collapsed[d] else 0)
            lo.append(0), hi.append(top)
        return tuple(lo), tuple(hi)

    def period(self):
        return tuple(self.ncells[d] if self.periodic[d] else 0 for d in range(3))

    def shifts(self):
        """Periodic image offsets (in cells) to try when looking for neighbours."""
        ranges = [(-1, 0, 1) if self.periodic[d] else (0,) for d in range(3)]
        per = self.period()
        return [tuple(s[d] * per[d] for d in range(3)) for s in itertools.product(*ranges)]

    def cell_centers(self, box):
        """Cell-centre coordinates (three 1D arrays) of an index box."""
        return [self.anchor[d] + (np.arange(box[0][d], box[1][d]) + 0.5) * self.dx[d] for d in range(3)]

    def node_positions(self, box):
        return [self.anchor[d] + np.arange(box[0][d], box[1][d]) * self.dx[d] for d in range(3)]

    # -- patch lookup ----------------------------------------------------------------
    def patch_at(self, idx):
        i, j, k = idx
        return self.patches[i + self.layout[0] * (j + self.layout[1] * k)]

    def cells_of(self, x):
        """Cell indices (n,3) int64 of positions x (n,3); collapsed directions give 0."""
        with np.errstate(invalid="ignore"):
            c = np.floor((x - self.anchor) / self.dx).astype(np.int64)
        for d in range(3):
            if self.collapsed[d]:
                c[:, d] = 0
        return c

    def patch_ids_of_cells(self, cells):
        """Owning patch id of each interior cell index (n,3); -1 outside the domain."""
        out = np.zeros(len(cells), dtype=np.int64)
        inside = np.ones(len(cells), dtype=bool)
        mult = 1
        for d in range(3):
            c = cells[:, d]
            inside &= (c >= 0) & (c < self.ncells[d])
            pidx = np.searchsorted(np.asarray(self.splits[d][1:-1]), c, side="right")
            out += pidx * mult
            mult *= self.layout[d]
        out[~inside] = -1
        return out

    def wrap_positions(self, x):
        """Map positions that left through a periodic face back into the domain."""
        for d in range(3):
            if self.periodic[d]:
                L = self.upper[d] - self.anchor[d]
                x[:, d] = self.anchor[d] + np.mod(x[:, d] - self.anchor[d], L)
        return x

    # -- neighbours and ghost regions --------------------------------------------
    def neighbours(self, patch):
        """Patches adjacent to `patch` (periodic images included), itself excluded unless periodic."""
        key = ("nbr", patch.id)
        if key not in self._cache:
            found = []
            for off in itertools.product((-1, 0, 1), repeat=3):
                idx = []
                for d in range(3):
                    v = patch.index[d] + off[d]
                    if self.periodic[d]:
                        v %= self.layout[d]
                    idx.append(v)
                if all(0 <= idx[d] < self.layout[d] for d in range(3)):
                    q = self.patch_at(idx)
                    if q not in found:
                        found.append(q)
            self._cache[key] = found
        return self._cache[key]

    def ghost_sources(self, patch, vt: VarType, g: int):
        """Where the ghost entries of `patch` (width g) come from.

        A list of (source patch, shift, box): `box` is in `patch`'s index space and the
        source data sits at `box - shift` in the source patch's owned region.
        """
        key = ("ghost", patch.id, vt, g)
        if key in self._cache:
            return self._cache[key]
        want = patch.window(vt, g)
        own = patch.owned(vt)
        out = []
        for q in self.neighbours(patch):
            qown = q.owned(vt)
            for s in self.shifts():
                if q is patch and s == (0, 0, 0):
                    continue
                ov = box_intersect(want, box_shift(qown, s))
                if ov is None or box_intersect(ov, own) == ov:
                    continue
                out.append((q, s, ov))
        self._cache[key] = out
        return out

    def particle_ghost_sources(self, patch, g: int):
        """(source patch, shift, cell box in the source's coordinates) for ghost particles."""
        key = ("pghost", patch.id, g)
        if key in self._cache:
            return self._cache[key]
        grow = tuple(0 if self.collapsed[d] else g for d in range(3))
        want = (tuple(patch.lo[d] - grow[d] for d in range(3)), tuple(patch.hi[d] + grow[d] for d in range(3)))
        out = []
        for q in self.neighbours(patch):
            for s in self.shifts():
                if q is patch and s == (0, 0, 0):
                    continue
                ov = box_intersect(want, box_shift((q.lo, q.hi), s))
                if ov is None:
                    continue
                out.append((q, s, box_shift(ov, tuple(-x for x in s))))
        self._cache[key] = out
        return out

    def clear_cache(self):
        self._cache.clear()
        for p in self.patches:
            p._cache.clear()


class Patch:
    """A box of interior cells [lo, hi) of a level, plus what it owns of the other types."""

    def __init__(self, pid, level: Level, index, lo, hi):
        self.id = pid
        self.level = level
        self.index = index
        self.lo = lo
        self.hi = hi
        self.at_low = tuple(lo[d] == 0 and not level.periodic[d] and not level.collapsed[d] for d in range(3))
        self.at_high = tuple(hi[d] == level.ncells[d] and not level.periodic[d] and not level.collapsed[d]
                             for d in range(3))
        self.boundary_faces = [FACES[2 * d + s] for d in range(3) for s in (0, 1)
                               if (self.at_low, self.at_high)[s][d]]
        self._cache: dict = {}

    def __repr__(self):
        return f"Patch({self.id}, {self.lo}-{self.hi})"

    @property
    def ncells(self) -> int:
        return box_cells((self.lo, self.hi))

    def owned(self, vt: VarType):
        """Indices of type vt this patch owns (extra cells on domain faces included)."""
        key = ("own", vt)
        if key not in self._cache:
            lv = self.level
            lo, hi = [], []
            for d in range(3):
                if lv.collapsed[d]:
                    lo.append(0), hi.append(1)
                    continue
                e = lv.extra[d]
                lo.append(self.lo[d] - (e if self.at_low[d] else 0))
                top = self.hi[d] + (e if self.at_high[d] else 0)
                if vt.node_like(d) and self.at_high[d]:
                    top += 1
                hi.append(top)
            self._cache[key] = (tuple(lo), tuple(hi))
        return self._cache[key]

    def window(self, vt: VarType, g: int):
        """The owned box grown by g ghost layers, clipped to the level (periodic: wrapped)."""
        key = ("win", vt, g)
        if key not in self._cache:
            lv = self.level
            own = self.owned(vt)
            tot = lv.total_box(vt)
            lo, hi = [], []
            for d in range(3):
                if lv.collapsed[d]:
                    lo.append(0), hi.append(1)
                    continue
                l, h = own[0][d] - g, own[1][d] + g
                if not lv.periodic[d]:
                    l, h = max(l, tot[0][d]), min(h, tot[1][d])
                lo.append(l), hi.append(h)
            self._cache[key] = (tuple(lo), tuple(hi))
        return self._cache[key]

    def alloc(self, vt: VarType):
        """The box a stored array of type vt covers: owned plus the level's halo for vt."""
        return self.window(vt, self.level.halo[vt])

    def alloc_shape(self, vt: VarType):
        lo, hi = self.alloc(vt)
        return tuple(h - l for l, h in zip(lo, hi))

    def low_index(self, vt: VarType = VarType.CC):
        """Global index of entry [0,0,0] of a stored array of type vt."""
        return self.alloc(vt)[0]

    def local(self, vt: VarType, box):
        """Local (lo, hi) index tuples of a global box inside a stored array of type vt."""
        base = self.low_index(vt)
        return (tuple(b - o for b, o in zip(box[0], base)), tuple(b - o for b, o in zip(box[1], base)))

    def slices(self, vt: VarType, box):
        lo, hi = self.local(vt, box)
        return tuple(slice(l, h) for l, h in zip(lo, hi))

    def interior(self, vt: VarType = VarType.CC):
        """Local (lo, hi) of the patch's entries inside the physical domain (no extra cells).

        For NC/SFC types this is the owned part of the domain's nodes/faces.
        """
        own = self.owned(vt)
        inner = self.level.interior_box(vt)
        box = box_intersect(own, inner)
        return self.local(vt, box)

    def owned_local(self, vt: VarType = VarType.CC):
        return self.local(vt, self.owned(vt))

    def cell_centers(self, vt: VarType = VarType.CC):
        """Coordinates (three 1D arrays) of the cell centres of a stored CC array."""
        return self.level.cell_centers(self.alloc(vt))
