"""Uintah's PassiveScalar model for ICE: a scalar f carried by one material's flow.

    <Models><Model type="PassiveScalar"><PassiveScalar>
      <material> name </material>
      <scalar name="f">                         the variable scalar-f (scalar-q for name="q", ...)
        <test_conservation> bool </test_conservation>      totalSum_scalar-f each step
        <constants> <diffusivity/> <rateOfChange0/> <rateOfChange1/> </constants>
        <exponentialDecay> <c1/> <c2 type="constant"><value/></c2> <c3/> </exponentialDecay>
                           or <c2 type="variable"><filename> x,y,z,c2 table </filename></c2>
                           (the per-cell c2 is the label scalar-f_expDecayCoef)
        <initialization> <geom_object> pieces <scalar/> [a profile flag] </geom_object> ...
        <interiorSources> <geom_object> pieces <scalar/> <maxScalar/> </geom_object> ...
      </scalar>
    </PassiveScalar></Model></Models>

f is mass specific: ICE advects m f with the material's mass fluxes (components/ice:
ICE::computeLagrangian_Transported_Vars and advectAndAdvanceInTime), so f stays bounded and
sum m f is conserved. Each step the model computes the Lagrangian source scalar-f_src from the
old f (Uintah's PassiveScalar::computeModelSources, in this order): diffusion, linear decay
-dt (r0 + r1 f), exponential decay f (exp(-(c1 c2 + c3) dt) - 1) (c2 a number, or per cell
from a csv table of cell centres and values, '#' lines a header, every interior cell once, as
Uintah's PassiveScalar::readTable), then inside an interior
source the source is *set* to <scalar>, with f + src kept at most <maxScalar>, and everywhere
f + src >= 0 (Uintah's rateOfChangeInterior is left out: its input specification refuses it). Uintah's diffusion source is
-dt sum_faces (flux area) with the flux -D grad f (D the harmonic mean on a face): not divided
by the cell volume, so <diffusivity> acts as D / V; pysus keeps that so that results agree.
The boundary conditions of scalar-f are <BCType label="scalar-f" var="Dirichlet|Neumann"> on
every face (or a symmetry face), as Uintah requires. totalSum_scalar-f is Uintah's
conservationTest of m f: the interior sum plus delT times the fluxes through the domain's upper
faces.
"""
from __future__ import annotations

import numpy as np

from components.ice import labels as I
from framework import labels as L
from framework.problemspec import Param
from framework.task import NEW, OLD, Task
from framework.variables import Ghost, VarType

from . import kernels as K
from .simple_burn import _material

CC, R = VarType.CC, VarType.REDUCTION
CONSTANTS = {
    "diffusivity": Param("float", 0.0, at_least=0.0),
    "rateOfChange0": Param("float", 0.0),
    "rateOfChange1": Param("float", 0.0),
    "AMR_Refinement_Criteria": Param("float", 1e100),
}
# initialization profiles (Uintah's Region flags): f over the piece's bounding box, d the
# position normalised to it, in [0, 1] per direction
PROFILES = ("sinusoidalInitialize", "linearInitialize", "cubicInitialize", "quadraticInitialize",
            "exponentialInitialize_1D", "exponentialInitialize_2D", "triangularInitialize")


class Region:
    """One <initialization><geom_object>: its piece, <scalar> and profile (None: uniform)."""

    def __init__(self, node, geo):
        self.piece = geo.read_object(node)
        self.value = node.get("scalar", "float")
        flags = [p for p in PROFILES if node.get(p, "bool", False)]
        if len(flags) > 1:
            raise node.error(f"more than one initialization profile ({', '.join(flags)}); accepted: one")
        self.profile = flags[0] if flags else None
        self.freq = np.array(node.get("freq", "ivector", (0, 0, 0)), dtype=np.float64)
        self.slope = np.array(node.get("slope", "vector", (0.0, 0.0, 0.0)))
        self.coeff = np.array(node.get("coeff", "vector", (0.0, 0.0, 0.0)))
        p = self.profile
        if p == "sinusoidalInitialize" and not self.freq.any():
            raise node.error("sinusoidalInitialize needs a non-zero <freq>")
        if p in ("linearInitialize", "triangularInitialize") and not self.slope.any():
            raise node.error(f"{p} needs a non-zero <slope>")
        if p in ("quadraticInitialize", "exponentialInitialize_1D", "exponentialInitialize_2D") \
                and not self.coeff.any():
            raise node.error(f"{p} needs a non-zero <coeff>")
        c = self.coeff
        if p == "exponentialInitialize_1D" and np.count_nonzero(c) > 1:
            raise node.child("coeff").error("exponentialInitialize_1D is a 1D profile: one non-zero <coeff>")
        if p == "exponentialInitialize_2D" and np.count_nonzero(c) == 3:
            raise node.child("coeff").error("exponentialInitialize_2D is a 2D profile: one <coeff> must be 0")

    def values(self, x):
        """f at the points x (n, 3) inside the piece (Uintah's PassiveScalar::initialize)."""
        if self.profile is None:
            return np.full(len(x), self.value)
        lo, hi = self.piece.bounds()
        d = (x - lo) / (hi - lo)
        p, c = self.profile, self.coeff
        if p == "sinusoidalInitialize":
            return np.sum(np.sin(2.0 * self.freq * d * np.pi), axis=1)
        if p == "linearInitialize":
            return d @ self.slope + self.value
        if p == "triangularInitialize":
            return np.where(d[:, 0] <= 0.5, self.slope[0] * d[:, 0], self.slope[0] * (1.0 - d[:, 0]))
        if p == "quadraticInitialize":
            return np.where(d[:, 0] <= 0.5, d[:, 0] ** 2 - d[:, 0], (1.0 - d[:, 0]) ** 2 - d[:, 0])
        if p == "cubicInitialize":
            e = np.where(d[:, 0] <= 0.5, d[:, 0], 1.0 - d[:, 0])
            return -1.3333333 * e ** 3 + e ** 2
        bump = np.exp(-1.0 / (d * (1.0 - d) + 1e-100))
        if p == "exponentialInitialize_1D":
            return bump @ c
        a, b = (1, 2) if c[0] == 0 else ((0, 2) if c[1] == 0 else (1, 0))
        return c[a] * bump[:, a] * c[b] * bump[:, b]


class InteriorSource:
    """One <interiorSources><geom_object>: the source is set to <scalar>, f + src at most <maxScalar>."""

    def __init__(self, node, geo):
        self.piece = geo.read_object(node)
        self.value = node.get("scalar", "float")
        self.clamp = node.get("maxScalar", "float", np.finfo(np.float64).max)


class PassiveScalar:
    """One <Model type="PassiveScalar">: its scalar's labels, constants and regions."""

    def __init__(self, node, ice, geo):
        self.ice = ice
        ps = node.child("PassiveScalar", required=True)
        solids = [m.name for m in getattr(ice, "_mpm_materials", ())]      # MPMICE: the global index space
        self.matl = _material(ps, "material", solids + ice.material_names())
        scalars = ps.children("scalar")
        if len(scalars) != 1:
            raise ps.error(f"{len(scalars)} <scalar> blocks; accepted: one per PassiveScalar model (as Uintah)")
        sc = scalars[0]
        name = sc.attr("name")
        if not name:
            raise sc.error('the scalar needs a name: <scalar name="f">')
        self.name = f"scalar-{name}"
        self.f = L.create(self.name, CC)
        self.src = L.create(self.name + "_src", CC)
        self.f_L = L.create(self.name + "_L", CC)          # Lagrangian m f (ICE's transported variable)
        self.total = L.create("totalSum_" + self.name, R, reduction="sum")
        self.conservation = sc.get("test_conservation", "bool", False)
        if sc.get("reinitializeDomain", "bool", False):
            raise sc.child("reinitializeDomain").error("<reinitializeDomain> (restarts) is not available; "
                                                       "accepted: false")
        const = sc.child("constants", required=True).read(CONSTANTS)
        self.diffusivity = const["diffusivity"]
        self.rate0, self.rate1 = const["rateOfChange0"], const["rateOfChange1"]
        self.decay = None
        ed = sc.child("exponentialDecay")
        if ed is not None:
            c2 = ed.child("c2", required=True)
            c1, c3 = ed.get("c1", "float"), ed.get("c3", "float", 0.0)
            if c2.attr("type", default="constant", choices=("constant", "variable")) == "variable":
                self.c2 = _read_c2_table(c2.child("filename", required=True), geo.level)    # per interior cell
            else:
                self.c2 = c2.get("value", "float")
            self.decay = c1 * self.c2 + c3
            self.decay_coef = L.create(self.name + "_expDecayCoef", CC)
        init = sc.child("initialization", required=True)
        self.regions = [Region(go, geo) for go in init.children("geom_object")]
        if not self.regions:
            raise init.error(f"{self.name} has no initial value region (<geom_object>)")
        srcs = sc.child("interiorSources")
        self.sources = [InteriorSource(go, geo) for go in srcs.children("geom_object")] if srcs is not None else []
        self._masks = {}

    # -- scheduling (the ICE component calls these) ----------------------------------------------
    def schedule_initialize(self, sched):
        sched.add_task(Task(f"PassiveScalar::initialize_({self.name})", self.initialize, [self.matl])
                       .computes(self.f))
        self.schedule_decay_coef(sched)

    def schedule_decay_coef(self, sched):
        """scalar-f_expDecayCoef, the exponential decay's c2 per cell: a task the graph keeps only
        where a deck saves it (Uintah carries it from step to step; it never changes)."""
        if self.decay is not None:
            sched.add_task(Task(f"PassiveScalar::expDecayCoef_({self.name})", self.decay_coef_task, [self.matl])
                           .computes(self.decay_coef))

    def schedule_sources(self, sched):
        self.schedule_decay_coef(sched)
        t = Task(f"PassiveScalar::computeModelSources_({self.name})", self.sources_task, [self.matl]) \
            .requires(OLD, L.delT).computes(self.src)
        if self.diffusivity != 0.0:
            t.requires(OLD, self.f, Ghost.AROUND_CELLS, 1)
        else:
            t.requires(OLD, self.f)
        sched.add_task(t)

    def schedule_conservation(self, sched, dirs):
        if not self.conservation:
            return
        t = Task(f"PassiveScalar::testConservation_({self.name})", self.conservation_task, [self.matl]) \
            .requires(OLD, L.delT).requires(NEW, self.f).requires(NEW, I.rho_CC).computes(self.total)
        for d in dirs:
            t.requires(NEW, I.FC_VEL_ME[d])
        sched.add_task(t)

    # -- tasks -----------------------------------------------------------------------------------
    def initialize(self, patch, matls, old_dw, new_dw):
        """The regions in order over the patch's cells, extra cells included (cell centres), then
        the boundary conditions."""
        b = self.ice.boxes(patch)
        f = new_dw.allocate(self.f, self.matl, patch)
        own = patch.owned(VarType.CC)
        sl = patch.slices(VarType.CC, own)
        x = _centres(patch.level, own)
        shape = f[sl].shape
        out = np.zeros(x.shape[0])
        for region in self.regions:
            hit = region.piece.inside(x)
            out[hit] = region.values(x[hit])
        f[sl] = out.reshape(shape)
        self.ice.bcs.scalar(patch, f, self.name, self.matl, b)

    def sources_task(self, patch, matls, old_dw, new_dw):
        """scalar-f_src of the interior cells (module docstring)."""
        b = self.ice.boxes(patch)
        dt = old_dw.get_reduction(L.delT)
        f_old = old_dw.get(self.f, self.matl, patch)
        src = new_dw.allocate(self.src, self.matl, patch)
        if self.diffusivity != 0.0:
            K.scalar_diffusion_source(f_old, self.diffusivity, src, self.ice.dims, b.lo, b.hi, patch.level.dx, dt)
        sl = tuple(slice(l, h) for l, h in zip(b.lo, b.hi))
        fi, si = f_old[sl], src[sl]
        if self.rate0 != 0.0 or self.rate1 != 0.0:
            si -= dt * (self.rate0 + self.rate1 * fi)
        if self.decay is not None:
            si += fi * np.exp(-self._decay_rate(patch, b) * dt) - fi
        for n, region in enumerate(self.sources):
            inside = self._mask(patch, n, region, b)
            si[inside] = region.value
            over = inside & (fi + si > region.clamp)
            si[over] = region.clamp - fi[over]
        negative = fi + si < 0.0
        si[negative] = -fi[negative]

    def decay_coef_task(self, patch, matls, old_dw, new_dw):
        """c2 in every cell (a constant), or the table's value in the interior cells and 0 in the
        extra cells (Uintah's PassiveScalar::initialize and readTable)."""
        out = new_dw.allocate(self.decay_coef, self.matl, patch)
        if np.ndim(self.c2) == 0:
            out[...] = self.c2
            return
        out[...] = 0.0
        b = self.ice.boxes(patch)
        lo = np.array(patch.low_index(VarType.CC)) + b.lo
        hi = np.array(patch.low_index(VarType.CC)) + b.hi
        out[tuple(slice(l, h) for l, h in zip(b.lo, b.hi))] = self.c2[tuple(slice(l, h) for l, h in zip(lo, hi))]

    def conservation_task(self, patch, matls, old_dw, new_dw):
        """totalSum_scalar-f: sum m f over the interior plus delT times its upper-face fluxes."""
        b = self.ice.boxes(patch)
        dt = float(old_dw.get_reduction(L.delT))
        rho, f = new_dw.get(I.rho_CC, self.matl, patch), new_dw.get(self.f, self.matl, patch)
        total = K.scalar_mass_sum(rho, f, b.vol, b.lo, b.hi)
        for d in range(3):
            if self.ice.dims[d] and "xyz"[d] + "+" in patch.boundary_faces:
                total -= dt * K.scalar_upper_face_flux(rho, f, b.vol, new_dw.get(I.FC_VEL_ME[d], self.matl, patch),
                                                       d, b.lo, b.hi, b.sh[d])
        new_dw.put_reduction(self.total, total)

    def _decay_rate(self, patch, b):
        """c1 c2 + c3: the number, or the table's values over the patch's interior cells."""
        if np.ndim(self.decay) == 0:
            return self.decay
        lo = np.array(patch.low_index(VarType.CC)) + b.lo
        hi = np.array(patch.low_index(VarType.CC)) + b.hi
        return self.decay[tuple(slice(l, h) for l, h in zip(lo, hi))]

    def _mask(self, patch, n, region, b):
        """Whether each interior cell's centre lies in interior source n (cached per patch)."""
        key = (patch.id, n)
        if key not in self._masks:
            lo = np.array(patch.low_index(VarType.CC)) + b.lo
            hi = np.array(patch.low_index(VarType.CC)) + b.hi
            box = (tuple(lo), tuple(hi))
            self._masks[key] = region.piece.inside(_centres(patch.level, box)).reshape(tuple(hi - lo))
        return self._masks[key]


def _centres(level, box):
    """Cell-centre coordinates (n, 3) of a global index box, x slowest (C order)."""
    xs = level.cell_centers(box)
    X, Y, Z = np.meshgrid(*xs, indexing="ij")
    return np.stack([X.ravel(), Y.ravel(), Z.ravel()], axis=1)


def _read_c2_table(node, level):
    """Uintah's c2 table (PassiveScalar::readTable): lines x,y,z,c2 after '#' header lines, one
    per interior cell of the level (the cell holding the point), as an array over those cells.
    The file is looked for as named, then next to the deck."""
    import os
    name = node.value("str").strip()
    cands = [name] if os.path.isabs(name) else [name, os.path.join(os.path.dirname(os.path.abspath(node.filename)), name)]
    path = next((c for c in cands if os.path.isfile(c)), None)
    if path is None:
        raise node.error(f"no file {name} (looked in " + " and ".join(os.path.dirname(os.path.abspath(c)) for c in cands)
                         + "); accepted: a csv table x,y,z,c2")
    try:
        table = np.atleast_2d(np.loadtxt(path, delimiter=",", comments="#", dtype=np.float64))
    except ValueError as e:
        raise node.error(f"{name}: not a csv table x,y,z,c2 ({e})") from None
    if table.shape[1] != 4:
        raise node.error(f"{name}: {table.shape[1]} columns; accepted: x,y,z,c2")
    cells = level.cells_of(table[:, :3])
    n = np.asarray(level.ncells)
    outside = np.any((cells < 0) | (cells >= n), axis=1)
    if outside.any():
        raise node.error(f"{name}: the point {tuple(table[np.argmax(outside), :3])} is not in an interior cell "
                         "of the level")
    flat = np.ravel_multi_index(tuple(cells.T), tuple(n))
    if len(flat) != n.prod() or len(np.unique(flat)) != n.prod():
        raise node.error(f"{name}: {len(np.unique(flat))} of the level's {n.prod()} cells given ({len(flat)} lines); "
                         "accepted: every interior cell once")
    c2 = np.empty(n.prod())
    c2[flat] = table[:, 3]
    return c2.reshape(tuple(n))
