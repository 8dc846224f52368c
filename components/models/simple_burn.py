"""Uintah's Simple_Burn (paper 001 sec. 3): a solid reactant's surface burns into a product gas.

Burn rate (per unit surface, eq. 5): m_dot'' = K (p / p_ref)^0.778 where the reactant's
surface cell is hotter than ThresholdTemp and p > ThresholdPressure, at most the reactant's
cMass there. As in Uintah the burned mass leaves the reactant (its modelMass/Mom/Eng/Vol_src,
negative, in its Lagrangian values: MPMICE's computeLagrangianValuesMPM) and enters the
product gas in the same cell with the solid's cell velocity and internal energy cv_s T_s plus
the heat of reaction (Enthalpy). The particles lose it through the nodes (Uintah's
massBurnFraction): each node takes the mean |modelMass_src| / cMass of the cells around it,
each particle the interpolation f of those, p.mass+ = max(m (1 - f), 0), its volume and size
scaled alike; one left with minimum_particle_mass or less is deleted (p.x+ = NaN). The
particles' loss equals the product's gain only where the nodes see uniform particles
(tests/models/burn1d.ups: 1.3e-15 of the total mass; guni2dRT's reactant mass per cell equals
sus's, tests/mpmice/test_guni2drt.py).

Tasks, each added right after the MPMICE task named (models/__init__.py):
  MPMICE::computeEquilibrationPressure -> Simple_Burn::computeModelSources
        surface cells from the reactant's node masses, burned mass per cell, the
        reactant's and the product's mass/momentum/energy/volume sources;
        the reductions totalMassBurned and totalHeatReleased (this step; <save> them)
  ICE::computeDelPressAndUpdatePressCC -> Simple_Burn::addPressureSource
        p += m_burned (v_product - v_reactant) / (V sum_m theta_m kappa_m) (001 eq. 9,
        Uintah's delP_MassX, sum_m m_src,m v_m with the equilibrated v_m); with semi-implicit
        ICE instead eq. P's right-hand side takes the same term (mass_exchange_term)
  MPMICE::computeLagrangianValuesMPM -> Simple_Burn::addReactantLagrangianSources
        the reactant's m^L, (m u)^L, (m e)^L += its sources (Uintah's minimum-mass rule)
  ICE::computeLagrangianValues -> Simple_Burn::addLagrangianSources
        the product's m^L, (m u)^L, (m e)^L += sources (eqs. 7-8)
  in ICE::computeLagrangianSpecificVolume (before its clamp, Models.volume_sources)
        the product's Lagrangian volume holds the new mass at V_created (modelVol_src)
  MPM::computeStressTensor -> Simple_Burn::burnParticles
        p.mass+, p.volume+, p.size+ *= 1 - f (f from the nodes); deleted: p.x+ = NaN
V_created (modelVol_src) is the volume the burned solid held, burned * v_solid (Uintah's; the
next equilibration expands it); volume_of_solid False makes it at the product's density at the
cell's pressure and its own temperature e_src / (m_src cv). Energy: the hand-over is exact; ICE's later evolution of
the hot, compressed product in mixed cells is not energy-conservative (tests/models:
total energy -9 % by the end of the 1D burn, the same with the pressure source off).
"""
from __future__ import annotations

import numpy as np

from components.ice import labels as I
from components.ice.tasks import _rho_micro_array
from components.mpm import labels as M
from components.mpm import shape as SH
from components.mpm.thermal import g2p_heat
from components.mpmice import labels as MI
from framework import labels as FL
from framework.problemspec import Param
from framework.task import NEW, OLD, Task
from framework.variables import Ghost, VarType

from . import kernels as K
from . import labels as ML

CC, NC = VarType.CC, VarType.NC
TABLE = {
    "ThresholdTemp": Param("float", doc="K"),
    "ThresholdPressure": Param("float", doc="Pa"),
    "Enthalpy": Param("float", doc="heat of reaction, J/kg"),
    "BurnCoeff": Param("float", doc="K of eq. 5, kg/(m^2 s)"),
    "refPressure": Param("float", doc="Pa"),
}


class IceSources:
    """The two task bodies every reaction model shares: its mass, momentum and energy sources
    added to ICE's Lagrangian state, and its volume source to the Lagrangian specific volume."""

    def lagrangian_sources(self, patch, matls, old_dw, new_dw):
        b = self.comp.ice.boxes(patch)
        sl = tuple(slice(l, h) for l, h in zip(b.lo, b.hi))
        for m in matls:
            new_dw.get_modifiable(I.mass_L_CC, m, patch)[sl] += new_dw.get(ML.modelMass_src, m, patch)[sl]
            new_dw.get_modifiable(I.mom_L_CC, m, patch)[sl] += new_dw.get(ML.modelMom_src, m, patch)[sl]
            new_dw.get_modifiable(I.int_eng_L_CC, m, patch)[sl] += new_dw.get(ML.modelEng_src, m, patch)[sl]

    def volume_source(self, patch, matls, old_dw, new_dw):
        """ICE's (m v)^L counts the new mass at the cell's v; Uintah's adds modelVol_src instead."""
        b = self.comp.ice.boxes(patch)
        for m in matls:
            K.volume_source(new_dw.get(ML.modelMass_src, m, patch), new_dw.get(ML.modelVol_src, m, patch),
                            new_dw.get(I.sp_vol_CC, m, patch), b.lo, b.hi, new_dw.get_modifiable(I.sp_vol_L_CC, m, patch))


class SimpleBurn(IceSources):
    def __init__(self, node, comp, root):
        self.comp = comp
        sb = node.child("Simple_Burn", required=True)
        names = comp.material_names()
        self.react = _material(sb, "fromMaterial", names)
        self.prod = _material(sb, "toMaterial", names)
        if self.react not in comp.mpm_matls:
            raise sb.child("fromMaterial").error("<fromMaterial> must be an MPM material (the solid reactant)")
        if self.prod in comp.mpm_matls:
            raise sb.child("toMaterial").error("<toMaterial> must be an ICE material (the product gas)")
        p = sb.read(TABLE)
        mat = root.child("MaterialProperties").child("MPM").children("material")[self.react]
        self.cv_react = mat.get("specific_heat", "float", 0.0)
        if self.cv_react <= 0:
            raise mat.error("Simple_Burn's reactant needs <specific_heat> > 0 (the energy its burned mass carries)")
        self.T_thresh, self.p_thresh = p["ThresholdTemp"], p["ThresholdPressure"]
        self.heat_of_reaction, self.coeff, self.p_ref = p["Enthalpy"], p["BurnCoeff"], p["refPressure"]
        if self.p_ref <= 0:
            raise sb.child("refPressure").error("<refPressure> must be positive")
        if self.coeff < 0:
            raise sb.child("BurnCoeff").error("<BurnCoeff> must be >= 0")

    # -- scheduling ----------------------------------------------------------------------------
    def tasks_after(self):
        return [("MPMICE::computeEquilibrationPressure", self._sources_task),
                ("ICE::computeDelPressAndUpdatePressCC", self._pressure_task),
                ("MPMICE::computeLagrangianValuesMPM", self._reactant_lagrangian_task),
                ("ICE::computeLagrangianValues", self._lagrangian_task),
                ("MPM::computeStressTensor", self._particles_task)]

    name = "Simple_Burn"
    volume_of_solid = True      # the product's new volume: burned * v_solid (Uintah's); False: at (p, T_product)
    cell_ghost = ()             # Steady_Burn reads the cell state of the 26 neighbours too
    solid_temp_dw = NEW         # the solids' temp_CC: this step's (Unsteady_Burn: last step's, OLD)
    energy_temp_dw = NEW        # the reactant's temp_CC the burned mass carries (cv T): this step's (Uintah's)

    def _sources_task(self):
        c, r, gh, both = self.comp, [self.react], self.cell_ghost, [self.react, self.prod]
        t = Task(f"{self.name}::computeModelSources", self.compute_sources, both) \
            .requires(OLD, FL.delT).requires(NEW, M.gMass, Ghost.AROUND_CELLS, 1, matls=r) \
            .requires(NEW, MI.cMass, matls=r).requires(NEW, I.vel_CC, matls=r).requires(NEW, I.sp_vol_CC, matls=r) \
            .requires(NEW, I.press_equil_CC, *gh, matls=[0]).requires(NEW, I.vol_frac_CC, *gh, matls=c.all_matls) \
            .computes(ML.modelMass_src, matls=both).computes(ML.modelMom_src, matls=both) \
            .computes(ML.modelEng_src, matls=both).computes(ML.modelVol_src, matls=both) \
            .computes(ML.totalMassBurned).computes(ML.totalHeatReleased)
        if self.solid_temp_dw is OLD:
            t.requires(OLD, I.temp_CC, *gh, matls=c.all_matls)
        else:
            t.requires(NEW, I.temp_CC, *gh, matls=c.mpm_matls).requires(OLD, I.temp_CC, *gh, matls=c.ice.ice_matls)
        if self.energy_temp_dw is NEW and self.solid_temp_dw is OLD:
            t.requires(NEW, I.temp_CC, matls=r)
        return self._own_labels(t)

    def _own_labels(self, t):
        """The model's own requires and computes on the sources task (the burning area)."""
        return t.computes(ML.burnArea, matls=[self.react])

    def _pressure_task(self):
        c = self.comp
        return Task(f"{self.name}::addPressureSource", self.pressure_source, c.all_matls) \
            .requires(NEW, ML.modelMass_src, matls=[self.prod]).requires(NEW, ML.modelVol_src, matls=[self.prod]) \
            .requires(NEW, I.vol_frac_CC) \
            .requires(NEW, I.sp_vol_CC).requires(NEW, I.speedSound_CC).modifies(I.press_CC, matls=[0])

    def _lagrangian_task(self):
        g = [self.prod]
        return Task(f"{self.name}::addLagrangianSources", self.lagrangian_sources, g) \
            .requires(NEW, ML.modelMass_src).requires(NEW, ML.modelMom_src).requires(NEW, ML.modelEng_src) \
            .modifies(I.mass_L_CC).modifies(I.mom_L_CC).modifies(I.int_eng_L_CC)

    def _particles_task(self):
        mpm = self.comp.mpm
        t = Task(f"{self.name}::burnParticles", self.burn_particles, [self.react]) \
            .requires(NEW, ML.modelMass_src, Ghost.AROUND_CELLS, 2).requires(NEW, MI.cMass, Ghost.AROUND_CELLS, 2) \
            .requires(OLD, M.pX).modifies(M.pMassPre).modifies(M.pVolumePre).modifies(M.pXpre)
        for lab in mpm.size_labels():
            t.requires(OLD, lab)
        if M.pSizePre.name in {pre.name for _, pre in mpm.carry}:
            t.modifies(M.pSizePre)
        return t

    def _reactant_lagrangian_task(self):
        return Task(f"{self.name}::addReactantLagrangianSources", self.reactant_lagrangian_sources, [self.react]) \
            .requires(NEW, MI.cMass).requires(NEW, ML.modelMass_src).requires(NEW, ML.modelMom_src) \
            .requires(NEW, ML.modelEng_src).modifies(I.mass_L_CC).modifies(I.mom_L_CC).modifies(I.int_eng_L_CC) \
            .modifies(MI.mom_mpm_CC)

    def volume_source_into(self, patch, matls, new_dw, sp_vol_L):
        """The product's Lagrangian volume holds the new mass at V_created (K.volume_source) in
        sp_vol_L (ICE's arrays of matls), before ICE's clamp, as Uintah adds modelVol_src."""
        b = self.comp.ice.boxes(patch)
        m = self.prod
        K.volume_source(new_dw.get(ML.modelMass_src, m, patch), new_dw.get(ML.modelVol_src, m, patch),
                        new_dw.get(I.sp_vol_CC, m, patch), b.lo, b.hi, sp_vol_L[list(matls).index(m)])

    def volume_sources_requires(self, t):
        t.requires(NEW, ML.modelMass_src, matls=[self.prod]).requires(NEW, ML.modelVol_src, matls=[self.prod])

    def volume_sources(self, patch, new_dw):
        """{material: the volume it gains this step}: the product its V_created, the reactant
        loses the burned mass at its specific volume (Uintah's modelVol_src of both)."""
        ms = new_dw.get(ML.modelMass_src, self.prod, patch)
        return {self.prod: new_dw.get(ML.modelVol_src, self.prod, patch),
                self.react: -ms * new_dw.get(I.sp_vol_CC, self.react, patch)}

    def mass_exchange_requires(self, t, dw):
        """What mass_exchange_term reads (semi-implicit ICE's eq. P)."""
        t.requires(dw, ML.modelMass_src, matls=[self.prod]).requires(dw, I.sp_vol_CC, matls=[self.react, self.prod])

    def mass_exchange_term(self, patch, dw):
        """Uintah's implicit massExchTerm per cell, sum_m m_src,m v_m / V: the burned mass leaves the
        reactant at its specific volume and joins the product at the product's."""
        ms = dw.get(ML.modelMass_src, self.prod, patch)
        return ms * (dw.get(I.sp_vol_CC, self.prod, patch) - dw.get(I.sp_vol_CC, self.react, patch)) \
            / self.comp.ice.boxes(patch).vol

    # -- task bodies -----------------------------------------------------------------------------
    def compute_sources(self, patch, matls, old_dw, new_dw):
        """The burned mass per cell (burned_mass, at most the reactant's cMass) leaves the reactant
        and joins the product with the solid's cell velocity and energy cv_s T_s (plus the heat of
        reaction), as Uintah's: both materials' modelMass/Mom/Eng/Vol_src."""
        c = self.comp
        dt = old_dw.get_reduction(FL.delT)
        r, g = self.react, self.prod
        shape = patch.alloc_shape(CC)
        solid_dw = new_dw if self.solid_temp_dw is NEW else old_dw
        temps = tuple((solid_dw if m in c.mpm_matls else old_dw).get(I.temp_CC, m, patch) for m in c.all_matls)
        vfs = tuple(new_dw.get(I.vol_frac_CC, m, patch) for m in c.all_matls)
        burned = np.zeros(shape)
        cmass = np.ascontiguousarray(new_dw.get(MI.cMass, r, patch)).reshape(-1)
        self.burned_mass(patch, old_dw, new_dw, temps, vfs, cmass, dt, burned)
        heat = self.released_heat(patch)
        burned_total = float(burned.sum())
        new_dw.put_reduction(ML.totalMassBurned, burned_total)
        new_dw.put_reduction(ML.totalHeatReleased,
                             burned_total * heat if np.isscalar(heat) else float((burned * heat).sum()))
        mom = burned[..., None] * new_dw.get(I.vel_CC, r, patch)
        e_solid = burned * (self.cv_react * (new_dw if self.energy_temp_dw is NEW else old_dw).get(I.temp_CC, r, patch))
        v_solid = burned * new_dw.get(I.sp_vol_CC, r, patch)
        for m, sign in ((r, -1.0), (g, 1.0)):
            new_dw.allocate(ML.modelMass_src, m, patch)[...] = sign * burned
            new_dw.allocate(ML.modelMom_src, m, patch)[...] = sign * mom
        new_dw.allocate(ML.modelEng_src, r, patch)[...] = -e_solid
        e = new_dw.allocate(ML.modelEng_src, g, patch)
        e[...] = e_solid + burned * heat
        new_dw.allocate(ML.modelVol_src, r, patch)[...] = -v_solid
        vs = new_dw.allocate(ML.modelVol_src, g, patch)
        on = burned > 0
        if self.volume_of_solid:       # the volume the burned solid held (Uintah's)
            vs[...] = v_solid
        elif on.any():       # the product made at the cell's pressure and its own temperature
            code, params, cv, gamma = c.ice._eos(g)
            t_prod = e[on] / (burned[on] * cv)
            rho = _rho_micro_array(new_dw.get(I.press_equil_CC, 0, patch)[on], t_prod, 1.0, code, params, cv, gamma)
            vs[on] = burned[on] / rho

    def released_heat(self, patch):
        """J/kg the burned mass releases (a number, or per cell: DDT1's)."""
        return self.heat_of_reaction

    def burned_mass(self, patch, old_dw, new_dw, temps, vfs, mass_c, dt, burned):
        """001 eqs. 5-6: the reactant mass each surface cell burns this step (into `burned`)."""
        c, r = self.comp, self.react
        b, cc_low, node_low, _, n_lo, n_hi = c._geom(patch)
        n_lo, n_hi = symmetry_nodes(c, n_lo, n_hi)
        area = new_dw.allocate(ML.burnArea, r, patch)
        K.burn_cells(new_dw.get(M.gMass, r, patch), node_low, cc_low, b.lo, b.hi, c.dims_i, patch.level.dx, n_lo,
                     n_hi, temps, vfs, new_dw.get(I.press_equil_CC, 0, patch), mass_c,
                     self.T_thresh, self.p_thresh, self.coeff, self.p_ref, dt, burned, area)

    def pressure_source(self, patch, matls, old_dw, new_dw):
        c = self.comp
        b = c.ice.boxes(patch)
        get = lambda lab: tuple(new_dw.get(lab, m, patch) for m in matls)
        press = new_dw.get_modifiable(I.press_CC, 0, patch)
        ms = new_dw.get(ML.modelMass_src, self.prod, patch)
        # Uintah's delP_MassX: the new mass counted at the product's equilibrated specific volume
        created = ms * new_dw.get(I.sp_vol_CC, self.prod, patch) if self.volume_of_solid \
            else new_dw.get(ML.modelVol_src, self.prod, patch)
        K.pressure_source(ms, created,
                          new_dw.get(I.sp_vol_CC, self.react, patch), get(I.vol_frac_CC), get(I.sp_vol_CC),
                          get(I.speedSound_CC), b.lo, b.hi, b.vol, press)
        c.ice.bcs.scalar(patch, press, "Pressure", 0, b)

    def reactant_lagrangian_sources(self, patch, matls, old_dw, new_dw):
        """Uintah's computeLagrangianValuesMPM with a model: the reactant's m^L, (mu)^L, (me)^L take its
        (negative) sources, each kept above its share of a cell's minimum mass (kernels.solid_sources);
        mom_MPM_CC takes the momentum's change too, so that dV/dt holds only the exchange and grad p."""
        b = self.comp.ice.boxes(patch)
        for m in matls:
            K.solid_sources(new_dw.get(MI.cMass, m, patch), new_dw.get(ML.modelMass_src, m, patch),
                            new_dw.get(ML.modelMom_src, m, patch), new_dw.get(ML.modelEng_src, m, patch),
                            self.comp.tiny * b.vol, b.olo, b.ohi, new_dw.get_modifiable(I.mass_L_CC, m, patch),
                            new_dw.get_modifiable(I.mom_L_CC, m, patch), new_dw.get_modifiable(I.int_eng_L_CC, m, patch),
                            new_dw.get_modifiable(MI.mom_mpm_CC, m, patch))

    def burn_particles(self, patch, matls, old_dw, new_dw):
        """Each reactant particle loses the fraction of its mass its nodes burn (Uintah's massBurnFraction
        at the nodes, |modelMass_src| / cMass averaged over the cells around each, interpolated to the
        particle with the step's weights); kernels.burn_particles."""
        c, mpm, lv = self.comp, self.comp.mpm, patch.level
        b, cc_low, node_low, dims, n_lo, n_hi = c._geom(patch)
        sym_lo, sym_hi = c._sym(self.react)
        carried = {pre.name for _, pre in mpm.carry}
        kind = {"linear": SH.LINEAR, "gimp": SH.GIMP}.get(mpm.kind, SH.CPDI)
        act = sum(1 << d for d in range(3) if dims[d])
        for m in matls:
            frac_nc = np.zeros(patch.alloc_shape(NC))
            K.mass_burn_fraction(new_dw.get(ML.modelMass_src, m, patch), new_dw.get(MI.cMass, m, patch), cc_low,
                                 node_low, dims, np.array(b.lo, np.int64), n_lo, n_hi, sym_lo, sym_hi, frac_nc)
            px = old_dw.get(M.pX, m, patch)
            n = len(px)
            frac = np.empty(n)
            g2p_heat(kind, act, px, np.zeros(n), np.zeros(n), mpm._lp_read_only(old_dw, m, patch, n), lv.anchor, lv.dx,
                     node_low, frac_nc, 1.0, frac, 0.0, frac_nc, np.empty((0, 3)))
            size = new_dw.get_modifiable(M.pSizePre, m, patch) if M.pSizePre.name in carried else np.empty((0, 3))
            K.burn_particles(frac, mpm.flags["minimum_particle_mass"], new_dw.get_modifiable(M.pMassPre, m, patch),
                             new_dw.get_modifiable(M.pVolumePre, m, patch), size,
                             new_dw.get_modifiable(M.pXpre, m, patch))


def symmetry_nodes(comp, n_lo, n_hi):
    """The first / last domain node per direction where that face is a symmetry plane (of
    material 0, as Uintah's NC_CCweight), else an index no node has."""
    sym_lo, sym_hi = comp._sym(0)
    return np.where(sym_lo, n_lo, -(1 << 40)), np.where(sym_hi, n_hi, 1 << 40)


def _material(node, tag, names):
    """A material named by its name attribute (as Uintah) or by its global index."""
    raw = node.get(tag, "str")
    if raw in names:
        return names.index(raw)
    if raw.isdigit() and int(raw) < len(names):
        return int(raw)
    raise node.child(tag).error(f"<{tag}> '{raw}' is not a material; accepted: {', '.join(names)}")


def copy_to_symmetry_extra_cells(a, b, sym_lo, sym_hi):
    """The interior layer next to a symmetry face copied into the patch's extra cells there."""
    for d in range(3):
        for on, out, src in ((sym_lo[d], slice(b.olo[d], b.lo[d]), slice(b.lo[d], b.lo[d] + 1)),
                             (sym_hi[d], slice(b.hi[d], b.ohi[d]), slice(b.hi[d] - 1, b.hi[d]))):
            if on and out.start < out.stop:
                dst, s = [slice(None)] * 3, [slice(None)] * 3
                dst[d], s[d] = out, src
                a[tuple(dst)] = a[tuple(s)]

