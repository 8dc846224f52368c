"""ICE task bodies, in the order of paper 000 sec. 3.3 (steps 2-12).

Each task gets arrays from the warehouses, calls kernels (kernels.py, advection.py,
bc.py) and puts its results. Index boxes of a patch are cached in `_boxes`.
"""
from __future__ import annotations

import math
import operator

import numpy as np

from framework import labels as L
from framework.geometry import cell_fractions
from framework.variables import VarType

from . import advection as A
from . import custom_init as CI
from . import equilibration as E
from . import kernels as K
from . import labels as I
from . import slip_exchange as SL

FC_TYPES = (VarType.SFCX, VarType.SFCY, VarType.SFCZ)
UNIT = np.eye(3, dtype=np.int64)
DELT_START = 1000.0     # s: the value Uintah's actuallyComputeStableTimestep starts its minimum from
# advection_faces: ICE alone moves nothing besides the fluxes (and needs no pressure for their flow work)
_NO_TRANSFERS = (np.zeros((1, 1, 1)),) * 3
_NO_PRESS = np.zeros((1, 1, 1))
_NO_TMV = np.zeros((0, 0, 0))      # lagrangian: the flow work over the cell's volume (ICE alone)


class Boxes:
    """Local index ranges of one patch: interior/owned cells, faces of interior cells."""

    def __init__(self, patch, dims):
        lv = patch.level
        self.lo, self.hi = (np.array(x, dtype=np.int64) for x in patch.interior(VarType.CC))
        self.olo, self.ohi = (np.array(x, dtype=np.int64) for x in patch.owned_local(VarType.CC))
        cc0 = np.array(patch.low_index(VarType.CC))
        self.sh, self.flo, self.fhi = [], [], []
        for d in range(3):
            vt = FC_TYPES[d]
            f0 = np.array(patch.low_index(vt))
            glo = np.array(patch.lo)
            ghi = np.array(patch.hi) + (UNIT[d] if dims[d] else 0)
            self.sh.append((f0 - cc0).astype(np.int64) if dims[d] else np.zeros(3, np.int64))
            self.flo.append((glo - f0).astype(np.int64))
            self.fhi.append((ghi - f0).astype(np.int64))
        self.vol = float(np.prod(lv.dx))
        # advection works on views with the collapsed axes first, so that the last axis
        # (unit stride) is a long one: a 2D run's arrays (nx, ny, 1) are seen as (1, nx, ny)
        self.perm = np.array([d for d in range(3) if not dims[d]] + [d for d in range(3) if dims[d]],
                             dtype=np.int64)
        p = self.perm
        self.identity = bool(np.all(p == np.arange(3)))
        self._pick = operator.itemgetter(*p)
        self.v_lo, self.v_hi = self.lo[p], self.hi[p]
        self.v_olo, self.v_ohi = self.olo[p], self.ohi[p]
        self.axis = np.argsort(p)                           # the view axis of each direction
        self.v_dims = np.asarray(dims)[p]
        self.v_dx = np.asarray(lv.dx, dtype=np.float64)[p]
        self.v_sh = np.array([self.sh[d][p] for d in p])
        self.v_flo = np.array([self.flo[d][p] for d in p])
        self.v_fhi = np.array([self.fhi[d][p] for d in p])

    def view(self, a):
        """a (a stored array) with its axes in the order perm: free, collapsed axes have length 1.
        Never a copy, so writes always reach the stored array (a non-contiguous array gets a
        view whose .shape assignment raises if it would need one)."""
        if self.identity:
            return a
        shape = self._pick(a.shape) + a.shape[3:]
        if a.flags.c_contiguous:
            return a.reshape(shape)
        r = a.view()
        r.shape = shape
        return r


class IceTasks:
    model_volume_sources = None     # f(patch, matls, new_dw, sp_vol_L arrays): reactions' volume (MPMICE)
    """Task callbacks of the ICE component (mixed into the component class)."""

    press_floor = -np.inf       # lowest press_CC (eq. 30); MPMICE clamps at 1e-12 as Uintah does
    turbulence = None           # <turbulence> (turbulence.py), set by ICE.problem_setup

    def boxes(self, patch) -> Boxes:
        key = (patch.id, tuple(patch.level.halo.values()))     # the level's halo per type, in GRID_TYPES order
        b = self._geom_cache.get(key)
        if b is None:
            b = self._geom_cache[key] = Boxes(patch, self.dims)
        return b

    def _scratch(self, name, shape):
        """A work array of this shape: a view of one buffer per name, kept between calls and
        grown when a larger patch needs it (tasks run one at a time on a rank)."""
        cache = self.__dict__.setdefault("_scratch_arrays", {})
        size = int(math.prod(shape))
        a = cache.get(name)
        if a is None or a.size < size:
            a = cache[name] = np.empty(size)
        return a[:size].reshape(shape)

    def _eos(self, m):
        return self.codes[m], self.params[m], self.cvs[m], self.gammas[m]

    def _cv_model(self, m):
        """Material m's <SpecificHeatModel> (specific_heat.py), None without one."""
        return getattr(self.materials[m], "cv_model", None)

    def _cv(self, dw, m, patch, view=None):
        """Material m's cv in this step: its <specific_heat>, or with a <SpecificHeatModel> the
        field specific_heat (one value per cell) that the step computed, seen through view (a
        Boxes.view) when given."""
        if self._cv_model(m) is None and m not in self.caloric:
            return self.cvs[m]
        cv = dw.get(I.specific_heat, m, patch)
        return cv if view is None else view(cv)

    def _gamma(self, dw, m, patch, view=None):
        """Material m's gamma: <gamma>, or the mixture's per cell where a model owns its caloric EOS."""
        if m not in self.caloric:
            return self.gammas[m]
        g = dw.get(I.gamma, m, patch)
        return g if view is None else view(g)

    def _carrier_cv(self, m, patch, temp, y_dw, lo, hi, view=None):
        """The cv with which m cv T is the energy ICE carries: _cv, or e_s(T, Y) / T over [lo, hi)
        where a model owns the material's caloric EOS (Y from y_dw)."""
        model = self.caloric.get(m)
        if model is None:
            return self._cv(y_dw, m, patch, view)
        cv = model.carrier_cv(patch, temp, y_dw, lo, hi)
        return cv if view is None else view(cv)

    def _faces(self, dw, labels, m, patch):
        """The three face arrays of a material (a 1-element dummy for absent directions)."""
        dummy = np.zeros((1, 1, 1))
        return [dw.get(labels[d], m, patch) if self.dims[d] else dummy for d in range(3)]

    # -- initialization -----------------------------------------------------------------------
    def initialize(self, patch, matls, old_dw, new_dw):
        """Uintah's ICEMaterial::initializeCells and ICE::actuallyInitialize: a material takes
        rho_micro (the deck's <density>), T and velocity from the last of its geometry objects
        that covers a cell (its first object where none does), its volume fraction from the
        objects' cell fractions (1 where a lone material covers any of a cell), and
        rho_CC = rho_micro (theta + tiny_rho); press_CC is the EOS pressure of the last material.

        One difference, in cells a material does not cover at all (its trace of tiny_rho):
        Uintah gives it its first object's density there, so a trace of water in air starts at
        1000 kg/m^3 and the first steps compress or expand it by orders of magnitude, which
        heats it to absurd temperatures that then set delT; pysus gives it the micro density of
        the covering materials' pressure at its temperature."""
        b = self.boxes(patch)
        own = patch.owned(VarType.CC)
        lv = patch.level
        sl = patch.slices(VarType.CC, own)
        shape = tuple(h - l for l, h in zip(*own))
        many = len(self.materials) > 1
        state = []
        for m, mat in enumerate(self.materials):
            g0 = mat.objects[0][1]
            theta = np.zeros(shape)
            rho_micro, temp = np.full(shape, g0["density"]), np.full(shape, g0["temperature"])
            vel = np.broadcast_to(np.array(g0["velocity"], float), shape + (3,)).copy()
            for piece, g in mat.objects:
                f = cell_fractions(piece, lv, own, g["res"])
                hit = f > 0.0
                if not many:
                    theta[hit] = 1.0
                elif g["volumeFraction"] == -1.0:
                    theta += f
                else:
                    theta = g["volumeFraction"] * f
                rho_micro[hit], temp[hit], vel[hit] = g["density"], g["temperature"], g["velocity"]
            state.append((theta, rho_micro, temp, vel))
        if many:
            covered_p, covered = np.zeros(shape), np.zeros(shape)
            for m, (theta, rho_micro, temp, _) in enumerate(state):
                covered_p += theta * _press_array(rho_micro, temp, *self._eos(m))
                covered += theta
            p_cover = covered_p / np.maximum(covered, 1e-300)
            for m, (theta, rho_micro, temp, _) in enumerate(state):
                trace = (theta == 0.0) & (covered > 0.0)
                if trace.any():
                    rho_micro[trace] = _rho_micro_array(p_cover[trace], temp[trace], float(rho_micro[trace][0]),
                                                        *self._eos(m))
        p_arr = new_dw.allocate(I.press_CC, 0, patch)
        arrs_by_m = {}
        vortices = self.custom_init is not None and self.custom_init.vortices is not None
        for m, (mat, (theta, rho_micro, temp, vel)) in enumerate(zip(self.materials, state)):
            arrs = [new_dw.allocate(lab, m, patch) for lab in (I.rho_CC, I.vel_CC, I.temp_CC, I.sp_vol_CC,
                                                                I.speedSound_CC)]
            arrs[0][sl] = rho_micro * theta + mat.tiny_rho * rho_micro
            arrs[1][sl] = vel
            if self.custom_init is not None:        # <customInitialization>: profiles over the geometry's velocity
                self.custom_init.apply(arrs[1], self.custom_profiles[m], b.olo, b.ohi,
                                       np.array(patch.low_index(VarType.CC), dtype=np.int64))
            arrs[2][sl] = temp
            if self.custom_init is not None and self.custom_init.gauss is not None:
                # gaussianTemperature: before the EOS pressure and sound speed, as Uintah's (interior cells)
                self.custom_init.temperature(arrs[2], b.lo, b.hi, np.array(patch.low_index(VarType.CC)))
                temp = arrs[2][sl]
            arrs[3][sl] = 1.0 / rho_micro
            model = self._cv_model(m)
            eos = self._eos(m)
            if model is not None:           # cv(T) of the cells' own temperature
                cv_own = np.empty(temp.shape)
                model.fill(temp, cv_own)
                eos = (eos[0], eos[1], cv_own, eos[3])
            p_arr[sl] = _press_array(rho_micro, temp, *eos)
            if vortices:
                # Uintah's doesComputePressure: the objects' <pressure>, then the vortices' own
                p_arr[sl] = self._deck_pressure(mat, patch, own, shape)
                self.custom_init.add_vortices(arrs[1], p_arr, arrs[0], b.lo, b.hi,
                                              np.array(patch.low_index(VarType.CC), dtype=np.int64))
            # extra cells outside every geometry object get their boundary values
            self.bcs.scalar(patch, arrs[0], "Density", m, b)
            self.bcs.scalar(patch, arrs[2], "Temperature", m, b)
            self.bcs.velocity(patch, arrs[1], m, b, initial=True)
            self.bcs.scalar(patch, arrs[3], "Temperature", m, b, copy=True)
            arrs_by_m[m] = arrs[3]
            eos = self._eos(m)
            cv_field = self._thermo_fields(patch, m, arrs[2], new_dw)   # Uintah's: after T's conditions
            if model is not None:
                eos = (eos[0], eos[1], cv_field, eos[3])
            _speed_sound(arrs[3], arrs[2], arrs[4], *eos)
        self.bcs.scalar(patch, p_arr, "Pressure", 0, b)
        if vortices:                # the sound speed at the vortices' pressure, extra cells included
            CI.speed_sound_at_pressure(arrs[3], arrs[2], p_arr, arrs[4], b.olo, b.ohi, *eos)
        if self.hydrostatic:        # Uintah's initializeSubTask_hydrostaticAdj, extra cells included
            K.hydrostatic_adjust(p_arr, 1.0 / arrs_by_m[self.surrounding], self.gravity,
                                 patch.level.anchor + np.array(patch.low_index(VarType.CC)) * patch.level.dx,
                                 patch.level.anchor, patch.level.dx, b.olo, b.ohi)

    @staticmethod
    def _deck_pressure(mat, patch, own, shape):
        """The <pressure> of the material's last geometry object covering each cell (its first
        object's where none does): Uintah's initializeCells."""
        press = np.full(shape, mat.objects[0][1]["pressure"])
        for piece, g in mat.objects:
            press[cell_fractions(piece, patch.level, own, g["res"]) > 0.0] = g["pressure"]
        return press

    def stable_timestep_step(self, patch, matls, old_dw, new_dw):
        """stable_timestep at a step's end: a model owning a material's caloric EOS gives its
        cells' own viscosity and thermal conductivity (at the start, the material's values)."""
        self.stable_timestep(patch, matls, old_dw, new_dw, per_cell_transport=True)

    def stable_timestep(self, patch, matls, old_dw, new_dw, per_cell_transport=False):
        """Uintah's delT (ICE::actuallyComputeStableTimestep): 'aggressive' (the default) is
        cfl min dx / (knob c + |u|) over cells, materials and directions, and the diffusion
        limit cfl / (2 D sum 1/dx^2); 'conservative' is cfl vol / swept outflow volume. Like
        Uintah, every direction counts, one-cell ones too, unless <delT_activeDirectionsOnly>.
        Implicit ICE takes the same step (as Uintah). A fluid at rest with knob 0 gets Uintah's
        start value DELT_START, then the deck's delt_max and max_delt_increase. With
        <delT_traceVolFrac> a material's sound speed counts only where its volume fraction
        (rho_CC sp_vol_CC) reaches that value."""
        b = self.boxes(patch)
        count = self.dims if self.delt_active_dirs_only else np.ones(3, dtype=bool)
        dx = patch.level.dx
        dt = np.inf
        for m in matls:
            mat = self.materials[m]
            vel, speed_sound, sp_vol = (new_dw.get(lab, m, patch) for lab in (I.vel_CC, I.speedSound_CC, I.sp_vol_CC))
            if self.delt_trace_vol_frac > 0.0:      # a trace's sound speed aside; c + |u| = 0 gives inf
                trace = new_dw.get(I.rho_CC, m, patch) * sp_vol < self.delt_trace_vol_frac
                speed_sound = np.where(trace, 0.0, speed_sound)
            cp = mat.cv * mat.gamma
            if self._cv_model(m) is not None:       # the field's smallest cp: the largest diffusivity
                sl = tuple(slice(l, h) for l, h in zip(b.lo, b.hi))
                cp = float(new_dw.get(I.specific_heat, m, patch)[sl].min()) * mat.gamma
            if self.conservative_dt:
                grav_vel = float(np.sqrt(np.sum(dx * np.abs(self.gravity))))
                dt = min(dt, K.stable_dt_swept(vel, speed_sound, sp_vol, cp, count, self.dims, dx, b.lo,
                                               b.hi, self.knob, mat.conductivity, mat.viscosity, grav_vel))
                continue
            dt = min(dt, K.stable_dt(vel, speed_sound, count, dx, b.lo, b.hi, np.arange(3), self.knob))
            if m in self.caloric and (mat.viscosity > 0 or mat.conductivity > 0):
                # Uintah's per-cell limit with the mixture's cv, gamma and (after a step) mu, k
                inv_sum = sum(1.0 / dx[d] ** 2 for d in range(3) if count[d])
                shape = patch.alloc_shape(VarType.CC)
                if per_cell_transport:
                    k_cells, mu_cells = new_dw.get(I.thermalCond, m, patch), new_dw.get(I.viscosity, m, patch)
                else:
                    k_cells, mu_cells = np.full(shape, mat.conductivity), np.full(shape, mat.viscosity)
                dt = min(dt, K.stable_dt_diffusion_cells(new_dw.get(I.specific_heat, m, patch),
                                                         new_dw.get(I.gamma, m, patch), k_cells, mu_cells, sp_vol,
                                                         b.lo, b.hi, self.knob_diffusion, inv_sum))
            elif mat.viscosity > 0 or mat.conductivity > 0:
                sl = tuple(slice(l, h) for l, h in zip(b.lo, b.hi))
                diffusivity = self.knob_diffusion * float(sp_vol[sl].max()) * max(
                    mat.conductivity / cp, mat.viscosity)
                inv_sum = sum(1.0 / dx[d] ** 2 for d in range(3) if count[d])
                dt = min(dt, 0.5 / (inv_sum * max(diffusivity, 1e-300)))
        new_dw.put_reduction(L.delT, min(self.cfl * dt, DELT_START))

    def specific_heat_field(self, patch, matls, old_dw, new_dw):
        """specific_heat = cv(temp_CC) of the step's start in every cell, extra cells included, and
        gamma (Uintah's computeThermoTransportProperties)."""
        for m in matls:
            self._thermo_fields(patch, m, old_dw.get(I.temp_CC, m, patch), new_dw, old_dw)

    def _thermo_fields(self, patch, m, temp, new_dw, y_dw=None):
        """Material m's specific_heat (its model's cv(temp), else <specific_heat>) and gamma
        (<gamma>, as sus: see specific_heat.py) in a patch's own cells; returns specific_heat.
        A model owning the material's caloric EOS gives the mixture's cv and gamma at (temp, Y of
        y_dw) (at the start, before its Y exist, the deck's values, which the model then sets)."""
        b = self.boxes(patch)
        own = tuple(slice(l, h) for l, h in zip(b.olo, b.ohi))
        cv = new_dw.allocate(I.specific_heat, m, patch)
        gamma = new_dw.allocate(I.gamma, m, patch)
        model = self._cv_model(m)
        if m in self.caloric and y_dw is not None:
            self.caloric[m].thermo(patch, temp, cv, gamma, y_dw, b.olo, b.ohi)
            return cv
        if model is None:
            cv[own] = self.cvs[m]
        else:
            model.fill(temp, cv, b.olo, b.ohi)
        gamma[own] = self.gammas[m]
        return cv

    # -- step 2: equilibration pressure (eq. 13) ------------------------------------------------
    def equilibration_pressure(self, patch, matls, old_dw, new_dw):
        b = self.boxes(patch)
        peq = new_dw.allocate(I.press_equil_CC, 0, patch)
        if len(matls) == 1:
            out = [new_dw.allocate(lab, 0, patch) for lab in (I.sp_vol_CC, I.vol_frac_CC, I.speedSound_CC)]
            v = b.view
            K.equilibrate_one(v(old_dw.get(I.rho_CC, 0, patch)), v(old_dw.get(I.temp_CC, 0, patch)), v(out[0]),
                              v(peq), v(out[1]), v(out[2]), self.codes[0], self.params[0],
                              self._cv(new_dw, 0, patch, v), self._gamma(new_dw, 0, patch, v), b.v_olo, b.v_ohi)
        else:
            get = lambda lab: tuple(old_dw.get(lab, m, patch) for m in matls)
            new = lambda lab: tuple(new_dw.allocate(lab, m, patch) for m in matls)
            spv, vfs, css = new(I.sp_vol_CC), new(I.vol_frac_CC), new(I.speedSound_CC)
            if self.all_ideal:
                v = b.view
                K.equilibrate_ideal(tuple(v(a) for a in get(I.rho_CC)), tuple(v(a) for a in get(I.temp_CC)),
                                    tuple(v(a) for a in spv), tuple(v(a) for a in vfs), tuple(v(a) for a in css),
                                    v(peq), self.cvs, self.gammas, b.v_olo, b.v_ohi)
            else:
                v = b.view
                E.equilibrate(tuple(v(a) for a in get(I.rho_CC)), tuple(v(a) for a in get(I.temp_CC)),
                              tuple(v(a) for a in get(I.sp_vol_CC)), v(old_dw.get(I.press_CC, 0, patch)),
                              tuple(v(a) for a in spv), tuple(v(a) for a in vfs), tuple(v(a) for a in css), v(peq),
                              self.codes, self.params, self.cvs, self.gammas, b.v_olo, b.v_ohi, 1e-11, self.max_iter,
                              False)      # given, not defaulted: the specialisation MPMICE compiles
        if self.hydrostatic:
            sp_vol_surr = out[0] if len(matls) == 1 else spv[self.surrounding]
        if self.lodi is not None:       # one material (component._check_lodi)
            self.lodi_press(patch, peq, out[2], old_dw, new_dw)
        self.press_bc(patch, peq, sp_vol_surr if self.hydrostatic else None)

    def press_bc(self, patch, press, sp_vol_surr=None):
        """press_CC's boundary conditions; with gravity, Uintah's hydrostatic adjustment of the
        extra cells from the surrounding material's rho_micro = 1 / sp_vol (BoundaryCond.cc)."""
        b = self.boxes(patch)
        self.bcs.scalar(patch, press, "Pressure", 0, b)
        if self.hydrostatic:
            self.bcs.hydrostatic_pressure(patch, press, sp_vol_surr, self.gravity, b)

    # -- step 3: face velocities (eq. 28) and their exchange --------------------------------------
    def vel_fc(self, patch, matls, old_dw, new_dw):
        b = self.boxes(patch)
        dt = old_dw.get_reduction(L.delT)
        peq = new_dw.get(I.press_equil_CC, 0, patch)
        for m in matls:
            rho, vel = old_dw.get(I.rho_CC, m, patch), old_dw.get(I.vel_CC, m, patch)
            spv = new_dw.get(I.sp_vol_CC, m, patch)
            for d in range(3):
                if not self.dims[d]:
                    continue
                uf = new_dw.allocate(I.FC_VEL[d], m, patch)
                a, v = b.axis[d], b.view
                K.face_velocity(v(rho), v(vel), v(spv), v(peq), v(uf), b.v_sh[a], UNIT[a], d, b.v_flo[a], b.v_fhi[a],
                                dt, patch.level.dx[d], self.gravity[d])
                self.bcs.face_velocity(patch, uf, d, m, b.flo[d], b.fhi[d])
                if not self.exchange and not self.implicit:
                    new_dw.put(I.FC_VEL_ME[d], m, patch, uf)   # one material: the exchange is the identity

    def exchange_fc(self, patch, matls, old_dw, new_dw):
        b = self.boxes(patch)
        dt = old_dw.get_reduction(L.delT)
        vfs = tuple(new_dw.get(I.vol_frac_CC, m, patch) for m in matls)
        sps = tuple(new_dw.get(I.sp_vol_CC, m, patch) for m in matls)
        coeffs = self.face_exchange_coefficients(new_dw, patch, b.view)
        for d in range(3):
            if not self.dims[d]:
                continue
            ufs = tuple(new_dw.get(I.FC_VEL[d], m, patch) for m in matls)
            out = tuple(new_dw.allocate(I.FC_VEL_ME[d], m, patch) for m in matls)
            a, v = b.axis[d], b.view
            K.exchange_faces(tuple(v(x) for x in ufs), tuple(v(x) for x in vfs), tuple(v(x) for x in sps),
                             tuple(v(x) for x in out), b.v_sh[a], UNIT[a], b.v_flo[a], b.v_fhi[a], dt, *coeffs)
            for m in matls:
                self.bcs.face_velocity(patch, out[m], d, m, b.flo[d], b.fhi[d])

    def face_exchange_coefficients(self, dw, patch, view=None):
        """The coefficient arguments of the face exchange: (K,), or with the slip model
        (slip_exchange.py) (ones, its K of each cell) from dw."""
        if getattr(self, "slip", None) is None:
            return (self.K,)
        kc = dw.get(SL.slipK_CC, 0, patch)
        return np.ones_like(self.K), kc if view is None else view(kc)

    # -- step 5: pressure increment (eqs. 29-30) ------------------------------------------------
    def delp_press(self, patch, matls, old_dw, new_dw):
        """press_CC = press_equil_CC + delP_Dilatate, delP_Dilatate = -dt sum_m div(theta_m u*_m) /
        sum_m theta_m kappa_m (eqs. 29-30). theta on the faces: the donor cell's, or with
        limiter="BarthJespersen" (Uintah's advector) the second-order advected fractions as Uintah's."""
        b = self.boxes(patch)
        dt = old_dw.get_reduction(L.delT)
        shape = patch.alloc_shape(VarType.CC)
        div, ksum = np.zeros(shape), np.zeros(shape)
        one = len(matls) == 1
        v = b.view
        for m in matls:
            vf = new_dw.get(I.vol_frac_CC, m, patch)
            self.add_dilatation(patch, vf, self._faces(new_dw, I.FC_VEL_ME, m, patch), one, dt, div)
            K.add_theta_kappa(v(vf), v(new_dw.get(I.sp_vol_CC, m, patch)), v(new_dw.get(I.speedSound_CC, m, patch)),
                              v(ksum), b.v_lo, b.v_hi)
        delP = new_dw.allocate(I.delP_Dilatate, 0, patch)
        press = new_dw.allocate(I.press_CC, 0, patch)
        K.update_pressure(v(new_dw.get(I.press_equil_CC, 0, patch)), v(div), v(ksum), v(delP), v(press),
                          b.v_lo, b.v_hi, self.press_floor)
        if self.lodi is not None:
            self.lodi_press(patch, press, new_dw.get(I.speedSound_CC, self.lodi.matl, patch), old_dw, new_dw)
        self.press_bc(patch, press, new_dw.get(I.sp_vol_CC, self.surrounding, patch) if self.hydrostatic else None)

    def vol_frac_second_order(self, one):
        """Are the face volume fractions of the dilatation (eq. 29) advected second order with
        Uintah's limiter (limiter="BarthJespersen", not `one` material), as Uintah's advectQ of
        vol_frac? Otherwise they are the donor cell's (pysus's vanLeer default, first order)."""
        return not one and self.second_order and self.limiter == A.EXTREMA

    def add_dilatation(self, patch, vf, uf, one, dt, div):
        """div += dt div(theta u) of one material (eq. 29) over the patch's cells, from its volume
        fraction vf and face velocities uf (three arrays, a dummy for absent directions); theta on
        the faces as vol_frac_second_order says (then vf needs 2 ghost layers, uf 1)."""
        b = self.boxes(patch)
        v = b.view
        if self.vol_frac_second_order(one):
            vshape = v(vf).shape
            A.outflow_fraction(v(vf), *(v(uf[p]) for p in b.perm), b.v_sh, b.v_flo, b.v_fhi, b.v_lo, b.v_hi, dt,
                               patch.level.dx[b.perm], self.dims[b.perm], False, self._scratch("q", (1,) + vshape),
                               self._scratch("acc", (1,) + vshape), self._scratch("buf", (1, vshape[2] + 1)),
                               self._scratch("grad", (3, 1) + vshape), self._scratch("rc", (3,) + vshape), v(div))
        else:
            K.div_theta_u(v(vf), one, *(v(uf[p]) for p in b.perm), b.v_sh[0], b.v_sh[1], b.v_sh[2], b.v_dims,
                          b.v_lo, b.v_hi, dt, b.v_dx, v(div))

    def delp_mass_exchange(self, patch, matls, old_dw, new_dw):
        """Uintah's delP_MassX diagnostic, computed only when a deck saves it: what press_CC holds
        beyond p_eq + delP_Dilatate (the models' mass sources; 0, to round-off, without them)."""
        b = self.boxes(patch)
        out = new_dw.allocate(I.delP_MassX, 0, patch)
        K.pressure_from_mass_exchange(new_dw.get(I.press_CC, 0, patch), new_dw.get(I.press_equil_CC, 0, patch),
                                      new_dw.get(I.delP_Dilatate, 0, patch), out, b.lo, b.hi)

    def mass_exchange_term(self, patch, matls, old_dw, new_dw):
        """Uintah's term2 diagnostic (the mass-exchange term of the pressure equation,
        sumKappa delP_MassX), computed only when a deck saves it."""
        b = self.boxes(patch)
        out = new_dw.allocate(I.term2, 0, patch)
        dpm = new_dw.get(I.delP_MassX, 0, patch)
        for m in matls:
            K.add_kappa_times(new_dw.get(I.vol_frac_CC, m, patch), new_dw.get(I.sp_vol_CC, m, patch),
                              new_dw.get(I.speedSound_CC, m, patch), dpm, out, b.lo, b.hi)

    def momentum_source(self, patch, matls, old_dw, new_dw):
        """Uintah's mom_source_CC diagnostic, computed only when a deck saves it: the Lagrangian
        momentum less the old momentum (pressure, viscous and gravity sources times delT)."""
        b = self.boxes(patch)
        for m in matls:
            out = new_dw.allocate(I.mom_source_CC, m, patch)
            K.momentum_source(new_dw.get(I.mom_L_CC, m, patch), old_dw.get(I.rho_CC, m, patch),
                              old_dw.get(I.vel_CC, m, patch), b.vol, out, b.lo, b.hi)

    # -- step 6: face pressure (eq. 31) -------------------------------------------------------------
    def press_fc(self, patch, matls, old_dw, new_dw):
        b = self.boxes(patch)
        press = new_dw.get(I.press_CC, 0, patch)
        rho = old_dw.get(I.rho_CC, 0, patch)
        if len(matls) > 1:
            rho = rho.copy()
            for m in matls[1:]:
                rho += old_dw.get(I.rho_CC, m, patch)
        for d in range(3):
            if self.dims[d]:
                pf = new_dw.allocate(I.PRESS_FC[d], 0, patch)
                a, v = b.axis[d], b.view
                K.face_pressure(v(press), v(rho), v(pf), b.v_sh[a], UNIT[a], b.v_flo[a], b.v_fhi[a])

    # -- step 7: fluid stresses and heat flux (only when the deck has them) -----------------------
    def vel_tau(self, patch, vel):
        """Uintah's velTau_CC: a copy of vel_CC whose extra cells on the domain's faces make
        the face value the boundary value (kernels.vel_tau_boundary)."""
        b = self.boxes(patch)
        vt = vel.copy()
        tlo, thi = b.lo.copy(), b.hi.copy()
        for d in range(3):          # along a face: into the halo, but not the domain's edge cells
            if self.dims[d]:
                tlo[d] = b.lo[d] if patch.at_low[d] else 0
                thi[d] = b.hi[d] if patch.at_high[d] else vel.shape[d]
        for d in range(3):
            for side, at in ((0, patch.at_low[d]), (1, patch.at_high[d])):
                if at and self.dims[d]:
                    K.vel_tau_boundary(vt, d, side, b.lo, b.hi, tlo, thi)
        return vt

    def viscosity_array(self, patch, m, old_dw):
        """Uintah's computeThermoTransportProperties (viscosity): <dynamic_viscosity> in every cell
        (extra cells too), then the material's models on the interior cells from the old
        temperature (Sutherland), or in a box (SpongeLayer). The models also fill the first
        ghost layer, the neighbours' interior cells that Uintah's viscous stress reads
        (the viscosity with ghosts): the face between two patches sees both cells' model values."""
        b = self.boxes(patch)
        mat = self.materials[m]
        mu = np.full(patch.alloc_shape(VarType.CC), float(mat.viscosity))
        c0 = np.array(patch.low_index(VarType.CC))
        grow = np.asarray(self.dims, dtype=np.int64)
        glo = np.maximum(b.lo - grow * (1 - np.array(patch.at_low, dtype=np.int64)), 0)
        ghi = np.minimum(b.hi + grow * (1 - np.array(patch.at_high, dtype=np.int64)), np.array(mu.shape))
        for model in getattr(mat, "viscosity_models", ()):      # MPMICE's solids have none
            if model[0] == "Sutherland":
                K.sutherland_viscosity(mu, old_dw.get(I.temp_CC, m, patch), model[1], model[2], glo, ghi)
            else:
                a = np.maximum(model[2] - c0, glo)
                z = np.minimum(model[3] - c0, ghi)
                if np.all(z > a):
                    mu[a[0]:z[0], a[1]:z[1], a[2]:z[2]] = model[1]
        return mu

    def viscosity_field(self, patch, matls, old_dw, new_dw):
        """Uintah's viscosity label, computed only when a deck saves it."""
        for m in matls:
            new_dw.put(I.viscosity, m, patch, self.viscosity_array(patch, m, old_dw))

    def _viscous_here(self, patch, m):
        """Uintah's isViscosityDefinedFlag: a constant viscosity, a Sutherland model, or a sponge
        layer with cells on this patch."""
        mat = self.materials[m]
        models = getattr(mat, "viscosity_models", ())
        if mat.viscosity > 0 or any(model[0] == "Sutherland" for model in models):
            return True
        c0 = np.array(patch.lo)
        c1 = np.array(patch.hi)
        return any(model[1] > 0 and np.all(np.minimum(model[3], c1) > np.maximum(model[2], c0))
                   for model in models)

    def _mu(self, patch, m, old_dw):
        """The cells' viscosity: with models each step's field, else a cached constant array."""
        if getattr(self.materials[m], "viscosity_models", ()):
            return self.viscosity_array(patch, m, old_dw)
        key = ("mu", m, patch.id, patch.alloc_shape(VarType.CC))
        if key not in self._geom_cache:
            self._geom_cache[key] = np.full(patch.alloc_shape(VarType.CC), float(self.materials[m].viscosity))
        return self._geom_cache[key]

    def turbulent_viscosity(self, patch, matls, old_dw, new_dw):
        """Uintah's callTurb: turb_viscosity_CC (the model's) and total_viscosity_CC (molecular
        plus turbulent, the viscosity of the stress), from the face velocities uvel_FCME, ..."""
        b = self.boxes(patch)
        for m in matls:
            vel = old_dw.get(I.vel_CC, m, patch)
            turb, tot = self.turbulence.viscosities(
                patch, b, self.dims, self._faces(new_dw, I.FC_VEL_ME, m, patch),
                self.vel_tau(patch, vel) if self.turbulence.dynamic else vel,
                old_dw.get(I.rho_CC, m, patch), self._mu(patch, m, old_dw), new_dw.get(I.vol_frac_CC, m, patch))
            new_dw.put(I.turb_viscosity_CC, m, patch, turb)
            new_dw.put(I.total_viscosity_CC, m, patch, tot)

    def _stress_viscosity(self, patch, m, old_dw, new_dw):
        """The viscosity of the stress: total_viscosity_CC with a turbulence model, the mixture's
        per cell (viscosity) where a model owns the material's caloric EOS, else mu."""
        if self.turbulence is not None:
            return new_dw.get(I.total_viscosity_CC, m, patch)
        if m in self.caloric:
            return new_dw.get(I.viscosity, m, patch)
        return self._mu(patch, m, old_dw)

    def _conductivity(self, patch, m, new_dw):
        """The cells' thermal conductivity: the mixture's (thermalCond) where a model owns the
        material's caloric EOS, else a cached array of <thermal_conductivity>."""
        if m in self.caloric:
            return new_dw.get(I.thermalCond, m, patch)
        key = ("k", m, patch.id, patch.alloc_shape(VarType.CC))
        if key not in self._geom_cache:
            self._geom_cache[key] = np.full(patch.alloc_shape(VarType.CC), float(self.materials[m].conductivity))
        return self._geom_cache[key]

    def viscous_source(self, patch, matls, old_dw, new_dw):
        """Uintah's viscous_src_CC = V div(tau) (a force: the Lagrangian momentum adds dt times it)."""
        b = self.boxes(patch)
        for m in matls:
            out = new_dw.allocate(I.viscous_src_CC, m, patch)
            if not self._viscous_here(patch, m):
                continue
            mu = self._stress_viscosity(patch, m, old_dw, new_dw)
            K.viscous_stress_source(self.vel_tau(patch, old_dw.get(I.vel_CC, m, patch)),
                                    new_dw.get(I.vol_frac_CC, m, patch), mu, out,
                                    self.dims, b.lo, b.hi, patch.level.dx, b.vol)

    def tau_fc(self, patch, matls, old_dw, new_dw):
        """Uintah's tau_X_FC, tau_Y_FC, tau_Z_FC (the face stresses of viscous_source), computed
        only when a deck saves them."""
        b = self.boxes(patch)
        for m in matls:
            vt = self.vel_tau(patch, old_dw.get(I.vel_CC, m, patch))
            vf = new_dw.get(I.vol_frac_CC, m, patch)
            for d in range(3):
                if self.dims[d]:
                    tau = new_dw.allocate(I.TAU_FC[d], m, patch)
                    if self._viscous_here(patch, m):
                        K.tau_face(vt, vf, self._stress_viscosity(patch, m, old_dw, new_dw), tau, d, b.sh[d], b.flo[d],
                                   b.fhi[d], self.dims, patch.level.dx)

    def conduction_source(self, patch, matls, old_dw, new_dw):
        b = self.boxes(patch)
        dt = old_dw.get_reduction(L.delT)
        for m in matls:
            out = new_dw.allocate(I.heatCond_src_CC, m, patch)
            K.diffusion_source(old_dw.get(I.temp_CC, m, patch)[..., None], new_dw.get(I.vol_frac_CC, m, patch),
                               self._conductivity(patch, m, new_dw), out[..., None], self.dims, b.lo, b.hi,
                               patch.level.dx, dt, b.vol)

    # -- steps 8-9: sources and Lagrangian values (eqs. 33-37) ----------------------------------
    def lagrangian_values(self, patch, matls, old_dw, new_dw, tmv=None):
        """Eqs. 33-37 (K.lagrangian); tmv: MPMICE's TMV_CC, the flow work's volume (else the cell's)."""
        b = self.boxes(patch)
        tmv = _NO_TMV if tmv is None else b.view(tmv)
        dt = old_dw.get_reduction(L.delT)
        pf = self._faces(new_dw, I.PRESS_FC, 0, patch)
        press, delP = new_dw.get(I.press_CC, 0, patch), new_dw.get(I.delP_Dilatate, 0, patch)
        masses, moms, engs, tots = [], [], [], []
        for m in matls:
            mass = new_dw.allocate(I.mass_L_CC, m, patch, fill=None)
            mom = new_dw.allocate(I.mom_L_CC, m, patch, fill=None)
            eng = new_dw.allocate(I.int_eng_L_CC, m, patch, fill=None)
            masses.append(mass), moms.append(mom), engs.append(eng)
            v = b.view
            cv = self._cv(new_dw, m, patch)
            if m in self.caloric:       # the carried energy m e_s(T_old, Y_old), extra cells included
                cv = self._carrier_cv(m, patch, old_dw.get(I.temp_CC, m, patch), old_dw, b.olo, b.ohi)
            K.lagrangian(v(old_dw.get(I.rho_CC, m, patch)), v(old_dw.get(I.vel_CC, m, patch)),
                         v(old_dw.get(I.temp_CC, m, patch)), v(new_dw.get(I.vol_frac_CC, m, patch)),
                         v(new_dw.get(I.sp_vol_CC, m, patch)), v(new_dw.get(I.speedSound_CC, m, patch)), v(press),
                         v(delP), *(v(pf[p]) for p in b.perm), b.v_sh[0], b.v_sh[1], b.v_sh[2], b.v_dims,
                         v(mass), v(mom), v(eng), b.v_olo, b.v_ohi, b.v_lo, b.v_hi, b.vol, b.v_dx, dt,
                         v(cv) if np.ndim(cv) else cv, self.gravity, self.use_gravity, self.codes[m],
                         self.params[m], self.gammas[m], tmv, b.perm)
            sl = tuple(slice(l, h) for l, h in zip(b.lo, b.hi))
            if self.viscous:
                mom[sl] += dt * new_dw.get(I.viscous_src_CC, m, patch)[sl]
            if self.conduction:
                eng[sl] += new_dw.get(I.heatCond_src_CC, m, patch)[sl]
            for model in self.source_models:        # Uintah's modelMom_src, modelEng_src
                model.add_lagrangian(patch, m, mass, mom, eng, old_dw, new_dw)
            if self.lodi is not None:
                if m not in self.caloric:           # else lodi_exchange_caloric, after the species' m Y_L
                    self.lodi_exchange(patch, m, mass, mom, eng, old_dw, new_dw)
            elif not self.exchange:
                self._lagrangian_bcs(patch, m, mass, mom, eng, b, new_dw, cv)
                new_dw.put(I.mom_L_ME_CC, m, patch, mom)      # no exchange: the same arrays
                new_dw.put(I.int_eng_L_ME_CC, m, patch, eng)
            if self.conserve_energy:
                tot = new_dw.allocate(I.tot_eng_L_CC, m, patch, fill=None)
                uf = self._faces(new_dw, I.FC_VEL_ME, m, patch)
                K.total_energy_lagrangian(old_dw.get(I.rho_CC, m, patch), old_dw.get(I.vel_CC, m, patch),
                                          old_dw.get(I.temp_CC, m, patch), new_dw.get(I.vol_frac_CC, m, patch),
                                          new_dw.get(I.sp_vol_CC, m, patch), len(matls) == 1,
                                          pf[0], pf[1], pf[2], uf[0], uf[1], uf[2],
                                          b.sh[0], b.sh[1], b.sh[2], self.dims, tot, b.olo, b.ohi, b.lo, b.hi,
                                          b.vol, patch.level.dx, dt, self._cv(new_dw, m, patch), self.gravity,
                                          self.use_gravity, self.codes[m], self.params[m])
                if self.conduction:
                    tot[sl] += new_dw.get(I.heatCond_src_CC, m, patch)[sl]
                tots.append(tot)
                if len(matls) == 1:
                    new_dw.put(I.tot_eng_L_ME_CC, m, patch, tot)       # one material: no exchange
        if self.conserve_energy and len(matls) > 1 and not self.exchange:
            self._share_total_energy(patch, matls, new_dw, tuple(masses), tuple(moms), tuple(engs), tuple(tots))

    def _share_total_energy(self, patch, matls, new_dw, masses, moms, engs, tots):
        """tot_eng_L_ME_CC of several materials: each one's m (e + |u|^2/2) after the exchange plus
        its m cv share of what the mixture's conserved total energy (tots) says is missing."""
        b = self.boxes(patch)
        out = tuple(new_dw.allocate(I.tot_eng_L_ME_CC, m, patch, fill=None) for m in matls)
        K.share_total_energy(masses, moms, engs, self.cvs[list(matls)], tots, out, b.olo, b.ohi, b.lo, b.hi)

    # -- step 10: momentum and heat exchange (eqs. 38-39) ---------------------------------------
    def exchange_cc(self, patch, matls, old_dw, new_dw):
        b = self.boxes(patch)
        dt = old_dw.get_reduction(L.delT)
        get = lambda lab: tuple(new_dw.get(lab, m, patch) for m in matls)
        mom_out = tuple(new_dw.allocate(I.mom_L_ME_CC, m, patch, fill=None) for m in matls)
        eng_out = tuple(new_dw.allocate(I.int_eng_L_ME_CC, m, patch, fill=None) for m in matls)
        v = b.view
        vs = lambda arrs: tuple(v(x) for x in arrs)
        args = (vs(get(I.mass_L_CC)), vs(get(I.mom_L_CC)), vs(get(I.int_eng_L_CC)), vs(get(I.vol_frac_CC)),
                vs(get(I.sp_vol_CC)), self.cvs, vs(mom_out), vs(eng_out), b.v_olo, b.v_ohi, dt, self.K, self.H)
        if self.var_K or self.var_H:        # <CoefficientModel> linearVariation
            K.exchange_cells_variable(*args, self.var_K, self.var_H)
        else:
            K.exchange_cells(*args)
        sl = getattr(self, "slip", None)
        if sl is not None and sl.use_coeffs:        # the solid's surface cells again, with slip
            SL.exchange_surface_cells(
                vs(get(I.mass_L_CC)), vs(get(I.mom_L_CC)), vs(get(I.int_eng_L_CC)), vs(get(I.vol_frac_CC)),
                vs(get(I.sp_vol_CC)), self.cvs, v(new_dw.get(SL.isSurfaceCell, 0, patch)),
                v(new_dw.get(SL.surfaceNorm, sl.solid, patch)), v(new_dw.get(SL.meanFreePath, sl.fluid, patch)),
                self.gammas[sl.fluid], patch.level.dx, sl.fluid, sl.solid, sl.a_v, sl.a_t, vs(mom_out), vs(eng_out),
                b.v_lo, b.v_hi, dt, self.K, self.H)
        for m, mass, mom, eng in zip(matls, get(I.mass_L_CC), mom_out, eng_out):
            if m in self.matls:                # fluids (MPMICE: not the solids)
                self._lagrangian_bcs(patch, m, mass, mom, eng, b, new_dw)
        if self.conserve_energy:
            self._share_total_energy(patch, matls, new_dw, get(I.mass_L_CC), mom_out, eng_out, get(I.tot_eng_L_CC))

    def _lagrangian_bcs(self, patch, m, mass, mom, eng, b, new_dw, cv=None):
        """mom_L_ME_CC and int_eng_L_ME_CC in the extra cells from u and T with every face's
        conditions, as Uintah's exchange task ends (BoundaryConditions.lagrangian_extra_cells)."""
        cv = self._cv(new_dw, m, patch) if cv is None else cv
        self.bcs.lagrangian_extra_cells(patch, mass, mom, eng, cv, m, b, self.dims)

    # -- step 11: specific volume (eq. 40) --------------------------------------------------------
    def lagrangian_sp_vol(self, patch, matls, old_dw, new_dw):
        b = self.boxes(patch)
        delP = new_dw.get(I.delP_Dilatate, 0, patch)
        outs = [new_dw.allocate(I.sp_vol_L_CC, m, patch, fill=None) for m in matls]
        if len(matls) == 1:
            K.sp_vol_lagrangian_one(new_dw.get(I.mass_L_CC, 0, patch), new_dw.get(I.sp_vol_CC, 0, patch),
                                    new_dw.get(I.vol_frac_CC, 0, patch), new_dw.get(I.speedSound_CC, 0, patch),
                                    delP, outs[0], b.olo, b.ohi, b.vol)
        else:
            dt = old_dw.get_reduction(L.delT)
            v = b.view
            get = lambda lab: tuple(v(new_dw.get(lab, m, patch)) for m in matls)
            K.sp_vol_lagrangian_many(get(I.mass_L_CC), get(I.sp_vol_CC), get(I.vol_frac_CC), get(I.speedSound_CC),
                                     v(delP), get(I.int_eng_L_ME_CC),
                                     tuple(v(old_dw.get(I.temp_CC, m, patch)) for m in matls),
                                     self.codes, self.params, self.cvs, self.gammas, tuple(v(o) for o in outs),
                                     b.v_olo, b.v_ohi, b.vol, dt, v(new_dw.get(I.press_CC, 0, patch)))
        if self.save_sp_vol_src:
            self._sp_vol_source(patch, matls, new_dw, outs, b)
        if self.model_volume_sources is not None:    # MPMICE's reactions, before the clamp (Uintah's order)
            self.model_volume_sources(patch, matls, new_dw, outs)
        if self.clamp_sp_vol:
            for m, out in zip(matls, outs):
                tiny_rho = getattr(self.materials[m], "tiny_rho", 1e-12)    # MPMICE's solids: Uintah's 1e-12
                K.clamp_sp_vol_lagrangian(out, new_dw.get(I.sp_vol_CC, m, patch), tiny_rho, b.vol, b.lo, b.hi)

    def _sp_vol_source(self, patch, matls, new_dw, outs, b):
        """Uintah's sp_vol_src_CC, computed only when a deck saves it: the specific volume source of
        eq. 40 per unit mass, ((m v)^L - m v) / (rho V) with rho = theta / v, in the interior cells
        (before the clamp and the reactions' volume sources; zero in the extra cells)."""
        inner = tuple(slice(l, h) for l, h in zip(b.lo, b.hi))
        for m, out in zip(matls, outs):
            sp, vf = new_dw.get(I.sp_vol_CC, m, patch)[inner], new_dw.get(I.vol_frac_CC, m, patch)[inner]
            src = new_dw.allocate(I.sp_vol_src_CC, m, patch)
            src[inner] = (out[inner] - new_dw.get(I.mass_L_CC, m, patch)[inner] * sp) * sp / (vf * b.vol)

    # -- models' transported scalars ---------------------------------------------------------------
    def lagrangian_transported(self, patch, matls, old_dw, new_dw):
        """Uintah's computeLagrangian_Transported_Vars: f_L = f_old plus the model's source in the
        interior, the scalar's boundary conditions, then times mass_L_CC (what advection moves)."""
        b = self.boxes(patch)
        own = tuple(slice(l, h) for l, h in zip(b.olo, b.ohi))
        inner = tuple(slice(l, h) for l, h in zip(b.lo, b.hi))
        for model in self.scalars:
            m = model.matl
            f_L = new_dw.allocate(model.f_L, m, patch)
            f_L[own] = old_dw.get(model.f, m, patch)[own]
            f_L[inner] += new_dw.get(model.src, m, patch)[inner]
            self.bcs.scalar(patch, f_L, model.name, m, b)
            f_L[own] *= new_dw.get(I.mass_L_CC, m, patch)[own]

    # -- step 12: advection and the new state ----------------------------------------------------
    def advect_and_advance(self, patch, matls, old_dw, new_dw):
        b = self.boxes(patch)
        dt = old_dw.get_reduction(L.delT)
        for m in matls:
            mass, mom = new_dw.get(I.mass_L_CC, m, patch), new_dw.get(I.mom_L_ME_CC, m, patch)
            eng, volm = new_dw.get(I.int_eng_L_ME_CC, m, patch), new_dw.get(I.sp_vol_L_CC, m, patch)
            rho = new_dw.allocate(I.rho_CC, m, patch)
            vel = new_dw.allocate(I.vel_CC, m, patch)
            temp = new_dw.allocate(I.temp_CC, m, patch)
            spv = new_dw.get_modifiable(I.sp_vol_CC, m, patch)
            heating = self.dissipation_heating and not self.conserve_energy
            with_e = self.conserve_energy or heating
            if self.conserve_energy:
                tot, tot_o = new_dw.get(I.tot_eng_L_ME_CC, m, patch), np.empty_like(mass)
            else:
                tot = tot_o = mass                              # unused
            uf, ef, pw = self.advection_faces(patch, m, new_dw, dt)
            v = b.view
            shape = v(mass).shape
            # the models' scalars of this material (m f), advected with the others
            mine = [model for model in self.scalars if model.matl == m]
            scal, scal_o = self._scratch("scal", (len(mine),) + shape), self._scratch("scal_o", (len(mine),) + shape)
            for s, model in enumerate(mine):
                scal[s] = v(new_dw.get(model.f_L, m, patch))
            nq = (A.NQ if with_e else A.NQ - 1) + len(mine)
            common = (v(mass), v(mom), v(eng), v(volm), v(tot), scal, with_e, heating, *(v(uf[p]) for p in b.perm),
                      *(v(ef[p]) if ef[p].size > 1 else ef[p] for p in b.perm), v(pw) if pw.size > 1 else pw,
                      b.v_sh, b.v_flo, b.v_fhi, b.v_lo, b.v_hi, dt, patch.level.dx[b.perm], self.dims[b.perm])
            scratch = (self._scratch("q", (nq,) + shape), self._scratch("acc", (nq,) + shape),
                       self._scratch("buf", (nq, shape[2] + 1)))
            caloric = self.caloric.get(m)
            # a caloric owner's advected energy is e_s itself: the kernel's T = e / cv with cv = 1
            cv = 1.0 if caloric else self._cv(new_dw, m, patch, v)
            extrema = self.second_order and self.limiter == A.EXTREMA
            # advect_extrema takes cv per cell (a constant fills a scratch field, ~0.3 % of its time):
            # one specialisation for materials with and without a cv model (each cost 3.5-9 CPU s)
            if extrema and np.ndim(cv) == 0:
                cells = self._scratch("cv", shape)
                cells[...] = cv
                cv = cells
            out = (b.vol, cv, v(rho), v(vel), v(temp), v(spv), v(tot_o), scal_o)
            if extrema:
                A.advect_extrema(*common, self.compatible_fluxes, *scratch,
                                 self._scratch("grad", (3, nq) + shape), self._scratch("rc", (3,) + shape), *out)
            else:
                A.advect(*common, b.perm, self.second_order, self.transverse, *scratch,
                         self._scratch("sl", (shape[2],)), *out)
            if self.conserve_energy:
                A.energy_finish(rho, vel, temp, tot_o, b.lo, b.hi, b.vol, self._cv(new_dw, m, patch), self.codes[m],
                                self.params[m])
            if caloric is not None:     # T from e_s and the advected Y (Uintah's computeTempFromSensibleEnergy)
                idx = [mine.index(s) for s in caloric.species]
                caloric.temperature(patch, v(temp), np.ascontiguousarray(scal_o[idx]), v(temp), b.v_lo, b.v_hi)
            if self.lodi is not None:
                self.lodi_advected(patch, m, rho, vel, temp, new_dw)
            self.bcs.scalar(patch, rho, "Density", m, b)
            self.bcs.scalar(patch, temp, "Temperature", m, b)
            self.bcs.velocity(patch, vel, m, b)
            self.bcs.sp_vol(patch, spv, new_dw.get(I.vol_frac_CC, m, patch), rho, m, b)
            inner = tuple(slice(l, h) for l, h in zip(b.v_lo, b.v_hi))
            for s, model in enumerate(mine):     # Uintah's conservedtoPrimitive_Vars: f = (m f)_adv / m_adv
                f = new_dw.allocate(model.f, m, patch)
                v(f)[inner] = scal_o[s][inner]
                self.bcs.scalar(patch, f, model.name, m, b)

    def advection_faces(self, patch, m, new_dw, dt):
        """The face velocities that advect material m, per direction the fractions of a donor
        cell's totals moved across each face besides (1-element dummies: none; MPMICE's next
        to its solids, advection._open_transfers) and the pressure for their flow work."""
        return self._faces(new_dw, I.FC_VEL_ME, m, patch), _NO_TRANSFERS, _NO_PRESS

    # -- diagnostics ----------------------------------------------------------------------------
    def conserved_sums(self, patch, matls, old_dw, new_dw):
        """TotalMass, KineticEnergy, TotalIntEng, TotalMomentum as Uintah's conservationTest."""
        acc = self._conserved_sums(patch, matls, old_dw, new_dw)
        new_dw.put_reduction(I.TotalMass, acc[0])
        new_dw.put_reduction(I.KineticEnergy, acc[1])
        new_dw.put_reduction(I.TotalIntEng, acc[2])
        new_dw.put_reduction(I.TotalMomentum, acc[3:6])

    def fluid_sums(self, patch, matls, old_dw, new_dw):
        """Under MPMICE (Uintah's conservationTest over the fluids' subset): each fluid's
        TotalMass, KineticEnergy, TotalIntEng and TotalMomentum, and TotalIntEng of them all
        (the particles add no internal energy; MPMICE adds their mass, KE and momentum)."""
        new_dw.put_reduction(I.TotalIntEng, self._conserved_sums(patch, matls, old_dw, new_dw)[2])
        for m in matls:
            acc = self._conserved_sums(patch, (m,), old_dw, new_dw)
            new_dw.put_reduction(I.TotalMass, acc[0], m)
            new_dw.put_reduction(I.KineticEnergy, acc[1], m)
            new_dw.put_reduction(I.TotalIntEng, acc[2], m)
            new_dw.put_reduction(I.TotalMomentum, acc[3:6], m)

    def _conserved_sums(self, patch, matls, old_dw, new_dw):
        """[mass, kinetic energy, internal energy, momentum x, y, z]: the sums over interior
        cells plus delT times the fluxes through the domain's faces. Uintah reads each face's
        velocity at the extra cell's own (lower) face: the boundary face on upper faces; on
        lower faces a face outside the domain that ICE never sets, so only the upper faces
        contribute (zero on closed domains)."""
        b = self.boxes(patch)
        acc = np.zeros(6)
        delt = float(old_dw.get_reduction(L.delT))
        for m in matls:
            rho, vel, temp = new_dw.get(I.rho_CC, m, patch), new_dw.get(I.vel_CC, m, patch), new_dw.get(I.temp_CC, m, patch)
            cv = self._carrier_cv(m, patch, temp, new_dw, b.olo, b.ohi)
            K.conserved_sums(rho, vel, temp, cv, b.vol, b.lo, b.hi, acc)
            for d in range(3):
                if self.dims[d] and "xyz"[d] + "+" in patch.boundary_faces:
                    K.upper_face_fluxes(rho, vel, temp, cv, b.vol, new_dw.get(I.FC_VEL_ME[d], m, patch), d,
                                        b.lo, b.hi, b.sh[d], delt, acc)
        return acc

    def compute_mach(self, patch, matls, old_dw, new_dw):
        b = self.boxes(patch)
        for m in matls:
            out = new_dw.allocate(I.mach, m, patch)
            K.mach_number(new_dw.get(I.vel_CC, m, patch), new_dw.get(I.speedSound_CC, m, patch), out, b.olo, b.ohi)


def _speed_sound(sp_vol, temp, out, code, params, cv, gamma):
    """Initial speedSound_CC of one material over a whole array, extra cells included."""
    flat = np.empty(sp_vol.size)
    K.speed_sound_fill(np.ascontiguousarray(sp_vol).ravel(), np.ascontiguousarray(temp).ravel(), flat,
                       code, params, _flat_cv(cv), gamma)
    out[...] = flat.reshape(sp_vol.shape)


def _press_array(rho_micro, temp, code, params, cv, gamma):
    """EOS pressure of one material over an array (initial press_CC)."""
    out = np.empty(rho_micro.size)
    K.press_fill(np.ascontiguousarray(rho_micro).ravel(), np.ascontiguousarray(temp).ravel(), out,
                 code, params, _flat_cv(cv), gamma)
    return out.reshape(rho_micro.shape)


def _rho_micro_array(press, temp, guess, code, params, cv, gamma):
    """rho_micro(p, T) of one material over an array (initial condition, eos_rho_micro per cell)."""
    out = np.empty(press.size)
    K.rho_micro_fill(np.ascontiguousarray(press).ravel(), np.ascontiguousarray(temp).ravel(), out, guess,
                     code, params, _flat_cv(cv), gamma)
    return out.reshape(press.shape)


def _flat_cv(cv):
    """cv for the flat-array kernels: one number as it is, a per-cell field flattened."""
    return np.ascontiguousarray(cv).ravel() if np.ndim(cv) else cv
