"""Uintah's TracerParticles model for ICE: massless particles carried by one material's flow.

    <Models><Model type="TracerParticles"><TracerParticles>
      <material> name </material>
      <timeStart> s </timeStart> <timeStop> s </timeStop>          (default: always)
      <cloneVariables> <CCVarLabel label="press_CC"/> ... </cloneVariables>
      <scalar name="p.age">                                      (optional, any number)
        <initialValue> 1 </initialValue>
        <exponentialDecay> <c1/> <c2 type="constant"><value/></c2> <c3/> </exponentialDecay>   (optional;
                           or <c2 type="variable"><filename> x,y,z,c2 table </filename></c2>)
      </scalar>
      <tracer name="f">
        <initialization>
          <geom_object> pieces <particlesPerCell> n </particlesPerCell> </geom_object> ...
        </initialization>
        <interiorSources>
          <geom_object> pieces <particlesPerCellPerSecond> n </particlesPerCellPerSecond> </geom_object> ...
        </interiorSources>
      </tracer>
    </TracerParticles></Model></Models>

Particles: p.x, p.displacement, p.velocity, p.particleID and p.clone-<label> for each cloned
cell variable, relocated between patches by the framework (their material's particle set), so
<save label="p.x"/> etc. write them as particle variables. At t = 0 every interior cell whose
centre lies in an initialization piece gets particlesPerCell particles at random points of the
cell; the generator is the 32-bit Mersenne Twister seeded with i + j + k of the cell (Uintah's
MTRand), so the points are Uintah's. A particle's ID is Uintah's: the cell index packed as
i << 16 | j << 32 | k << 48, or'ed with the count of particles made in that cell so far (the
cell variable nPPC).
Each step (Uintah's computeModelSources, reading only the state at the start of the step):
p.clone-<label> takes the cell value of <label> where the particle is; the particle moves with
that cell's vel_CC, x+ = x + u dt (first order, no interpolation: Uintah's); one that leaves the
domain is deleted. An interior source adds floor(particlesPerCellPerSecond * elapsed)
particles to each of its cells once that number is at least one, elapsed being the time since
it last added some (a reduction carried in the warehouse, so a restart continues it); the new
particles start with zero displacement and velocity and the cell values of the clones.
A <scalar name="s"> is a particle variable s that starts at <initialValue> (on every new
particle too) and, with <exponentialDecay>, decays each step as s *= exp(-(c1 c2 + c3) dt) while
s_totalDecay accumulates c2 dt (Uintah's); c2 read from a table (<c2 type="variable"><filename>,
PassiveScalar's x,y,z,c2 table) is the value of the particle's cell, and s_expDecayCoef is c2
per cell (for output). Under MPMICE the tracers ride on an ICE material and relocate in the same
relocation task as the MPM particles (each set over its own materials).
"""
from __future__ import annotations

import numpy as np

from components.ice import labels as I
from framework import labels as L
from framework.task import OLD, Task
from framework.variables import VarType

from . import kernels as K
from .passive_scalar import _read_c2_table
from .simple_burn import _material

CC, P, R = VarType.CC, VarType.PARTICLE, VarType.REDUCTION


def _pair(name, shape=(), dtype=np.float64):
    """A particle label and its pre-relocation twin (name+)."""
    return L.create(name, P, shape, dtype), L.create(name + "+", P, shape, dtype)


pX, pXpre = _pair("p.x", (3,))
pDisp, pDispPre = _pair("p.displacement", (3,))
pVelocity, pVelocityPre = _pair("p.velocity", (3,))
pID, pIDPre = _pair("p.particleID", dtype=np.int64)
nPPC = L.create("nPPC", CC, dtype=np.int64)         # particles made in each cell so far (their IDs)


class Region:
    """One <geom_object> of <initialization> (particlesPerCell) or <interiorSources>
    (particlesPerCellPerSecond)."""

    def __init__(self, node, geo, tag):
        self.piece = geo.read_object(node)
        self.rate = node.get(tag, "int", at_least=0)
        lo, hi = self.piece.bounds()
        self.box = (np.asarray(lo, float), np.asarray(hi, float))


class Scalar:
    """One <scalar name="s">: its particle labels (s, and s_totalDecay with a decay), initial value
    and decay rate c1 c2 + c3."""

    def __init__(self, node, level):
        name = node.attr("name")
        if not name:
            raise node.error('the scalar needs a name: <scalar name="p.age">')
        self.label, self.pre = _pair(name)
        self.initial = node.get("initialValue", "float")
        self.decay = None
        ed = node.child("exponentialDecay")
        if ed is not None:
            c2 = ed.child("c2", required=True)
            self.c1, self.c3 = ed.get("c1", "float"), ed.get("c3", "float", 0.0)
            if c2.attr("type", default="constant", choices=("constant", "variable")) == "variable":
                self.c2 = _read_c2_table(c2.child("filename", required=True), level)   # per interior cell
            else:
                self.c2 = c2.get("value", "float")
            self.decay = self.c1 * self.c2 + self.c3
            self.total, self.total_pre = _pair(name + "_totalDecay")
            self.coef = L.create(name + "_expDecayCoef", CC)      # c2 per cell (Uintah's, for output)

    def pairs(self):
        """(final, pre-relocation, value of a new particle) of each of its particle variables."""
        out = [(self.label, self.pre, self.initial)]
        if self.decay is not None:
            out.append((self.total, self.total_pre, 0.0))
        return out


class TracerParticles:
    """One <Model type="TracerParticles">: its material, regions and cloned variables."""

    def __init__(self, node, ice, geo, t0=0.0):
        self.ice = ice
        self.t0 = t0            # the initial time (<Time><initTime>)
        tp = node.child("TracerParticles", required=True)
        solids = [m.name for m in getattr(ice, "_mpm_materials", ())]      # MPMICE: the global index space
        self.matl = _material(tp, "material", solids + ice.material_names())
        self.start = tp.get("timeStart", "float", 0.0)
        self.stop = tp.get("timeStop", "float", 9e99)
        if tp.get("reinitializeDomain", "bool", False):
            raise tp.child("reinitializeDomain").error("<reinitializeDomain> (restarts) is not available; "
                                                       "accepted: false")
        self.scalars = [Scalar(sn, geo.level) for sn in tp.children("scalar")]
        tracers = tp.children("tracer")
        if len(tracers) != 1:
            raise tp.error(f"{len(tracers)} <tracer> blocks; accepted: one per TracerParticles model (as Uintah)")
        tr = tracers[0]
        name = tr.attr("name")
        if not name:
            raise tr.error('the tracer needs a name: <tracer name="f">')
        self.name = f"tracer-{name}"
        init = tr.child("initialization", required=True)
        self.init_regions = [Region(go, geo, "particlesPerCell") for go in init.children("geom_object")]
        if not self.init_regions:
            raise init.error(f"{self.name} has no initialization region (<geom_object>)")
        srcs = tr.child("interiorSources")
        self.sources = [Region(go, geo, "particlesPerCellPerSecond")
                        for go in srcs.children("geom_object")] if srcs is not None else []
        self.elapsed = L.create(f"{self.name}.elapsedTime", R, (max(len(self.sources), 1),), reduction="max")
        cv = tp.child("cloneVariables")
        self._clone_nodes = cv.children("CCVarLabel") if cv is not None else []
        self.clones = []        # [(cell label, its material, particle label, pre-relocation label)]

    def resolve(self):
        """Find the cloned cell variables (after every model has made its labels)."""
        for n in self._clone_nodes:
            name = n.attr("label")
            lab = L.find(name)
            if lab is None or lab.vartype is not CC or lab.shape != () or lab.dtype is not np.float64:
                raise n.error(f'label="{name}" is not a cell-centred scalar variable; accepted: one such as '
                              "press_CC, rho_CC, temp_CC or a passive scalar's scalar-<name>")
            m = 0 if lab.name == I.press_CC.name else self.matl        # press_CC: one field, material 0
            self.clones.append((lab, m) + _pair("p.clone-" + name))

    # -- scheduling (the ICE component calls these) ----------------------------------------------
    def _particle_labels(self):
        return [pX, pDisp, pVelocity, pID] + [c[2] for c in self.clones] + [f for s in self.scalars
                                                                            for f, _, _ in s.pairs()]

    def schedule_initialize(self, sched):
        t = Task(f"TracerParticles::initializeTask_({self.name})", self.initialize, [self.matl]) \
            .computes(nPPC).computes(self.elapsed)
        for lab in self._particle_labels():
            t.computes(lab)
        sched.add_task(t)

    def schedule_sources(self, sched):
        t = Task(f"TracerParticles::moveParticles_({self.name})", self.move_task, [self.matl]) \
            .requires(OLD, L.delT).requires(OLD, L.simTime).requires(OLD, I.vel_CC).requires(OLD, nPPC) \
            .requires(OLD, self.elapsed).computes(nPPC).computes(self.elapsed)
        for lab in (pX, pDisp, pID):
            t.requires(OLD, lab)
        for lab in (pXpre, pDispPre, pVelocityPre, pIDPre):
            t.computes(lab)
        for cc, m, _, pre in self.clones:
            t.requires(OLD, cc, matls=[m]).computes(pre)
        for sc in self.scalars:
            for final, pre, _ in sc.pairs():
                t.requires(OLD, final).computes(pre)
        sched.add_task(t)

    def schedule_diagnostics(self, sched):
        """s_expDecayCoef, c2 per cell, of each decaying scalar (only when saved)."""
        coefs = [sc for sc in self.scalars if sc.decay is not None]
        if coefs:
            t = Task(f"TracerParticles::expDecayCoef_({self.name})", self.decay_coefficients, [self.matl])
            for sc in coefs:
                t.computes(sc.coef)
            sched.add_task(t)

    def schedule_relocation(self, sched):
        pairs = [(f, p) for sc in self.scalars for f, p, _ in sc.pairs()]
        pre = [pDispPre, pVelocityPre, pIDPre] + [c[3] for c in self.clones] + [p for _, p in pairs]
        final = [pDisp, pVelocity, pID] + [c[2] for c in self.clones] + [f for f, _ in pairs]
        sched.schedule_particle_relocation(pXpre, pre, pX, final, [self.matl], id_label=pID)

    # -- tasks -----------------------------------------------------------------------------------
    def initialize(self, patch, matls, old_dw, new_dw):
        """Particles in the initialization regions, clones 0 (Uintah's initializeTask)."""
        m = self.matl
        count = new_dw.allocate(nPPC, m, patch, fill=0)
        now = self.start <= self.t0 <= self.stop
        x, ids = self._lay_down(patch, self.init_regions, [r.rate if now else 0 for r in self.init_regions], count)
        n = len(x)
        new_dw.create_particles(m, patch, n)
        new_dw.put(pX, m, patch, x)
        new_dw.put(pDisp, m, patch, np.zeros((n, 3)))
        new_dw.put(pVelocity, m, patch, np.zeros((n, 3)))
        new_dw.put(pID, m, patch, ids)
        for _, _, lab, _ in self.clones:
            new_dw.put(lab, m, patch, np.zeros(n))
        for sc in self.scalars:
            for final, _, value in sc.pairs():
                new_dw.put(final, m, patch, np.full(n, value))
        new_dw.put_reduction(self.elapsed, np.zeros(self.elapsed.shape))

    def decay_coefficients(self, patch, matls, old_dw, new_dw):
        """c2 in the interior cells (the table's or the constant), 0 in the extra cells."""
        lo, hi = patch.interior(CC)
        inner = tuple(slice(l, h) for l, h in zip(lo, hi))
        g0 = np.array(patch.low_index(CC)) + np.array(lo)
        cells = tuple(slice(a, a + h - l) for a, l, h in zip(g0, lo, hi))
        for sc in self.scalars:
            if sc.decay is not None:
                out = new_dw.allocate(sc.coef, self.matl, patch)
                out[inner] = sc.c2[cells] if np.ndim(sc.c2) else sc.c2

    def move_task(self, patch, matls, old_dw, new_dw):
        """Clone the cell values, move the particles with vel_CC, delete those that left the
        domain, then add the interior sources' particles (Uintah's setParticleVars,
        moveParticles, addParticles)."""
        m = self.matl
        lv = patch.level
        dt = float(old_dw.get_reduction(L.delT))
        t = float(old_dw.get_reduction(L.simTime))
        x_old = old_dw.get(pX, m, patch)
        n = len(x_old)
        x, disp, vel = np.empty((n, 3)), np.empty((n, 3)), np.empty((n, 3))
        cells = np.empty((n, 3), np.int64)
        cc_low = np.array(patch.low_index(CC), np.int64)
        K.move_tracers(x_old, old_dw.get(pDisp, m, patch), old_dw.get(I.vel_CC, m, patch), lv.anchor, lv.dx,
                       cc_low, lv.anchor, lv.anchor + lv.dx * np.array(lv.ncells), dt, x, disp, vel, cells)
        ci = tuple(cells.T)
        clones = [old_dw.get(cc, mc, patch)[ci] for cc, mc, _, _ in self.clones]
        ids = old_dw.get(pID, m, patch)
        scalar_values = []                    # the scalars: s, s_totalDecay carried, decayed
        for sc in self.scalars:
            s = old_dw.get(sc.label, m, patch).copy()
            if sc.decay is None:
                scalar_values.append(s)
                continue
            c2, decay = sc.c2, sc.decay
            if np.ndim(c2):                 # the table's value in each particle's cell
                at = tuple(np.clip(cells + cc_low, 0, np.array(c2.shape) - 1).T)
                c2, decay = c2[at], decay[at]
            scalar_values += [s * np.exp(-decay * dt), old_dw.get(sc.total, m, patch) + c2 * dt]
        count = new_dw.allocate(nPPC, m, patch, fill=None)
        count[...] = old_dw.get(nPPC, m, patch)
        elapsed = np.array(old_dw.get_reduction(self.elapsed), dtype=np.float64).reshape(self.elapsed.shape)
        if self.sources and self.start <= t <= self.stop:
            elapsed[:len(self.sources)] += dt
            per_cell = [int(np.floor(r.rate * e)) for r, e in zip(self.sources, elapsed)]
            for k, p in enumerate(per_cell):
                if p > 0:
                    elapsed[k] = 0.0
            x_add, id_add = self._lay_down(patch, self.sources, per_cell, count)
            if len(x_add):
                new_dw.add_particles(m, patch, len(x_add))
                c_add = tuple((lv.cells_of(x_add) - cc_low).T)
                x, ids = np.concatenate([x, x_add]), np.concatenate([ids, id_add])
                disp = np.concatenate([disp, np.zeros((len(x_add), 3))])
                vel = np.concatenate([vel, np.zeros((len(x_add), 3))])
                clones = [np.concatenate([c, old_dw.get(cc, mc, patch)[c_add]])
                          for c, (cc, mc, _, _) in zip(clones, self.clones)]
                new = [v for sc in self.scalars for _, _, v in sc.pairs()]
                scalar_values = [np.concatenate([a, np.full(len(x_add), v)]) for a, v in zip(scalar_values, new)]
        new_dw.put(pXpre, m, patch, x)
        new_dw.put(pDispPre, m, patch, disp)
        new_dw.put(pVelocityPre, m, patch, vel)
        new_dw.put(pIDPre, m, patch, ids.copy())
        for c, (_, _, _, pre) in zip(clones, self.clones):
            new_dw.put(pre, m, patch, c)
        for a, (_, pre, _) in zip(scalar_values, [q for sc in self.scalars for q in sc.pairs()]):
            new_dw.put(pre, m, patch, a)
        new_dw.put_reduction(self.elapsed, elapsed)

    # -- particle placement ----------------------------------------------------------------------
    def _lay_down(self, patch, regions, per_cell, count):
        """Positions and IDs of per_cell[r] particles in each interior cell of the patch whose
        centre lies in region r, region by region, cells with i fastest (Uintah's
        distributeParticles and initializeCoreVariables); count (nPPC) is advanced."""
        lv = patch.level
        cc_low = np.array(patch.low_index(CC), np.int64)
        own = patch.owned(CC)
        ext_lo, ext_hi = lv.anchor + np.array(own[0]) * lv.dx, lv.anchor + np.array(own[1]) * lv.dx
        xs, ids = [], []
        for region, npc in zip(regions, per_cell):
            blo, bhi = np.maximum(region.box[0], ext_lo), np.minimum(region.box[1], ext_hi)
            if npc <= 0 or np.any(blo >= bhi):
                continue
            cells = _interior_cells(patch)
            cells = cells[region.piece.inside(lv.anchor + lv.dx * cells + lv.dx * 0.5)]    # Uintah's cell centres
            x, i = np.empty((len(cells) * npc, 3)), np.empty(len(cells) * npc, np.int64)
            K.seed_tracers(cells, npc, lv.anchor, lv.dx, cc_low, count, x, i)
            xs.append(x), ids.append(i)
        if not xs:
            return np.zeros((0, 3)), np.zeros(0, np.int64)
        return np.concatenate(xs), np.concatenate(ids)


def _interior_cells(patch):
    """Global indices (n, 3) of the patch's interior cells, i fastest (Uintah's CellIterator)."""
    lo, hi = patch.lo, patch.hi
    k, j, i = np.meshgrid(*(np.arange(lo[d], hi[d]) for d in (2, 1, 0)), indexing="ij")
    return np.stack([i.ravel(), j.ravel(), k.ravel()], axis=1).astype(np.int64)
