"""The EFEM component: multi-material Eulerian finite elements for solid-fluid interaction
(paper 003, Doig, Okazawa and Fujikubo).

`<SimulationComponent type="efem">`. Solids (Hooke) and incompressible fluids (Newtonian
shear) share one fixed mesh of bilinear elements with one Gauss point (2D: x and y, one
cell in z). Each step (the paper's flowchart, sec. 2):
  Lagrangian step  element stresses, mixed by volume fraction (eqs. 18-23); nodal
                   masses, forces, gravity and v* (eq. 14); the pressure Poisson equation
                   over the whole mesh (eq. 16, solved by components.ice.solver's PCG) and
                   the velocity correction (eq. 17);
  Eulerian step    remap to the fixed mesh: volume fractions (van Leer's MUSCL), solid
                   stresses and momentum along mesh lines, x then y (sec. 6).
The pressure equation is a 5-point element Laplacian with the mean density of the two
elements on each face, an approximate projection in place of the Q1-P0 C^T M^-1 C + S of
eq. 20 (no checkerboard mode, no stabilisation S). Deck tags: materials.py; the method
and what differs from the paper: docs/EFEM.md.
"""
from __future__ import annotations

import numpy as np

from components.ice.solver.pcg import PCG
from framework import labels as L
from framework.component import Component, register
from framework.geometry import GeometryReader
from framework.task import NEW, OLD, Task
from framework.variables import Ghost

from . import kernels as K
from . import labels as E
from .materials import SETTINGS, SOLVER, read_boundaries, read_material
from .tasks import EfemTasks

G = Ghost.AROUND_CELLS
GADV = 2           # MUSCL reads two elements upwind of a face


@register("efem")
class EFEM(EfemTasks, Component):
    """Solid and fluid on one Eulerian mesh: Lagrangian step, projection, remap."""

    def problem_setup(self, root, level):
        self.level = level
        grid = root.child("Grid", required=True)
        if level.collapsed[0] or level.collapsed[1] or not level.collapsed[2]:
            raise grid.error(f"EFEM is two-dimensional: the grid needs more than one cell along x and y and "
                             f"one along z; this one has {level.ncells[0]} x {level.ncells[1]} x {level.ncells[2]}")
        if level.extra[0] < 1 or level.extra[1] < 1:
            # the pressure solver's vectors hold zeros in the extra cells behind the domain faces
            raise grid.child("Level").child("Box").error(
                f"EFEM needs one layer of extra cells along x and y; this grid has <extraCells> "
                f"{list(level.extra)}; accepted: [1, 1, 1]")
        if any(level.periodic):
            raise grid.child("Level").child("periodic").error("EFEM has no periodic directions; accepted: [0, 0, 0]")
        efem = root.child("EFEM")
        self.settings = efem.read(SETTINGS) if efem is not None else {k: p.default for k, p in SETTINGS.items()}
        self.limiter = {"vanleer": K.LIMITER_VAN_LEER, "superbee": K.LIMITER_SUPERBEE}[
            self.settings["volume_fraction_limiter"]]
        self.stress_muscl = self.settings["stress_remap"] == "muscl"
        sn = efem.child("pressure_solver") if efem is not None else None
        solver = sn.read(SOLVER) if sn is not None else {k: p.default for k, p in SOLVER.items()}
        pc = root.child("PhysicalConstants")
        g = pc.get("gravity", "vector", (0.0, 0.0, 0.0)) if pc is not None else (0.0, 0.0, 0.0)
        self.gravity = np.array(g, dtype=np.float64)
        # the mesh direction across gravity (the free surface's), -1 without gravity
        self.side = int(np.argmin(np.abs(self.gravity[:2]))) if np.any(self.gravity[:2]) else -1
        mp = root.child("MaterialProperties", required=True)
        en = mp.child("EFEM", required=True)
        geo = GeometryReader(level)
        self.materials = [read_material(m, geo, i) for i, m in enumerate(en.children("material"))]
        if not self.materials:
            raise en.error("no <material>: EFEM needs at least one")
        self.solids = [m for m, mat in enumerate(self.materials) if mat.solid]
        self.solid_of = np.full(len(self.materials), -1, dtype=np.int64)
        for s, m in enumerate(self.solids):
            self.solid_of[m] = s
        self.densities = np.array([m.density for m in self.materials])
        bcs = read_boundaries(efem, self.materials)
        self.walls, self.wall_vel, self.inflow_matl, self.open_faces = bcs.walls, bcs.velocity, bcs.material, bcs.open
        self.wave_speed = max(m.wave_speed() for m in self.materials)
        self.matls = list(range(len(self.materials)))
        self.vol = float(np.prod(level.dx))
        self.dims = np.array([1, 1, 0], dtype=np.int64)
        precond = solver["preconditioner"]
        if precond == "mg" and not PCG.mg_possible(level):
            precond = "jacobi"           # multigrid restricts inside patches: even patch extents only
        self.pcg = PCG("efem.cg", E.press_A, level, self.dims, precond, solver["tolerance"],
                       solver["max_iterations"])
        self._frames = {}

    def material_names(self):
        return [m.name for m in self.materials]

    # -- scheduling -----------------------------------------------------------------------
    def schedule_initialize(self, level, sched):
        t = Task("EFEM::initialize", self.initialize, self.matls) \
            .computes(E.vol_frac_CC).computes(E.mass_CC, matls=[0]).computes(E.mom_CC, matls=[0])
        if self.solids:
            t.computes(E.stress_CC, matls=self.solids).computes(E.hourglass_CC, matls=self.solids)
        sched.add_task(t)
        sched.add_task(Task("EFEM::initializeVelocity", self.initialize_velocity, [0])
                       .requires(NEW, E.mass_CC, G, 1).requires(NEW, E.mom_CC, G, 1).computes(E.gVelocity))

    def schedule_compute_stable_timestep(self, level, sched):
        sched.add_task(Task("EFEM::computeStableTimestep", self.stable_timestep, [0])
                       .requires(NEW, E.gVelocity).computes(L.delT))

    def schedule_time_advance(self, level, sched):
        m0, solids = [0], self.solids
        # Lagrangian step
        # the slide condition's interface normal: the gradient of the solid's volume fraction
        g = (G, 1) if self.settings["slide_condition"] and solids else ()
        t = Task("EFEM::computeStressTensor", self.compute_stress, self.matls) \
            .requires(OLD, L.delT).requires(OLD, E.gVelocity, G, 1, matls=m0).requires(OLD, E.vol_frac_CC, *g) \
            .computes(E.sigma_CC, matls=m0).computes(E.rho_CC, matls=m0).computes(E.fill_CC, matls=m0) \
            .computes(E.hgForce_CC, matls=m0).computes(E.excess_CC, matls=m0) \
            .computes(E.fluid_CC, matls=m0)
        if solids:
            t.requires(OLD, E.stress_CC, matls=solids).computes(E.stress_L_CC, matls=solids) \
                .requires(OLD, E.hourglass_CC, matls=solids).computes(E.hourglass_L_CC, matls=solids)
        sched.add_task(t)
        sched.add_task(Task("EFEM::computeVelocityStar", self.velocity_star, m0)
                       .requires(OLD, L.delT).requires(OLD, E.gVelocity, G, 1).requires(NEW, E.sigma_CC, G, 1)
                       .requires(NEW, E.hgForce_CC, G, 1)
                       .requires(NEW, E.rho_CC, G, 1).requires(NEW, E.fill_CC, G, 1)
                       .computes(E.gVelocityStar).computes(E.gMass))
        t = Task("EFEM::setupPressureSystem", self.pressure_system, m0) \
            .requires(OLD, L.delT).requires(NEW, E.gVelocityStar, G, 1).requires(NEW, E.rho_CC, G, 1) \
            .requires(NEW, E.fill_CC, G, 1).requires(NEW, E.fluid_CC, G, 1).computes(E.press_A).computes(E.press_rhs)
        if self.pcg.precond == "mg":
            t.computes(self.pcg.OP)
        sched.add_task(t)
        seed = Task("EFEM::pressureSolveSetup", self.pressure_seed, m0) \
            .requires(NEW, E.press_A).requires(NEW, E.press_rhs)
        if self.pcg.precond == "mg":
            seed.requires(NEW, self.pcg.OP)
        sched.add_task(self.pcg.seed_computes(seed))
        sched.add_task(self.pcg.loop("EFEM::pressureSolve", E.press_CC))
        sched.add_task(Task("EFEM::projectVelocity", self.project, m0)
                       .requires(OLD, L.delT).requires(NEW, E.gVelocityStar).requires(NEW, E.gMass)
                       .requires(NEW, E.press_CC, G, 1).requires(NEW, E.rho_CC, G, 1)
                       .requires(NEW, E.excess_CC, G, 1).computes(E.gVelocityL))
        sched.add_task(Task("EFEM::computeMeanStress", self.mean_stress, m0)       # only when saved
                       .requires(NEW, E.sigma_CC).requires(NEW, E.press_CC).computes(E.mean_stress_CC))
        # Eulerian step
        t = Task("EFEM::advectAndRemap", self.remap, self.matls) \
            .requires(OLD, L.delT).requires(NEW, E.gVelocityL, G, GADV + 1, matls=m0) \
            .requires(NEW, E.gVelocityStar, G, GADV + 1, matls=m0).requires(NEW, E.gMass, G, GADV + 1, matls=m0) \
            .requires(NEW, E.press_CC, G, GADV, matls=m0) \
            .requires(NEW, E.rho_CC, G, GADV, matls=m0).requires(NEW, E.fill_CC, G, GADV, matls=m0) \
            .requires(OLD, E.vol_frac_CC, G, GADV) \
            .computes(E.vol_frac_CC).computes(E.dvel_CC, matls=m0).computes(E.mass_CC, matls=m0)
        if solids:
            t.requires(NEW, E.stress_L_CC, G, GADV, matls=solids).computes(E.stress_CC, matls=solids) \
                .requires(NEW, E.hourglass_L_CC, G, GADV, matls=solids).computes(E.hourglass_CC, matls=solids)
        sched.add_task(t)
        sched.add_task(Task("EFEM::remapNodalVelocity", self.remap_velocity, m0)
                       .requires(NEW, E.gVelocityL, G, 1).requires(NEW, E.gMass, G, 1).requires(NEW, E.dvel_CC, G, 1)
                       .requires(NEW, E.mass_CC, G, 1).computes(E.gVelocity))
        sched.add_task(Task("EFEM::sumConservedQuantities", self.conserved, self.matls)
                       .requires(NEW, E.vol_frac_CC).requires(NEW, E.gVelocity, matls=m0)
                       .requires(NEW, E.gMass, matls=m0)
                       .computes(E.TotalMass).computes(E.KineticEnergy))
