"""Pressure boundary conditions on MPM particles, `<PhysicalBC><MPM><pressure>` (Uintah's
PressureBC with `<MPM><use_load_curves>true</use_load_curves>`).

    <PhysicalBC><MPM>
      <pressure>
        <geom_object><cylinder label="inner"><bottom>..</bottom><top>..</top><radius>..</radius>
                     </cylinder></geom_object>          (or a <box> of zero or least thickness)
        <load_curve><id>1</id>
          <time_point><time>0</time><load>0</load></time_point>
          <time_point><time>1e-3</time><load>1e6</load></time_point> ...
        </load_curve>
      </pressure> ...
    </MPM></PhysicalBC>

As Uintah does it:
* At initialization a particle is flagged with the curve's id (p.loadCurveID) when it
  lies on the surface of its own geometry (a neighbour one particle spacing away along
  an active direction is outside it) and on the loaded surface: a box face, the box
  widened by one particle spacing in its thinnest direction; the side of a cylinder,
  the annulus radius +- 0.9 times the smallest particle spacing.
* Each step, at the time t of its start, every flagged particle gets the external force
  p(t) A / N along the surface normal: +thinnest axis of the box, the outward radial
  direction of the cylinder; p(t) from the load curve (linear between time points, held
  beyond the ends), A the surface area, N the number of flagged particles (all patches,
  all ranks). Positive pressure pushes along the outward normal (internal pressure on
  the inner surface of a tube is positive).
* The force enters fext_i of particle-to-grid (000 eq. 22) and is saved as
  p.externalforce.

pysus difference: A is the part of the surface that lies inside the computational
domain (Uintah takes the whole surface and warns that this is wrong when the piece
leaves the domain), so quarter- and half-symmetry models get the right load.
"""
from __future__ import annotations

import numpy as np

from framework.geometry import Box, Cylinder

MAX_BCS = 16


class PressureBC:
    def __init__(self, node, geom, level):
        g = node.child("geom_object", required=True)
        piece = geom.read_object(g)
        if not isinstance(piece, (Box, Cylinder)):
            raise g.error("the pressure surface must be one <box> or one <cylinder>")
        self.piece = piece
        lc = node.child("load_curve", required=True)
        self.id = lc.get("id", "int")
        if self.id < 1:
            raise lc.child("id").error("load curve ids start at 1")
        pts = lc.children("time_point")
        if not pts:
            raise lc.error("a <load_curve> needs at least one <time_point>")
        self.times = np.array([p.get("time", "float") for p in pts])
        self.loads = np.array([p.get("load", "float") for p in pts])
        if np.any(np.diff(self.times) <= 0):
            raise lc.error("the <time> of the time points must increase")
        if isinstance(piece, Box):
            ext = piece.hi - piece.lo
            self.thin = int(np.argmin(ext))
        self.area = self._area_in_domain(level)
        if self.area <= 0:
            raise g.error("the pressure surface lies outside the computational domain")

    # -- Uintah's PressureBC pieces --------------------------------------------------------
    def pressure(self, t):
        return float(np.interp(t, self.times, self.loads))

    def _surface_samples(self, n=400):
        """Points spread evenly over the loaded surface (for the area inside the domain)."""
        u = (np.arange(n) + 0.5) / n
        if isinstance(self.piece, Box):
            lo, hi = self.piece.lo, self.piece.hi
            a, b = [d for d in range(3) if d != self.thin]
            A, B = np.meshgrid(lo[a] + u * (hi[a] - lo[a]), lo[b] + u * (hi[b] - lo[b]), indexing="ij")
            x = np.empty((A.size, 3))
            x[:, self.thin] = 0.5 * (lo[self.thin] + hi[self.thin])
            x[:, a], x[:, b] = A.ravel(), B.ravel()
            return x, float(np.prod([hi[d] - lo[d] for d in (a, b)]))
        c = self.piece
        e = c.axis / np.sqrt(c.length2)
        t1 = np.cross(e, [1.0, 0, 0] if abs(e[0]) < 0.9 else [0, 1.0, 0])
        t1 /= np.linalg.norm(t1)
        t2 = np.cross(e, t1)
        th, s = np.meshgrid(2 * np.pi * u, u, indexing="ij")
        x = (c.bottom + s.ravel()[:, None] * c.axis
             + c.radius * (np.cos(th.ravel())[:, None] * t1 + np.sin(th.ravel())[:, None] * t2))
        return x, 2 * np.pi * c.radius * np.sqrt(c.length2)

    def _area_in_domain(self, level):
        x, area = self._surface_samples()
        lo = np.asarray(level.anchor, float)
        hi = lo + np.asarray(level.ncells) * np.asarray(level.dx)
        inside = np.all((x >= lo) & (x <= hi), axis=1)
        return area * inside.mean()

    def on_surface(self, x, dxpp, dims):
        """Particles (already on their object's surface) that this BC loads; dxpp the
        particle spacing, dims the active directions (the tolerance uses those)."""
        if isinstance(self.piece, Box):
            extra = np.zeros(3)
            extra[self.thin] = dxpp[self.thin]
            return Box(self.piece.lo - extra, self.piece.hi + extra).inside(x)
        c = self.piece
        tol = 0.9 * dxpp[dims].min()
        rel = x - c.bottom
        s = rel @ c.axis / c.length2
        r = np.sqrt(np.maximum(np.sum(rel ** 2, axis=1) - s ** 2 * c.length2, 0.0))
        return (s >= 0) & (s <= 1) & (r <= c.radius + tol) & (r > c.radius - tol)

    def normals(self, x):
        if isinstance(self.piece, Box):
            n = np.zeros((len(x), 3))
            n[:, self.thin] = 1.0
            return n
        c = self.piece
        rel = x - c.bottom
        s = rel @ c.axis / c.length2
        radial = rel - s[:, None] * c.axis
        norm = np.linalg.norm(radial, axis=1)
        return radial / np.where(norm > 0, norm, 1.0)[:, None]


class PressureBCs:
    """All pressure BCs of a deck; p.loadCurveID holds the id of the BC loading a particle."""

    def __init__(self, bcs, mpm):
        self.bcs = bcs
        self.by_id = {b.id: b for b in bcs}
        self.dims = np.array(mpm.dims, bool)

    def __bool__(self):
        return bool(self.bcs)

    @classmethod
    def read(cls, root, mpm):
        pbc = root.child("PhysicalBC")
        if pbc is None:
            return None
        node = pbc.child("MPM")
        if node is None:
            return None
        items = node.children("pressure")
        for tag in ("force", "normal_force", "crack", "heatflux", "arches_heatflux", "torque", "scalar_flux"):
            if node.has(tag):
                raise node.child(tag).error(f"<{tag}> is not supported; accepted: <pressure>")
        if not items:
            return None
        if not mpm.flags["use_load_curves"]:
            raise items[0].error("<pressure> needs <MPM><use_load_curves>true</use_load_curves> "
                                 "(without it Uintah applies no pressure)")
        if len(items) > MAX_BCS:
            raise items[MAX_BCS].error(f"at most {MAX_BCS} pressure BCs")
        geom = getattr(root, "_geometry_reader", None)
        if geom is None:
            from framework.geometry import GeometryReader
            geom = GeometryReader()
        bcs = [PressureBC(it, geom, mpm.level) for it in items]
        ids = [b.id for b in bcs]
        for k, i in enumerate(ids):
            if i in ids[:k]:
                raise items[k].child("load_curve").child("id").error(f"load curve id {i} is used twice")
        return cls(bcs, mpm)

    def flag(self, x, piece, dxpp):
        """p.loadCurveID (0: not loaded) of new particles of one geometry object."""
        surface = np.zeros(len(x), bool)
        for d in range(3):
            if self.dims[d]:
                for sgn in (-1.0, 1.0):
                    y = x.copy()
                    y[:, d] += sgn * dxpp[d]
                    surface |= ~piece.inside(y)
        ids = np.zeros(len(x))
        for b in self.bcs:
            sel = surface & (ids == 0) & b.on_surface(x, dxpp, self.dims)
            ids[sel] = b.id
        return ids

    def counts(self, ids):
        """Flagged particles per BC (in deck order): this patch's share of N."""
        return np.array([np.count_nonzero(ids == b.id) for b in self.bcs] +
                        [0] * (MAX_BCS - len(self.bcs)), float)

    def forces(self, x, ids, t, totals):
        """p.externalforce at time t of particles x with p.loadCurveID ids."""
        f = np.zeros((len(x), 3))
        for k, b in enumerate(self.bcs):
            sel = np.flatnonzero(ids == b.id)
            if len(sel) and totals[k] > 0:
                f[sel] = b.normals(x[sel]) * (b.pressure(t) * b.area / totals[k])
        return f
