"""Uintah's Steady_Burn: Simple_Burn's container of burning explosive (paper 001 sec. 3) with the
burn rate of Ward, Son and Brewster's steady deflagration model (WSB) instead of eq. 5.

    <Model type="Steady_Burn"><Steady_Burn>
      <fromMaterial/> <toMaterial/>           reactant (MPM) and product (ICE) by name or index
      <IdealGasConst> R   <PreExpCondPh> Ac   <ActEnergyCondPh> Ec   <PreExpGasPh> Bg
      <CondPhaseHeat> Qc  <GasPhaseHeat> Qg   <HeatConductGasPh> Kg  <HeatConductCondPh> Kc
      <SpecificHeatBoth> Cp  <MoleWeightGasPh> W  <BoundaryParticles> BP
      <ThresholdPressure> Pa  <IgnitionTemp> K
    </Steady_Burn></Model>

Burning surface: a cell holding reactant particles whose reactant node masses vary (min/max
< 0.7); it burns when a neighbour (of 27) with at most BP reactant particles has a material
(volume fraction > 0.2) above IgnitionTemp, and the pressure p of the neighbour richest in
product is at least ThresholdPressure. With T0 the reactant's temperature in the neighbour
richest in reactant and v_c the reactant's specific volume in the cell, the mass flux m
(kg/m^2/s) and surface temperature Ts solve

    m^2 = Ac R Kc Ts^2 / (v_c Ec Cp (Ts - T0 - Qc/(2 Cp))) exp(-Ec / (R Ts))      (condensed phase)
    Ts = T0 + Qc/Cp + (Qg/Cp) C3 / (sqrt(m^2 + C3) + m)^2,  C3 = 4 Kg Bg W^2 p^2 / (Cp R^2)   (gas flame)

(Uintah's bisection-Newton from Ts = 850 K, |Ts - Ts(m(Ts))| < 1e-6). The cell burns
dt A m, A the surface area from the gradient of the node masses (Uintah's
computeSurfaceArea), at most its cMass less 1e-12 kg/m^3 V. The burned mass leaves the
reactant's particles and enters the product with the solid's cell velocity and the energy
Cp T_solid + Qc + Qg per kg (every temp_CC of the last step, Uintah's), as Simple_Burn's (simple_burn.py: the particles' share, the
pressure, Lagrangian and volume sources are its tasks). Outputs: SteadyBurn.BurningCell,
SteadyBurn.SurfTemp, SteadyBurn.numPPC (per reactant cell) and the reductions
totalMassBurned, totalHeatReleased (burned (Qc + Qg)).
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
from .simple_burn import SimpleBurn, _material, symmetry_nodes

CC = VarType.CC
# the WSB burn rate's constants; DDT1 reads them too
WSB_CONSTANTS = {
    "IdealGasConst": Param("float", doc="R, J/(mol K)", above=0.0),
    "PreExpCondPh": Param("float", doc="Ac, 1/s", above=0.0),
    "ActEnergyCondPh": Param("float", doc="Ec, J/mol", above=0.0),
    "PreExpGasPh": Param("float", doc="Bg, m^3/(kg s K^2)", above=0.0),
    "CondPhaseHeat": Param("float", doc="Qc, J/kg"),
    "GasPhaseHeat": Param("float", doc="Qg, J/kg"),
    "HeatConductGasPh": Param("float", doc="Kg, W/(m K)", above=0.0),
    "HeatConductCondPh": Param("float", doc="Kc, W/(m K)", above=0.0),
    "SpecificHeatBoth": Param("float", doc="Cp, J/(kg K)", above=0.0),
    "MoleWeightGasPh": Param("float", doc="W, kg/mol", above=0.0),
}
TABLE = {
    **WSB_CONSTANTS,
    "BoundaryParticles": Param("float", doc="BP: a neighbour with at most BP particles can ignite a cell",
                               at_least=0.0),
    "ThresholdPressure": Param("float", doc="Pa"),
    "IgnitionTemp": Param("float", doc="K", above=0.0),
}
EPSILON = 1e-6          # |Ts - Ts(m(Ts))| that ends the surface-temperature iteration (K)
TINY_RHO = 1e-12        # kg/m^3: a burning cell keeps at least this density of reactant


class SteadyBurn(SimpleBurn):
    name = "Steady_Burn"
    volume_of_solid = True
    cell_ghost = (Ghost.AROUND_CELLS, 1)
    solid_temp_dw = OLD         # Uintah's Steady_Burn reads every material's temp_CC of the last step
    energy_temp_dw = OLD

    table = TABLE

    def __init__(self, node, comp, root):
        self.comp = comp
        sb = node.child(self.name, required=True)
        names = comp.material_names()
        self.react = _material(sb, "fromMaterial", names)
        self.prod = _material(sb, "toMaterial", names)
        if self.react not in comp.mpm_matls:
            raise sb.child("fromMaterial").error("<fromMaterial> must be an MPM material (the solid reactant)")
        if self.prod in comp.mpm_matls:
            raise sb.child("toMaterial").error("<toMaterial> must be an ICE material (the product gas)")
        p = self.params = sb.read(self.table)
        R, Ec, Cp, W = p["IdealGasConst"], p["ActEnergyCondPh"], p["SpecificHeatBoth"], p["MoleWeightGasPh"]
        Qc, Qg = p["CondPhaseHeat"], p["GasPhaseHeat"]
        self.R, self.Ec, self.cv_react = R, Ec, Cp
        self.BP, self.T_ign, self.p_thresh = p["BoundaryParticles"], p["IgnitionTemp"], p["ThresholdPressure"]
        self.heat_of_reaction = Qc + Qg
        self.CC = np.array([p["PreExpCondPh"] * R * p["HeatConductCondPh"] / Ec / Cp, Qc / Cp / 2,
                            4 * p["HeatConductGasPh"] * p["PreExpGasPh"] * W * W / Cp / R / R, Qc / Cp, Qg / Cp])

    def tasks_after(self):
        return [("MPMICE::computeEquilibrationPressure", self._numppc_task)] + super().tasks_after()

    def _numppc_task(self):
        return Task("Steady_Burn::computeNumPPC", self.count_particles, [self.react]) \
            .requires(OLD, M.pX).computes(ML.numPPC)

    def _own_labels(self, t):
        r = [self.react]
        return t.requires(NEW, ML.numPPC, Ghost.AROUND_CELLS, 1, matls=r).requires(NEW, I.sp_vol_CC, matls=r) \
            .computes(ML.burningCell, matls=r).computes(ML.surfTemp, matls=r)

    def count_particles(self, patch, matls, old_dw, new_dw):
        """numPPC in the interior cells; the domain's extra cells copy their interior neighbour
        (Uintah's zero-Neumann)."""
        lv, b = patch.level, self.comp.ice.boxes(patch)
        for m in matls:
            count = new_dw.allocate(ML.numPPC, m, patch)
            count[...] = 0.0
            K.particles_per_cell(old_dw.get(M.pX, m, patch), lv.anchor, lv.dx, np.array(patch.low_index(CC), np.int64),
                                 b.lo, b.hi, count)
            for d in range(3):
                sl_lo, sl_hi = [slice(None)] * 3, [slice(None)] * 3
                if b.olo[d] < b.lo[d]:
                    sl_lo[d], src = slice(b.olo[d], b.lo[d]), [slice(None)] * 3
                    src[d] = slice(b.lo[d], b.lo[d] + 1)
                    count[tuple(sl_lo)] = count[tuple(src)]
                if b.ohi[d] > b.hi[d]:
                    sl_hi[d], src = slice(b.hi[d], b.ohi[d]), [slice(None)] * 3
                    src[d] = slice(b.hi[d] - 1, b.hi[d])
                    count[tuple(sl_hi)] = count[tuple(src)]

    def burned_mass(self, patch, old_dw, new_dw, temps, vfs, mass_c, dt, burned):
        """The WSB burn of every burning surface cell (module docstring) into `burned`."""
        c, r = self.comp, self.react
        b, cc_low, node_low, _, n_lo, n_hi = c._geom(patch)
        n_lo, n_hi = symmetry_nodes(c, n_lo, n_hi)
        burning = new_dw.allocate(ML.burningCell, r, patch)
        ts = new_dw.allocate(ML.surfTemp, r, patch)
        burning[...] = 0.0
        ts[...] = 0.0
        K.steady_burn_cells(new_dw.get(M.gMass, r, patch), node_low, cc_low, b.lo, b.hi, c.dims_i, patch.level.dx,
                            n_lo, n_hi, new_dw.get(ML.numPPC, r, patch), temps, vfs,
                            new_dw.get(I.press_equil_CC, 0, patch), new_dw.get(I.sp_vol_CC, r, patch), mass_c,
                            r, self.prod, self.BP, self.T_ign, self.p_thresh, self.CC, self.Ec, self.R, EPSILON,
                            TINY_RHO * b.vol, dt, burned, burning, ts)
