"""Level and Patch: index boxes, extra (boundary) cells, ghost regions and neighbours.

Cell (0,0,0) has its low corner at the level's anchor; extra cells carry indices -1
and N as in Uintah. A direction with a single cell is *collapsed*: it has no extra
or ghost cells and one node layer, so 1D and 2D scenes pay nothing for the unused
directions. Each cell, node and face is owned by exactly one patch: a patch owns the
nodes and faces at the low corners of its cells, plus the upper ones on the domain's
upper boundary.

A level read from several <Box>es whose union is not one box (an L-shaped level) is the
box that holds them, cut by every box's edges and patch boundaries into a tensor layout of
slots; only the slots inside a box are patches. Each face of a patch then borders one other
patch or none: a face with none is a boundary face (extra cells, conditions), as on the
domain's outer faces. On a re-entrant edge two patches own the same extra cells or nodes;
each keeps its own values there, and the ghost copies of other patches take one of them.
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


def box_minus(a, b):
    """The part of box a outside box b, as disjoint boxes (none when b covers a)."""
    if box_intersect(a, b) is None:
        return [a]
    out, lo, hi = [], list(a[0]), list(a[1])
    for d in range(3):
        if lo[d] < b[0][d]:
            out.append((tuple(lo), tuple(hi[:d] + [b[0][d]] + hi[d + 1:])))
            lo[d] = b[0][d]
        if hi[d] > b[1][d]:
            out.append((tuple(lo[:d] + [b[1][d]] + lo[d + 1:]), tuple(hi)))
            hi[d] = b[1][d]
    return out


def split_points(n, p):
    """Cut n cells into p nearly equal parts."""
    return [n * i // p for i in range(p + 1)]


class Level:
    """A box of cells split into a tensor layout of patches (slots without a patch: holes)."""

    def __init__(self, lower, upper, ncells, patches=(1, 1, 1), extra=(0, 0, 0),
                 periodic=(False, False, False), index=0, splits=None, present=None):
        """splits: the patch boundaries (cell indices from 0 to ncells) in each direction, in
        place of `patches` nearly equal parts (a level read from several <Box>es). present:
        a boolean array over the layout, False at the slots that are no patch (the cells
        outside every <Box> of a level that is not one box); None: every slot is a patch."""
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
        self.holes = present is not None and not np.all(present)
        if self.holes and any(self.periodic):
            raise ValueError("a periodic direction on a level that is not one box")
        self.present = np.asarray(present, dtype=bool) if self.holes else None
        self.halo = {vt: 0 for vt in GRID_TYPES}
        self.patches: list[Patch] = []
        self._slot = np.full(self.layout, -1, dtype=np.int64) if self.holes else None
        for k, j, i in itertools.product(range(self.layout[2]), range(self.layout[1]), range(self.layout[0])):
            idx = (i, j, k)
            if self.holes:
                if not self.present[idx]:
                    continue
                self._slot[idx] = len(self.patches)
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
        """The patch at layout index idx; None at a hole."""
        i, j, k = idx
        if self.holes:
            pid = self._slot[i, j, k]
            return self.patches[pid] if pid >= 0 else None
        return self.patches[i + self.layout[0] * (j + self.layout[1] * k)]

    def has_patch(self, idx):
        """Whether layout index idx (possibly outside the layout) holds a patch."""
        if not all(0 <= idx[d] < self.layout[d] for d in range(3)):
            return False
        return not self.holes or bool(self.present[tuple(idx)])

    def cells_of(self, x):
        """Cell indices (n,3) int64 of positions x (n,3); collapsed directions give 0."""
        with np.errstate(invalid="ignore"):
            c = np.floor((x - self.anchor) / self.dx).astype(np.int64)
        for d in range(3):
            if self.collapsed[d]:
                c[:, d] = 0
        return c

    def patch_ids_of_cells(self, cells):
        """Owning patch id of each interior cell index (n,3); -1 outside the domain (or in a hole)."""
        out = np.zeros(len(cells), dtype=np.int64)
        inside = np.ones(len(cells), dtype=bool)
        mult = 1
        slots = []
        for d in range(3):
            c = cells[:, d]
            inside &= (c >= 0) & (c < self.ncells[d])
            pidx = np.searchsorted(np.asarray(self.splits[d][1:-1]), c, side="right")
            out += pidx * mult
            mult *= self.layout[d]
            slots.append(pidx)
        if self.holes:
            s = [np.minimum(x, n - 1) for x, n in zip(slots, self.layout)]
            out = self._slot[s[0], s[1], s[2]]
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
                if self.has_patch(idx):
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
        if self.holes:
            self._cache[key] = out = self._hole_ghost_sources(patch, vt, want, own)
            return out
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

    def _hole_ghost_sources(self, patch, vt, want, own):
        """ghost_sources on a level with holes: owned boxes overlap on re-entrant edges, so
        each source gives only what neither `patch` nor an earlier source holds."""
        out, taken = [], [own]
        for q in self.neighbours(patch):
            if q is patch:
                continue
            ov = box_intersect(want, q.owned(vt))
            if ov is None:
                continue
            parts = [ov]
            for t in taken:
                parts = [r for b in parts for r in box_minus(b, t)]
            out.extend((q, (0, 0, 0), b) for b in parts)
            taken.append(ov)
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
        if level.holes:                      # a face on a hole is a boundary face too
            side = [tuple(index[c] + (s if c == d else 0) for c in range(3)) for d in range(3) for s in (-1, 1)]
            self.at_low = tuple(self.at_low[d] or (not level.collapsed[d] and not level.has_patch(side[2 * d]))
                                for d in range(3))
            self.at_high = tuple(self.at_high[d] or (not level.collapsed[d] and not level.has_patch(side[2 * d + 1]))
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
        key = ("shape", vt, self.level.halo[vt])
        shape = self._cache.get(key)
        if shape is None:
            lo, hi = self.alloc(vt)
            shape = self._cache[key] = tuple(h - l for l, h in zip(lo, hi))
        return shape

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
        return self.local(vt, self.interior_box(vt))

    def interior_box(self, vt: VarType = VarType.CC):
        """Global (lo, hi) of the owned indices inside the physical domain: the owned box
        without extra cells (on a level with holes two patches share the nodes of a
        re-entrant edge)."""
        key = ("inner", vt)
        if key not in self._cache:
            lv = self.level
            lo, hi = [], []
            for d in range(3):
                if lv.collapsed[d]:
                    lo.append(0), hi.append(1)
                    continue
                lo.append(self.lo[d])
                hi.append(self.hi[d] + (1 if vt.node_like(d) and self.at_high[d] else 0))
            self._cache[key] = (tuple(lo), tuple(hi))
        return self._cache[key]

    def face_index(self, d: int, s: int) -> int:
        """Global index of the face nodes of side s (0 low, 1 high) in direction d (a
        boundary face: at_low or at_high)."""
        return self.hi[d] if s else self.lo[d]

    def owned_local(self, vt: VarType = VarType.CC):
        return self.local(vt, self.owned(vt))

    def cell_centers(self, vt: VarType = VarType.CC):
        """Coordinates (three 1D arrays) of the cell centres of a stored CC array."""
        return self.level.cell_centers(self.alloc(vt))
