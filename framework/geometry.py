"""Geometry pieces of Uintah decks (`<geom_object>` contents), shared by MPM and ICE.

A piece answers `inside(points) -> bool array` for points of shape (n, 3). Pieces:

  <box>          <min> <max>                      axis-aligned box (closed)
  <sphere>       <origin> <radius>
  <cylinder>     <bottom> <top> <radius>          finite circular cylinder
  <parallelepiped> <p1> <p2> <p3> <p4>            p1 + a (p2-p1) + b (p3-p1) + c (p4-p1), a, b, c in (0, 1]
  <ellipsoid>    <origin> and <rx> <ry> <rz>      axis-aligned, or <v1> <v2> <v3>: orthogonal
                                                  semi-axis vectors (they take precedence)
  <cone>         <bottom> <top> <bottom_radius> <top_radius>   a frustum (a radius may be 0)
  <torus>        <center> <major_radius> <minor_radius> <axis> (x, y or z) [<theta>]
                                                  ring about the axis, turned by theta (radians)
                                                  in the plane Uintah turns it in
  <polyhedron>   <center> <bounds> of <half_space>s: type="absolute" (<planePoint>, <normal>
                                                  pointing inwards) or "relative" (<offset> from
                                                  the centre to the plane, normal = -offset);
                                                  the convex region inside every plane
  <smoothcyl>    <discretization_scheme> (pie_slices | constant_particle_volumes), <bottom>,
                 <top>, <outer_radius>, [<inner_radius>], <num_radial>, <num_axial>,
                 [<num_angular>], [<endcap_thickness>], [<arc_start_angle>], [<arc_angle>]
                                                  a hollow cylinder (or an arc of one) whose MPM
                                                  particles are laid in rings (SmoothCylinder.points),
                                                  not on the lattice
  <null>                                          everywhere for ICE; for MPM, no particles
                                                  (its bounding box is a point, as Uintah's)
  <tri>          <name>                           closed triangulated surface from the files
                                                  name.pts (x y z per line) and name.tri (three
                                                  0-based point indices per line), as Uintah;
                                                  a relative name is looked up in the working
                                                  directory, then next to the deck
  <union>        two or more pieces               inside any
  <intersection> two or more pieces               inside all
  <difference>   exactly two pieces               inside the first, not the second

The inside tests are Uintah's, tolerances and open/closed faces included (geometry_kernels).

Any piece may carry `label="name"`; a later empty element with the same tag and
label (`<box label="name"></box>`) reuses the earlier piece, as in Uintah. The
labels are remembered by a `GeometryReader`, which lives as long as one deck.
"""
from __future__ import annotations

import numpy as np

PRIMITIVES = ("box", "sphere", "cylinder", "tri", "parallelepiped", "ellipsoid", "cone", "torus",
              "polyhedron", "smoothcyl", "null")
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


def _run(kernel, x, *args):
    """A geometry_kernels inside test over points x (n, 3)."""
    x = np.ascontiguousarray(x, float).reshape(-1, 3)
    out = np.empty(len(x), np.bool_)
    kernel(x, *args, out)
    return out


class Parallelepiped:
    """Uintah's <parallelepiped> (NaaBoxGeometryPiece): the points p1 + a (p2-p1) + b (p3-p1)
    + c (p4-p1) with a, b, c in (0, 1]."""

    def __init__(self, p1, p2, p3, p4):
        self.p1 = np.asarray(p1, float)
        self.edges = np.stack([np.asarray(q, float) - self.p1 for q in (p2, p3, p4)], axis=1)
        self.to_unit = np.ascontiguousarray(np.linalg.inv(self.edges))
        corners = self.p1 + np.array([[a, b, c] for a in (0, 1) for b in (0, 1) for c in (0, 1)], float) @ self.edges.T
        self.lo, self.hi = corners.min(axis=0), corners.max(axis=0)

    def bounds(self):
        return self.lo, self.hi

    def inside(self, x):
        from .geometry_kernels import inside_parallelepiped
        return _run(inside_parallelepiped, x, self.p1, self.to_unit)


class Ellipsoid:
    """Uintah's <ellipsoid>: (x - o) . M (x - o) - 1 < 1e-12 with M = U diag(1/r^2) U^T."""
    TOL = 1e-12

    def __init__(self, origin, axes):
        self.origin = np.asarray(origin, float)
        axes = np.asarray(axes, float)                   # rows: the semi-axis vectors
        radii = np.linalg.norm(axes, axis=1)
        u = axes.T / radii
        self.m = np.ascontiguousarray(u @ np.diag(1.0 / radii ** 2) @ u.T)
        self.half = np.sqrt(np.diag(u @ np.diag(radii ** 2) @ u.T))

    def bounds(self):
        return self.origin - self.half, self.origin + self.half

    def inside(self, x):
        from .geometry_kernels import inside_ellipsoid
        return _run(inside_ellipsoid, x, self.origin, self.m, self.TOL)


class Cone:
    """Uintah's <cone>: a frustum with radius r_bottom at <bottom> and r_top at <top>."""

    def __init__(self, bottom, top, r_bottom, r_top):
        self.bottom, self.top = np.asarray(bottom, float), np.asarray(top, float)
        self.r_bottom, self.r_top = float(r_bottom), float(r_top)

    def bounds(self):
        r = max(self.r_bottom, self.r_top)
        return np.minimum(self.bottom, self.top) - r, np.maximum(self.bottom, self.top) + r

    def inside(self, x):
        from .geometry_kernels import inside_cone
        return _run(inside_cone, x, self.bottom, self.top, self.r_bottom, self.r_top)


class Torus:
    """Uintah's <torus>: a ring of tube radius `minor` at distance `major` from an axis (x, y or
    z) through the centre, turned by theta as TorusGeometryPiece::inside does."""

    def __init__(self, center, major, minor, axis, theta=0.0):
        self.center, self.major, self.minor = np.asarray(center, float), float(major), float(minor)
        self.axis, self.theta = "xyz".index(axis), float(theta)

    def bounds(self):
        r = self.major + self.minor
        return self.center - r, self.center + r

    def inside(self, x):
        from .geometry_kernels import inside_torus
        return _run(inside_torus, x, self.center, self.major, self.minor, self.axis, self.theta)


class Polyhedron:
    """Uintah's <polyhedron> (ConvexPolyhedronGeometryPiece): inside every bounding plane (unit
    normals pointing inwards, 1e-6 tolerance) and the box of the vertices."""
    TOL = 1e-6

    def __init__(self, points, normals):
        n = np.asarray(normals, float)
        self.normals = np.ascontiguousarray(n / np.linalg.norm(n, axis=1)[:, None])
        self.offsets = np.ascontiguousarray(-np.sum(np.asarray(points, float) * self.normals, axis=1))
        self.vertices = self._vertices()
        if len(self.vertices) >= 4:
            self.lo, self.hi = self.vertices.min(axis=0), self.vertices.max(axis=0)

    def _vertices(self):
        """The points where three planes meet that lie inside all (distinct to 1e-10)."""
        from .geometry_kernels import inside_halfspaces
        cands = []
        k = len(self.normals)
        for i in range(k):
            for j in range(i + 1, k):
                for m in range(j + 1, k):
                    a = self.normals[[i, j, m]]
                    if abs(np.linalg.det(a)) > self.TOL:
                        cands.append(np.linalg.solve(a, -self.offsets[[i, j, m]]))
        if not cands:
            return np.empty((0, 3))
        cands = np.array(cands)
        big = np.full(3, np.inf)
        keep = _run(inside_halfspaces, cands, self.normals, self.offsets, -big, big, self.TOL)
        verts = []
        for v in cands[keep]:
            if all(np.linalg.norm(v - w) >= 1e-10 for w in verts):
                verts.append(v)
        return np.array(verts).reshape(-1, 3)

    def bounds(self):
        return self.lo, self.hi

    def inside(self, x):
        from .geometry_kernels import inside_halfspaces
        return _run(inside_halfspaces, x, self.normals, self.offsets, self.lo, self.hi, self.TOL)


class Null:
    """Uintah's <null>: every point is inside (ICE fills every cell with it), but its bounding
    box is a point, so an MPM object made of it creates no particles (Uintah skips objects whose
    box misses the patch)."""

    def bounds(self):
        return None

    def inside(self, x):
        return np.ones(len(x), bool)


class SmoothCylinder:
    """Uintah's <smoothcyl> (SmoothCylGeomPiece): a hollow cylinder, or an arc of one, between
    inner and outer radius, optionally lengthened by end caps for the inside test. MPM lays
    its particles in rings (`points`) rather than on the lattice."""

    def __init__(self, bottom, top, r_outer, r_inner, n_radial, n_axial, n_angular, scheme,
                 cap=0.0, arc_start=0.0, arc=2.0 * np.pi):
        self.bottom, self.top = np.asarray(bottom, float), np.asarray(top, float)
        self.r_outer, self.r_inner, self.cap = float(r_outer), float(r_inner), float(cap)
        self.n_radial, self.n_axial, self.n_angular = int(n_radial), int(n_axial), int(n_angular)
        self.scheme, self.arc_start, self.arc = scheme, float(arc_start), float(arc)

    def bounds(self):
        axis = self.top - self.bottom
        c = axis * (self.cap / np.linalg.norm(axis))
        lo, hi = np.minimum(self.bottom - c, self.top + c), np.maximum(self.bottom - c, self.top + c)
        return lo - self.r_outer, hi + self.r_outer

    def inside(self, x):
        from .geometry_kernels import inside_smooth_cylinder
        return _run(inside_smooth_cylinder, x, self.bottom, self.top, self.r_outer, self.r_inner, self.cap)

    def cached_points(self, cell_dx):
        """points(cell_dx), computed once per cell size (every patch asks): positions,
        volumes and size matrices."""
        key = tuple(float(d) for d in cell_dx)
        if getattr(self, "_points", (None,))[0] != key:
            self._points = (key, self.points(cell_dx))
        return self._points[1]

    def points(self, cell_dx):
        """Particle positions (n, 3), volumes (n,) and size matrices (n, 3, 3) of Uintah's
        createCylPoints: num_axial
        layers, num_radial rings of width (outer - inner) / num_radial, each ring cut into
        equal arcs (particle at the arc's middle, volume = ring sector area * layer height).
        The arcs: constant_particle_volumes, int(span r / dr) of them (at least 1);
        pie_slices, num_angular, times 0.9 (repeatedly, truncated) while a particle would be
        under 5 % of a cell. The span of the arcs is arc_angle - arc_start_angle, as Uintah
        computes it. The layers are laid in the x-y plane and turned onto the axis with
        Uintah's rotation. End caps get no particles: Uintah's createCylPoints discards
        them. A particle's size matrix (m) has the edges of its ring sector as columns: the arc
        (span r / n, tangential), the ring width (radial), the layer height (axial), turned onto
        the axis as R S R^T; CPDI takes the particle's domain from it. It is Uintah's p.size
        times the cell size where the cells are square in the plane of the rings (Uintah divides
        both components of the arc by dx and of the width by dy)."""
        axis = self.top - self.bottom
        length = float(np.sqrt(axis @ axis))
        axis = axis / length
        cell_vol = float(cell_dx[0] * cell_dx[1] * cell_dx[2])
        phi = float(np.arccos(axis[2]))
        a = np.cross([0.0, 0.0, 1.0], axis)
        a = a / (np.sqrt(a @ a) + 1e-100)
        rot = _uintah_rotation(phi, a)
        span = self.arc - self.arc_start
        axis_inc = length / self.n_axial
        rad_inc = (self.r_outer - self.r_inner) / self.n_radial
        xs, vols, sizes = [], [], []
        z = 0.5 * axis_inc
        for _ in range(self.n_axial):
            centre = self.bottom + axis * z
            z += axis_inc
            for i in range(self.n_radial):
                prev = self.r_inner + i * rad_inc
                r = prev + rad_inc * 0.5
                nxt = self.r_inner + (i + 1) * rad_inc
                if self.scheme == "constant_particle_volumes":
                    n_ang = max(int(span * r / rad_inc), 1)
                    inc = span / n_ang
                    area = 0.5 * inc * (nxt * nxt - prev * prev)
                else:
                    reduce = 1.0
                    while True:
                        n_ang = int(self.n_angular * reduce)
                        inc = span / n_ang if n_ang > 0 else np.inf
                        area = 0.5 * inc * (nxt * nxt - prev * prev)
                        if area * axis_inc / cell_vol < 5e-2:
                            reduce *= 0.9
                        else:
                            break
                ang = self.arc_start + (np.arange(n_ang) + 0.5) * inc
                local = np.stack([r * np.cos(ang), r * np.sin(ang), np.zeros(n_ang)], axis=1)
                xs.append(local @ rot.T + centre)
                vols.append(np.full(n_ang, axis_inc * area))
                size = np.zeros((n_ang, 3, 3))
                arc, width = span / n_ang, rad_inc / r
                size[:, 0, 0], size[:, 1, 0] = arc * local[:, 1], -arc * local[:, 0]
                size[:, 0, 1], size[:, 1, 1] = width * local[:, 0], width * local[:, 1]
                size[:, 2, 2] = axis_inc
                sizes.append(rot @ size @ rot.T)
        return (np.concatenate(xs).reshape(-1, 3), np.concatenate(vols),
                np.concatenate(sizes).reshape(-1, 3, 3))


def _uintah_rotation(angle, a):
    """Uintah's Matrix3(angle, axis): (I - a a^T) cos + a a^T - A sin, A the cross-product
    matrix of a (a turn by -angle about a)."""
    aa = np.outer(a, a)
    cross = np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])
    return (np.eye(3) - aa) * np.cos(angle) + aa - cross * np.sin(angle)


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

    def read_object(self, node, outside_ok=False):
        """The union of the pieces of a <geom_object> (an error if it has none). With a level,
        an object wholly outside it is an error unless outside_ok (the caller then decides,
        with `outside`); a lone <null> is never checked (Uintah's "no particles" for MPM)."""
        pieces = [self.read(c) for c in self._piece_children(node)]
        if not pieces:
            raise node.error(f"no geometry piece; accepted: {', '.join('<%s>' % t for t in PIECE_TAGS)}")
        piece = pieces[0] if len(pieces) == 1 else Union(pieces)
        if self.level is not None and not outside_ok and not isinstance(piece, Null):
            self.check_overlap(piece, node)
        return piece

    def _domain(self):
        lv = self.level
        extra = np.asarray(lv.extra) * lv.dx
        return lv.anchor - extra, lv.upper + extra

    def outside(self, piece):
        """Does the piece miss every cell of the level (extra cells included)?"""
        lo, hi = self._domain()
        b = piece.bounds()
        return b is None or bool(np.any(b[1] < lo) or np.any(b[0] > hi))

    def check_overlap(self, piece, node, hint=""):
        """An object that cannot reach any cell of the level (extra cells included) puts no
        material anywhere: refuse it, naming it, rather than run without that material."""
        if self.outside(piece):
            lo, hi = self._domain()
            b = piece.bounds()
            where = "is empty" if b is None else f"spans {_fmt(b[0])} to {_fmt(b[1])}"
            raise node.error(f"this geometry object {where}, wholly outside the domain {_fmt(lo)} to {_fmt(hi)} "
                             "(extra cells included), so it puts no material anywhere; accepted: an object "
                             "that overlaps the domain" + hint)

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
            with np.errstate(over="ignore"):
                length2 = float(np.subtract(t, b) @ np.subtract(t, b))
            if not np.isfinite(length2):
                raise node.error(f"<bottom> {b} and <top> {t} are too far apart: the axis's length squared "
                                 "overflows a double; accepted: a distance below 1e154")
            return Cylinder(b, t, r)
        if tag == "tri":
            return _read_tri(node)
        if tag in _ANALYTIC:
            return _ANALYTIC[tag](node)
        parts = [self.read(c) for c in self._piece_children(node)]
        other = [c for c in node.children() if c.tag not in PIECE_TAGS]
        if other:
            raise other[0].error(f"<{other[0].tag}> is not a geometry piece; accepted in <{tag}>: "
                                 + ", ".join("<%s>" % t for t in PIECE_TAGS))
        if tag == "difference":
            if len(parts) != 2:
                raise node.error(f"<difference> needs exactly two pieces, found {len(parts)}")
            return Difference(*parts)
        if len(parts) < 1:
            raise node.error(f"<{tag}> needs at least one piece")
        return Union(parts) if tag == "union" else Intersection(parts)


def _positive(node, tag, value, zero_ok=False):
    if value < 0 or (value == 0 and not zero_ok):
        raise node.child(tag).error(f"{tag} must be {'at least 0' if zero_ok else 'positive'}")
    return value


def _read_parallelepiped(node):
    p = [np.asarray(node.get(f"p{k}", "vector"), float) for k in (1, 2, 3, 4)]
    if abs(np.linalg.det(np.stack([q - p[0] for q in p[1:]]))) <= 1e-300:
        raise node.error("<p2>-<p1>, <p3>-<p1> and <p4>-<p1> must not lie in one plane "
                         "(the parallelepiped has no volume)")
    return Parallelepiped(*p)


def _read_ellipsoid(node):
    origin = node.get("origin", "vector")
    vs = [np.asarray(node.get(t, "vector", (0.0, 0.0, 0.0)), float) for t in ("v1", "v2", "v3")]
    if all(np.linalg.norm(v) > Ellipsoid.TOL for v in vs):
        if any(abs(vs[i] @ vs[j]) >= 1e-12 for i, j in ((0, 1), (1, 2), (2, 0))):
            raise node.error("<v1>, <v2>, <v3> must be orthogonal (to 1e-12, as Uintah)")
        return Ellipsoid(origin, vs)
    r = [node.get(t, "float", 0.0) for t in ("rx", "ry", "rz")]
    if min(r) <= 0:
        raise node.error("an <ellipsoid> needs <rx>, <ry>, <rz> all > 0, or three non-zero "
                         "orthogonal vectors <v1>, <v2>, <v3>")
    return Ellipsoid(origin, np.diag(r))


def _read_cone(node):
    b, t = node.get("bottom", "vector"), node.get("top", "vector")
    rb = _positive(node, "bottom_radius", node.get("bottom_radius", "float", 0.0), zero_ok=True)
    rt = _positive(node, "top_radius", node.get("top_radius", "float", 0.0), zero_ok=True)
    if rb == 0 and rt == 0:
        raise node.error("a <cone> needs <bottom_radius> or <top_radius> > 0")
    if np.linalg.norm(np.subtract(t, b)) < 1e-100:
        raise node.error("<bottom> and <top> coincide")
    return Cone(b, t, rb, rt)


def _read_torus(node):
    major = _positive(node, "major_radius", node.get("major_radius", "float"), zero_ok=True)
    minor = _positive(node, "minor_radius", node.get("minor_radius", "float"))
    axis = node.get("axis", "str")
    if axis not in ("x", "y", "z"):
        raise node.child("axis").error(f"value '{axis}' is not accepted; accepted: x, y, z")
    return Torus(node.get("center", "vector"), major, minor, axis, node.get("theta", "float", 0.0))


def _read_polyhedron(node):
    center = np.asarray(node.get("center", "vector"), float)
    bounds = node.child("bounds", required=True)
    points, normals = [], []
    for hs in bounds.children("half_space"):
        kind = hs.attr("type", default="absolute", choices=("absolute", "relative"))
        if kind == "absolute":
            point, normal = np.asarray(hs.get("planePoint", "vector"), float), np.asarray(hs.get("normal", "vector"), float)
        else:
            offset = np.asarray(hs.get("offset", "vector"), float)
            point, normal = center + offset, -offset
        if not np.linalg.norm(normal) > 0:
            raise hs.error("the plane's normal is zero")
        points.append(point)
        normals.append(normal)
    if len(normals) < 4:
        raise bounds.error(f"a <polyhedron> needs at least four <half_space>s to enclose a volume, found {len(normals)}")
    piece = Polyhedron(points, normals)
    if len(piece.vertices) < 4:
        raise bounds.error("the <half_space>s do not enclose a volume (fewer than four vertices)")
    return piece


def _read_smoothcyl(node):
    scheme = node.get("discretization_scheme", "str")
    if scheme not in ("pie_slices", "constant_particle_volumes"):
        raise node.child("discretization_scheme").error(
            f"value '{scheme}' is not accepted; accepted: pie_slices, constant_particle_volumes")
    b, t = node.get("bottom", "vector"), node.get("top", "vector")
    if not np.sum(np.subtract(t, b) ** 2) > 0:
        raise node.error("<bottom> and <top> coincide")
    r_out = _positive(node, "outer_radius", node.get("outer_radius", "float"))
    n_rad, n_ax = node.get("num_radial", "int"), node.get("num_axial", "int")
    for tag, n in (("num_radial", n_rad), ("num_axial", n_ax)):
        if n < 1:
            raise node.child(tag).error(f"{tag} must be at least 1")
    n_ang = node.get("num_angular", "int", 0)
    if scheme == "pie_slices" and n_ang < 1:
        raise node.error("pie_slices needs <num_angular> at least 1")
    if scheme == "constant_particle_volumes" and node.has("num_angular"):
        node.child("num_angular").mark_used()          # Uintah ignores it there too
    r_in = _positive(node, "inner_radius", node.get("inner_radius", "float", 0.0), zero_ok=True)
    if r_in > r_out:
        raise node.child("inner_radius").error("inner_radius exceeds outer_radius")
    cap = _positive(node, "endcap_thickness", node.get("endcap_thickness", "float", 0.0), zero_ok=True)
    start = node.get("arc_start_angle", "float", 0.0)
    start = np.pi / 180.0 * start if start > 0 else 0.0
    if start > 2 * np.pi:
        raise node.child("arc_start_angle").error("arc_start_angle must be in 0..360 (degrees)")
    angle = node.get("arc_angle", "float", -1.0)
    angle = np.pi / 180.0 * angle if angle > 0 else 2 * np.pi
    if angle > 2 * np.pi:
        raise node.child("arc_angle").error("arc_angle must be in 0..360 (degrees)")
    if node.has("output_file"):
        raise node.child("output_file").error("writing the points to a file is not supported; accepted: "
                                              "no <output_file>")
    return SmoothCylinder(b, t, r_out, r_in, n_rad, n_ax, n_ang, scheme, cap, start, angle)


_ANALYTIC = {"parallelepiped": _read_parallelepiped, "ellipsoid": _read_ellipsoid, "cone": _read_cone,
             "torus": _read_torus, "polyhedron": _read_polyhedron, "smoothcyl": _read_smoothcyl,
             "null": lambda node: Null()}


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
    box is sampled a group of x-slabs at a time (about SAMPLES_PER_CALL points), so that
    memory stays bounded on big patches and a piece made of many parts (a union of boxes)
    is not called once per slab.
    """
    shape = tuple(h - l for l, h in zip(*box))
    axes = []
    for d in range(3):
        n = 1 if level.collapsed[d] else int(res[d])
        off = (np.arange(n) + 0.5) / n
        cells = np.arange(box[0][d], box[1][d])
        axes.append(level.anchor[d] + (cells[:, None] + off[None, :]) * level.dx[d])
    out = np.empty(shape)
    per_slab = max(1, axes[0].shape[1] * axes[1].size * axes[2].size)
    slabs = max(1, SAMPLES_PER_CALL // per_slab)
    Y = axes[1][None, :, None, :, None, None]
    Z = axes[2][None, None, :, None, :, None]
    for i in range(0, shape[0], slabs):
        X = axes[0][i:i + slabs][:, None, None, None, None, :]
        Xb, Yb, Zb = np.broadcast_arrays(X, Y, Z)
        pts = np.stack([Xb.ravel(), Yb.ravel(), Zb.ravel()], axis=1)
        out[i:i + slabs] = piece.inside(pts).reshape(Xb.shape).mean(axis=(3, 4, 5))
    return out


SAMPLES_PER_CALL = 1 << 18
