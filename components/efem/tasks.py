"""EFEM task bodies, in the order of the paper's flowchart (sec. 2): Lagrangian step
(stresses, nodal forces and velocities, pressure, velocity correction), then the
Eulerian step (remap of volume fractions, stresses and momentum, back to the nodes).
Each body gets arrays from the warehouses, calls kernels and puts the results.
"""
from __future__ import annotations

import numpy as np

from framework import labels as L
from framework.geometry import cell_fractions
from framework.variables import VarType

from . import kernels as K
from . import labels as E

CC, NC = VarType.CC, VarType.NC


class Frame:
    """A patch's index frames: global cells [clo, chi), owned domain nodes [nlo, nhi), and the
    global indices c0 / n0 of entry [0, 0, 0] of its stored CC / NC arrays (x, y only)."""

    def __init__(self, patch):
        lv = patch.level
        self.c0 = np.array(patch.low_index(CC)[:2], dtype=np.int64)
        self.n0 = np.array(patch.low_index(NC)[:2], dtype=np.int64)
        self.clo = np.array(patch.lo[:2], dtype=np.int64)
        self.chi = np.array(patch.hi[:2], dtype=np.int64)
        own = patch.owned(NC)
        inner = lv.interior_box(NC)
        self.nlo = np.array([max(own[0][d], inner[0][d]) for d in range(2)], dtype=np.int64)
        self.nhi = np.array([min(own[1][d], inner[1][d]) for d in range(2)], dtype=np.int64)
        self.N = np.array(lv.ncells[:2], dtype=np.int64)
        self.dx = np.array(lv.dx[:2], dtype=np.float64)
        self.dz = float(lv.dx[2])
        self.vol = float(lv.dx[0] * lv.dx[1] * lv.dx[2])


class EfemTasks:
    """Task bodies of the EFEM component (mixed into the component class)."""

    def frame(self, patch):
        f = self._frames.get(patch.id)
        if f is None:
            f = self._frames[patch.id] = Frame(patch)
        return f

    # -- initialization -------------------------------------------------------------------
    def initialize(self, patch, matls, old_dw, new_dw):
        """Volume fractions from the geometry objects (deck order, each material into what is
        left free), zero solid stress, the elements' mass and momentum for the nodal velocity."""
        lv = patch.level
        own = patch.owned(CC)
        sl = patch.slices(CC, own)
        free = np.ones(patch.alloc_shape(CC))
        mass = new_dw.allocate(E.mass_CC, 0, patch)
        mom = new_dw.allocate(E.mom_CC, 0, patch)
        for m, mat in enumerate(self.materials):
            vf = new_dw.allocate(E.vol_frac_CC, m, patch)
            for piece, g in mat.objects:
                f = np.minimum(cell_fractions(piece, lv, own, g["res"]), free[sl])
                vf[sl] += f
                free[sl] -= f
                mass[sl] += mat.density * f * self.vol
                mom[sl] += (mat.density * f * self.vol)[..., None] * np.asarray(g["velocity"])
            if mat.solid:
                new_dw.allocate(E.stress_CC, m, patch)
                new_dw.allocate(E.hourglass_CC, m, patch)

    def initialize_velocity(self, patch, matls, old_dw, new_dw):
        """Nodal velocity: the mass-weighted mean of the elements' initial velocities."""
        f = self.frame(patch)
        vel = new_dw.allocate(E.gVelocity, 0, patch)
        K.nodal_from_momentum(new_dw.get(E.mass_CC, 0, patch), new_dw.get(E.mom_CC, 0, patch), vel,
                              f.n0, f.c0, f.nlo, f.nhi, f.N, self.walls, self.wall_vel)

    # -- the Lagrangian step --------------------------------------------------------------
    def compute_stress(self, patch, matls, old_dw, new_dw):
        """Element stresses: solids by Hooke (eqs. 21-22), fluids by Newton (eqs. 18-19), mixed by
        volume fraction (eq. 23); the mixture density and fill for the nodal masses and eq. 16; the
        solids' volume strain sum_s phi_s e_v,s for the volume correction."""
        f = self.frame(patch)
        dt = old_dw.get_reduction(L.delT)
        vel = old_dw.get(E.gVelocity, 0, patch)
        D = np.zeros(patch.alloc_shape(CC) + (5,))
        K.strain_rate(vel, f.n0, f.c0, f.clo, f.chi, f.dx, D)
        sigma = new_dw.allocate(E.sigma_CC, 0, patch)
        rho = new_dw.allocate(E.rho_CC, 0, patch)
        fill = new_dw.allocate(E.fill_CC, 0, patch)
        hg_force = new_dw.allocate(E.hgForce_CC, 0, patch)
        excess = new_dw.allocate(E.excess_CC, 0, patch)
        fluid = new_dw.allocate(E.fluid_CC, 0, patch)
        for m, mat in enumerate(self.materials):
            vf = old_dw.get(E.vol_frac_CC, m, patch)
            rho += mat.density * vf
            fill += vf
            if not mat.solid:
                fluid += vf
        for m, mat in enumerate(self.materials):
            vf = old_dw.get(E.vol_frac_CC, m, patch)
            if mat.solid:
                sig = new_dw.allocate(E.stress_L_CC, m, patch)
                K.solid_stress(D, old_dw.get(E.stress_CC, m, patch), vf, fluid, sig, sigma, excess, mat.lam,
                               mat.mu, dt, self.settings["slide_condition"], self.settings["solid_min"], f.c0, f.clo,
                               f.chi, f.N)
                hg = new_dw.allocate(E.hourglass_L_CC, m, patch)
                kx, ky = self.hourglass_stiffness(mat, f)
                K.solid_hourglass(D, old_dw.get(E.hourglass_CC, m, patch), vf, hg, hg_force, kx, ky, dt,
                                  self.settings["solid_min"], f.c0, f.clo, f.chi)
            elif mat.viscosity > 0.0:
                K.fluid_stress(D, vf, sigma, mat.viscosity, f.c0, f.clo, f.chi)

    def hourglass_stiffness(self, mat, f):
        """(k_x, k_y) of the hourglass mode: (4 V / 3) E' / dx^2 with the plane-strain modulus
        E' = 4 mu of the incompressible solid, times <hourglass_stiffness>."""
        c = self.settings["hourglass_stiffness"] * 4.0 * f.vol / 3.0 * 4.0 * mat.mu
        return c / f.dx[0] ** 2, c / f.dx[1] ** 2

    def velocity_star(self, patch, matls, old_dw, new_dw):
        """Nodal masses, internal forces and gravity; v* of eq. (14)."""
        f = self.frame(patch)
        dt = old_dw.get_reduction(L.delT)
        vstar = new_dw.allocate(E.gVelocityStar, 0, patch)
        mass = new_dw.allocate(E.gMass, 0, patch)
        K.velocity_star(old_dw.get(E.gVelocity, 0, patch), new_dw.get(E.sigma_CC, 0, patch),
                        new_dw.get(E.hgForce_CC, 0, patch), new_dw.get(E.rho_CC, 0, patch), new_dw.get(E.fill_CC, 0, patch), vstar, mass, f.n0, f.c0,
                        f.nlo, f.nhi, f.N, f.dx, f.vol, dt, self.gravity, self.settings["hourglass_damping"],
                        self.settings["damping"], self.walls, self.wall_vel, self.settings["fill_min"])

    def pressure_system(self, patch, matls, old_dw, new_dw):
        """The stencil and right-hand side of the pressure Poisson equation (eq. 16), with the fill
        correction."""
        f = self.frame(patch)
        dt = old_dw.get_reduction(L.delT)
        A = new_dw.allocate(E.press_A, 0, patch)
        rhs = new_dw.allocate(E.press_rhs, 0, patch)
        K.pressure_system(new_dw.get(E.gVelocityStar, 0, patch), new_dw.get(E.rho_CC, 0, patch),
                          new_dw.get(E.fill_CC, 0, patch), new_dw.get(E.fluid_CC, 0, patch), A, rhs, f.n0, f.c0,
                          f.clo, f.chi, f.N, f.dx, f.dz, dt, self.open_faces, self.settings["fill_min"],
                          self.settings["fill_correction"], self.side)
        if self.pcg.precond == "mg":
            self.pcg.put_coarse_operator(patch, A, new_dw)

    def pressure_seed(self, patch, matls, old_dw, new_dw):
        if self.pcg.precond == "mg":
            self.pcg.setup_hierarchy(new_dw.get_reduction(self.pcg.OP))
        self.pcg.put_seeds(patch, new_dw.get(E.press_rhs, 0, patch), new_dw)

    def project(self, patch, matls, old_dw, new_dw):
        """Eq. (17): the pressure's correction of the nodal velocities, plus the solids' volume
        correction: a pressure q = -beta rho dx dy e_v / (2 dt^2) on their volume strain e_v, which
        takes the share beta of it back per step (the 5-point projection leaves the nodal
        velocities slightly compressible, and a solid would otherwise bend as if it were)."""
        f = self.frame(patch)
        dt = old_dw.get_reduction(L.delT)
        beta = self.settings["volume_correction"] * f.dx[0] * f.dx[1] / (2.0 * dt * dt)
        q = new_dw.get(E.press_CC, 0, patch) - beta * new_dw.get(E.rho_CC, 0, patch) * new_dw.get(E.excess_CC, 0, patch)
        vel = new_dw.allocate(E.gVelocityL, 0, patch)
        K.project(new_dw.get(E.gVelocityStar, 0, patch), q, new_dw.get(E.gMass, 0, patch), vel, f.n0, f.c0,
                  f.nlo, f.nhi, f.N, f.dx, f.vol, dt, self.walls, self.wall_vel)

    # -- the Eulerian step ----------------------------------------------------------------
    def remap(self, patch, matls, old_dw, new_dw):
        """Eq. (4) by directional splitting: an x sweep over the patch's columns on its rows and two
        ghost rows either side, then a y sweep over the patch (sec. 6, MUSCL, ref. 17)."""
        f = self.frame(patch)
        dt = old_dw.get_reduction(L.delT)
        velL = new_dw.get(E.gVelocityL, 0, patch)
        nm = len(self.materials)
        phi = np.stack([old_dw.get(E.vol_frac_CC, m, patch)[..., 0] for m in range(nm)])
        # each solid's state moved with it: [sxx, syy, sxy, Qx, Qy]
        sig = np.stack([np.concatenate((new_dw.get(E.stress_L_CC, m, patch)[..., 0, :],
                                        new_dw.get(E.hourglass_L_CC, m, patch)[..., 0, :]), axis=-1)
                        for m in self.solids]) if self.solids else np.zeros((1,) + phi.shape[1:] + (5,))
        u0 = np.zeros(phi.shape[1:] + (2,))
        glo = np.maximum(f.clo - 2, 0)
        ghi = np.minimum(f.chi + 2, f.N)
        K.element_velocity(velL, new_dw.get(E.gMass, 0, patch), f.n0, f.c0, glo, ghi, u0)
        # the x sweep on rows [lo - 2, hi + 2), then the y sweep on the patch
        xlo = np.array([f.clo[0], glo[1]], dtype=np.int64)
        xhi = np.array([f.chi[0], ghi[1]], dtype=np.int64)
        phi1, sig1, u1 = phi.copy(), sig.copy(), u0.copy()
        faces = (new_dw.get(E.gVelocityStar, 0, patch), new_dw.get(E.press_CC, 0, patch),
                 new_dw.get(E.rho_CC, 0, patch), new_dw.get(E.fill_CC, 0, patch), self.settings["fill_min"], f.n0, f.c0)
        bcs = (self.walls, self.wall_vel, self.inflow_matl, self.limiter, self.stress_muscl, self.settings["solid_min"])
        K.remap_sweep(0, phi, sig, self.solid_of, self.densities, u0, *faces, xlo, xhi, f.N, f.dx, dt, *bcs,
                      phi1, sig1, u1)
        phi2, sig2, u2 = phi1.copy(), sig1.copy(), u1.copy()
        K.remap_sweep(1, phi1, sig1, self.solid_of, self.densities, u1, *faces, f.clo, f.chi, f.N, f.dx, dt, *bcs,
                      phi2, sig2, u2)
        for m in range(nm):
            new_dw.put(E.vol_frac_CC, m, patch, np.ascontiguousarray(phi2[m][..., None]))
        for s, m in enumerate(self.solids):
            new_dw.put(E.stress_CC, m, patch, np.ascontiguousarray(sig2[s][:, :, None, :3]))
            new_dw.put(E.hourglass_CC, m, patch, np.ascontiguousarray(sig2[s][:, :, None, 3:]))
        dvel = new_dw.allocate(E.dvel_CC, 0, patch)
        dvel[..., 0, :2] = u2 - u0
        mass = new_dw.allocate(E.mass_CC, 0, patch)
        mass[..., 0] = np.tensordot(self.densities, phi2, axes=1) * f.vol

    def remap_velocity(self, patch, matls, old_dw, new_dw):
        """The remapped element velocities back to the nodes."""
        f = self.frame(patch)
        vel = new_dw.allocate(E.gVelocity, 0, patch)
        K.nodal_remap(new_dw.get(E.gVelocityL, 0, patch), new_dw.get(E.gMass, 0, patch),
                      new_dw.get(E.dvel_CC, 0, patch), new_dw.get(E.mass_CC, 0, patch), vel, f.n0, f.c0, f.nlo,
                      f.nhi, f.N, self.walls, self.wall_vel)

    # -- diagnostics and the time step ----------------------------------------------------
    def conserved(self, patch, matls, old_dw, new_dw):
        """TotalMass (sum_m rho_m phi_m V) and KineticEnergy (nodal masses of the step)."""
        f = self.frame(patch)
        sl = (slice(f.clo[0] - f.c0[0], f.chi[0] - f.c0[0]), slice(f.clo[1] - f.c0[1], f.chi[1] - f.c0[1]))
        total = 0.0
        for m, mat in enumerate(self.materials):
            total += mat.density * float(new_dw.get(E.vol_frac_CC, m, patch)[sl].sum()) * f.vol
        new_dw.put_reduction(E.TotalMass, total)
        ke, _ = K.kinetic_energy_max_speed(new_dw.get(E.gVelocity, 0, patch), new_dw.get(E.gMass, 0, patch),
                                           f.n0, f.nlo, f.nhi)
        new_dw.put_reduction(E.KineticEnergy, ke)

    def mean_stress(self, patch, matls, old_dw, new_dw):
        """The element stress of eq. (23) with the projection pressure: sigma - p I."""
        out = new_dw.allocate(E.mean_stress_CC, 0, patch)
        out[...] = new_dw.get(E.sigma_CC, 0, patch)
        p = new_dw.get(E.press_CC, 0, patch)
        out[..., 0] -= p
        out[..., 1] -= p

    def stable_timestep(self, patch, matls, old_dw, new_dw):
        """delT = cfl min(dx) / (c + max|v|), c the largest solid wave speed; and the explicit
        viscous limit rho dx^2 / (4 mu) of the fluids."""
        f = self.frame(patch)
        vel = new_dw.get(E.gVelocity, 0, patch)
        _, vmax = K.kinetic_energy_max_speed(vel, np.zeros(vel.shape[:3]), f.n0, f.nlo, f.nhi)
        h = float(f.dx.min())
        dt = self.settings["cfl"] * h / max(self.wave_speed + vmax, 1e-300)
        for mat in self.materials:
            if mat.viscosity > 0.0:
                dt = min(dt, 0.25 * mat.density * h * h / mat.viscosity)
        new_dw.put_reduction(L.delT, dt)
