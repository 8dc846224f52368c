"""A tiny component that proves the framework on physics with exact solutions.

`<SimulationComponent type="examples">` with an `<Examples>` block holding any of:
  <diffusion>  explicit heat diffusion of a Gaussian on CC variables (temp_CC); the
               exact solution is a spreading Gaussian.
  <particles>  particles carried by a given velocity field (uniform plus solid-body
               rotation) across patch boundaries and relocated; their mass is also
               interpolated to the nodes (g.mass) with ghost particles.
  <diffusion><implicit>true</implicit> takes backward-Euler steps solved by a
               Jacobi-preconditioned conjugate gradient that runs as an iterated
               sub-graph (framework.scheduler.loop), across patches and ranks.
Only the blocks present are scheduled.
"""
from __future__ import annotations

import numpy as np

from framework import labels as L
from framework.component import Component, register
from framework.problemspec import Param
from framework.scheduler.loop import Loop
from framework.task import NEW, OLD, PARENT_OLD, Task
from framework.variables import Ghost, VarType

from . import kernels

temp_CC = L.create("temp_CC", VarType.CC)
TotalHeat = L.create("TotalHeat", VarType.REDUCTION, reduction="sum")
pX = L.create("p.x", VarType.PARTICLE, (3,))
pMass = L.create("p.mass", VarType.PARTICLE)
pID = L.create("p.particleID", VarType.PARTICLE, dtype=np.int64)
pXpre = L.create("p.x+", VarType.PARTICLE, (3,))
pMassPre = L.create("p.mass+", VarType.PARTICLE)
pIDpre = L.create("p.particleID+", VarType.PARTICLE, dtype=np.int64)
gMass = L.create("g.mass", VarType.NC)
TotalMass = L.create("TotalMass", VarType.REDUCTION, reduction="sum")

DIFFUSION = {
    "alpha": Param("float", doc="thermal diffusivity (m^2/s)", above=0.0),
    "cfl": Param("float", 0.4, doc="fraction of the explicit stability limit (may exceed 1 if implicit)",
                 above=0.0),
    "implicit": Param("bool", False, doc="backward Euler solved by preconditioned CG"),
    "tolerance": Param("float", 1e-10, doc="CG stops when |r| <= tolerance |r0|", above=0.0),
    "max_iterations": Param("int", 500, at_least=1),
}

# implicit solve: timestep-level seeds and the CG iteration's own variables
cg_x0 = L.create("implicit.x0", VarType.CC)
cg_r0 = L.create("implicit.r0", VarType.CC)
cg_p0 = L.create("implicit.p0", VarType.CC)
cg_rz0 = L.create("implicit.rz0", VarType.REDUCTION, reduction="sum")
cg_rr0 = L.create("implicit.rr0", VarType.REDUCTION, reduction="sum")
cg_X = L.create("cg.x", VarType.CC)
cg_R = L.create("cg.r", VarType.CC)
cg_Z = L.create("cg.z", VarType.CC)
cg_P = L.create("cg.p", VarType.CC)
cg_Q = L.create("cg.q", VarType.CC)
cg_RZ = L.create("cg.rz", VarType.REDUCTION, reduction="sum")
cg_RR = L.create("cg.rr", VarType.REDUCTION, reduction="sum")
cg_PQ = L.create("cg.pq", VarType.REDUCTION, reduction="sum")
GAUSSIAN = {
    "center": Param("vector"),
    "width": Param("float", doc="standard deviation sigma0", above=0.0),
    "amplitude": Param("float", 1.0),
    "background": Param("float", 0.0),
}
PARTICLES = {
    "velocity": Param("vector", (0.0, 0.0, 0.0), doc="uniform part of the velocity"),
    "omega": Param("float", 0.0, doc="rotation rate about the z axis through <center>"),
    "center": Param("vector", (0.0, 0.0, 0.0)),
    "cfl": Param("float", 0.5, doc="largest fraction of a cell a particle moves per step", above=0.0),
    "lower": Param("vector", doc="box filled with particles"),
    "upper": Param("vector"),
    "res": Param("ivector", (2, 2, 2), doc="particles per cell per direction", at_least=1),
    "density": Param("float", 1.0, above=0.0),
}


def gaussian(x, y, z, g, alpha, t, dims):
    """Exact solution of T_t = alpha lap T from a Gaussian of width sigma0 (d = dims)."""
    s2 = g["width"] ** 2 + 2.0 * alpha * t
    c = g["center"]
    r2 = np.zeros(np.broadcast_shapes(x.shape, y.shape, z.shape))
    for d, arr in enumerate((x, y, z)):
        if dims[d]:
            r2 = r2 + (arr - c[d]) ** 2
    n = sum(dims)
    return g["background"] + g["amplitude"] * (g["width"] ** 2 / s2) ** (n / 2) * np.exp(-r2 / (2 * s2))


@register("examples", "heat", "advect_particles")
class Examples(Component):
    """Heat diffusion and particle advection: small physics, exact answers."""

    def problem_setup(self, root, level):
        ex = root.child("Examples", required=True)
        self.level = level
        self.dims = tuple(not c for c in level.collapsed)
        self.diffusion = self.gauss = self.particles = None
        dn = ex.child("diffusion")
        if dn is not None:
            self.diffusion = dn.read(DIFFUSION)
            self.gauss = dn.child("gaussian", required=True).read(GAUSSIAN)
            if self.diffusion["alpha"] < 0:
                raise dn.child("alpha").error("alpha must be >= 0")
        pn = ex.child("particles")
        if pn is not None:
            self.particles = pn.read(PARTICLES)
        if self.diffusion is None and self.particles is None:
            raise ex.error("nothing to simulate: give <diffusion> and/or <particles>")
        self.materials = ["example"]

    # -- scheduling -------------------------------------------------------------------
    def schedule_initialize(self, level, sched):
        if self.diffusion:
            sched.add_task(Task("initializeTemperature", self.initialize_temperature, [0])
                           .computes(temp_CC))
        if self.particles:
            sched.add_task(Task("createParticles", self.create_particles, [0])
                           .computes(pX).computes(pMass).computes(pID))
            sched.register_particle_labels(pX, pID)

    def schedule_compute_stable_timestep(self, level, sched):
        t = Task("computeStableTimestep", self.compute_stable_timestep, [0]).computes(L.delT)
        sched.add_task(t)

    def schedule_time_advance(self, level, sched):
        if self.diffusion and self.diffusion["implicit"]:
            self.schedule_implicit_diffusion(sched)
        elif self.diffusion:
            sched.add_task(Task("diffuseHeat", self.diffuse_heat, [0])
                           .requires(OLD, temp_CC, Ghost.AROUND_CELLS, 1)
                           .requires(OLD, L.delT)
                           .computes(temp_CC))
        if self.diffusion:
            sched.add_task(Task("sumHeat", self.sum_heat, [0])
                           .requires(NEW, temp_CC).computes(TotalHeat))
        if self.particles:
            sched.add_task(Task("advectParticles", self.advect_particles, [0])
                           .requires(OLD, pX).requires(OLD, pMass).requires(OLD, pID).requires(OLD, L.delT)
                           .computes(pXpre).computes(pMassPre).computes(pIDpre))
            sched.add_task(Task("interpolateParticlesToGrid", self.interpolate_to_grid, [0])
                           .requires(OLD, pX, Ghost.AROUND_NODES, 1)
                           .requires(OLD, pMass, Ghost.AROUND_NODES, 1)
                           .computes(gMass))
            sched.add_task(Task("sumGridMass", self.sum_grid_mass, [0])
                           .requires(NEW, gMass).computes(TotalMass))
            sched.schedule_particle_relocation(pXpre, [pMassPre, pIDpre], pX, [pMass, pID], [0], id_label=pID)

    def schedule_implicit_diffusion(self, sched):
        """(I - dt alpha lap) T = T_old by CG: seed, iterate as a sub-graph, set boundaries."""
        sched.add_task(Task("implicitHeatSetup", self.cg_setup, [0])
                       .requires(OLD, temp_CC, Ghost.AROUND_CELLS, 1).requires(OLD, L.delT)
                       .computes(cg_x0).computes(cg_r0).computes(cg_p0).computes(cg_rz0).computes(cg_rr0))
        body = [
            Task("cgApplyOperator", self.cg_apply, [0])
            .requires(OLD, cg_P, Ghost.AROUND_CELLS, 1).requires(PARENT_OLD, L.delT)
            .computes(cg_Q).computes(cg_PQ),
            Task("cgUpdateSolution", self.cg_update, [0])
            .requires(OLD, cg_X).requires(OLD, cg_R).requires(OLD, cg_P).requires(OLD, cg_RZ)
            .requires(NEW, cg_Q).requires(NEW, cg_PQ).requires(PARENT_OLD, L.delT)
            .computes(cg_X).computes(cg_R).computes(cg_Z).computes(cg_RZ).computes(cg_RR),
            Task("cgUpdateDirection", self.cg_direction, [0])
            .requires(OLD, cg_P).requires(OLD, cg_RZ).requires(NEW, cg_Z).requires(NEW, cg_RZ)
            .computes(cg_P),
        ]
        tol = self.diffusion["tolerance"]

        def converged(dw, k, parent_new):
            return dw.get_reduction(cg_RR) <= tol * tol * parent_new.get_reduction(cg_rr0)

        self.solve = Loop("implicitHeatSolve", [0], body, init={cg_X.name: cg_x0, cg_R.name: cg_r0,
                                                                 cg_P.name: cg_p0, cg_RZ.name: cg_rz0},
                          results={cg_X.name: temp_CC}, converged=converged,
                          max_iterations=self.diffusion["max_iterations"])
        sched.add_task(self.solve)
        sched.add_task(Task("implicitHeatBoundary", self.heat_boundary, [0]).modifies(temp_CC))

    def _coef(self, dt):
        a = self.diffusion["alpha"]
        return np.array([a * dt / self.level.dx[d] ** 2 if self.dims[d] else 0.0 for d in range(3)])

    def _neumann(self, patch, a):
        lo, hi = (np.array(x) for x in patch.interior())
        for d in range(3):
            if patch.at_low[d]:
                kernels.neumann_face(a, lo, hi, d, 0)
            if patch.at_high[d]:
                kernels.neumann_face(a, lo, hi, d, 1)

    def cg_setup(self, patch, matls, old_dw, new_dw):
        c = self._coef(old_dw.get_reduction(L.delT))
        T = old_dw.get(temp_CC, 0, patch)
        lo, hi = (np.array(x) for x in patch.interior())
        x = new_dw.allocate(cg_x0, 0, patch)
        x[...] = T
        q = np.zeros_like(T)
        kernels.helmholtz(T, q, lo, hi, c)
        r = new_dw.allocate(cg_r0, 0, patch)
        r[...] = 0.0
        sl = tuple(slice(a, b) for a, b in zip(lo, hi))
        r[sl] = T[sl] - q[sl]
        p = new_dw.allocate(cg_p0, 0, patch)
        p[...] = r / (1.0 + 2.0 * c.sum())
        self._neumann(patch, p)
        new_dw.put_reduction(cg_rz0, float((r[sl] * p[sl]).sum()))
        new_dw.put_reduction(cg_rr0, float((r[sl] ** 2).sum()))

    def cg_apply(self, patch, matls, old_dw, new_dw, parent_old, parent_new):
        c = self._coef(parent_old.get_reduction(L.delT))
        p = old_dw.get(cg_P, 0, patch)
        q = new_dw.allocate(cg_Q, 0, patch)
        lo, hi = (np.array(x) for x in patch.interior())
        new_dw.put_reduction(cg_PQ, kernels.helmholtz(p, q, lo, hi, c))

    def cg_update(self, patch, matls, old_dw, new_dw, parent_old, parent_new):
        c = self._coef(parent_old.get_reduction(L.delT))
        alpha = old_dw.get_reduction(cg_RZ) / new_dw.get_reduction(cg_PQ)
        lo, hi = (np.array(x) for x in patch.interior())
        xn = new_dw.allocate(cg_X, 0, patch)
        rn = new_dw.allocate(cg_R, 0, patch)
        zn = new_dw.allocate(cg_Z, 0, patch)
        rz, rr = kernels.cg_update(old_dw.get(cg_X, 0, patch), old_dw.get(cg_R, 0, patch),
                                   old_dw.get(cg_P, 0, patch), new_dw.get(cg_Q, 0, patch), xn, rn, zn,
                                   alpha, 1.0 + 2.0 * c.sum(), lo, hi)
        new_dw.put_reduction(cg_RZ, rz)
        new_dw.put_reduction(cg_RR, rr)

    def cg_direction(self, patch, matls, old_dw, new_dw, parent_old, parent_new):
        beta = new_dw.get_reduction(cg_RZ) / old_dw.get_reduction(cg_RZ)
        lo, hi = (np.array(x) for x in patch.interior())
        pn = new_dw.allocate(cg_P, 0, patch)
        kernels.cg_direction(new_dw.get(cg_Z, 0, patch), old_dw.get(cg_P, 0, patch), pn, beta, lo, hi)
        self._neumann(patch, pn)

    def heat_boundary(self, patch, matls, old_dw, new_dw):
        self._neumann(patch, new_dw.get_modifiable(temp_CC, 0, patch))

    # -- tasks --------------------------------------------------------------------------
    def initialize_temperature(self, patch, matls, old_dw, new_dw):
        T = new_dw.allocate(temp_CC, 0, patch)
        x, y, z = patch.cell_centers()
        T[...] = gaussian(x[:, None, None], y[None, :, None], z[None, None, :], self.gauss, 0.0, 0.0, self.dims)

    def compute_stable_timestep(self, patch, matls, old_dw, new_dw):
        dx = self.level.dx
        dt = np.inf
        if self.diffusion and self.diffusion["alpha"] > 0:
            inv = sum(1.0 / dx[d] ** 2 for d in range(3) if self.dims[d])
            dt = min(dt, self.diffusion["cfl"] / (2.0 * self.diffusion["alpha"] * inv))
        if self.particles:
            p = self.particles
            r = np.abs(np.array(self.level.upper) - np.array(p["center"])).max() + \
                np.abs(np.array(self.level.anchor) - np.array(p["center"])).max()
            vmax = np.abs(p["velocity"]).max() + abs(p["omega"]) * r
            if vmax > 0:
                dt = min(dt, p["cfl"] * dx[np.array(self.dims)].min() / vmax)
        new_dw.put_reduction(L.delT, dt if np.isfinite(dt) else 1.0)

    def diffuse_heat(self, patch, matls, old_dw, new_dw):
        dt = old_dw.get_reduction(L.delT)
        T = old_dw.get(temp_CC, 0, patch)
        Tn = new_dw.allocate(temp_CC, 0, patch)
        a = self.diffusion["alpha"]
        c = np.array([a * dt / self.level.dx[d] ** 2 if self.dims[d] else 0.0 for d in range(3)])
        lo, hi = patch.interior()
        kernels.diffuse(T, Tn, np.array(lo), np.array(hi), c)
        for d in range(3):
            if patch.at_low[d]:
                kernels.neumann_face(Tn, np.array(lo), np.array(hi), d, 0)
            if patch.at_high[d]:
                kernels.neumann_face(Tn, np.array(lo), np.array(hi), d, 1)

    def sum_heat(self, patch, matls, old_dw, new_dw):
        T = new_dw.get(temp_CC, 0, patch)
        lo, hi = patch.interior()
        vol = float(np.prod(self.level.dx))
        new_dw.put_reduction(TotalHeat, T[lo[0]:hi[0], lo[1]:hi[1], lo[2]:hi[2]].sum() * vol)

    def create_particles(self, patch, matls, old_dw, new_dw):
        p = self.particles
        lv = self.level
        res = [r if self.dims[d] else 1 for d, r in enumerate(p["res"])]
        x, y, z = patch.level.cell_centers((patch.lo, patch.hi))
        offs = [(np.arange(res[d]) + 0.5) / res[d] - 0.5 for d in range(3)]
        pts = []
        for d, cc in enumerate((x, y, z)):
            pts.append((cc[:, None] + offs[d][None, :] * lv.dx[d]).ravel())
        X, Y, Z = np.meshgrid(*pts, indexing="ij")
        px = np.stack([X.ravel(), Y.ravel(), Z.ravel()], axis=1)
        inside = np.all((px >= np.array(p["lower"])) & (px <= np.array(p["upper"])), axis=1)
        # IDs from the global sub-cell index: independent of the patch layout
        sub = [np.floor((px[:, d] - lv.anchor[d]) / lv.dx[d] * res[d]).astype(np.int64) for d in range(3)]
        n_sub = [lv.ncells[d] * res[d] for d in range(3)]
        ids = sub[0] + n_sub[0] * (sub[1] + n_sub[1] * sub[2])
        px, ids = px[inside], ids[inside]
        order = np.argsort(ids)
        new_dw.create_particles(0, patch, len(ids))
        new_dw.put(pX, 0, patch, px[order])
        new_dw.put(pID, 0, patch, ids[order])
        vol = float(np.prod([lv.dx[d] / res[d] for d in range(3)]))
        new_dw.put(pMass, 0, patch, np.full(len(ids), p["density"] * vol))

    def advect_particles(self, patch, matls, old_dw, new_dw):
        p = self.particles
        dt = old_dw.get_reduction(L.delT)
        px = old_dw.get(pX, 0, patch)
        pxn = np.empty_like(px)
        kernels.advect(px, pxn, dt, np.array(p["velocity"]), p["omega"], np.array(p["center"]))
        new_dw.put(pXpre, 0, patch, pxn)
        new_dw.put(pMassPre, 0, patch, old_dw.get(pMass, 0, patch))
        new_dw.put(pIDpre, 0, patch, old_dw.get(pID, 0, patch))

    def interpolate_to_grid(self, patch, matls, old_dw, new_dw):
        px = old_dw.get(pX, 0, patch)
        pm = old_dw.get(pMass, 0, patch)
        gm = new_dw.allocate(gMass, 0, patch)
        lo, hi = patch.owned_local(VarType.NC)
        kernels.mass_to_nodes(px, pm, gm, self.level.anchor, self.level.dx, np.array(patch.low_index(VarType.NC)),
                              np.array(lo), np.array(hi), np.array(self.dims))

    def sum_grid_mass(self, patch, matls, old_dw, new_dw):
        gm = new_dw.get(gMass, 0, patch)
        lo, hi = patch.owned_local(VarType.NC)
        new_dw.put_reduction(TotalMass, gm[lo[0]:hi[0], lo[1]:hi[1], lo[2]:hi[2]].sum())
