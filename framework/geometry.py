"""Geometry pieces of Uintah decks (`<geom_object>` contents), shared by MPM and ICE.

A piece answers `inside(points) -> bool array` for points of shape (n, 3). Pieces:

  <box>          <min> <max>                      axis-aligned box (closed)
  <sphere>       <origin> <radius>
  <cylinder>     <bottom> <top> <radius>          finite circular cylinder
  <tri>          <name>                           closed triangulated surface from the files
                                                  name.pts (x y z per line) and name.tri (three
                                                  0-based point indices per line), as Uintah;
                                                  a relative name is looked up in the working
                                                  directory, then next to the deck
  <union>        two or more pieces               inside any
  <intersection> two or more pieces               inside all
  <difference>   exactly two pieces               inside the first, not the second

Any piece may carry `label="name"`; a later empty element with the same tag and
label (`<box label="name"></box>`) reuses the earlier piece, as in Uintah. The
labels are remembered by a `GeometryReader`, which lives as long as one deck.
"""
from __future__ import annotations

import numpy as np

PRIMITIVES = ("box", "sphere", "cylinder", "tri")
COMBINERS = ("union", "intersection", "difference")
PIECE_TAGS = PRIMITIVES + COMBINERS


class Box:
    def __init__(self, lo, hi):
        self.lo, self.hi = np.asarray(lo, float), np.asarray(hi, float)

    def bounds(self):
        return self.lo, self.hi

    def inside(self, x):
        return np.all((x >= self.lo) & (x <= self.hi), axis=1)


class Sphere:
    def __init__(self, origin, radius):
        self.origin, self.radius = np.asarray(origin, float), float(radius)

    def bounds(self):
        return self.origin - self.radius, self.origin + self.radius

    def inside(self, x):
        return np.sum((x - self.origin) ** 2, axis=1) <= self.radius ** 2


class Cylinder:
    def __init__(self, bottom, top, radius):
        self.bottom, self.top, self.radius = np.asarray(bottom, float), np.asarray(top, float), float(radius)
        self.axis = self.top - self.bottom
        self.length2 = float(self.axis @ self.axis)

    def bounds(self):
        return np.minimum(self.bottom, self.top) - self.radius, np.maximum(self.bottom, self.top) + self.radius

    def inside(self, x):
        rel = x - self.bottom
        s = rel @ self.axis / self.length2          # position along the axis, 0..1
        r2 = np.sum(rel ** 2, axis=1) - s ** 2 * self.length2
        return (s >= 0.0) & (s <= 1.0) & (r2 <= self.radius ** 2)


class TriSurface:
    """A closed surface of triangles; inside by ray casting (geometry_kernels.inside_surface)."""

    def __init__(self, points, tris):
        self.points = np.ascontiguousarray(points, float).reshape(-1, 3)
        self.tris = np.ascontiguousarray(tris, np.int64).reshape(-1, 3)
        p = self.points[self.tris]
        self.v0 = np.ascontiguousarray(p[:, 0])
        self.e1 = np.ascontiguousarray(p[:, 1] - p[:, 0])
        self.e2 = np.ascontiguousarray(p[:, 2] - p[:, 0])
        fudge = 1e-12 * max(1.0, float(np.abs(self.points).max()))
        self.lo, self.hi = self.points.min(axis=0) - fudge, self.points.max(axis=0) + fudge
        self._bins = None

    def bounds(self):
        return self.lo, self.hi

    def _binned(self):
        """Per ray: the triangles binned across it (geometry_kernels.build_bins)."""
        if self._bins is None:
            from .geometry_kernels import CROSS, TILT, build_bins
            ext = self.hi - self.lo
            nside = max(1, min(512, int(np.sqrt(len(self.tris)))))
            blo, bw, nb, offs, items = np.empty((3, 2)), np.empty((3, 2)), np.empty((3, 2), np.int64), [], []
            for r in range(3):
                for q in range(2):
                    d = CROSS[r, q]
                    blo[r, q], nb[r, q] = self.lo[d], nside
                    bw[r, q] = max(ext[d], 1e-300) / nside
                pad = 2.0 * TILT * float(ext.max()) + 1e-12 * float(ext.max())
                off = np.zeros(nside * nside + 1, np.int64)
                build_bins(self.v0, self.e1, self.e2, CROSS[r], blo[r], bw[r], nb[r], pad, off, np.empty(0, np.int64))
                it = np.empty(int(off[-1]), np.int64)
                build_bins(self.v0, self.e1, self.e2, CROSS[r], blo[r], bw[r], nb[r], pad, off, it)
                offs.append(off)
                items.append(it)
            self._bins = (blo, bw, nb, tuple(offs), tuple(items))
        return self._bins

    @classmethod
    def from_files(cls, base):
        """Uintah's <tri><name>base</name></tri>: base.pts and base.tri."""
        pts = np.loadtxt(base + ".pts", ndmin=2)
        tri = np.loadtxt(base + ".tri", ndmin=2)
        if pts.shape[1] != 3 or tri.shape[1] != 3:
            raise ValueError(f"{base}.pts / .tri need three numbers per line")
        if np.any(tri != np.round(tri)) or tri.min() < 0 or tri.max() >= len(pts):
            raise ValueError(f"{base}.tri: indices must be integers in 0..{len(pts) - 1} (points in {base}.pts)")
        return cls(pts, tri.astype(np.int64))

    def inside(self, x):
        from .geometry_kernels import CROSS, RAYS, inside_surface
        x = np.ascontiguousarray(x, float).reshape(-1, 3)
        out = np.empty(len(x), np.bool_)
        blo, bw, nb, offs, items = self._binned()
        inside_surface(x, self.v0, self.e1, self.e2, self.lo, self.hi, RAYS, CROSS, blo, bw, nb, offs, items, out)
        return out


class Union:
    def __init__(self, pieces):
        self.pieces = list(pieces)

    def bounds(self):
        """The box around every piece's box (None when no piece has one)."""
        boxes = [b for b in (p.bounds() for p in self.pieces) if b is not None]
        if not boxes:
            return None
        return np.min([b[0] for b in boxes], axis=0), np.max([b[1] for b in boxes], axis=0)

    def inside(self, x):
        out = np.zeros(len(x), bool)
        for p in self.pieces:
            out |= p.inside(x)
        return out


class Intersection(Union):
    def bounds(self):
        """The overlap of the pieces' boxes (None when they do not overlap)."""
        boxes = [p.bounds() for p in self.pieces]
        if any(b is None for b in boxes):
            return None
        lo, hi = np.max([b[0] for b in boxes], axis=0), np.min([b[1] for b in boxes], axis=0)
        return None if np.any(hi < lo) else (lo, hi)

    def inside(self, x):
        out = np.ones(len(x), bool)
        for p in self.pieces:
            out &= p.inside(x)
        return out


class Difference:
    def __init__(self, a, b):
        self.a, self.b = a, b

    def bounds(self):
        return self.a.bounds()

    def inside(self, x):
        return self.a.inside(x) & ~self.b.inside(x)


class GeometryReader:
    """Builds pieces from deck elements and remembers labelled ones for reuse."""

    def __init__(self, level=None):
        self.labelled: dict = {}
        self.level = level        # when given, an object wholly outside it is an error

    @staticmethod
    def _piece_children(node):
        for tag in PIECE_TAGS:
            node.children(tag)          # note the accepted tags for error messages
        return [c for c in node.children() if c.tag in PIECE_TAGS]

    def read_object(self, node):
        """The union of the pieces of a <geom_object> (an error if it has none)."""
        pieces = [self.read(c) for c in self._piece_children(node)]
        if not pieces:
            raise node.error(f"no geometry piece; accepted: {', '.join('<%s>' % t for t in PIECE_TAGS)}")
        piece = pieces[0] if len(pieces) == 1 else Union(pieces)
        if self.level is not None:
            self._check_overlap(piece, node)
        return piece

    def _check_overlap(self, piece, node):
        """An object that cannot reach any cell of the level (extra cells included) puts no
        material anywhere: refuse it, naming it, rather than run without that material."""
        lv = self.level
        extra = np.asarray(lv.extra) * lv.dx
        lo, hi = lv.anchor - extra, lv.upper + extra
        b = piece.bounds()
        if b is None or np.any(b[1] < lo) or np.any(b[0] > hi):
            where = "is empty" if b is None else f"spans {_fmt(b[0])} to {_fmt(b[1])}"
            raise node.error(f"this geometry object {where}, wholly outside the domain {_fmt(lo)} to {_fmt(hi)} "
                             "(extra cells included), so it puts no material anywhere; accepted: an object "
                             "that overlaps the domain")

    def read(self, node):
        """One piece element (primitive, combination or labelled reference)."""
        label = node.attr("label", default=None)
        if label is not None and not node.children():
            key = (node.tag, label)
            if key not in self.labelled:
                raise node.error(f'<{node.tag} label="{label}"> refers to no earlier piece with that label')
            return self.labelled[key]
        piece = self._build(node)
        if label is not None:
            self.labelled[(node.tag, label)] = piece
        return piece

    def _build(self, node):
        tag = node.tag
        if tag == "box":
            lo, hi = node.get("min", "vector"), node.get("max", "vector")
            if any(h < l for l, h in zip(lo, hi)):
                raise node.error(f"<max> {hi} is below <min> {lo}")
            return Box(lo, hi)
        if tag == "sphere":
            r = node.get("radius", "float")
            if r <= 0:
                raise node.child("radius").error("radius must be positive")
            return Sphere(node.get("origin", "vector"), r)
        if tag == "cylinder":
            b, t, r = node.get("bottom", "vector"), node.get("top", "vector"), node.get("radius", "float")
            if r <= 0:
                raise node.child("radius").error("radius must be positive")
            if np.allclose(b, t):
                raise node.error("<bottom> and <top> coincide")
            return Cylinder(b, t, r)
        if tag == "tri":
            return _read_tri(node)
        parts = [self.read(c) for c in self._piece_children(node)]
        if tag == "difference":
            if len(parts) != 2:
                raise node.error(f"<difference> needs exactly two pieces, found {len(parts)}")
            return Difference(*parts)
        if len(parts) < 1:
            raise node.error(f"<{tag}> needs at least one piece")
        return Union(parts) if tag == "union" else Intersection(parts)


def _fmt(v):
    return "[" + ", ".join(f"{x:g}" for x in v) + "]"


def _read_tri(node):
    import os
    name = node.get("name", "str")
    cands = [name] if os.path.isabs(name) else [name, os.path.join(os.path.dirname(os.path.abspath(node.filename)), name)]
    for base in cands:
        if os.path.exists(base + ".pts") and os.path.exists(base + ".tri"):
            try:
                return TriSurface.from_files(base)
            except ValueError as e:
                raise node.child("name").error(str(e)) from None
    raise node.child("name").error(f"no files {name}.pts and {name}.tri (looked in "
                                   + " and ".join(os.path.dirname(os.path.abspath(c + ".x")) for c in cands) + ")")


def cell_fractions(piece, level, box, res):
    """Fraction of each cell of an index box inside `piece`, from res samples per direction.

    Returns an array over the box; collapsed directions use one sample per cell. The
    box is sampled one x-slab at a time so memory stays bounded on big patches.
    """
    shape = tuple(h - l for l, h in zip(*box))
    axes = []
    for d in range(3):
        n = 1 if level.collapsed[d] else int(res[d])
        off = (np.arange(n) + 0.5) / n
        cells = np.arange(box[0][d], box[1][d])
        axes.append(level.anchor[d] + (cells[:, None] + off[None, :]) * level.dx[d])
    out = np.empty(shape)
    Y = axes[1][:, None, :, None]
    Z = axes[2][None, :, None, :]
    for i in range(shape[0]):
        X = axes[0][i][None, None, None, None, :]
        Xb, Yb, Zb = np.broadcast_arrays(X, Y[..., None], Z[..., None])
        pts = np.stack([Xb.ravel(), Yb.ravel(), Zb.ravel()], axis=1)
        out[i] = piece.inside(pts).reshape(Xb.shape).mean(axis=(2, 3, 4))
    return out
