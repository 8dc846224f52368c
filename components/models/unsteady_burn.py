"""Uintah's Unsteady_Burn: Steady_Burn's burning surface (steady_burn.py) with the WSB burn
rate relaxed in time, the solid's surface temperature Ts and surface temperature gradient beta
remembered from step to step on the reactant's particles.

    <Model type="Unsteady_Burn"><Unsteady_Burn>
      Steady_Burn's tags (fromMaterial ... IgnitionTemp), and
      <BurnrateModCoef> Bm  <CondUnsteadyCoef> Nc  <GasUnsteadyCoef> Ng
    </Unsteady_Burn></Model>

Each burning cell solves the steady WSB problem at this step's T0, p, v_c (Ts*, m*, as
Steady_Burn, from the cell's last Ts) and beta* = (Ts* - T0) m* Cp/Kc. A cell burning for
the first time starts from (beta, Ts) of its neighbour (of 27) that has burned the most steps
in a row, or from (1e12 K/m, 300 K); it then burns at the steady rate. Afterwards beta and Ts
relax towards (beta*, Ts*) over n = Nc Kc / (Cp v_c dt m*^2) and Ng n steps, and the mass flux
is the unsteady condensed-phase solution

    m = 2c / (sqrt(b^2 - 4c) + b),  b = 2 Kc beta / Qc,  c = 2 Ac R Kc Ts^2 exp(-Ec/(R Ts)) / (Ec Qc v_c),

scaled m* (m/m*)^Bm. b^2 < 4c stops the run (Uintah: the timestep is too large for the unsteady
burn rate). The burned mass, its momentum and energy go to the product as in Steady_Burn
(Cp T_solid + Qc + Qg per kg), with T_solid and the ignition temperatures of the previous
step (Uintah reads temp_CC from the old data warehouse here: the solids' exchanged temperature;
before the first step MPMICE's initial one, the object's temperature near it). A burning cell's particles keep its (beta, Ts); all others go
back to (1e12, 300). Outputs: UnsteadyBurn.BurningCell (steps burned in a row),
UnsteadyBurn.SurfTemp, UnsteadyBurn.SurfTempGrad (per cell), UnsteadyBurn.PartSurfTemp,
UnsteadyBurn.PartSurfTempGrad (per particle), totalMassBurned, totalHeatReleased.
"""
from __future__ import annotations

import numpy as np

from components.ice import labels as I
from components.mpm import labels as M
from framework.problemspec import Param
from framework.task import NEW, OLD, Task
from framework.variables import Ghost, VarType

from . import kernels as K
from . import labels as ML
from .simple_burn import copy_to_symmetry_extra_cells, symmetry_nodes
from .steady_burn import EPSILON, TABLE as STEADY, TINY_RHO, SteadyBurn

CC = VarType.CC
TABLE = {
    **STEADY,
    "BurnrateModCoef": Param("float", doc="Bm: the unsteady rate is m* (m/m*)^Bm"),
    "CondUnsteadyCoef": Param("float", doc="Nc: relaxation of the surface temperature gradient", at_least=0.0),
    "GasUnsteadyCoef": Param("float", doc="Ng: relaxation of the surface temperature, in units of Nc's",
                             at_least=0.0),
}
INIT_TS = 300.0         # K: a particle's surface temperature before it burns
INIT_BETA = 1.0e12      # K/m: its surface temperature gradient before it burns
PART = ((ML.ubPartSurfTemp, ML.ubPartSurfTempPre), (ML.ubPartSurfTempGrad, ML.ubPartSurfTempGradPre))
CELL = (ML.ubBurningCell, ML.ubSurfTemp, ML.ubSurfTempGrad)


class UnsteadyBurn(SteadyBurn):
    name = "Unsteady_Burn"
    table = TABLE
    solid_temp_dw = OLD
    energy_temp_dw = OLD

    def __init__(self, node, comp, root):
        super().__init__(node, comp, root)
        p = self.params
        Cp, Kc, Qc = p["SpecificHeatBoth"], p["HeatConductCondPh"], p["CondPhaseHeat"]
        if Qc == 0.0:
            raise node.child(self.name).child("CondPhaseHeat").error("<CondPhaseHeat> must not be 0 (b = 2 Kc beta / Qc)")
        self.UC = np.array([Cp / Kc, Kc / Cp, 2 * Kc / Qc, 2 * p["PreExpCondPh"] * self.R * Kc / (self.Ec * Qc),
                            p["CondUnsteadyCoef"], p["GasUnsteadyCoef"], p["BurnrateModCoef"]])
        comp.mpm.carry_models = tuple(comp.mpm.carry_models) + PART
        self.others = [m for m in comp.mpm_matls if m != self.react]

    # -- scheduling ----------------------------------------------------------------------------
    def schedule_initialize(self, sched):
        c, r = self.comp, [self.react]
        t = Task("Unsteady_Burn::initialize", self.initialize, c.mpm_matls).requires(NEW, M.pX)
        for lab in CELL:
            t.computes(lab, matls=r)
        for final, _ in PART:
            t.computes(final)
        sched.add_task(t)

    def tasks_after(self):
        out = super().tasks_after()
        if self.others:
            out.append(("MPM::computeStressTensor", self._carry_task))
        return out

    def _carry_task(self):
        t = Task("Unsteady_Burn::carryParticleState", self.carry_particle_state, self.others)
        for final, pre in PART:
            t.requires(OLD, final).computes(pre)
        return t

    def _own_labels(self, t):
        r, g1 = [self.react], (Ghost.AROUND_CELLS, 1)
        t.requires(NEW, ML.numPPC, *g1, matls=r).requires(NEW, I.sp_vol_CC, matls=r).requires(OLD, M.pX, matls=r)
        for lab in CELL:
            t.requires(OLD, lab, *g1, matls=r).computes(lab, matls=r)
        for final, pre in PART:
            t.requires(OLD, final, matls=r).computes(pre, matls=r)
        return t

    # -- task bodies -----------------------------------------------------------------------------
    def initialize(self, patch, matls, old_dw, new_dw):
        """Cells and particles that never burned (the solids' temp_CC of the first step's ignition
        test is MPMICE's initial one)."""
        for m in matls:
            n = len(new_dw.get(M.pX, m, patch))
            new_dw.put(ML.ubPartSurfTemp, m, patch, np.full(n, INIT_TS))
            new_dw.put(ML.ubPartSurfTempGrad, m, patch, np.full(n, INIT_BETA))
            if m == self.react:
                for lab, value in zip(CELL, (0.0, INIT_TS, INIT_BETA)):
                    new_dw.allocate(lab, m, patch)[...] = value

    def carry_particle_state(self, patch, matls, old_dw, new_dw):
        for m in matls:
            for final, pre in PART:
                new_dw.put(pre, m, patch, old_dw.get(final, m, patch).copy())

    def burned_mass(self, patch, old_dw, new_dw, temps, vfs, mass_c, dt, burned):
        """The unsteady WSB burn of every burning surface cell (module docstring) into `burned`;
        the cells' and the particles' new (beta, Ts)."""
        c, r, lv = self.comp, self.react, patch.level
        b, cc_low, node_low, _, n_lo, n_hi = c._geom(patch)
        n_lo, n_hi = symmetry_nodes(c, n_lo, n_hi)
        burning = new_dw.allocate(ML.ubBurningCell, r, patch)
        ts = new_dw.allocate(ML.ubSurfTemp, r, patch)
        beta = new_dw.allocate(ML.ubSurfTempGrad, r, patch)
        for a in (burning, ts, beta):
            a[...] = 0.0
        px = old_dw.get(M.pX, r, patch)
        K.unsteady_cells_from_particles(px, old_dw.get(ML.ubPartSurfTempGrad, r, patch),
                                        old_dw.get(ML.ubPartSurfTemp, r, patch), lv.anchor, lv.dx, cc_low, b.lo,
                                        b.hi, INIT_BETA, beta, ts)
        bad = K.unsteady_burn_cells(new_dw.get(M.gMass, r, patch), node_low, cc_low, b.lo, b.hi, c.dims_i, lv.dx,
                                    n_lo, n_hi, new_dw.get(ML.numPPC, r, patch), temps, vfs,
                                    new_dw.get(I.press_equil_CC, 0, patch), new_dw.get(I.sp_vol_CC, r, patch),
                                    mass_c, r, self.prod, self.BP, self.T_ign, self.p_thresh, self.CC, self.UC,
                                    self.Ec, self.R, EPSILON, TINY_RHO * b.vol, dt,
                                    old_dw.get(ML.ubBurningCell, r, patch), old_dw.get(ML.ubSurfTemp, r, patch),
                                    old_dw.get(ML.ubSurfTempGrad, r, patch), INIT_TS, INIT_BETA, burned, burning,
                                    ts, beta)
        if bad:
            raise RuntimeError(f"Unsteady_Burn: in {bad} cell(s) of patch {patch.id} the timestep {dt:g} s is too "
                               "large to compute the unsteady burn rate (b^2 < 4c; Uintah stops here too)")
        sym_lo, sym_hi = c._sym(r)
        for a in (burning, ts, beta):            # Uintah's set_if_sym_BC
            copy_to_symmetry_extra_cells(a, b, sym_lo, sym_hi)
        pts, pbeta = np.empty(len(px)), np.empty(len(px))
        K.unsteady_particles_from_cells(px, lv.anchor, lv.dx, cc_low, b.lo, b.hi, burning, beta, ts, INIT_BETA,
                                        INIT_TS, pbeta, pts)
        new_dw.put(ML.ubPartSurfTempPre, r, patch, pts)
        new_dw.put(ML.ubPartSurfTempGradPre, r, patch, pbeta)

