"""Load-curve boundary conditions on MPM particles, `<PhysicalBC><MPM><pressure>`, `<torque>`
and `<heat_flux>` (Uintah's PressureBC, TorqueBC and HeatFluxBC with
`<MPM><use_load_curves>true</use_load_curves>`).

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
* At initialization a particle is flagged with the curve's id (p.loadCurveID holds up to
  three ids, Uintah's IntVector, in deck order: pressures, then torques) when it lies on
  the surface of its own geometry (a neighbour one particle spacing away along an active
  direction is outside it), is of the load curve's <material> (default any) and on the
  loaded surface: a box face, the box widened by one particle spacing in its thinnest
  direction; the side of a cylinder, the annulus radius +- 0.9 times the smallest
  particle spacing; with <cylinder_end>true</cylinder_end> in the cylinder, its end:
  the cylinder lengthened by 1.2 times the smallest spacing at both ends. A heat flux
  flags the box widened by one particle spacing in every direction, or the annulus
  radius +- half the length of the particle-spacing vector.
* Each step, at the time t of its start, every flagged particle gets the external force
  p(t) A / N along the surface normal: +thinnest axis of the box, the outward radial
  direction of the cylinder, the axis (bottom to top) for a cylinder end (A = pi r^2);
  p(t) from the load curve (linear between time points, held beyond the ends), A the
  surface area, N the number of flagged particles (all patches, all ranks). Positive
  pressure pushes along the outward normal (internal pressure on the inner surface of a
  tube is positive).
* A torque T(t) on the side of a cylinder: each of its N particles gets the force
  T/N * (x - bottom) x a / r^2, a the unit axis, r the distance from the axis (magnitude
  T/(N r), sum of moments -T a: Uintah's TorqueBC sign).
* A heat flux q(t) (W/m^2) gives each of its N particles the heat rate q A / N (W,
  p.externalHeatRate in Uintah), A the box face or the cylinder's side; it reaches the
  nodes as sum S_ip q_p and adds sum S_ip q_p / (m_i c_v) to g.temperatureRate
  (thermal.py; Uintah's HeatConduction::solveHeatEquations). It needs heat conduction
  in the loaded material.
* The force enters fext_i of particle-to-grid (000 eq. 22) and is saved as
  p.externalforce.

pysus difference: A is the part of the surface that lies inside the computational
domain (Uintah takes the whole surface and warns that this is wrong when the piece
leaves the domain), so quarter- and half-symmetry models get the right load.

Axisymmetric MPM (<MPM><axisymmetric>true; x is r, y the axis, volumes per radian): A is
Uintah's, the whole surface (its decks rely on it), and a cylinder about the y axis may carry
<axisymmetric_side>true (A = the side's area per radian, r L) or <axisymmetric_end>true with
<res> in the <pressure> block: the end's particles each get p(t) r dx/res_x along the axis
(the area of their ring per radian), whatever their number.
"""
from __future__ import annotations

import numpy as np

from framework.geometry import Box, Cylinder

MAX_BCS = 16
IDS_PER_PARTICLE = 3      # Uintah's p.loadCurveID is an IntVector


class PressureBC:
    kind = "pressure"

    def __init__(self, node, geom, level, nmat, axisymmetric=False):
        g = node.child("geom_object", required=True)
        piece = geom.read_object(g)
        if not isinstance(piece, self.pieces):
            raise g.error(f"the {self.kind} surface must be " + " or ".join(f"one <{t.__name__.lower()}>"
                                                                          for t in self.pieces))
        self.piece = piece
        self.cylinder_end = self.axisymmetric_end = self.axisymmetric_side = False
        cyl = g.child("cylinder")
        if cyl is not None:
            for tag in ("axisymmetric_end", "axisymmetric_side"):
                if cyl.get(tag, "bool", False):
                    if not axisymmetric:
                        raise cyl.child(tag).error(f"<{tag}> needs <MPM><axisymmetric>true; accepted: false")
                    if self.kind != "pressure":
                        raise cyl.child(tag).error(f"<{tag}> is read for a pressure only; accepted: false")
                    setattr(self, tag, True)
            self.cylinder_end = cyl.get("cylinder_end", "bool", False)
            if self.cylinder_end and self.kind != "pressure":
                raise cyl.child("cylinder_end").error(f"a {self.kind} acts on the side of a cylinder; accepted: false")
        self.end = self.cylinder_end or self.axisymmetric_end         # a cylinder's end is loaded
        # CBDI (cbdi.py): false flips n when the loaded face of a particle's domain is sought
        self.outward_normal = node.get("outward_normal", "bool", True)
        if self.axisymmetric_end:
            self.dr = level.dx[0] / node.get("res", "ivector", at_least=1)[0]     # the particles' r spacing
        lc = node.child("load_curve", required=True)
        self.id = lc.get("id", "int")
        if self.id < 1:
            raise lc.child("id").error("load curve ids start at 1")
        self.material = lc.get("material", "int", -1)
        if not -1 <= self.material < nmat:
            raise lc.child("material").error(f"material {self.material} does not exist; accepted: 0 to {nmat - 1}")
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
        self.area = self._whole_area() if axisymmetric else self._area_in_domain(level)
        if self.area <= 0:
            raise g.error(f"the {self.kind} surface lies outside the computational domain")

    pieces = (Box, Cylinder)

    # -- Uintah's PressureBC pieces --------------------------------------------------------
    def pressure(self, t):
        return float(np.interp(t, self.times, self.loads))

    def _whole_area(self):
        """Uintah's A: the whole loaded surface (per radian for <axisymmetric_side>)."""
        if isinstance(self.piece, Box):
            ext = np.sort(self.piece.hi - self.piece.lo)
            return float(ext[1] * ext[2])
        c = self.piece
        if self.axisymmetric_end:
            return 0.5 * c.radius ** 2
        if self.cylinder_end:
            return np.pi * c.radius ** 2
        side = 2 * np.pi * c.radius * np.sqrt(c.length2)
        return side / (2 * np.pi) if self.axisymmetric_side else side

    def _surface_samples(self, n=400):
        """Points spread evenly over the loaded surface (for the area inside the domain)."""
        u = (np.arange(n) + 0.5) / n
        if self.cylinder_end:
            c = self.piece
            e = c.axis / np.sqrt(c.length2)
            t1 = np.cross(e, [1.0, 0, 0] if abs(e[0]) < 0.9 else [0, 1.0, 0])
            t1 /= np.linalg.norm(t1)
            t2 = np.cross(e, t1)
            th, s = np.meshgrid(2 * np.pi * u, u, indexing="ij")     # equal-area rings
            rad = c.radius * np.sqrt(s.ravel())[:, None]
            x = (0.5 * (c.bottom + c.top) + rad * (np.cos(th.ravel())[:, None] * t1
                                                   + np.sin(th.ravel())[:, None] * t2))
            return x, np.pi * c.radius ** 2
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
        if self.end:
            tol = 1.2 * dxpp[dims].min()
            e = c.axis / np.sqrt(c.length2)
            return Cylinder(c.bottom - tol * e, c.top + tol * e, c.radius).inside(x)
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
        if self.end:
            return np.broadcast_to(c.axis / np.sqrt(c.length2), x.shape)
        rel = x - c.bottom
        s = rel @ c.axis / c.length2
        radial = rel - s[:, None] * c.axis
        norm = np.linalg.norm(radial, axis=1)
        return radial / np.where(norm > 0, norm, 1.0)[:, None]

    def load(self, x, t, count):
        """The external force on each of `count` flagged particles at x, time t."""
        if self.axisymmetric_end:         # p times the particle's ring area per radian, r dr
            return self.normals(x) * (self.pressure(t) * self.dr * x[:, 0])[:, None]
        return self.normals(x) * (self.pressure(t) * self.area / count)


class TorqueBC(PressureBC):
    """Uintah's TorqueBC: a torque about the axis of a cylinder, spread over its side."""
    kind = "torque"
    pieces = (Cylinder,)

    def load(self, x, t, count):
        c = self.piece
        a = c.axis / np.sqrt(c.length2)
        arm = np.cross(x - c.bottom, a)                          # |arm| = r, the distance from the axis
        r2 = np.sum(arm ** 2, axis=1)
        return arm * (self.pressure(t) / count / np.where(r2 > 0, r2, np.inf))[:, None]


class HeatFluxBC(PressureBC):
    """Uintah's HeatFluxBC: a heat flux through a box face or a cylinder's side."""
    kind = "heat_flux"

    def on_surface(self, x, dxpp, dims):
        if isinstance(self.piece, Box):
            return Box(self.piece.lo - dxpp, self.piece.hi + dxpp).inside(x)
        c = self.piece
        tol = 0.5 * np.linalg.norm(dxpp)
        rel = x - c.bottom
        s = rel @ c.axis / c.length2
        r = np.sqrt(np.maximum(np.sum(rel ** 2, axis=1) - s ** 2 * c.length2, 0.0))
        return (s >= 0) & (s <= 1) & (r <= c.radius + tol) & (r > c.radius - tol)

    def load(self, x, t, count):
        """The heat rate (W) on each of `count` flagged particles."""
        return np.full(len(x), self.pressure(t) * self.area / count)


class PressureBCs:
    """All pressure BCs of a deck; p.loadCurveID holds the id of the BC loading a particle."""

    def __init__(self, bcs, mpm):
        self.bcs = bcs
        self.by_id = {b.id: b for b in bcs}
        self.dims = np.array(mpm.dims, bool)
        self.cbdi = mpm.flags.get("use_CBDI_boundary_condition", False)

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
        items = [(PressureBC, it) for it in node.children("pressure")]
        items += [(TorqueBC, it) for it in node.children("torque")]
        items += [(HeatFluxBC, it) for it in node.children("heat_flux")]
        for tag in ("force", "normal_force", "crack", "arches_heat_flux", "scalar_flux", "pressure_pts"):
            if node.has(tag):
                raise node.child(tag).error(f"<{tag}> is not supported; accepted: <pressure>, <torque>, <heat_flux>")
        if not items:
            return None
        if not mpm.flags["use_load_curves"]:
            raise items[0][1].error(f"<{items[0][0].kind}> needs <MPM><use_load_curves>true</use_load_curves> "
                                    "(without it Uintah applies no load)")
        if len(items) > MAX_BCS:
            raise items[MAX_BCS][1].error(f"at most {MAX_BCS} load-curve BCs")
        if mpm.flags.get("use_CBDI_boundary_condition", False):
            for cls_, it in items:
                if cls_ is not HeatFluxBC and not it.has("outward_normal"):
                    raise it.error(f"with <use_CBDI_boundary_condition>true a <{cls_.kind}> needs "
                                   "<outward_normal> (true or false; Uintah requires it)")
        geom = getattr(root, "_geometry_reader", None)
        if geom is None:
            from framework.geometry import GeometryReader
            geom = GeometryReader()
        axi = getattr(mpm, "axisymmetric", False)
        bcs = [cls_(it, geom, mpm.level, len(mpm.materials), axi) for cls_, it in items]
        ids = [b.id for b in bcs]
        for k, i in enumerate(ids):
            if i in ids[:k]:
                raise items[k][1].child("load_curve").child("id").error(f"load curve id {i} is used twice")
        for b, (_, it) in zip(bcs, items):
            if b.kind == "heat_flux":
                mats = range(len(mpm.materials)) if b.material < 0 else [b.material]
                cold = [m for m in mats if m not in mpm.conducting]
                if cold:
                    raise it.error(f"a <heat_flux> needs heat conduction in material {cold[0]} "
                                   "(<DoExplicitHeatConduction>true and <thermal_conductivity> > 0)")
        return cls(bcs, mpm)

    def flag(self, x, piece, dxpp, matl):
        """p.loadCurveID, (n, 3): the ids (0: none) of the BCs loading the new particles of
        one geometry object of material matl, at most three, in deck order."""
        from .materials import on_surface
        surface = on_surface(x, piece, dxpp, self.dims)
        ids = np.zeros((len(x), IDS_PER_PARTICLE))
        used = np.zeros(len(x), np.int64)
        for b in self.bcs:
            if b.material not in (-1, matl):
                continue
            sel = np.flatnonzero(surface & (used < IDS_PER_PARTICLE) & b.on_surface(x, dxpp, self.dims))
            ids[sel, used[sel]] = b.id
            used[sel] += 1
        return ids

    def counts(self, ids):
        """Flagged particles per BC (in deck order): this patch's share of N."""
        return np.array([np.count_nonzero(ids == b.id) for b in self.bcs] +
                        [0] * (MAX_BCS - len(self.bcs)), float)

    def forces(self, x, ids, t, totals):
        """p.externalforce at time t of particles x with p.loadCurveID ids."""
        f = np.zeros((len(x), 3))
        for k, b in enumerate(self.bcs):
            sel = np.flatnonzero(np.any(ids == b.id, axis=1))
            if len(sel) and totals[k] > 0 and b.kind != "heat_flux":
                f[sel] += b.load(x[sel], t, totals[k])
        return f

    def cbdi_forces(self, x, ids, t, totals, F, psize, dx):
        """p.externalforce at time t and the loaded-face corners (n, 4, 3) of particles x with
        p.loadCurveID ids under CBDI (cbdi.py): F and psize (Uintah's p.size in cells) of the
        step's start."""
        from .cbdi import NO_CORNER, corner_loads
        f = np.zeros((len(x), 3))
        corners = np.full((len(x), 4, 3), NO_CORNER)
        for k, b in enumerate(self.bcs):
            sel = np.flatnonzero(np.any(ids == b.id, axis=1))
            if not len(sel) or totals[k] <= 0 or b.kind == "heat_flux":
                continue
            if b.kind == "pressure":
                xs = x[sel]
                corner_loads(sel, x, b.load(xs, t, totals[k]), np.ascontiguousarray(b.normals(xs)),
                             b.outward_normal, F, psize, np.asarray(dx, float), f, corners)
            else:
                f[sel] += b.load(x[sel], t, totals[k])
        return f, corners

    @property
    def heat_flux(self):
        return any(b.kind == "heat_flux" for b in self.bcs)

    def heat_rates(self, x, ids, t, totals):
        """p.externalHeatRate (W) at time t of particles x with p.loadCurveID ids."""
        q = np.zeros(len(x))
        for k, b in enumerate(self.bcs):
            sel = np.flatnonzero(np.any(ids == b.id, axis=1))
            if len(sel) and totals[k] > 0 and b.kind == "heat_flux":
                q[sel] += b.load(x[sel], t, totals[k])
        return q
