"""The task bodies of explicit MPM (paper 000 eqs. 21-27; paper 004 eqs. 5-17).

Each method is one task written for one patch and loops over the MPM materials:
get arrays from the warehouses, call kernels, put results. Node arrays are filled
from owned plus ghost particles, so no cross-patch sum of nodal values is needed.
"""
from __future__ import annotations

import numpy as np

from framework import labels as FL
from framework.scheduler.particle_kernels import runs as particle_runs
from framework.variables import VarType

from . import kernels, shape, transfer
from . import labels as L
from .constitutive import damage
from .artificial_viscosity import stress_less_q
from .cbdi import cells_size, corners_to_grid
from .thermal import divide_by_mass, p2g_heat

NC = VarType.NC


def _zeros33(n):
    """A read-only (n, 3, 3) array of zeros that costs no memory."""
    return np.broadcast_to(np.zeros((3, 3)), (n, 3, 3))


def _zero_rows(n):
    """A read-only zero-filled (n, 3) buffer (np.zeros: pages the kernels never touch cost no memory)."""
    z = np.zeros((n, 3))
    z.flags.writeable = False
    return z


_ZERO_ROWS = _zero_rows(0)


def _read_only(a):
    """a, or a read-only view of it."""
    if a.flags.writeable:
        a = a.view()
        a.flags.writeable = False
    return a


def _zeros3(n):
    """A read-only (n, 3) array of zeros, C-contiguous for every n: rows of one shared buffer,
    grown when needed. (A stride-0 broadcast view is C-contiguous for n <= 1 only, so numba
    compiled every kernel that takes p.size's stand-in twice: ~40 % of disks_50x50's cold
    compile.) Linear weights never read it."""
    global _ZERO_ROWS
    if len(_ZERO_ROWS) < n:
        _ZERO_ROWS = _zero_rows(max(n, 2 * len(_ZERO_ROWS)))
    return _ZERO_ROWS[:n]


# never-read stand-ins for arguments a kernel variant does not use
_NOF = np.zeros((1, 3))            # no p.externalforce
_NOL = np.zeros((1, 3, 3))         # MUSL: no L_p from the g2p kernel
_NOG = np.zeros((1, 1, 1, 3))      # USL: no remapped momentum
_NOV = np.zeros(1)                 # MUSL: F and V come later (grad kernel)
_NOS = np.zeros((1, 1, 1))         # no g.volume (component._grid_volume_needed)


def _split(dw, label, m, patch):
    """(owned, ghost, ID order) of a particle variable (TaskView.get_split); a bare
    warehouse holds no ghosts."""
    if hasattr(dw, "get_split"):
        return dw.get_split(label, m, patch)
    own = dw.get(label, m, patch)
    return own, own[:0], None


def scale_factor(F, size):
    """Uintah's p.scalefactor, F diag(dx) p.size with its p.size in cells: F diag(2 h) with
    pysus's half-widths h, or F 2 H with a size matrix H (p.sizeMatrix) (the particle's
    deformed extent, for visualisation)."""
    if size.ndim == 3:
        return np.matmul(F, 2.0 * size)
    return F * (2.0 * size)[:, None, :]


def matls_not_in(matls, chosen):
    return [m for m in matls if m not in chosen]


class MPMTasks:
    """Mixed into the MPM component: needs self.materials, interp, p2g, flags ..."""

    # -- helpers ----------------------------------------------------------------------------
    def _lp(self, dw, m, patch, n):
        """What the weights read of each particle besides x: p.size (GIMP), the CPDI domain
        (shape.cpdi_domains of p.size and F at the step's start) or zeros (linear)."""
        if self.kind == "linear":
            return _zeros3(n)
        if self.kind == "gimp":
            return dw.get(L.pSize, m, patch)
        return self._domains(dw.get(L.pF, m, patch), dw.get(self._size_label, m, patch))

    def _lp_read_only(self, dw, m, patch, n):
        """_lp as a read-only array, the numba type of linear's stand-in (_zeros3): the kernels that
        take the interpolator as a run-time value (kernels.p2g_stress, transfer.mass_gradient, the
        heat kernels) then compile once for linear and GIMP, not once for each."""
        return _read_only(self._lp(dw, m, patch, n))

    @property
    def _size_label(self):
        """What CPDI's domains and p.scalefactor read: p.size, or p.sizeMatrix (<smoothcyl>)."""
        return L.pSizeMatrix if getattr(self, "size_matrix", False) else L.pSize

    def _domains(self, F, size):
        """CPDI's domains; axisymmetric: the in-plane ones (F's hoop stretch is not a side of the
        domain), without cpdi_lcrit, as Uintah's axiCpdiInterpolator."""
        out = np.empty((len(F), 18))
        lcrit = np.inf if self.axisymmetric else self.flags["cpdi_lcrit"]
        shape.cpdi_domains(self.axes, F, size, self.level.dx, lcrit, out)
        return out

    def size_labels(self):
        """The particle labels the weights read besides p.x (ghosted where p.x is)."""
        return {"linear": [], "gimp": [L.pSize]}.get(self.kind, [self._size_label, L.pF])

    def _constitutive(self, mat, Lg, F_old, F_new, vol, mass, vel, dt, s_old, s_new, energy,
                      old=None, new=None, scale=None, temperature=None, color=None, time=0.0):
        """Call the material's model; `old`/`new` are its state arrays (plastic strain; a tuple
        for a model with several); membrane: (tangent, thickness, volume) before and after (the
        model sets the volume); `temperature`: p.temperature for the models that read it;
        `color`: p.color for those that read it (UCNHVar); `time`: the step's start, for the
        erosion of a damage model (damage.py)."""
        # Uintah's UCNH takes a pressure-stabilized particle's wave speed from J/rho0 (its V follows
        # the unstabilized J)
        stab = ({"rho0": mat.density} if self.flags["DoPressureStabilization"]
                and getattr(mat.model, "STABILIZED_WAVE_SPEED", False) else {})
        if mat.damage is not None:
            return mat.model.update(mat.params, Lg, F_old, F_new, vol, mass, vel, dt, s_old, s_new,
                                    energy, old, new, time=time, color=color, **stab)
        if mat.erosion:             # a model with its own localization (elastic_plastic_hp)
            return mat.model.update(mat.params, Lg, F_old, F_new, vol, mass, vel, dt, s_old, s_new,
                                    energy, old, new, time=time)
        if getattr(mat.model, "USES_COLOR", False):
            return mat.model.update(mat.params, Lg, F_old, F_new, vol, mass, vel, dt, s_old, s_new,
                                    energy, old, new, color=color)
        if mat.is_membrane:
            (t_old, h_old, v_old), (t_new, h_new, v_new) = old, new
            return mat.model.update(mat.params, Lg, F_old, F_new, v_old, mass, vel, dt, s_old, s_new,
                                    energy, t_old, t_new, h_old, h_new, v_new, getattr(mat, "hoop", False))
        if scale is not None:
            return mat.model.update(mat.params, Lg, F_old, F_new, vol, mass, vel, dt, s_old, s_new,
                                    energy, old, new, scale)
        if mat.uses_temperature:
            return mat.model.update(mat.params, Lg, F_old, F_new, vol, mass, vel, dt, s_old, s_new,
                                    energy, old, new, temperature)
        if mat.state:
            return mat.model.update(mat.params, Lg, F_old, F_new, vol, mass, vel, dt, s_old, s_new,
                                    energy, old, new, **stab)
        return mat.model.update(mat.params, Lg, F_old, F_new, vol, mass, vel, dt, s_old, s_new, energy, **stab)

    def _obj_base(self, m):
        return sum(len(self.materials[k].objects) for k in range(m))

    # -- initialization ------------------------------------------------------------------
    def initialize(self, patch, matls, old_dw, new_dw):
        """Particles from the geometry objects; zero stress, F = I; totals and wave speed."""
        ws = np.zeros(3)
        tot = np.zeros(8)
        se = 0.0
        for m in matls:
            mat = self.materials[m]
            d = mat.create(patch, self._obj_base(m), self.pressure_bcs, surface=self.contact.needs_lr,
                           axisymmetric=self.axisymmetric)
            n = len(d["id"])
            new_dw.create_particles(m, patch, n)
            if hasattr(mat.model, "initial_deformation"):     # jwlpp_mpm's initial pressure
                F, stress = mat.model.initial_deformation(mat.params, n)
            else:
                F = np.zeros((n, 3, 3))
                F[:, 0, 0] = F[:, 1, 1] = F[:, 2, 2] = 1.0
                stress = np.zeros((n, 3, 3))
            energy = np.zeros(n)
            state = mat.initial_state(d)
            if mat.is_membrane:
                state = state + (d["vol"],)
            old = new = state
            if mat.needs_temperature:           # (p.temperature, p.dTdt) follow the state
                old, new = state + (d["temp"],), state + (np.zeros(n),)
            ws = np.maximum(ws, self._constitutive(mat, np.zeros((n, 3, 3)), F, F, d["vol"], d["mass"],
                                                   d["vel"], 0.0, stress, stress, energy, old, new,
                                                   temperature=d["temp"], color=d["color"]))
            put = {L.pX: d["x"], L.pVelocity: d["vel"], L.pMass: d["mass"], L.pVolume: d["vol"],
                   L.pStress: stress, L.pF: F, L.pID: d["id"], L.pSize: d["size"], L.pColor: d["color"],
                   L.pSizeMatrix: d["size_matrix"],
                   L.pStrainEnergy: energy, L.pSurface: d.get("surf"), L.pDisp: np.zeros((n, 3)),
                   L.pQ: np.zeros(n)}
            if self.saves_scale:
                put[L.pScaleFactor] = scale_factor(F, d["size_matrix"] if self.size_matrix else d["size"])
            if self.projection:
                put[L.pVelGradLast] = np.zeros((n, 3, 3))
            own = dict(zip(mat.state_names, state if len(mat.state_names) > 1 else (state,)))
            for lab, _ in self.carry:           # the carried model states: this material's, else zeros
                if lab.name in L.STATE:
                    put[lab] = own[lab.name] if lab.name in own else np.zeros((n,) + lab.shape)
            put[L.pTangent] = state[0] if mat.is_membrane else np.zeros((n, 3))
            put[L.pThickness] = state[1] if mat.is_membrane else np.zeros(n)
            new_dw.put(L.pX, m, patch, d["x"])
            for final, _ in self.carry:
                if final in put:
                    new_dw.put(final, m, patch, put[final])
            if self.pressure_bcs:
                new_dw.put(L.pLoadCurveID, m, patch, d["lcid"])
                new_dw.put(L.pExtForce, m, patch, np.zeros((n, 3)))
                if self.pressure_bcs.heat_flux:
                    new_dw.put(L.pExternalHeatRate, m, patch, np.zeros(n))
                new_dw.put_reduction(L.PressureBCParticles, self.pressure_bcs.counts(d["lcid"]))
            kernels.sums(d["mass"], d["vel"], d["x"], tot)
            se += energy.sum()
        self._put_totals(new_dw, tot)
        new_dw.put_reduction(L.StrainEnergy, se)
        new_dw.put_reduction(L.WaveSpeed, ws)

    def _put_totals(self, dw, tot):
        mass, ke, mom = self.totals
        dw.put_reduction(mass, tot[0])
        dw.put_reduction(ke, tot[1])
        dw.put_reduction(mom, tot[2:5])
        dw.put_reduction(L.CenterOfMassPosition, tot[5:8])

    def compute_stable_timestep(self, patch, matls, old_dw, new_dw):
        """delT = min_d dx_d / (c + |v_d|) (Uintah's MPM rule) over the active directions, or with
        <delT_activeDirectionsOnly>false over all three, a one-cell direction too, as Uintah's
        constitutive models (a thin cell along a collapsed z then sets the step)."""
        ws = np.asarray(new_dw.get_reduction(L.WaveSpeed))
        dt = np.inf
        every = not self.flags["delT_activeDirectionsOnly"]
        for d in range(3):
            if (every or self.dims[d]) and ws[d] > 0:
                dt = min(dt, self.level.dx[d] / ws[d])
        dt = min([dt] + [mat.max_delT for mat in self.materials])    # visco_scram: at most 1 microsecond
        new_dw.put_reduction(FL.delT, dt if np.isfinite(dt) else 1e30)

    # -- particles -> grid ------------------------------------------------------------------
    def interpolate_particles_to_grid(self, patch, matls, old_dw, new_dw):
        """m_i, v_i, V_i (where needed), fext_i (000 eq. 22) and fint_i (000 eq. 24) per material,
        scattered straight into the warehouse's node arrays (transfer.py) from the owned
        and ghost particles' own arrays (no merged copy)."""
        lv = self.level
        low = np.array(patch.low_index(NC), np.int64)
        has_f = bool(self.pressure_bcs) or bool(self.mms)
        labs = [L.pX, L.pMass, L.pVelocity, L.pVolume, L.pStress]
        labs += [L.pLoadCurveID] if self.pressure_bcs else [L.pDisp] if self.mms else []
        labs += [L.pF, self._size_label] if self.cbdi else []
        labs += [L.pQ] if self.av else []
        for m in matls:
            own, ghost, runs = self._parts(old_dw, m, patch, labs)
            if self.av:                 # the internal force's stress: sigma - q I
                own, ghost = [a[:4] + [self._stress_less_q(a[4], a[-2])] + a[5:] for a in (own, ghost)]
            if self.cbdi:               # fext from the loaded faces' corners, after p2g (cbdi.py)
                loads = [(a[5],) + self._cbdi_forces(old_dw, a[0], a[5], a[6], a[7]) for a in (own, ghost)]
                has_f = False
            own, ghost = [tuple(a[:5] + [self._body_forces(old_dw, a) if has_f else _NOF, a[-1]])
                          for a in (own, ghost)]
            gm = new_dw.allocate(L.gMass, m, patch, 0.0)
            gv = new_dw.allocate(L.gVelocity, m, patch, 0.0)     # momentum, then velocity
            gvol = new_dw.allocate(L.gVolume, m, patch, 0.0) if self.grid_volume else _NOS
            grads = _split(old_dw, L.pVelGradLast, m, patch)[:2] if self.projection else ()
            if self.projection and not self.grid_volume:
                gvol = np.zeros_like(gm)      # the projected p2g computes the volume anyway
            gfe = new_dw.allocate(L.gExtForce, m, patch, 0.0)
            self.p2g_runs(own, ghost, runs, has_f, self.grid_volume, lv.anchor, lv.dx, low, gm, gv, gvol,
                          gfe, new_dw.allocate(L.gIntForce, m, patch, 0.0), *grads)
            if self.cbdi:
                corners_to_grid(self.act, loads[0], loads[1], runs, lv.anchor, lv.dx, low, gfe)
            kernels.divide_by_mass(gm, gv, gv)
            self.bcs.apply_symmetric(patch, m, gv)             # as Uintah (bc.py)

    @staticmethod
    def _stress_less_q(stress, q):
        out = np.empty_like(stress)
        stress_less_q(stress, q, out)
        return out

    def _parts(self, old_dw, m, patch, labels):
        """[owned arrays], [ghost arrays] of the (ghosted) particle labels, each list ending
        with _lp's array (p.size, the CPDI domain or zeros), and the runs of their merged ID order."""
        extra = self.size_labels()
        split = [_split(old_dw, lab, m, patch) for lab in labels + extra]
        own, ghost = [s[0] for s in split], [s[1] for s in split]
        n_own, n_gh, order = len(own[0]), len(ghost[0]), split[0][2]
        if self.kind == "linear":
            own.append(_zeros3(n_own))
            ghost.append(_zeros3(n_gh))
        elif len(extra) == 2:
            own, ghost = [a[:-2] + [self._domains(a[-1], a[-2])] for a in (own, ghost)]
        if order is not None:
            runs = particle_runs(order, n_own)
        else:
            runs = np.array([[0, 0, n_own], [1, 0, n_gh]], np.int64)[:1 + (n_gh > 0)]
        return own, ghost, runs

    def _body_forces(self, old_dw, a):
        """p.externalforce of the particle arrays a (p.x, p.mass, ..., then p.loadCurveID or
        p.displacement): the pressure BCs' or the manufactured solution's (mms.py)."""
        if self.mms:
            return self.mms.forces(a[0], a[5], a[1], old_dw.get_reduction(FL.simTime))
        return self._forces(old_dw, a[0], a[5])

    def _ext_force(self, old_dw, m, patch, px):
        """p.externalforce of the pressure BCs at the time this step starts (pressure.py)."""
        if self.cbdi:
            return self._cbdi_forces(old_dw, px, old_dw.get(L.pLoadCurveID, m, patch), old_dw.get(L.pF, m, patch),
                                     old_dw.get(self._size_label, m, patch))[0]
        return self._forces(old_dw, px, old_dw.get(L.pLoadCurveID, m, patch))

    def _cbdi_forces(self, old_dw, px, lcid, F, size):
        """(p.externalforce, loaded-face corners) under CBDI (cbdi.py), with F and p.size of the
        step's start."""
        return self.pressure_bcs.cbdi_forces(px, lcid, old_dw.get_reduction(FL.simTime),
                                             old_dw.get_reduction(L.PressureBCParticles), F,
                                             cells_size(size, self.level.dx), self.level.dx)

    def _forces(self, old_dw, px, lcid):
        return self.pressure_bcs.forces(px, lcid, old_dw.get_reduction(FL.simTime),
                                        old_dw.get_reduction(L.PressureBCParticles))

    def interpolate_stress_to_grid(self, patch, matls, old_dw, new_dw):
        """g.stressFS = sum S m sigma / sum S m: a nodal stress for output only."""
        lv = self.level
        alo, ahi = patch.alloc(NC)
        pad = np.array([self.ng + 2 if self.dims[d] else 0 for d in range(3)])
        shape = tuple(np.array(ahi) - np.array(alo) + 2 * pad)
        inner = tuple(slice(pad[d], pad[d] + ahi[d] - alo[d]) for d in range(3))
        kind = transfer.INTERPOLATORS[self.kind]
        for m in matls:
            px = old_dw.get(L.pX, m, patch)
            gm = np.zeros(shape)
            gs = np.zeros(shape + (3, 3))
            kernels.p2g_stress(kind, self.act, px, old_dw.get(L.pMass, m, patch), old_dw.get(L.pStress, m, patch),
                               self._lp_read_only(old_dw, m, patch, len(px)), lv.anchor, lv.dx, np.array(alo) - pad,
                               gm, gs)
            out = new_dw.allocate(L.gStressFS, m, patch, None)
            kernels.divide_by_mass(np.ascontiguousarray(gm[inner]), np.ascontiguousarray(gs[inner]), out)

    # -- grid ---------------------------------------------------------------------------------
    def ex_mom_interpolated(self, patch, matls, old_dw, new_dw):
        """Contact on the interpolated velocities (friction: normals first)."""
        gm = {m: new_dw.get(L.gMass, m, patch) for m in matls}
        gv = {m: new_dw.get_modifiable(L.gVelocity, m, patch) for m in matls}
        traction = {} if self.contact.needs_traction else None
        normals = self._normals(patch, old_dw, new_dw, traction) if self.contact.needs_normals else None
        lr, color = self._lr(patch, new_dw)
        t = old_dw.get_reduction(FL.simTime) if self.contact.needs_time else 0.0
        self.contact.exchange(gm, gv, None, None, old_dw.get_reduction(FL.delT), t=t, normals=normals,
                              dx=self.level.dx, node_x=(self.level.anchor, self.level.dx, patch.low_index(NC)),
                              lr=lr, color=color, traction=traction)

    def logistic_regression(self, patch, matls, old_dw, new_dw):
        """friction_LR's g.alphaMaterial, g.normAlphaToBeta (material 0) and each material's
        g.matlProminence (Uintah's computeLogisticRegression; contact.py), and for
        friction_LRVar the master material's g.color."""
        lv, c = self.level, self.contact
        low = np.array(patch.low_index(NC), np.int64)
        shape = np.array(patch.alloc_shape(NC), np.int64)
        own_lo, own_hi = (np.array(b, np.int64) for b in patch.owned_local(NC))
        kind = 0 if self.kind == "linear" else 1
        nm, nn = len(matls), int(np.prod(shape))
        gmass = np.stack([new_dw.get(L.gMass, m, patch).reshape(-1) for m in matls])
        possible = np.ones(nm, np.bool_)
        rigid = np.array([self.materials[m].is_rigid for m in matls], np.bool_)
        alpha = np.empty(nn, np.int64)
        n_matls = np.empty(nn, np.int64)
        kernels.lr_alpha(gmass, possible, rigid, alpha, n_matls)
        px = {m: old_dw.get(L.pX, m, patch) for m in matls}
        size = {m: old_dw.get(L.pSize, m, patch) for m in matls}
        # read-only as the other kernels with the interpolator at run time: one compilation each
        lp = {m: _read_only(size[m]) if self.kind == "gimp" else _zeros3(len(px[m])) for m in matls}
        count = np.zeros((nn, nm), np.int64)
        for k, m in enumerate(matls):         # particles of each material near each node
            col = np.zeros(nn, np.int64)
            kernels.lr_near(kind, self.axes, px[m], lp[m], lv.anchor, lv.dx, low, shape, own_lo, own_hi,
                            n_matls, 1e-8, col, False, col, np.empty((0, 3)))
            count[:, k] = col
        start = (np.cumsum(count.reshape(-1)) - count.reshape(-1)).reshape(nn, nm)
        xs = np.empty((int(count.sum()), 3))
        for k, m in enumerate(matls):
            col = np.zeros(nn, np.int64)
            kernels.lr_near(kind, self.axes, px[m], lp[m], lv.anchor, lv.dx, low, shape, own_lo, own_hi,
                            n_matls, 1e-8, col, True, np.ascontiguousarray(start[:, k]), xs)
        normal = new_dw.allocate(L.gNormAlphaToBeta, 0, patch, 0.0)
        flat_normal = normal.reshape(-1, 3)
        kernels.lr_normals(alpha, start, count, xs, 1e-7 * lv.dx[0] ** 2, flat_normal)
        self.bcs.symmetric_normal(patch, normal)     # and no component along a collapsed direction
        flat_normal[:, ~np.asarray(self.dims, bool)] = 0.0
        length = np.linalg.norm(flat_normal, axis=1, keepdims=True)
        flat_normal /= length + 1e-100
        flat_normal[alpha < 0] = 0.0
        near = count.sum(axis=1)
        for k, m in enumerate(matls):
            pmax = np.full(nn, -9.0e99)
            pmin = np.full(nn, 9.0e99)
            kernels.lr_prominence(kind, self.axes, px[m], lp[m], size[m], old_dw.get(L.pSurface, m, patch),
                                  lv.anchor, lv.dx, low, shape, own_lo, own_hi, near, alpha, flat_normal, k,
                                  pmax, pmin)
            prom = new_dw.allocate(L.gMatlProminence, m, patch, -99.0).reshape(-1)
            np.copyto(prom, pmax, where=(alpha == k) & (pmax > -9.0e99))
            np.copyto(prom, pmin, where=(alpha != k) & (pmin < 9.0e99))
        new_dw.allocate(L.gAlphaMaterial, 0, patch, None).reshape(-1)[...] = alpha
        if c.needs_color:
            m = c.master
            gmc = np.zeros(patch.alloc_shape(NC))
            p2g_heat(kind, self.axes, px[m], old_dw.get(L.pMass, m, patch), old_dw.get(L.pColor, m, patch),
                             lp[m], lv.anchor, lv.dx, low, gmc)
            divide_by_mass(new_dw.get(L.gMass, m, patch), gmc, new_dw.allocate(L.gColor, m, patch, None))

    def _lr(self, patch, new_dw):
        """(alpha, normal, {material: prominence}), master's g.color: friction_LR's inputs."""
        c = self.contact
        if not c.needs_lr:
            return None, None
        lr = (new_dw.get(L.gAlphaMaterial, 0, patch), new_dw.get(L.gNormAlphaToBeta, 0, patch),
              {m: new_dw.get(L.gMatlProminence, m, patch) for m in self.matls})
        return lr, (new_dw.get(L.gColor, c.master, patch) if c.needs_color else None)

    def _normals(self, patch, old_dw, new_dw, traction=None):
        """g.surfNorm per contact material, as Uintah's computeNormals: g_m = sum m_p grad S
        (outward: mass falls off along it), made collinear with the other materials'
        (0.5 (g_m - mass-weighted mean of the others' g)) unless <computeColinearNormals>
        false, then unit length. Axisymmetric, as Uintah's: g_m = sum rho_p (dS/dr, dS/dz, 0) with
        the r-weighted weights and the derivatives in cell units (the particles' mass grows with
        r, their density does not). traction (a dict): friction_bard's g.normtraction of each
        contact material goes there."""
        lv = self.level
        low = np.array(patch.low_index(NC), np.int64)
        kind = transfer.INTERPOLATORS[self.kind]
        g, gm = {}, {}
        for m in self.contact.materials:
            px = old_dw.get(L.pX, m, patch)
            g[m] = np.zeros(patch.alloc_shape(NC) + (3,))
            weight = old_dw.get(L.pMass, m, patch)
            if self.axisymmetric:
                weight = weight / old_dw.get(L.pVolume, m, patch)
            transfer.mass_gradient(kind, self.act, px, weight,
                                   self._lp_read_only(old_dw, m, patch, len(px)), lv.anchor, lv.dx, low, g[m])
            if self.axisymmetric:
                g[m][..., :2] *= np.asarray(lv.dx)[:2]
                g[m][..., 2] = 0.0
            gm[m] = new_dw.get(L.gMass, m, patch)[..., None]
        out = {}
        collinear = self.flags.get("computeColinearNormals", True)
        for m in self.contact.materials:
            n = new_dw.allocate(L.gSurfNorm, m, patch, None)
            if collinear:
                others = [k for k in self.contact.materials if k != m]
                mon = sum(gm[k] for k in others)
                mwon = sum(gm[k] * g[k] for k in others) / (mon + 1e-100)
                np.multiply(0.5, g[m] - mwon, out=n)
                n[np.broadcast_to(gm[m] <= 1e-200, n.shape)] = 0.0
            else:
                n[...] = g[m]
            self.bcs.symmetric_normal(patch, n)        # Uintah's "Symmetric" condition on g.surfNorm
            norm = np.linalg.norm(n, axis=-1, keepdims=True)
            np.divide(n, norm, out=n, where=norm > 1e-15)
            out[m] = n
            if traction is not None:
                traction[m] = self._normal_traction(patch, old_dw, new_dw, m, n)
        for m in matls_not_in(self.matls, self.contact.materials):
            new_dw.allocate(L.gSurfNorm, m, patch, 0.0)
            if self.contact.needs_traction:
                new_dw.allocate(L.gNormTraction, m, patch, 0.0)
        return out

    def _normal_traction(self, patch, old_dw, new_dw, m, n):
        """friction_bard's g.normtraction = n . (sum_p S sigma_p) . n (Uintah's computeNormals; its
        sign tells a node in compression)."""
        lv = self.level
        alo, ahi = patch.alloc(NC)
        pad = np.array([self.ng + 2 if self.dims[d] else 0 for d in range(3)])
        shape = tuple(np.array(ahi) - np.array(alo) + 2 * pad)
        px = old_dw.get(L.pX, m, patch)
        gs = np.zeros(shape + (3, 3))
        kernels.p2g_stress(transfer.INTERPOLATORS[self.kind], self.act, px, np.ones(len(px)),
                           old_dw.get(L.pStress, m, patch), self._lp_read_only(old_dw, m, patch, len(px)), lv.anchor,
                           lv.dx, np.array(alo) - pad, np.zeros(shape), gs)
        gs = gs[tuple(slice(p, p + h - l) for p, l, h in zip(pad, alo, ahi))]
        tn = np.ascontiguousarray(np.einsum("...i,...ij,...j->...", n, gs, n))
        new_dw.put(L.gNormTraction, m, patch, tn)
        return tn

    def _traction(self, new_dw, patch):
        if not self.contact.needs_traction:
            return None
        return {m: new_dw.get(L.gNormTraction, m, patch) for m in self.contact.materials}

    def integrate_acceleration(self, patch, matls, old_dw, new_dw):
        """a_i = (fint + fext)/m_i + g (000 eq. 21), v*_i = v_i + a_i dt (000 eq. 25). fint takes
        the symmetry conditions first (no normal force on a symmetry plane's nodes, the extra
        nodes mirrored), as Uintah's computeInternalForce: v* is read before the grid's velocity
        conditions by contact and by MPMICE's Lagrangian momentum, which then see no normal
        velocity on the plane (g.internalforce itself, which the boundary forces read, is kept)."""
        dt = old_dw.get_reduction(FL.delT)
        f = self.flags
        ftm_sums = np.zeros(L.FTMForce.shape) if self.ftm else None
        for m in matls:
            gm = new_dw.get(L.gMass, m, patch)
            gv = new_dw.get(L.gVelocity, m, patch)
            gvs = new_dw.allocate(L.gVelocityStar, m, patch, None)
            ga = new_dw.allocate(L.gAcceleration, m, patch, None)
            fext = new_dw.get(L.gExtForce, m, patch)
            fint = new_dw.get(L.gIntForce, m, patch)
            if self.bcs.has_symmetric(patch, m):
                fint = fint.copy()
                self.bcs.apply_symmetric(patch, m, fint)
            kernels.integrate_acceleration(gm, gv, fint, fext, self.gravity, dt,
                                           f["minimum_mass_for_acc"], f["artificial_damping_coeff"], gvs, ga)
            if ftm_sums is not None:    # nodal mass and external force over the patch's nodes
                own = patch.slices(NC, patch.owned(NC))
                ftm_sums[4 * m] = gm[own].sum()
                ftm_sums[4 * m + 1:4 * m + 4] = fext[own].reshape(-1, 3).sum(axis=0)
                if m in self.ftm:       # moves with its initial grid velocity until ftm_grid_velocity
                    ga[...] = 0.0
                    gvs[...] = gv
        if ftm_sums is not None:
            new_dw.put_reduction(L.FTMForce, ftm_sums)

    def ex_mom_integrated(self, patch, matls, old_dw, new_dw):
        """Contact on the integrated velocities; a = (v* - v)/dt where it acts."""
        dt = old_dw.get_reduction(FL.delT)
        c = self.contact
        gm = {m: new_dw.get(L.gMass, m, patch) for m in matls}
        gv = {m: new_dw.get(L.gVelocity, m, patch) for m in matls}
        gvs = {m: new_dw.get_modifiable(L.gVelocityStar, m, patch) for m in matls}
        ga = {m: new_dw.get_modifiable(L.gAcceleration, m, patch) for m in matls}
        normals = {m: new_dw.get(L.gSurfNorm, m, patch) for m in c.materials} if c.needs_normals else None
        t = old_dw.get_reduction(FL.simTime) if c.needs_time else 0.0
        lr, color = self._lr(patch, new_dw)
        node_x = (self.level.anchor, self.level.dx, patch.low_index(NC))
        if c.type == "rigid":          # the reaction on the rigid body, before its velocity is imposed
            force, torque = c.reaction(gm, {m: new_dw.get(L.gIntForce, m, patch) for m in c.materials}, t,
                                       node_x, patch.owned_local(NC))
            new_dw.put_reduction(L.RigidReactionForce, force)
            new_dw.put_reduction(L.RigidReactionTorque, torque)
        before = {m: gvs[m].copy() for m in c.materials} if self.ftm_contact else None
        c.exchange(gm, gvs, ga, gv, dt, t=t, normals=normals, dx=self.level.dx, node_x=node_x, lr=lr, color=color,
                   traction=self._traction(new_dw, patch))
        if before is not None:      # the force the rigid body exerts, taken back by it (Uintah's STF)
            inner = tuple(slice(lo, hi) for lo, hi in zip(*patch.interior(NC)))     # no extra nodes, as Uintah
            force = np.zeros(3)
            for m in c.materials:
                dmv = (gm[m][..., None] * (gvs[m] - before[m]))[inner]
                force -= dmv.reshape(-1, 3).sum(axis=0) / dt
            new_dw.put_reduction(L.FTMContactForce, force)

    def set_grid_bcs(self, patch, matls, old_dw, new_dw):
        dt = old_dw.get_reduction(FL.delT)
        for m in matls:
            self.bcs.apply(patch, m, new_dw.get_modifiable(L.gVelocityStar, m, patch),
                           new_dw.get_modifiable(L.gAcceleration, m, patch),
                           new_dw.get(L.gVelocity, m, patch), dt)

    def insert_particles(self, patch, matls, old_dw, new_dw):
        """Uintah's insertParticles: the colours due in this step move and take their velocity."""
        from . import insert_particles
        time, dt = old_dw.get_reduction(FL.simTime), old_dw.get_reduction(FL.delT)
        for m in matls:
            insert_particles.insert(self.insertion, time, dt, old_dw.get(L.pColor, m, patch),
                                    new_dw.get_modifiable(L.pXpre, m, patch),
                                    new_dw.get_modifiable(L.pVelocityPre, m, patch))

    def set_prescribed_motion(self, patch, matls, old_dw, new_dw):
        """Uintah's setPrescribedMotion: v*_i = M x_i at the step's start time, a_i = 0 (prescribed.py)."""
        from . import prescribed
        M = prescribed.velocity_gradient(self.prescribed, old_dw.get_reduction(FL.simTime))
        low = np.array(patch.low_index(NC), np.int64)
        for m in matls:
            prescribed.set_nodes(M, np.asarray(self.level.anchor, float), np.asarray(self.level.dx, float), low,
                                 new_dw.get_modifiable(L.gVelocityStar, m, patch),
                                 new_dw.get_modifiable(L.gAcceleration, m, patch))

    def xpic_grid_velocity(self, patch, matls, old_dw, new_dw):
        """XPIC(2) (Hammerquist & Nairn 2017; Uintah's computeSSPlusVp and computeSPlusSSPlusVp in
        one pass): v+_p = sum S v_i at every owned and ghost particle, then g.velSPSSP =
        sum S m_p v+_p / m_i, the grid velocity smoothed twice through the particles. Rigid
        materials keep FLIP (zeros here, as Uintah)."""
        lv = self.level
        low = np.array(patch.low_index(NC), np.int64)
        for m in matls:
            out = new_dw.allocate(L.gVelSPSSP, m, patch, 0.0)
            if self.materials[m].is_rigid:
                continue
            own, ghost, runs = self._parts(old_dw, m, patch, [L.pX, L.pMass])
            self.xpic_spssp(tuple(own), tuple(ghost), runs, lv.anchor, lv.dx, low, new_dw.get(L.gVelocity, m, patch),
                            out)
            kernels.divide_by_mass(new_dw.get(L.gMass, m, patch), out, out)

    def ftm_grid_velocity(self, patch, matls, old_dw, new_dw):
        """Force-transmitting materials (Uintah's computeGridVelocityForFTM): a = F / M at every
        node, F the sum over the level of the material's nodal external forces (and, for the
        rigid contact's master, the force it exerts on the others, with the opposite sign), M
        its nodal mass; v* = v + a dt. SumTransmittedForce: all materials' external forces
        and that contact force."""
        dt = old_dw.get_reduction(FL.delT)
        sums = np.asarray(new_dw.get_reduction(L.FTMForce)).reshape(-1, 4)
        contact = np.asarray(new_dw.get_reduction(L.FTMContactForce)) if self.ftm_contact else np.zeros(3)
        for m in matls:
            force = sums[m, 1:] + (contact if self.ftm_contact and m == self.contact.master else 0.0)
            acc = force / sums[m, 0]
            ga = new_dw.get_modifiable(L.gAcceleration, m, patch)
            ga[...] = acc
            np.add(new_dw.get(L.gVelocity, m, patch), acc * dt, out=new_dw.get_modifiable(L.gVelocityStar, m, patch))
        first = patch.id == min(p.id for p in self.level.patches)     # the level's total, put once
        new_dw.put_reduction(L.SumTransmittedForce, sums[:, 1:].sum(axis=0) + contact if first else np.zeros(3))

    # -- grid -> particles ----------------------------------------------------------------------
    def interpolate_to_particles(self, patch, matls, old_dw, new_dw):
        """v_p += dt sum S a (000 eq. 26), x_p += dt sum S v* (eq. 27); totals; deletion by
        minimum_particle_mass / maximum_particle_velocity; one fused kernel (transfer.py).
        With <XPIC2> (not for rigid materials) v_p = 2 v+ - v++ + dt sum S a and
        x_p += dt (sum S v* - (dt sum S a + v_p - 2 v+ + v++) / 2), v+ = sum S v_i and
        v++ = sum S g.velSPSSP (xpic_grid_velocity), as Uintah's SerialMPM.

        USL: L_p = sum v*_i (x) grad S (000 eq. 23) for the stress update.
        MUSL (004 eqs. 11-14): the updated velocities of owned AND ghost particles are
        mapped back to the nodes, v^L_i = sum S m_p v_p^{k+1} / m_i, and the stress
        update takes L_p from v^L (next task): no node of little mass can hand a
        particle a large velocity gradient."""
        lv = self.level
        dt = old_dw.get_reduction(FL.delT)
        low = np.array(patch.low_index(NC), np.int64)
        tot = np.zeros(8)
        f = self.flags
        remapped = {}
        for m in matls:
            mat = self.materials[m]
            if self.musl:           # owned and ghost particles, the owned ones written
                own, ghost, runs = self._parts(old_dw, m, patch, [L.pX, L.pVelocity, L.pMass])
                n = n_own = len(own[0])
                gvl = remapped[m] = new_dw.allocate(L.gVelocityL, m, patch, 0.0)   # momentum, then velocity
                Lg, F_old, F_new, vol_new = _NOL, _NOL, _NOL, _NOV
            else:
                own, runs = self._parts(old_dw, m, patch, [L.pX, L.pVelocity, L.pMass])[::2]
                ghost, n = own, len(own[0])
                n_own, gvl = n, _NOG
                write_L = mat.uses_L or self.f_terms != 1
                Lg = np.empty((n, 3, 3)) if write_L else _NOL
                F_old = old_dw.get(L.pF, m, patch)
                F_new = new_dw.allocate(L.pFPre, m, patch, None)
                vol_new = new_dw.allocate(L.pVolumePre, m, patch, None)
            x_new = np.empty((n_own, 3))
            v_new = np.empty((n_own, 3))
            xpic = ((new_dw.get(L.gVelocity, m, patch), new_dw.get(L.gVelSPSSP, m, patch))
                    if self.xpic and not mat.is_rigid else None)
            self.g2p(self.musl, tuple(own), tuple(ghost), runs, lv.anchor, lv.dx, low,
                     new_dw.get(L.gVelocityStar, m, patch), new_dw.get(L.gAcceleration, m, patch), dt, x_new, v_new,
                     Lg, gvl, tot, f["minimum_particle_mass"], f["maximum_particle_velocity"],
                     mat.uses_L or (not self.musl and self.f_terms != 1), F_old, F_new, vol_new, mat.volume_density,
                     xpic=xpic)
            if not self.musl and self.f_terms != 1:     # Uintah's minimum_subcycles_for_F (prescribed.py)
                from .prescribed import deform_series
                deform_series(Lg, F_old, dt, self.f_terms, F_new, vol_new)
            if self.musl:
                kernels.divide_by_mass(new_dw.get(L.gMass, m, patch), gvl, gvl)
                if not self.contact.active:
                    self.bcs.apply(patch, m, gvl, np.empty_like(gvl), gvl, dt)
            else:
                if f["DoPressureStabilization"]:
                    self._stabilize(patch, own[0], dt, F_old, old_dw.get(L.pVolume, m, patch), F_new, vol_new, Lg)
                new_dw.put(L.pVelGrad, m, patch, Lg if mat.uses_L else _zeros33(n))
            new_dw.put(L.pXpre, m, patch, x_new)
            new_dw.put(L.pVelocityPre, m, patch, v_new)
        if self.musl and self.contact.active:
            self._contact_remapped(patch, matls, old_dw, new_dw, dt, remapped)
        self._put_totals(new_dw, tot)

    def _stabilize(self, patch, px, dt, F_old, vol_old, F_new, vol_new, Lg):
        """<DoPressureStabilization>: F_new and L_p of the owned particles (p.x at the step's
        start) take their cell's mean J, V_new follows V_old (kernels.pressure_stabilization)."""
        lv = self.level
        kernels.pressure_stabilization(px, lv.anchor, lv.dx, np.array(patch.lo), np.array(patch.hi),
                                       np.array(self.dims), dt, F_old, vol_old, F_new, vol_new, Lg)

    def _contact_remapped(self, patch, matls, old_dw, new_dw, dt, gvl):
        """MUSL with contact: the remapped velocities v^L get the same contact as v*
        (USL's L comes from the contacted v*), then the grid BCs."""
        c = self.contact
        gm = {m: new_dw.get(L.gMass, m, patch) for m in matls}
        normals = {m: new_dw.get(L.gSurfNorm, m, patch) for m in c.materials} if c.needs_normals else None
        t = old_dw.get_reduction(FL.simTime) if c.needs_time else 0.0
        lr, color = self._lr(patch, new_dw)
        c.exchange(gm, gvl, None, None, dt, t=t, normals=normals, dx=self.level.dx,
                   node_x=(self.level.anchor, self.level.dx, patch.low_index(NC)), lr=lr, color=color,
                   traction=self._traction(new_dw, patch))
        for m in matls:
            self.bcs.apply(patch, m, gvl[m], np.empty_like(gvl[m]), gvl[m], dt)

    def _owned(self, old_dw, patch, m, px):
        """Which of the owned + ghost particles the patch owns."""
        if hasattr(old_dw, "ghost_owned_mask"):
            own = old_dw.ghost_owned_mask(L.pX, m, patch)
            return np.ones(len(px), np.bool_) if own is None else own
        lv = self.level
        own = np.empty(len(px), np.bool_)
        kernels.owned_mask(px, lv.anchor, lv.dx, np.array(patch.lo), np.array(patch.hi),
                           np.array(self.dims), own)
        return own

    def _velocity_gradient(self, patch, m, old_dw, new_dw, dt, pm, F_old, F_new, vol_new, stress=None):
        """MUSL: L_p = sum v^L_i (x) grad S_i(x_p) (004 eqs. 13-14) for the owned particles,
        and F, V from it in the same pass; returns L_p (a stand-in if the model needs F only)
        and the wave speed. stress = (velocity, stress out, energy out): a model in
        transfer.FUSED computes them in that pass too (the wave speed is zero otherwise)."""
        lv = self.level
        mat = self.materials[m]
        px = old_dw.get(L.pX, m, patch)
        n = len(px)
        Lg = np.empty((n, 3, 3)) if mat.uses_L else _NOL
        if stress is None:
            model, K, mu, stress = 0, 0.0, 0.0, (_NOF, _NOL, _NOV)
        else:
            model, K, mu = transfer.FUSED[mat.model_name], mat.params.bulk_modulus, mat.params.shear_modulus
        ws = self.grad(px, self._lp(old_dw, m, patch, n), lv.anchor, lv.dx,
                       np.array(patch.low_index(NC), np.int64), new_dw.get(L.gVelocityL, m, patch), Lg,
                       mat.uses_L, dt, pm, mat.volume_density, F_old, F_new, vol_new, model, K, mu, *stress)
        return Lg, np.array(ws)

    def membrane_tangents(self, patch, matls, old_dw, new_dw):
        """004 sec. 3.2: the unit tangent of each owned membrane point from its neighbours
        in the numbering (ID - 1, ID + 1; owned or ghost particles, one cell around), at the
        positions this step starts from; zero where a neighbour is not found (the stress
        update then keeps the convected tangent)."""
        for m in matls:
            mat = self.materials[m]
            px = old_dw.get(L.pX, m, patch)
            own = self._owned(old_dw, patch, m, px)
            n_own = int(np.count_nonzero(own))
            out = np.zeros((n_own, 3))
            if mat.is_membrane and n_own:
                ids = old_dw.get(L.pID, m, patch)
                obj = ids >> 40
                idx = ids & ((1 << 40) - 1)
                k = obj - self._obj_base(m)
                nlen = np.array([len(o["chain"]) for o in mat.objects])[k]
                closed = np.array([o["closed"] for o in mat.objects])[k]
                prev = np.where(closed, (idx - 1) % nlen, np.maximum(idx - 1, 0)) + (obj << 40)
                nxt = np.where(closed, (idx + 1) % nlen, np.minimum(idx + 1, nlen - 1)) + (obj << 40)
                ip = np.minimum(np.searchsorted(ids, prev), len(ids) - 1)
                inx = np.minimum(np.searchsorted(ids, nxt), len(ids) - 1)
                ok = (ids[ip] == prev) & (ids[inx] == nxt)
                d = px[inx] - px[ip]
                nrm = np.linalg.norm(d, axis=1)
                ok &= nrm > 0
                t = np.zeros_like(d)
                t[ok] = d[ok] / nrm[ok, None]
                out[:] = t[own]
            new_dw.put(L.pTangentNbr, m, patch, out)

    def artificial_viscosity_scale(self, patch, matls, old_dw, new_dw):
        """Per fluid material with artificial viscosity: the largest sound speed and |div v|
        of its particles on this patch, max-reduced over the level (004 eq. 24 scales q with
        them: a per-patch maximum would make the answer depend on the patch layout)."""
        from .constitutive.ideal_gas_fluid import av_scale
        dt = old_dw.get_reduction(FL.delT)
        out = np.zeros(32)
        for m in matls:
            if m not in self.av_matls:
                continue
            if self.musl:
                pm = old_dw.get(L.pMass, m, patch)
                n = len(pm)
                Lg = self._velocity_gradient(patch, m, old_dw, new_dw, dt, pm, old_dw.get(L.pF, m, patch),
                                             np.empty((n, 3, 3)), np.empty(n))[0]
            else:
                Lg = new_dw.get(L.pVelGrad, m, patch)
            out[2 * m], out[2 * m + 1] = av_scale(self.materials[m].params.gamma, Lg,
                                                  old_dw.get(L.pIntEnergy, m, patch))
        new_dw.put_reduction(L.AVScale, out)

    def compute_stress_tensor(self, patch, matls, old_dw, new_dw):
        """F, V (004 eqs. 14, 17) and the stress from the constitutive model; strain energy
        (the total: rate models accumulate their increments in p.strainEnergy; and, for
        AccStrainEnergy, Uintah's StrainEnergy: the rate models' increments of the step, the
        others' totals); wave speed
        (c + |v| with the velocity the step started with, as Uintah's models)."""
        dt = old_dw.get_reduction(FL.delT)
        ws = np.zeros(3)
        se = se_step = 0.0
        for m in matls:
            mat = self.materials[m]
            pm = old_dw.get(L.pMass, m, patch)
            F_old = old_dw.get(L.pF, m, patch)
            n = len(F_old)
            s_new = new_dw.allocate(L.pStressPre, m, patch, None)
            energy = np.empty(n)
            fused = (self.musl and mat.model_name in transfer.FUSED and mat.damage is None      # stress in the grad pass
                     and not self.flags["DoPressureStabilization"])
            if self.musl:
                F_new = new_dw.allocate(L.pFPre, m, patch, None)
                vol_new = new_dw.allocate(L.pVolumePre, m, patch, None)
                Lg, w = self._velocity_gradient(patch, m, old_dw, new_dw, dt, pm, F_old, F_new, vol_new,
                                                (old_dw.get(L.pVelocity, m, patch), s_new, energy) if fused
                                                else None)
                if self.flags["DoPressureStabilization"]:
                    self._stabilize(patch, old_dw.get(L.pX, m, patch), dt, F_old, old_dw.get(L.pVolume, m, patch),
                                    F_new, vol_new, Lg)
            else:                                   # F and V were computed with L_p by g2p
                Lg = new_dw.get(L.pVelGrad, m, patch)
                F_new = new_dw.get(L.pFPre, m, patch)
                vol_new = new_dw.get(L.pVolumePre, m, patch)
                if mat.erodes_F:            # the erosion sets F of localized particles
                    F_new = F_new.copy()
                    new_dw.replace(L.pFPre, m, patch, F_new)
            if getattr(mat.params, "density_from_grid", False):    # fluid points (ideal_gas_fluid)
                lv = self.level
                gvol = {k: new_dw.get(L.gVolume, k, patch) for k in matls     # membranes: no area
                        if k == m or not self.materials[k].is_membrane}
                mat.model.grid_volumes(old_dw.get(L.pX, m, patch), lv.anchor, lv.dx, np.array(lv.ncells),
                                       np.array(lv.periodic), np.array(patch.low_index(NC), np.int64),
                                       new_dw.get(L.gMass, m, patch), gvol[m], sum(gvol.values()), pm, vol_new,
                                       self.axisymmetric)
            old = new = None
            olds, news = {}, {}
            for final, pre in self.carry:
                if final.name in L.STATE:
                    if final.name in mat.state_names:
                        olds[final.name] = old_dw.get(final, m, patch)
                        news[final.name] = np.empty((n,) + final.shape)
                        new_dw.put(pre, m, patch, news[final.name])
                    else:
                        new_dw.put(pre, m, patch, old_dw.get(final, m, patch))
            if len(mat.state_names) == 1:
                old, new = olds[mat.state], news[mat.state]
            elif mat.state_names:
                old, new = tuple(olds[k] for k in mat.state_names), tuple(news[k] for k in mat.state_names)
            if mat.needs_temperature:   # the model's p.dTdt is added to p.temperature+ below
                dTdt = np.empty(n)
                old, new = old + (old_dw.get(L.pTemperature, m, patch),), new + (dTdt,)
            if mat.is_membrane:         # 004 sec. 3.2: the model convects t, h and sets V
                t_new, h_new = np.empty((n, 3)), np.empty(n)
                new_dw.put(L.pTangentPre, m, patch, t_new)
                new_dw.put(L.pThicknessPre, m, patch, h_new)
                t_old = old_dw.get(L.pTangent, m, patch)
                t_nbr = new_dw.get(L.pTangentNbr, m, patch)
                t_old = np.where(np.any(t_nbr != 0.0, axis=1)[:, None], t_nbr, t_old)
                old = (np.ascontiguousarray(t_old), old_dw.get(L.pThickness, m, patch),
                       old_dw.get(L.pVolume, m, patch))
                new = (t_new, h_new, vol_new)
            elif self.has_membrane:
                for final, pre in ((L.pTangent, L.pTangentPre), (L.pThickness, L.pThicknessPre)):
                    new_dw.put(pre, m, patch, old_dw.get(final, m, patch))
            scale = None
            if m in getattr(self, "av_matls", ()) and getattr(self, "_av_level_wide", False):
                sc = new_dw.get_reduction(L.AVScale)
                scale = (float(sc[2 * m]), float(sc[2 * m + 1]))
            if fused:
                ws = np.maximum(ws, w)
            else:
                temp = old_dw.get(L.pTemperature, m, patch) if mat.uses_temperature and self.thermal else None
                ws = np.maximum(ws, self._constitutive(mat, Lg, F_old, F_new, vol_new, pm,
                                                       old_dw.get(L.pVelocity, m, patch), dt,
                                                       old_dw.get(L.pStress, m, patch), s_new, energy, old,
                                                       new, scale, temp,
                                                       old_dw.get(L.pColor, m, patch) if self.flags["withColor"]
                                                       else None,
                                                       old_dw.get_reduction(FL.simTime) if mat.needs_time
                                                       else 0.0))
            if self.projection:         # L_p for the next step's projection, eroded as Uintah's
                if mat.erodes_F:
                    Lg = damage.erode_kinematics(mat.erosion, old_dw.get(L.STATE["p.localizedMPM"][0], m, patch),
                                                 F_old, F_new.copy(), Lg)
                new_dw.put(L.pVelGradLastPre, m, patch, Lg)
            if self.av:                 # p.q for the next step's internal force (artificial_viscosity.py)
                q = self.av.q(m, mat, Lg, F_new, pm, vol_new)
                new_dw.put(L.pQPre, m, patch, q)
                if mat.needs_temperature and "p.energy" in news:     # elastic_plastic_hp's viscous heating
                    self.av.heat(mat, q, Lg, F_old, F_new, pm, vol_new, old[-1], dTdt, news["p.energy"])
            if mat.needs_temperature:   # Uintah's finalParticleUpdate: T += dT/dt dt
                new_dw.put(L.pdTdt, m, patch, dTdt)
                T_new = new_dw.get(L.pTemperaturePre, m, patch)
                T_new += dTdt * dt
            se_step += energy.sum()
            if any(f is L.pStrainEnergy for f, _ in self.carry):
                if mat.increment_energy:
                    energy = old_dw.get(L.pStrainEnergy, m, patch) + energy
                new_dw.put(L.pStrainEnergyPre, m, patch, energy)
            se += energy.sum()
            for final, pre in self.carry:
                if final in (L.pMass, L.pID, L.pSize, L.pSizeMatrix, L.pColor, L.pLoadCurveID, L.pSurface):
                    new_dw.put(pre, m, patch, old_dw.get(final, m, patch))
            if self.mms or self.saves_disp:
                new_dw.put(L.pDispPre, m, patch, old_dw.get(L.pDisp, m, patch) + new_dw.get(L.pXpre, m, patch)
                           - old_dw.get(L.pX, m, patch))
            if self.saves_scale:
                new_dw.put(L.pScaleFactorPre, m, patch, scale_factor(F_new, old_dw.get(self._size_label, m, patch)))
            if self.pressure_bcs:
                lcid = old_dw.get(L.pLoadCurveID, m, patch)
                px_old = old_dw.get(L.pX, m, patch)
                new_dw.put(L.pExtForcePre, m, patch, self._ext_force(old_dw, m, patch, px_old))
                if self.pressure_bcs.heat_flux:        # this step's heat rates (thermal.py), for output
                    new_dw.put(L.pExternalHeatRatePre, m, patch, self.pressure_bcs.heat_rates(
                        px_old, lcid, old_dw.get_reduction(FL.simTime), old_dw.get_reduction(L.PressureBCParticles)))
                new_dw.put_reduction(L.PressureBCParticles, self.pressure_bcs.counts(lcid))
        new_dw.put_reduction(L.StrainEnergy, se)
        if self.saves_acc_energy:
            new_dw.put_reduction(L.StepStrainEnergy, se_step)
        new_dw.put_reduction(L.WaveSpeed, ws)
