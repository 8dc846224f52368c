"""MPMICE's own task bodies (paper 000 sec. 3.3) and the warehouse view that lets ICE's
task bodies run over solid and fluid materials together.

ICE's bodies read the start-of-step state (rho_CC, vel_CC, temp_CC, sp_vol_CC) from
the OLD warehouse; for an MPM material that state is this step's interpolation of
its particles (step 1) in the NEW warehouse. `StartOfStep` wraps the old warehouse
and sends those reads of MPM materials to the new one (sp_vol_CC to sp_vol_mpm_CC).

Heat: a solid with a nonzero heat-exchange coefficient to a fluid carries p.temperature
(components/mpm/thermal.py). Its temp_CC is the mass-weighted cell mean of g.temperature,
its Lagrangian energy m cv T* holds this step's conduction, the exchange (eq. 39) changes
it as it does a fluid's, and dT/dt = (change) / (m cv dt) goes to the nodes (dTdt_NC, the
mean over the cells around a node, which hands the nodes exactly the heat the cells
exchanged) and from there to the particles with their conduction rate.
"""
from __future__ import annotations

import sys

import numpy as np

from components.ice import labels as I
from components.ice.bc import NEUMANN, SYMMETRY, bc_scalar, bc_vector
from components.ice.tasks import _press_array, _rho_micro_array, _speed_sound
from components.mpm import labels as M
from framework import labels as FL
from framework.geometry import cell_fractions
from framework.task import NEW, OLD, Task
from framework.variables import Ghost, VarType

from components.ice import equilibration as E
from components.ice.eos import IDEAL_GAS
from . import adiabatic as AD
from . import kernels as K
from . import labels as MI

NC, CC = VarType.NC, VarType.CC
_REDIRECT = {I.rho_CC.name: I.rho_CC, I.vel_CC.name: I.vel_CC, I.temp_CC.name: I.temp_CC,
             I.sp_vol_CC.name: MI.sp_vol_mpm_CC}
THETA_TRACE = 1e-6      # fluids all below this: they take the heat-exchanging solids' temperature (step 10)
_NO3 = np.zeros((1, 1, 1, 3))
_NO1 = np.zeros((1, 1, 1))
_ZERO3 = np.zeros(3)            # _extra_vector's value: its kinds (symmetry, zero gradient) add nothing


class StartOfStep:
    """The old warehouse, except that the state of MPM materials comes from the new one."""

    def __init__(self, old_dw, new_dw, mpm_matls):
        self.old, self.new, self.mpm = old_dw, new_dw, set(mpm_matls)

    def get(self, label, m, patch):
        if m in self.mpm and label.name in _REDIRECT:
            return self.new.get(_REDIRECT[label.name], m, patch)
        return self.old.get(label, m, patch)

    def get_reduction(self, label, m=-1):
        return self.old.get_reduction(label, m)


class _Capture:
    """A new warehouse whose put_reduction is kept (to combine two stable timesteps)."""

    def __init__(self, dw):
        self.dw, self.value = dw, None

    def __getattr__(self, name):
        return getattr(self.dw, name)

    def put_reduction(self, label, value, m=-1):
        self.value = value


class _KeepAllocated:
    """A new warehouse that remembers the arrays a task body allocates (to add to them after)."""

    def __init__(self, dw):
        self.dw, self.arrays = dw, {}

    def __getattr__(self, name):
        return getattr(self.dw, name)

    def allocate(self, label, m, patch, fill=0.0):
        a = self.dw.allocate(label, m, patch, fill=fill)
        self.arrays[(label.name, m)] = a
        return a


class MPMICETasks:
    """Mixed into the MPMICE component: needs self.mpm, self.ice, self.mpm_matls, ..."""

    # -- helpers ---------------------------------------------------------------------------
    def _geom(self, patch):
        """(boxes, cc_low, node_low, dims, first and last domain node) of a patch, kept per Boxes
        (a patch and the level's halos)."""
        b = self.ice.boxes(patch)
        cache = self.__dict__.setdefault("_geom_arrays", {})
        geom = cache.get(b)
        if geom is None:
            inner = patch.level.interior_box(NC)
            geom = cache[b] = (b, np.array(patch.low_index(CC), np.int64), np.array(patch.low_index(NC), np.int64),
                               self.dims_i, np.array(inner[0], np.int64), np.array(inner[1], np.int64) - 1)
        return geom

    def _sym(self, m):
        """Per direction: is the low / high domain face a symmetry plane for material m (kept)."""
        cache = self.__dict__.setdefault("_sym_faces", {})
        if m not in cache:
            lo, hi = np.zeros(3, np.bool_), np.zeros(3, np.bool_)
            for name, face in self.ice.bcs.table.items():
                i = ("x-", "x+", "y-", "y+", "z-", "z+").index(name)
                if face["Velocity"][m][0] == SYMMETRY:
                    (hi if i % 2 else lo)[i // 2] = True
            cache[m] = lo, hi
        return cache[m]

    def _nc_to_cc(self, patch, m, gmass, gvol, gvel, cmass, spv, vel, rho):
        b, cc_low, node_low, dims, n_lo, n_hi = self._geom(patch)
        sym_lo, sym_hi = self._sym(m)
        mat = self.mpm.materials[m]
        K.nc_to_cc(gmass, gvol, gvel, node_low, cc_low, b.lo, b.hi, dims, sym_lo, sym_hi, n_lo, n_hi,
                   self.tiny * b.vol, mat.density, b.vol, cmass, spv, vel, rho)

    def _scalar_to_cc(self, patch, m, gmass, gq, out, old=_NO1):
        """Mass-weighted cell mean of a nodal scalar of solid m (cells without solid: its object's
        temperature); with `old`, Uintah's blend of it with the cell's last value (kernels.nc_to_cc_scalar)."""
        b, cc_low, node_low, dims, n_lo, n_hi = self._geom(patch)
        sym_lo, sym_hi = self._sym(m)
        K.nc_to_cc_scalar(gmass, gq, node_low, cc_low, b.lo, b.hi, dims, sym_lo, sym_hi, n_lo, n_hi,
                          self.tiny * b.vol, self.solid_temp[m], old, out)

    def _extra_vector(self, patch, q, m, b, only_symmetry=False):
        """Extra cells of a CC vector: reflected on symmetry planes, copied elsewhere (unless
        only_symmetry)."""
        key = (patch.id, m, only_symmetry)
        faces = self.__dict__.setdefault("_extra_vector_faces", {}).get(key)
        if faces is None:
            faces = self._extra_vector_faces[key] = []
            for name in patch.boundary_faces:
                i = ("x-", "x+", "y-", "y+", "z-", "z+").index(name)
                kind = SYMMETRY if self.ice.bcs.table[name]["Velocity"][m][0] == SYMMETRY else NEUMANN
                if not (only_symmetry and kind != SYMMETRY):
                    faces.append((i // 2, i % 2, kind))
        for d, s, kind in faces:
            bc_vector(q, d, s, kind, _ZERO3, 0.0, b.lo, b.hi, b.olo, b.ohi)

    # -- initialization: the fluids from their geometry (or what the particles leave) -------
    def initialize_fluids(self, patch, matls, old_dw, new_dw):
        """ICE state of the fluids. gas_start geometry (Uintah's ICEMaterial::initializeCells): each
        fluid's volume fraction is its geometry's fraction of the cell (sampled at its <res>), plus
        Uintah's 1e-12 trace; the first equilibration scales it with the solid's (the TMV of
        kernels.solids_at_old_pressure). gas_start particles: the fluids' fractions are
        1 - theta_solid, split in proportion to their geometry fractions, theta_solid from the
        particles through the nodes (step 1), so the first equilibration sees sum theta = 1."""
        ice, lv = self.ice, patch.level
        b = ice.boxes(patch)
        own = patch.owned(CC)
        sl = patch.slices(CC, own)
        ths = np.zeros(patch.alloc_shape(CC))
        for m in self.mpm_matls:
            gm, gv = self._particle_nodes(patch, m, new_dw)
            cm = np.zeros_like(ths)
            spv = np.zeros_like(ths)
            self._nc_to_cc(patch, m, gm, gv, np.zeros(gm.shape + (3,)), cm, spv, np.zeros(ths.shape + (3,)), _NO1)
            ths += cm * spv / b.vol
        ice_mats = [ice.materials[m] for m in ice.ice_matls]
        obj_fr = [[cell_fractions(piece, lv, own, g["res"]) for piece, g in mat.objects] for mat in ice_mats]
        fr = [sum(fs) for fs in obj_fr]
        geometric = [np.minimum(f, 1.0) for f in fr]
        pw = sum(f * self._object_pressure(m, mat, k) for m, mat, fs in zip(ice.ice_matls, ice_mats, obj_fr)
                 for k, f in enumerate(fs))
        tot = sum(fr)
        empty = tot <= 0.0
        if empty.any():           # cells the solid's geometry fills: take the neighbours' fluid
            fr = [_spread(f, empty) for f in fr]
            pw = _spread(pw, empty)
            tot = sum(fr)
            fr = [np.where(tot > 0, f, 1.0 if k == 0 else 0.0) for k, f in enumerate(fr)]
            pw = np.where(tot > 0, pw, ice.reference_pressure)    # no fluid on the patch: Uintah's p_ref
            tot = np.where(tot > 0, tot, 1.0)
        press = pw / tot
        outside_idiom = empty.any() and ice_mats[-1].first_object_outside
        fr_last_none = geometric[-1] <= 0.0
        if outside_idiom:
            # Uintah's idiom (DDT.ups, PBX_array/oneCylinder.ups): the last fluid's first object
            # outside the domain; Uintah's ICE sets press_CC to each fluid's EOS pressure in turn,
            # so the cells no object covers, here those the solid fills, start at the last one's
            press[empty] = self._object_pressure(ice.ice_matls[-1], ice_mats[-1], 0)
        press_start = press
        if outside_idiom and self.gas_start == "geometry":
            # Uintah's ICE::actuallyInitialize: press_CC is each fluid's EOS pressure in turn, so the
            # last one's wherever its own objects leave it at its first object's state; the other
            # fluids keep their objects' densities
            press_start = press.copy()
            press_start[fr_last_none] = self._object_pressure(ice.ice_matls[-1], ice_mats[-1], 0)
        free = np.clip(1.0 - ths[sl], 0.0, 1.0)
        p_arr = new_dw.allocate(I.press_CC, 0, patch)
        p_arr[sl] = press_start
        for m, mat, f, fs, f_geom in zip(ice.ice_matls, ice_mats, fr, obj_fr, geometric):
            g0 = mat.objects[0][1]
            temp = np.full(press.shape, g0["temperature"])
            vel = np.broadcast_to(np.array(g0["velocity"], float), press.shape + (3,)).copy()
            for (_, g), fk in zip(mat.objects, fs):        # the last object covering a cell sets T, v (Uintah's)
                hit = fk > 0.0
                temp[hit], vel[hit] = g["temperature"], g["velocity"]
            rho_micro = _rho_micro_array(press_start if mat is ice_mats[-1] else press, temp, g0["density"],
                                         *ice._eos(m))
            if outside_idiom and mat is not ice_mats[-1]:
                rho_micro[empty] = g0["density"]        # Uintah's: the first object's, at any pressure
            arrs = [new_dw.allocate(lab, m, patch) for lab in (I.rho_CC, I.vel_CC, I.temp_CC, I.sp_vol_CC,
                                                                I.speedSound_CC)]
            if self.gas_start == "geometry":
                arrs[0][sl] = rho_micro * f_geom + 1e-12 * rho_micro
            else:
                arrs[0][sl] = np.maximum(rho_micro * free * f / tot, 1e-12 * rho_micro)
            arrs[1][sl] = vel
            arrs[2][sl] = temp
            arrs[3][sl] = 1.0 / rho_micro
            ice.bcs.scalar(patch, arrs[0], "Density", m, b)
            ice.bcs.scalar(patch, arrs[2], "Temperature", m, b)
            ice.bcs.velocity(patch, arrs[1], m, b, initial=True)
            ice.bcs.scalar(patch, arrs[3], "Temperature", m, b, copy=True)
            if self.gas_start == "geometry":     # Uintah: 1 / rho_micro, rho_micro under the Density BC
                rho_micro_bc = np.zeros(arrs[3].shape)
                rho_micro_bc[sl] = rho_micro
                ice.bcs.scalar(patch, rho_micro_bc, "Density", m, b)
                np.divide(1.0, rho_micro_bc, out=arrs[3], where=rho_micro_bc > 0.0)
            _speed_sound(arrs[3], arrs[2], arrs[4], *ice._eos(m))
        ice.bcs.scalar(patch, p_arr, "Pressure", 0, b)

    def _object_pressure(self, m, mat, k):
        """The pressure ICE material m's object k starts at: its <pressure>, unless its <density>
        and <temperature> give by the EOS a pressure that differs by more than 0.1 %;
        then that one, as Uintah's initialization, which takes the density and lets the EOS set the
        pressure (Uintah's DDT.ups: JWL products at 1500 kg/m^3 and 3000 K, 7e9 Pa, <pressure> 1 atm)."""
        g = mat.objects[k][1]
        p_eos = float(_press_array(np.array([g["density"]]), np.array([g["temperature"]]), *self.ice._eos(m))[0])
        if abs(p_eos - g["pressure"]) <= 1e-3 * max(abs(p_eos), abs(g["pressure"])):
            return g["pressure"]
        seen = self.__dict__.setdefault("_noted_objects", set())
        if (m, k) not in seen:
            seen.add((m, k))
            node = mat.object_nodes[k]
            where = f"{node.filename}:{node.line}: "
            print(f"pysus: note: {where}ICE material {mat.name!r}, geometry object {k + 1}: its <density> and "
                  f"<temperature> give {p_eos:.6g} Pa by its EOS, not its <pressure> {g['pressure']:.6g}; it starts at "
                  "the EOS pressure (Uintah's initialization takes the density)", file=sys.stderr)
        return p_eos

    def _particle_nodes(self, patch, m, dw):
        """Node mass and volume of material m from its particles (owned + ghost) in `dw`."""
        mpm, lv = self.mpm, patch.level
        px = dw.get(M.pX, m, patch)
        n = len(px)
        shape = patch.alloc_shape(NC)
        gm, gv = np.zeros(shape), np.zeros(shape)
        scratch = np.zeros(shape + (3,))
        mpm.p2g(px, dw.get(M.pMass, m, patch), np.zeros((n, 3)), dw.get(M.pVolume, m, patch),
                np.zeros((n, 3, 3)), np.zeros((1, 3)), False, mpm._lp(dw, m, patch, n), lv.anchor, lv.dx,
                np.array(patch.low_index(NC), np.int64), gm, scratch, gv, scratch.copy(), scratch.copy())
        return gm, gv

    # -- step 1: particle state -> nodes -> cell centres ------------------------------------------
    def interpolate_nc_to_cc(self, patch, matls, old_dw, new_dw):
        """interpolateNCToCC_0: cMass, rho_CC, vel_CC, temp_CC and the specific volume of each
        solid at the cell centres (the specific volume is the particles' volume, which MPM
        integrates in time through F: eq. 53 for the solid). A solid's temp_CC is, as Uintah's,
        its nodes' mean blended with the temperature the last step's exchange left in the cell
        in the proportion of the floor mass to cMass (a cell with no solid keeps that one)."""
        b = self.ice.boxes(patch)
        for m in matls:
            cm = new_dw.allocate(MI.cMass, m, patch)
            spv = new_dw.allocate(MI.sp_vol_mpm_CC, m, patch, 1.0 / self.mpm.materials[m].density)
            vel = new_dw.allocate(I.vel_CC, m, patch)
            rho = new_dw.allocate(I.rho_CC, m, patch)
            temp = new_dw.allocate(I.temp_CC, m, patch, self.solid_temp[m])
            self._nc_to_cc(patch, m, new_dw.get(M.gMass, m, patch), new_dw.get(M.gVolume, m, patch),
                           new_dw.get(M.gVelocity, m, patch), cm, spv, vel, rho)
            if self.mpm.thermal:
                self._scalar_to_cc(patch, m, new_dw.get(M.gMass, m, patch), new_dw.get(M.gTemperature, m, patch),
                                   temp, old_dw.get(I.temp_CC, m, patch))
                self.ice.bcs.scalar(patch, temp, "Temperature", m, b, copy=True)
            self.ice.bcs.scalar(patch, rho, "Density", m, b, copy=True)   # mass from particles, never the deck
            self.ice.bcs.scalar(patch, spv, "Temperature", m, b, copy=True)
            self.ice.bcs.scalar(patch, cm, "Temperature", m, b, copy=True)
            self._extra_vector(patch, vel, m, b)

    # -- steps 2-6: ICE's multi-material tasks over all materials ----------------------------------
    def equilibration_pressure(self, patch, matls, old_dw, new_dw):
        """Eq. 13 over solids and fluids (the solids with the sec. 3.1 threshold EOS): ICE's
        computeEquilibrationPressure with MPMICE's kernel (equilibration.equilibrate, the same values)
        on arrays seen with the collapsed axes first; an iterate below 0 and a cell that does not
        converge handled as Uintah's MPMICE (|dp|, then its binary search)."""
        ice, start = self.ice, StartOfStep(old_dw, new_dw, self.mpm_matls)
        b = ice.boxes(patch)
        peq = new_dw.allocate(I.press_equil_CC, 0, patch)
        get = lambda lab: tuple(b.view(start.get(lab, m, patch)) for m in matls)
        new = lambda lab: tuple(b.view(new_dw.allocate(lab, m, patch)) for m in matls)
        spv, vfs, css = new(I.sp_vol_CC), new(I.vol_frac_CC), new(I.speedSound_CC)
        rhos, temps, sp_old = get(I.rho_CC), get(I.temp_CC), get(I.sp_vol_CC)
        p_old = b.view(old_dw.get(I.press_CC, 0, patch))
        # the solids start from their EOS volume at the old pressure (Uintah's normalization); prescribed
        # (rmpmice) solids only with <gas_start>geometry (Uintah's start: the fluids scaled too, and the
        # deck model's EOS: sus's press_CC to 1e-12 on a rigid slab in 10 atm air,
        # tests/mpmice/test_solid_eos_decks.py); with pysus's particle start, their default, scaling the
        # solids alone by their stand-in EOS collapsed the Mach 3 wedge's time step (4e-8 s, not 5.7e-6)
        scaled, sp_start = rhos, sp_old
        tmv = new_dw.allocate(I.TMV_CC, 0, patch, fill=b.vol)
        if not self.rigid or self.gas_start == "geometry":
            solid = np.array([m in self.mpm_matls for m in matls])
            fluids_too = self.gas_start == "geometry"
            scaled = tuple(r.copy() if s or fluids_too else r for r, s in zip(rhos, solid))
            sp_start = tuple(np.empty_like(v) if s else v for v, s in zip(sp_old, solid))
            K.solids_at_old_pressure(rhos, temps, sp_old, p_old, solid, ice.codes, ice.params, ice.cvs, ice.gammas,
                                     fluids_too, scaled, sp_start, b.view(tmv), b.vol, b.v_olo, b.v_ohi)
        E.equilibrate(scaled, temps, sp_start, p_old,
                      spv, vfs, css, b.view(peq), ice.codes, ice.params, ice.cvs, ice.gammas, b.v_olo, b.v_ohi,
                      1e-11, ice.max_iter, True)
        ice.bcs.scalar(patch, peq, "Pressure", 0, b)

    def vel_fc(self, patch, matls, old_dw, new_dw):
        """Eq. 28 for every material (the solids' from their step-1 cell-centre state)."""
        self.ice.vel_fc(patch, matls, StartOfStep(old_dw, new_dw, self.mpm_matls), new_dw)

    def press_fc(self, patch, matls, old_dw, new_dw):
        """Eq. 31 with rho summed over solids and fluids."""
        self.ice.press_fc(patch, matls, StartOfStep(old_dw, new_dw, self.mpm_matls), new_dw)

    def lagrangian_sp_vol(self, patch, matls, old_dw, new_dw):
        """Eq. 40 for every material (the solids' result is unused: their volume is the particles')."""
        self.ice.lagrangian_sp_vol(patch, matls, StartOfStep(old_dw, new_dw, self.mpm_matls), new_dw)

    # -- step 12: the fluids' advection next to the solids -----------------------------------------
    def open_faces(self, patch, m, new_dw, dt):
        """What ICE's advection of fluid m moves across the faces (ice.advection_faces): its face
        velocities, and where a solid's particles advance from a cell toward a more open
        neighbour (the open part of a cell: the fluids' own volume over the cell's, their volume
        fractions times TMV_CC / V; kernels.open_fraction) the further
        fraction of the cell's fluid that the solid displaces through the face
        (kernels.open_face_transfers, at most OPEN_CAP of a cell a step). ICE's flux alone
        carries the fluid at the cell's mean density and leaves some of it in the cells a piston
        fills. The solid's motion is its particles' (vel_CC of step 1), not its exchanged face
        velocity, which a gas flowing through a solid at rest gives it: nothing changes where
        the particles are at rest or no solid moves into a cell that holds fluid. The fluid so
        moved carries its flow work p v with its energy (advection._open_transfers)."""
        ice = self.ice
        uf = ice._faces(new_dw, I.FC_VEL_ME, m, patch)
        none = [np.zeros((1, 1, 1))] * 3
        shape = patch.alloc_shape(CC)
        vf = lambda ms: tuple(new_dw.get(I.vol_frac_CC, k, patch) for k in ms)
        solid_vf = vf(self.mpm_matls)
        opn = np.empty(shape)
        b = ice.boxes(patch)
        K.open_fraction(vf(ice.ice_matls), new_dw.get(I.TMV_CC, 0, patch), b.vol, np.zeros(3, np.int64),
                        np.array(shape, np.int64), opn)
        mass = new_dw.get(I.mass_L_CC, m, patch)
        cap = self.OPEN_CAP / (2 * int(np.count_nonzero(ice.dims)))        # per face: a cell's faces together
        ef = list(none)
        moved = False
        solid_vel = tuple(new_dw.get(I.vel_CC, s, patch) for s in self.mpm_matls)    # step 1: the particles'
        far = 1 << 40           # the extra cells of the domain's boundary faces: no transfer into or out of them
        inside_lo = np.array([b.lo[d] if patch.at_low[d] else -far for d in range(3)], np.int64)
        inside_hi = np.array([b.hi[d] if patch.at_high[d] else far for d in range(3)], np.int64)
        for d in range(3):
            if ice.dims[d]:
                ef[d] = np.empty(uf[d].shape)
                moved |= K.open_face_transfers(solid_vel, solid_vf, opn, mass, b.sh[d], d, b.flo[d], b.fhi[d],
                                               dt / patch.level.dx[d], cap, ef[d], inside_lo, inside_hi)
        if not moved:
            return uf, none, none[0]
        return uf, ef, new_dw.get(I.press_CC, 0, patch)        # the transfers' flow work p v

    # at most this fraction of a cell's fluid moves besides ICE's fluxes in a step (through all its
    # faces): ICE's second-order flux of m v may itself take up to about 4 |u| dt/dx of a cell
    OPEN_CAP = 0.3

    # -- step 7: the equilibration pressure acting on the solid ------------------------------------
    def pressure_internal_force(self, patch, matls, old_dw, new_dw):
        """interpolatePressCCToPressNC + interpolatePAndGradP: p - p_ref at the particles and its
        share of the internal force, fint_i -= V_p (p_p - p_ref) grad S_ip (see kernels.py)."""
        mpm, lv = self.mpm, patch.level
        press = new_dw.get(I.press_CC, 0, patch)
        cc_low = np.array(patch.low_index(CC), np.int64)
        node_low = np.array(patch.low_index(NC), np.int64)
        fn = K.pressure_force(mpm.kind)
        for m in matls:
            px = old_dw.get(M.pX, m, patch)
            n = len(px)
            own = old_dw.ghost_owned_mask(M.pX, m, patch)
            own = np.zeros(0, np.bool_) if own is None else own
            n_own = n if own.size == 0 else int(np.count_nonzero(own))
            pp = np.empty(n_own)
            fn(mpm.dim, px, old_dw.get(M.pVolume, m, patch), mpm._lp(old_dw, m, patch, n), lv.anchor, lv.dx,
               node_low, press, cc_low, self.dims_i, self.ice.reference_pressure,
               new_dw.get_modifiable(M.gIntForce, m, patch), own, pp)
            new_dw.put(MI.pPressure, m, patch, pp)

    # -- step 10: the exchange, trace materials at the cell's temperature --------------------------
    def exchange(self, patch, matls, old_dw, new_dw):
        """ICE's addExchangeToMomentumAndEnergy over solids and fluids (eqs. 38-39), Uintah's
        exchange alone. With <MPMICE><trace_temperatures>true (pysus's rule, not Uintah's), in
        cells where every fluid's volume fraction is below THETA_TRACE, the fluids then take the
        temperature of the solids that exchange heat (kernels.trace_temperatures): those
        solids' temperature evolves, so the heat they give is carried to their particles.
        Solids that exchange no heat (<heat> 0) leave the slivers adiabatic, and a cell where a
        reaction model adds mass to a fluid keeps the exchange's temperatures."""
        keep = _KeepAllocated(new_dw)
        self.ice.exchange_cc(patch, matls, old_dw, keep)
        if not self.solid_heat or not self.trace_temperatures:
            return
        b = self.ice.boxes(patch)
        get = lambda lab: tuple(new_dw.get(lab, m, patch) for m in matls)
        role = np.array([1 if m in self.ice.ice_matls else (2 if m in self.solid_heat else 0) for m in matls])
        fed = np.zeros((0, 0, 0), np.bool_)
        if self.models is not None:
            from components.models import labels as ML
            fed = np.zeros(new_dw.get(I.mass_L_CC, matls[0], patch).shape, np.bool_)
            for m in self.models.products():
                fed |= new_dw.get(ML.modelMass_src, m, patch) != 0.0
        K.trace_temperatures(get(I.mass_L_CC), tuple(keep.arrays[(I.int_eng_L_ME_CC.name, m)] for m in matls),
                             get(I.vol_frac_CC), self.ice.cvs[np.array(matls)], role, THETA_TRACE, fed,
                             b.olo, b.ohi)

    # -- steps 8-9: the solid's Lagrangian values at the cell centres --------------------------------
    def lagrangian_values_mpm(self, patch, matls, old_dw, new_dw):
        """computeLagrangianValuesMPM: m^L = cMass, (mu)^L = sum_w m_i v*_i - dt V theta grad p*
        (eq. 33), (me)^L = m cv T* with T* the cell mean of the nodal temperature advanced
        by this step's conduction, g.temperature + dt g.temperatureRate with the Temperature face
        conditions applied (Uintah's gTemperatureStar; without a thermal model the solid's T is
        held); a cell with little more than the floor mass keeps its step-1 vel_CC and temp_CC
        (kernels.lagrangian_solid)."""
        ice = self.ice
        b = ice.boxes(patch)
        dt = old_dw.get_reduction(FL.delT)
        pf = ice._faces(new_dw, I.PRESS_FC, 0, patch)
        shape = patch.alloc_shape(CC)
        scratch = ice._scratch("mpmice.cmass", shape)
        for m in matls:
            vstar = np.zeros(shape + (3,))
            self._nc_to_cc(patch, m, new_dw.get(M.gMass, m, patch), new_dw.get(M.gVolume, m, patch),
                           new_dw.get(M.gVelocityStar, m, patch), scratch, _NO1, vstar, _NO1)
            self._extra_vector(patch, vstar, m, b)
            K.lagrangian_solid(new_dw.get(MI.cMass, m, patch), vstar, self._temperature_star(patch, m, new_dw, dt),
                               new_dw.get(I.vel_CC, m, patch), new_dw.get(I.temp_CC, m, patch), self.tiny * b.vol,
                               new_dw.get(I.vol_frac_CC, m, patch), pf[0], pf[1], pf[2], b.sh[0], b.sh[1], b.sh[2],
                               ice.dims, new_dw.allocate(I.mass_L_CC, m, patch, fill=None),
                               new_dw.allocate(I.mom_L_CC, m, patch, fill=None),
                               new_dw.allocate(I.int_eng_L_CC, m, patch, fill=None),
                               new_dw.allocate(MI.mom_mpm_CC, m, patch), b.olo, b.ohi, b.lo, b.hi, b.vol,
                               patch.level.dx, dt, ice.cvs[m])

    def _temperature_star(self, patch, m, new_dw, dt):
        """The solid's cell temperature after this step's conduction (temp_CC without it); the
        Temperature face conditions set on the ghost nodes too, as their owner sets them."""
        temp = new_dw.get(I.temp_CC, m, patch)
        if m not in self.mpm.conducting:
            return temp
        tstar = temp.copy()
        gT = new_dw.get(M.gTemperature, m, patch) + dt * new_dw.get(M.gTemperatureRate, m, patch)
        if self.mpm.temperature_bcs:
            self.mpm.bcs.apply_temperature(patch, m, gT, ghosts=True)
        self._scalar_to_cc(patch, m, new_dw.get(M.gMass, m, patch), gT, tstar)
        return tstar

    def lagrangian_values_fluid(self, patch, matls, old_dw, new_dw):
        """ICE::computeLagrangianValues for the fluids, their flow work over the cell's total
        material volume TMV_CC (Uintah's accumulateEnergySourceSinks), with <adiabatic_compression>
        a compressed ideal gas's work at most the adiabat's (adiabatic.py), plus <ADD_HEAT>: dt * coeff * rho_CC * V
        added to int_eng_L_CC where the material's volume fraction exceeds 0.001, while
        add_heat_t_start <= t <= add_heat_t_final (t: the time at the start of the step), as
        Uintah's accumulateEnergySourceSinks does."""
        tmv = new_dw.get(I.TMV_CC, 0, patch)
        if self.add_heat is None and not self.adiabatic_compression:
            self.ice.lagrangian_values(patch, matls, old_dw, new_dw, tmv)
            return
        keep = _KeepAllocated(new_dw)
        self.ice.lagrangian_values(patch, matls, old_dw, keep, tmv)
        if self.adiabatic_compression:
            self._limit_compression_work(patch, matls, old_dw, new_dw, keep, tmv)
        if self.add_heat is None:
            return
        coeffs, t0, t1 = self.add_heat
        t = float(old_dw.get_reduction(FL.simTime))
        if not t0 <= t <= t1:
            return
        dt = old_dw.get_reduction(FL.delT)
        b = self.ice.boxes(patch)
        sl = tuple(slice(lo, hi) for lo, hi in zip(b.lo, b.hi))
        for m in matls:
            if m not in coeffs:
                continue
            eng = keep.arrays[(I.int_eng_L_CC.name, m)]          # this task's own output
            rho = old_dw.get(I.rho_CC, m, patch)[sl]
            vf = new_dw.get(I.vol_frac_CC, m, patch)[sl]
            eng[sl] += np.where(vf > 0.001, (coeffs[m] * dt * b.vol) * rho, 0.0)

    def _limit_compression_work(self, patch, matls, old_dw, new_dw, keep, tmv):
        """adiabatic.limit_compression_work on the int_eng_L_CC of each ideal gas with a constant cv."""
        ice = self.ice
        b = ice.boxes(patch)
        lo, hi = np.array(b.lo, np.int64), np.array(b.hi, np.int64)
        press, delP = new_dw.get(I.press_CC, 0, patch), new_dw.get(I.delP_Dilatate, 0, patch)
        for m in matls:
            if ice.codes[m] != IDEAL_GAS or ice._cv_model(m) is not None or m in ice.caloric:
                continue
            new = lambda lab: new_dw.get(lab, m, patch)
            AD.limit_compression_work(old_dw.get(I.rho_CC, m, patch), old_dw.get(I.temp_CC, m, patch),
                                      new(I.vol_frac_CC), new(I.sp_vol_CC), new(I.speedSound_CC), press, delP, tmv,
                                      keep.arrays[(I.int_eng_L_CC.name, m)], lo, hi, float(ice.cvs[m]),
                                      float(ice.gammas[m]))

    # -- diagnostics: Uintah's source and rate labels (scheduled only when saved) -----------------
    def source_sinks(self, patch, matls, old_dw, new_dw):
        """mom_source_CC = mom_L - m_L u and intE_source_CC = (m e)_L - m_L cv T: what steps 8-9
        added to the start-of-step state (for a solid the momentum source holds all the nodal
        forces of the step, stress divergence included, not only the pressure gradient)."""
        start = StartOfStep(old_dw, new_dw, self.mpm_matls)
        o = _owned(self.ice.boxes(patch))
        for m in matls:
            mass = new_dw.get(I.mass_L_CC, m, patch)[o]
            ms = new_dw.allocate(MI.mom_source_CC, m, patch)
            ms[o] = new_dw.get(I.mom_L_CC, m, patch)[o] - mass[..., None] * start.get(I.vel_CC, m, patch)[o]
            es = new_dw.allocate(MI.intE_source_CC, m, patch)
            es[o] = new_dw.get(I.int_eng_L_CC, m, patch)[o] - (mass * self.ice.cvs[m]) * start.get(I.temp_CC, m, patch)[o]

    def temperature_rate(self, patch, matls, old_dw, new_dw):
        """Tdot = (T after the exchange - T at the start of the step) / dt over the owned cells
        (0 in empty cells; the halo of the Lagrangian arrays is never written, so it is not read)."""
        start = StartOfStep(old_dw, new_dw, self.mpm_matls)
        dt = old_dw.get_reduction(FL.delT)
        o = _owned(self.ice.boxes(patch))
        for m in matls:
            mass = new_dw.get(I.mass_L_CC, m, patch)[o]
            mcv = mass * self.ice.cvs[m]
            temp = np.divide(new_dw.get(I.int_eng_L_ME_CC, m, patch)[o], mcv, out=np.zeros_like(mcv), where=mass > 0)
            out = new_dw.allocate(MI.Tdot, m, patch)
            out[o] = np.where(mass > 0, (temp - start.get(I.temp_CC, m, patch)[o]) / dt, 0.0)

    def solid_temperature_after_exchange(self, patch, matls, old_dw, new_dw):
        """The solids' temp_CC that the step leaves (saves, and the next step's step 1 blends with)
        is their exchanged temperature (me)^L_ME / (m^L cv), as Uintah's exchange leaves it."""
        b = self.ice.boxes(patch)
        inner = tuple(slice(lo, hi) for lo, hi in zip(b.lo, b.hi))
        for m in matls:
            temp = new_dw.get_modifiable(I.temp_CC, m, patch)
            mcv = new_dw.get(I.mass_L_CC, m, patch)[inner] * self.ice.cvs[m]
            temp[inner] = new_dw.get(I.int_eng_L_ME_CC, m, patch)[inner] / mcv
            self.ice.bcs.scalar(patch, temp, "Temperature", m, b, copy=True)

    def initialize_solid_temperature(self, patch, matls, old_dw, new_dw):
        """The solids' temp_CC before the first step (Uintah's MPMMaterial::initializeCCVariables):
        300 K, and in the cells whose centre lies within three cells of an object's bounding box
        that object's temperature (the last such object's). Step 1 keeps it where a cell holds
        no solid."""
        dx, xc = patch.level.dx, patch.cell_centers()
        for m in matls:
            temp = new_dw.allocate(I.temp_CC, m, patch, 300.0)
            for obj in self.mpm.materials[m].objects:
                if "piece" not in obj:          # a membrane's particle sheet: no bounding box read
                    continue
                lo, hi = obj["piece"].bounds()
                near = [(x > lo[d] - 3.0 * dx[d]) & (x < hi[d] + 3.0 * dx[d]) for d, x in enumerate(xc)]
                temp[np.ix_(*near)] = obj["temperature"]

    def solid_velocity_after_exchange(self, patch, matls, old_dw, new_dw):
        """The solids' vel_CC that the step leaves (and saves) is their exchanged velocity
        (mu)^L_ME / m^L, as Uintah's exchange leaves it; the step's tasks read the step-1 value
        before this one."""
        b = self.ice.boxes(patch)
        inner = tuple(slice(lo, hi) for lo, hi in zip(b.lo, b.hi))
        for m in matls:
            vel = new_dw.get_modifiable(I.vel_CC, m, patch)
            mass = new_dw.get(I.mass_L_CC, m, patch)[inner]
            vel[inner] = new_dw.get(I.mom_L_ME_CC, m, patch)[inner] / mass[..., None]
            self._extra_vector(patch, vel, m, b)

    # -- steps 10 -> 13: the exchange's change carried back to the nodes ------------------------------
    def velocity_rates(self, patch, matls, old_dw, new_dw):
        """computeCCVelAndTempRates: dV/dt of each solid cell (kernels.velocity_rates)."""
        b = self.ice.boxes(patch)
        dt = old_dw.get_reduction(FL.delT)
        for m in matls:
            out = new_dw.allocate(MI.dVdt_CC, m, patch)
            mom_me, mass_L = new_dw.get(I.mom_L_ME_CC, m, patch), new_dw.get(I.mass_L_CC, m, patch)
            K.velocity_rates(mom_me, new_dw.get(MI.mom_mpm_CC, m, patch), mass_L, dt, b.lo, b.hi, out)
            self._extra_vector(patch, out, m, b)
            open_faces = [f for f in patch.boundary_faces
                          if self.ice.bcs.table[f]["Velocity"][m][0] != SYMMETRY]
            if open_faces:      # Uintah: the rate of every extra cell, then set_if_sym_BC
                vstar = np.zeros(out.shape)
                bb, cc_low, node_low, dims, n_lo, n_hi = self._geom(patch)
                sym_lo, sym_hi = self._sym(m)
                K.nc_to_cc(new_dw.get(M.gMass, m, patch), new_dw.get(M.gVolume, m, patch),
                           new_dw.get(M.gVelocityStar, m, patch), node_low, cc_low, b.olo, b.ohi, dims, sym_lo,
                           sym_hi, n_lo, n_hi, self.tiny * b.vol, self.mpm.materials[m].density, b.vol,
                           np.zeros(out.shape[:3]), _NO1, vstar, _NO1)
                K.velocity_rates_extra(mom_me, mass_L, vstar, dt, b.lo, b.hi, b.olo, b.ohi, out)
                self._extra_vector(patch, out, m, b, only_symmetry=True)

    def interpolate_cc_to_nc(self, patch, matls, old_dw, new_dw):
        """interpolateCCToNC: v*_i += dt <dV/dt>, a_i += <dV/dt> over the cells around node i."""
        dt = old_dw.get_reduction(FL.delT)
        lo, hi = patch.owned_local(NC)
        lo, hi = np.array(lo, np.int64), np.array(hi, np.int64)
        cc_low = np.array(patch.low_index(CC), np.int64)
        node_low = np.array(patch.low_index(NC), np.int64)
        for m in matls:
            K.cc_to_nc_increment(new_dw.get(MI.dVdt_CC, m, patch), cc_low, node_low, lo, hi, self.dims_i, dt,
                                 new_dw.get_modifiable(M.gVelocityStar, m, patch),
                                 new_dw.get_modifiable(M.gAcceleration, m, patch))

    # -- the solid's heat exchange: step 10 -> 13 for the temperature -------------------------------
    def setup_solid_heat(self):
        """After ICE is read: a solid that exchanges heat with a fluid (a nonzero <heat>
        coefficient) carries p.temperature, and the exchange's change of its cell
        temperature goes back to the nodes (dTdt_NC) and particles like dV/dt does."""
        H, fl = self.ice.H, self.ice.ice_matls
        self.solid_heat = [m for m in self.mpm_matls
                           if self.ice.var_H or any(H[m, f] > 0 or H[f, m] > 0 for f in fl)]
        for m in self.solid_heat:
            mat = self.mpm.materials[m]
            if mat.specific_heat <= 0:
                raise mat.node.error("a solid that exchanges heat (<heat> coefficient > 0) needs <specific_heat> > 0")
        if self.solid_heat and not self.mpm.thermal:
            self.mpm.thermal_needed = True
        if self.solid_heat:
            self.mpm.thermal_rates = (MI.dTdt_NC,)
        self.mpm.thermal_setup()
        if self.mpm.thermal and self.solid_temperature_bcs:    # Uintah's MPM sets them on gTemperature and
            self.mpm.temperature_bcs = self.mpm.bcs.use_temperature_bcs()   # gTemperatureStar in MPMICE too
        self.mpm._carried()

    def thermal_requires(self, t, step):
        """What the solid's temperature adds to the requires of step 1 ("nc_to_cc") or 8 ("lagrangian")."""
        if not self.mpm.thermal:
            return t
        t.requires(NEW, M.gTemperature, Ghost.AROUND_CELLS, 1)
        if step == "lagrangian" and self.mpm.conducting:
            t.requires(NEW, M.gTemperatureRate, Ghost.AROUND_CELLS, 1, matls=self.mpm.conducting)
        return t

    def schedule_solid_heat(self, sched):
        """computeCCVelAndTempRates and interpolateCCToNC for the temperature."""
        if not self.solid_heat:
            return
        ms = self.mpm_matls
        sched.add_task(Task("MPMICE::computeCCTempRates", self.temperature_rates, ms)
                       .requires(OLD, FL.delT).requires(NEW, I.int_eng_L_ME_CC).requires(NEW, I.int_eng_L_CC)
                       .requires(NEW, I.mass_L_CC).computes(MI.dTdt_CC))
        sched.add_task(Task("MPMICE::interpolateCCToNC_T", self.interpolate_temperature_rate, ms)
                       .requires(NEW, MI.dTdt_CC, Ghost.AROUND_CELLS, 1).computes(MI.dTdt_NC))

    def temperature_rates(self, patch, matls, old_dw, new_dw):
        """dTdt_CC = ((me)^L_ME - (me)^L) / (m^L cv dt) per solid cell. In the extra cells of a
        face that is not a symmetry plane, as Uintah's computeCCVelAndTempRates over the extra
        cells, the exchanged temperature the face's Temperature condition puts there less the
        extra cell's own Lagrangian temperature, over dt (kernels.temperature_rates_extra); on a
        symmetry plane the interior's rate (set_if_sym_BC)."""
        b = self.ice.boxes(patch)
        dt = old_dw.get_reduction(FL.delT)
        for m in matls:
            out = new_dw.allocate(MI.dTdt_CC, m, patch)
            if m not in self.solid_heat:
                continue
            eng_me, eng_L = new_dw.get(I.int_eng_L_ME_CC, m, patch), new_dw.get(I.int_eng_L_CC, m, patch)
            mass_L, cv = new_dw.get(I.mass_L_CC, m, patch), self.ice.cvs[m]
            K.temperature_rates(eng_me, eng_L, mass_L, cv, dt, b.lo, b.hi, out)
            self.ice.bcs.scalar(patch, out, "Temperature", m, b, copy=True)
            sym = {f: self.ice.bcs.table[f]["Velocity"][m][0] == SYMMETRY for f in patch.boundary_faces}
            if all(sym.values()):
                continue
            inner = tuple(slice(lo, hi) for lo, hi in zip(b.lo, b.hi))
            temp_me = np.zeros(out.shape)
            temp_me[inner] = eng_me[inner] / (mass_L[inner] * cv)
            self.ice.bcs.scalar(patch, temp_me, "Temperature", m, b)
            K.temperature_rates_extra(temp_me, eng_L, mass_L, cv, dt, b.lo, b.hi, b.olo, b.ohi, out)
            for name in (f for f, s in sym.items() if s):
                i = ("x-", "x+", "y-", "y+", "z-", "z+").index(name)
                bc_scalar(out, i // 2, i % 2, 0, 0.0, 0.0, b.lo, b.hi, b.olo, b.ohi)

    def interpolate_temperature_rate(self, patch, matls, old_dw, new_dw):
        """dTdt_NC: the mean dTdt_CC of the cells around each node (added to the particles'
        temperature rate by MPM::updateParticleTemperature)."""
        lo, hi = patch.owned_local(NC)
        lo, hi = np.array(lo, np.int64), np.array(hi, np.int64)
        cc_low = np.array(patch.low_index(CC), np.int64)
        node_low = np.array(patch.low_index(NC), np.int64)
        for m in matls:
            K.cc_to_nc_scalar(new_dw.get(MI.dTdt_CC, m, patch), cc_low, node_low, lo, hi, self.dims_i,
                              new_dw.allocate(MI.dTdt_NC, m, patch))

    # -- the stable timestep ------------------------------------------------------------------------
    def stable_timestep(self, patch, matls, old_dw, new_dw):
        """min(ICE's CFL step over the fluids, MPM's wave-speed step over the solids)."""
        a, b = _Capture(new_dw), _Capture(new_dw)
        self.ice.stable_timestep(patch, self.ice.ice_matls, old_dw, a)
        self.mpm.compute_stable_timestep(patch, self.mpm_matls, old_dw, b)
        new_dw.put_reduction(FL.delT, min(float(a.value), float(b.value)))


def _owned(b):
    """Slices of a patch's owned cells (interior + extra) in its stored CC arrays."""
    return tuple(slice(lo, hi) for lo, hi in zip(b.olo, b.ohi))


def _spread(f, empty):
    """Fill the cells marked `empty` with the mean of their non-empty face neighbours
    (repeated until every cell has a value or nothing changes)."""
    f = f.copy()
    known = ~empty
    while not known.all():
        s = np.zeros_like(f)
        n = np.zeros_like(f)
        for d in range(f.ndim):
            if f.shape[d] == 1:
                continue
            for sh in (1, -1):
                s += np.roll(np.where(known, f, 0.0), sh, axis=d)
                n += np.roll(known.astype(float), sh, axis=d)
        new = ~known & (n > 0)
        if not new.any():
            break
        f[new] = s[new] / n[new]
        known = known | new
    return f
