"""Uintah's DDT1: deflagration to detonation of a solid (MPM) explosive into an ICE product.

    <Model type="DDT1"><DDT1>
      <fromMaterial> reactant (MPM) </fromMaterial>  <toMaterial> product (ICE) </toMaterial>
      detonation (JWL++):  <G> <b> <E0> <ThresholdPressureJWL>  [<ThresholdVolFrac> 0.01, read, unused as Uintah's]
      deflagration (WSB, as Steady_Burn): <IdealGasConst> <PreExpCondPh> <ActEnergyCondPh> <PreExpGasPh>
        <CondPhaseHeat> <GasPhaseHeat> <HeatConductGasPh> <HeatConductCondPh> <SpecificHeatBoth>
        <MoleWeightGasPh> <BoundaryParticles> <IgnitionTemp> <ThresholdPressureSB>
      burning in cracks: <useCrackModel> false  (true: <Gcrack> <nCrack> [<CrackVolThreshold>], visco_scram reactant)
      ignition delay: <useInductionTime> false  (true: <IgnitionConst> <PressureShift> <PreexpoConst> <ExponentialConst>)
    </DDT1></Model>

Per interior cell holding reactant (volume fraction > 1e-10), with p the cell's equilibration pressure:
  p > ThresholdPressureJWL and particles in the cell: detonation, JWL++'s reacted fraction
      F = rho_p / (rho_r + rho_p), dF = dt G p^b (1 - F), burned = min(dF (m_r + m_p), m_r, 0.2 rho0 V),
      releasing E0 per kg;
  ThresholdPressureSB < p < ThresholdPressureJWL, and no neighbour (of 27) above ThresholdPressureJWL:
      conductive burn (code 2) on a surface cell that Steady_Burn would light (node masses
      min/max < 0.7, a neighbour with <= BoundaryParticles particles holding a material with
      volume fraction > 0.2 above IgnitionTemp) when the pressure of the neighbour richest in product
      is >= ThresholdPressureSB: WSB's burn over the area from the node-mass gradient;
      else convective burn (code 3) in a cracked cell (a particle's crack radius above
      sqrt(8e8 / p^2.84)) with a neighbour of any material above IgnitionTemp: WSB's burn over
      the area V / 0.002 m.
  With <useInductionTime> a cell lit so burns only once it has warmed (countTime, the steps'
  dt summed) for its induction time dx_mean A / (Fb (p_product / PressureShift)^Fc), relaxed
  0.2 new + 0.8 old, A from the angle between the node-mass gradient and the direction to the
  hot neighbour ((1 + IC)/2 + (1 - IC)/2 sin(2 theta - pi/2)), A = IC in a cracked interior cell
  next to a burning one; a cell that burned last step goes on burning (BurningCriteria 1: warming).
  WSB's burn (steady_burn.py) takes T0 from the neighbour richest in reactant and releases
  Qc + Qg per kg; every burn is at most rho_r theta_r V less 1e-12 kg/m^3 V.
The burned mass leaves the reactant's particles and enters the product with the solid's velocity,
the energy cv_reactant T_reactant per kg plus the heat released, and the solid's volume
(Simple_Burn's tasks, simple_burn.py). Outputs (reactant cells): burning, BurningCriteria,
detonating, detLocalTo, F, delF, surfaceTemp, onSurface, crackedEnough, SteadyBurn.numPPC,
inductionTime and countTime (with the ignition delay);
the reductions totalMassBurned and totalHeatReleased.
"""
from __future__ import annotations

import sys

import numpy as np
from numba import njit

from components.ice import labels as I
from components.mpm import labels as M
from framework.problemspec import Param
from framework.task import NEW, OLD, Task
from framework.variables import Ghost, VarType

from . import kernels as K
from . import labels as ML
from .simple_burn import _material, copy_to_symmetry_extra_cells, symmetry_nodes
from .steady_burn import EPSILON, WSB_CONSTANTS, SteadyBurn

CC = VarType.CC
TINY_RHO = 1e-12        # kg/m^3: a burning cell keeps at least this density of reactant
WARMINGUP, CONDUCTIVE, CONVECTIVE = 1.0, 2.0, 3.0       # Uintah's typeofBurning codes
CRACK_AREA_LENGTH = 0.002               # m: a convective cell burns over V / 0.002 m (Uintah's)
TABLE = {
    "G": Param("float", doc="JWL++ rate constant, 1/(s Pa^b)", at_least=0.0),
    "b": Param("float", doc="JWL++ pressure exponent"),
    "E0": Param("float", doc="J/kg released by detonation"),
    "ThresholdPressureJWL": Param("float", doc="Pa: above it a cell detonates"),
    "ThresholdVolFrac": Param("float", 0.01, doc="read, unused (as Uintah's DDT1)"),
    **WSB_CONSTANTS,
    "BoundaryParticles": Param("float", doc="a neighbour with at most this many particles can ignite a cell",
                               at_least=0.0),
    "IgnitionTemp": Param("float", doc="K", above=0.0),
    "ThresholdPressureSB": Param("float", doc="Pa: the least pressure a cell burns at"),
    "useCrackModel": Param("bool", False, doc="burn in cracked cells (visco_scram's p.crackRad)"),
    "useInductionTime": Param("bool", False, doc="an ignition delay before a cell burns"),
}
INDUCTION_TABLE = {"IgnitionConst": Param("float", doc="A of a cell lit through cracks; the angle's range otherwise"),
                   "PressureShift": Param("float", doc="Pa: the flame speed's pressure unit", above=0.0),
                   "PreexpoConst": Param("float", doc="flame speed Fb (m/s)", above=0.0),
                   "ExponentialConst": Param("float", doc="flame speed exponent Fc")}
CRACK_TABLE = {"Gcrack": Param("float", doc="read, unused (as Uintah's DDT1)"),
               "nCrack": Param("float", doc="read, unused (as Uintah's DDT1)"),
               "CrackVolThreshold": Param("float", 1e-14, doc="read, unused (as Uintah's DDT1)")}


@njit(cache=True)
def cracked_cells(px, crack_radius, anchor, dx, cc_low, lo, hi, press, cracked):
    """Uintah's crackedEnough: 1 in a cell where a particle's crack radius exceeds
    sqrt(8e8 / p^2.84), p the cell's equilibration pressure."""
    for q in range(px.shape[0]):
        i = int(np.floor((px[q, 0] - anchor[0]) / dx[0])) - cc_low[0]
        j = int(np.floor((px[q, 1] - anchor[1]) / dx[1])) - cc_low[1]
        k = int(np.floor((px[q, 2] - anchor[2]) / dx[2])) - cc_low[2]
        if lo[0] <= i < hi[0] and lo[1] <= j < hi[1] and lo[2] <= k < hi[2]:
            if crack_radius[q] > np.sqrt(8.0e8 / press[i, j, k] ** 2.84):
                cracked[i, j, k] = 1.0


@njit(cache=True)
def _angle(g0, g1, g2, dx, a, b, c):
    """cos and angle between the node-mass gradient and the direction (a, b, c) cells away
    (NaN where either is zero, as Uintah's)."""
    vx, vy, vz = a * dx[0], b * dx[1], c * dx[2]
    gx, gy, gz = g0 / dx[0], g1 / dx[1], g2 / dx[2]
    n = np.sqrt(vx * vx + vy * vy + vz * vz) * np.sqrt(gx * gx + gy * gy + gz * gz)
    if n == 0.0:
        return np.nan, np.nan
    cs = min(abs(gx * vx + gy * vy + gz * vz) / n, 1.0)
    return cs, np.arccos(cs)


@njit(cache=True)
def _induction(i, j, k, r0, r1, r2, surface, lit, min_over_max, use_cracks, cracked, burning_old, ind_old, count_old,
               ind_new, count_new, temps, vfs, T_ign, g0, g1, g2, dx, P, dt, induction):
    """Uintah's DDT1 induction time of one cell: (warmed long enough, lit from CONDUCTIVE or
    CONVECTIVE or 0); fills ind_new and count_new."""
    IC, PS, Fb, Fc, init = induction[1], induction[2], induction[3], induction[4], induction[5]
    nm = len(temps)
    lit_from = 0.0
    calc = False
    exceeded = False
    old = burning_old[i, j, k]
    if old == CONVECTIVE or old == CONDUCTIVE:
        ind_new[i, j, k] = ind_old[i, j, k]
        count_new[i, j, k] = count_old[i, j, k] + dt
        return True, old
    A = 12345e100
    A_solid = 12345e100
    A_gas = 12350e100
    from_solid = 0.0
    if surface:
        best_gas = -1.0
        best_solid = -1.0
        th_gas = 0.0
        th_solid = 0.0
        for a in range(-r0, r0 + 1):
            for b in range(-r1, r1 + 1):
                for c in range(-r2, r2 + 1):
                    if lit:
                        calc = True
                        for m in range(nm):
                            if vfs[m][i, j, k] > 0.2 and temps[m][i, j, k] > T_ign:
                                th_gas = 0.0
                            elif vfs[m][i + a, j + b, k + c] > 0.2 and temps[m][i + a, j + b, k + c] > T_ign:
                                cs, th = _angle(g0, g1, g2, dx, a, b, c)
                                if cs > best_gas:
                                    best_gas = cs
                                    th_gas = th
                            A_gas = (1 + IC) / 2 + (1 - IC) / 2 * np.sin(2 * th_gas - np.pi / 2)
                    bo = burning_old[i + a, j + b, k + c]
                    if use_cracks and cracked[i, j, k] > 0.0 and (bo == CONDUCTIVE or bo == CONVECTIVE):
                        calc = True
                        for m in range(nm):
                            if temps[m][i + a, j + b, k + c] > T_ign:
                                cs, th = _angle(g0, g1, g2, dx, a, b, c)
                                if cs > best_solid:
                                    best_solid = cs
                                    th_solid = th
                                    from_solid = bo
                        A_solid = (1 + IC) / 2 + (1 - IC) / 2 * np.sin(2 * th_solid - np.pi / 2)
                    if calc:
                        A = min(A_solid, A_gas)
                        lit_from = CONDUCTIVE if A == A_gas else from_solid
    elif use_cracks and min_over_max >= 0.7 and cracked[i, j, k] > 0.0:
        for a in range(-r0, r0 + 1):
            for b in range(-r1, r1 + 1):
                for c in range(-r2, r2 + 1):
                    bo = burning_old[i + a, j + b, k + c]
                    if bo == CONDUCTIVE or bo == CONVECTIVE:
                        calc = True
                        A = IC
                        lit_from = CONVECTIVE
    if calc:
        dx_mean = (dx[0] + dx[1] + dx[2]) / 3.0
        t_new = dx_mean * A / (Fb * (P / PS) ** Fc)
        ind_new[i, j, k] = t_new
        if ind_old[i, j, k] != init:
            ind_new[i, j, k] = 0.2 * t_new + 0.8 * ind_old[i, j, k]
        if count_old[i, j, k] + dt > count_new[i, j, k]:
            count_new[i, j, k] = count_old[i, j, k] + dt
        if count_new[i, j, k] >= ind_new[i, j, k]:
            exceeded = True
    return exceeded, lit_from


@njit(cache=True)
def ddt1_cells(gmass, node_low, cc_low, lo, hi, dims, dx, n_lo, n_hi, numppc, cracked, use_cracks, temps, vfs,
               press, rho_r, rho_p, v_solid, react, prod, jwl, wsb, CC, Ec, R, eps, min_mass, dt,
               burned, heat, criteria, detonating, det_local, F, dF, Ts_out, area_out,
               induction, burning_old, ind_old, count_old, ind_new, count_new):
    """DDT1's burn of each interior cell (module docstring) into `burned` (kg) and `heat` (J/kg);
    jwl = (G, b, E0, p_JWL, rho0), wsb = (BP, T_ign, p_SB, Qc + Qg); induction = (on, IC, PS, Fb,
    Fc, the initial inductionTime) with last step's burning, inductionTime, countTime."""
    G, bexp, E0, p_jwl, rho0 = jwl[0], jwl[1], jwl[2], jwl[3], jwl[4]
    BP, T_ign, p_sb, Q = wsb[0], wsb[1], wsb[2], wsb[3]
    vol = dx[0] * dx[1] * dx[2]
    r0 = 1 if dims[0] else 0
    r1 = 1 if dims[1] else 0
    r2 = 1 if dims[2] else 0
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                if not vfs[react][i, j, k] > 1e-10:
                    continue
                p = press[i, j, k]
                if p > p_jwl and numppc[i, j, k] > 0.0:             # JWL++ detonation
                    detonating[i, j, k] = 1.0
                    f = rho_p[i, j, k] / (rho_r[i, j, k] + rho_p[i, j, k])
                    F[i, j, k] = f
                    d = 0.0
                    if 0.0 <= f < 1.0:
                        d = G * p ** bexp * (1.0 - f)
                    d *= dt
                    dF[i, j, k] = d
                    m_r = rho_r[i, j, k] * vol
                    mb = min(d * (rho_p[i, j, k] * vol + m_r), m_r)
                    burned[i, j, k] = min(mb, 0.2 * rho0 * vol)
                    heat[i, j, k] = E0
                    continue
                if not (p_sb < p < p_jwl):
                    continue
                mx, mn, g0, g1, g2 = K._node_masses(gmass, node_low, i + cc_low[0], j + cc_low[1], k + cc_low[2],
                                                    dims, n_lo, n_hi)
                surface = mn / mx < 0.7 and numppc[i, j, k] > 0.0
                lit, T0, P, hot, near_det = K._ignition_neighbourhood(i, j, k, r0, r1, r2, vfs, temps, press,
                                                                      numppc, react, prod, BP, T_ign, p_jwl)
                lit = lit and surface
                det_local[i, j, k] = 1.0 if near_det else 0.0
                code = 0.0
                if induction[0] != 0.0:
                    exceeded, lit_from = _induction(i, j, k, r0, r1, r2, surface, lit, mn / mx, use_cracks, cracked,
                                                    burning_old, ind_old, count_old, ind_new, count_new, temps, vfs,
                                                    T_ign, g0, g1, g2, dx, P, dt, induction)
                    if not near_det and exceeded:
                        if lit and P >= p_sb and lit_from == CONDUCTIVE:
                            code = CONDUCTIVE
                        elif use_cracks and cracked[i, j, k] > 0.0 and hot and lit_from == CONVECTIVE:
                            code = CONVECTIVE
                    if code == 0.0 and 0.0 < count_new[i, j, k] < ind_new[i, j, k]:
                        criteria[i, j, k] = WARMINGUP
                elif not near_det:
                    if lit and P >= p_sb:
                        code = CONDUCTIVE
                    elif use_cracks and cracked[i, j, k] > 0.0 and hot:
                        code = CONVECTIVE
                if code == CONDUCTIVE:
                    gx, gy, gz = g0 / dx[0], g1 / dx[1], g2 / dx[2]
                    gn = np.sqrt(gx * gx + gy * gy + gz * gz) + 1e-100
                    nx, ny, nz = abs(gx) / gn, abs(gy) / gn, abs(gz) / gn
                    A = 0.0
                    if nx + ny + nz > 0.0:
                        A = vol / ((dx[0] * nx + dx[1] * ny + dx[2] * nz) * (1.0 / max(nx, max(ny, nz))) ** (1.0 / 3.0))
                    area_out[i, j, k] = A
                elif code == CONVECTIVE:
                    A = max(vol / CRACK_AREA_LENGTH, 1e-12)
                else:
                    continue
                criteria[i, j, k] = code
                C1, C2, C3, C4, C5 = K._ts_constants(T0, P, v_solid[i, j, k], CC[0], CC[1], CC[2], CC[3], CC[4])
                Ts = K.wsb_surface_temperature(850.0, C1, C2, C3, C4, C5, Ec, R, eps)
                Ts_out[i, j, k] = Ts
                mb = dt * A * K.wsb_mass_flux(Ts, C1, C2, Ec, R)
                have = rho_r[i, j, k] * vfs[react][i, j, k] * vol
                if mb + min_mass > have:
                    mb = max(have - min_mass, 0.0)
                burned[i, j, k] = mb
                heat[i, j, k] = Q


class DDT1(SteadyBurn):
    name = "DDT1"
    solid_temp_dw = NEW         # Uintah's DDT1 reads the solids' temp_CC of this step
    energy_temp_dw = NEW

    def __init__(self, node, comp, root):
        self.comp = comp
        dd = node.child("DDT1", required=True)
        names = comp.material_names()
        self.react = _material(dd, "fromMaterial", names)
        self.prod = _material(dd, "toMaterial", names)
        if self.react not in comp.mpm_matls:
            raise dd.child("fromMaterial").error("<fromMaterial> must be an MPM material (the solid reactant)")
        if self.prod in comp.mpm_matls:
            raise dd.child("toMaterial").error("<toMaterial> must be an ICE material (the product gas)")
        bm = dd.child("burnMaterial")
        if bm is not None and _material(dd, "burnMaterial", names) != self.prod:
            raise bm.error("<burnMaterial> other than <toMaterial> is not implemented; accepted: the "
                           "<toMaterial> (or no <burnMaterial>)")
        p = self.params = dd.read(TABLE)
        self.use_induction = p["useInductionTime"]
        self.induction = np.zeros(6)
        if self.use_induction:
            q = dd.read(INDUCTION_TABLE)
            tm = root.child("Time")
            init = tm.get("delt_init", "float", None) if tm is not None else None
            if init is None and tm is not None:
                init = tm.get("max_initial_delt", "float", 0.0)
            self.induction = np.array([1.0, q["IgnitionConst"], q["PressureShift"], q["PreexpoConst"],
                                       q["ExponentialConst"], (init or 0.0) + 1e-20])
        self.use_cracks = p["useCrackModel"]
        if self.use_cracks:
            dd.read(CRACK_TABLE)
            cm = comp.mpm.materials[self.react].model.__name__.rsplit(".", 1)[-1]
            if cm != "visco_scram":
                raise dd.child("useCrackModel").error("<useCrackModel> true needs the reactant's constitutive_model "
                                                      f"visco_scram (its crack radius); this one is {cm}")
        else:           # as Uintah, the crack tags of a deck with <useCrackModel> false change nothing
            for tag, prm in CRACK_TABLE.items():
                dd.get(tag, prm.type, None)
        adj = dd.child("adjust_IO_intervals")
        if adj is not None:
            adj.mark_used()
            print(f"pysus: note: {adj.filename}:{adj.line}: <adjust_IO_intervals> of DDT1 is ignored (the output "
                  "and checkpoint intervals stay the deck's)", file=sys.stderr)
        mat = root.child("MaterialProperties").child("MPM").children("material")[self.react]
        self.cv_react = mat.get("specific_heat", "float", 0.0)
        if self.cv_react <= 0:
            raise mat.error("DDT1's reactant needs <specific_heat> > 0 (the energy its burned mass carries)")
        R, Ec, Cp, W = p["IdealGasConst"], p["ActEnergyCondPh"], p["SpecificHeatBoth"], p["MoleWeightGasPh"]
        Qc, Qg = p["CondPhaseHeat"], p["GasPhaseHeat"]
        self.R, self.Ec = R, Ec
        self.CC = np.array([p["PreExpCondPh"] * R * p["HeatConductCondPh"] / Ec / Cp, Qc / Cp / 2,
                            4 * p["HeatConductGasPh"] * p["PreExpGasPh"] * W * W / Cp / R / R, Qc / Cp, Qg / Cp])
        self.jwl = np.array([p["G"], p["b"], p["E0"], p["ThresholdPressureJWL"], comp.mpm.materials[self.react].density])
        self.wsb = np.array([p["BoundaryParticles"], p["IgnitionTemp"], p["ThresholdPressureSB"], Qc + Qg])
        self.heat_of_reaction = Qc + Qg
        self._heat = {}

    def schedule_initialize(self, sched):
        if not self.use_induction:
            return
        t = Task("DDT1::initialize", self.initialize, [self.react])
        for lab in (ML.ddtBurning, ML.ddtInductionTime, ML.ddtCountTime):
            t.computes(lab)
        sched.add_task(t)

    def initialize(self, patch, matls, old_dw, new_dw):
        """No cell has burned or warmed; inductionTime at Uintah's marker delt_init + 1e-20."""
        for m in matls:
            for lab, value in ((ML.ddtBurning, 0.0), (ML.ddtInductionTime, self.induction[5]), (ML.ddtCountTime, 0.0)):
                new_dw.allocate(lab, m, patch)[...] = value

    def _numppc_task(self):
        t = Task("DDT1::computeNumPPC", self.count_particles, [self.react]).requires(OLD, M.pX).computes(ML.numPPC)
        if self.use_cracks:
            t.requires(OLD, M.STATE["p.crackRad"][0]).requires(NEW, I.press_equil_CC, matls=[0]).computes(ML.ddtCracked)
        return t

    def _own_labels(self, t):
        r = [self.react]
        t.requires(NEW, ML.numPPC, Ghost.AROUND_CELLS, 1, matls=r).requires(NEW, I.sp_vol_CC, matls=r) \
            .requires(NEW, I.rho_CC, matls=r).requires(OLD, I.rho_CC, matls=[self.prod])
        if self.use_cracks:
            t.requires(NEW, ML.ddtCracked, matls=r)
        if self.use_induction:
            t.requires(OLD, ML.ddtBurning, Ghost.AROUND_CELLS, 1, matls=r).requires(OLD, ML.ddtInductionTime, matls=r) \
                .requires(OLD, ML.ddtCountTime, matls=r).computes(ML.ddtInductionTime, matls=r) \
                .computes(ML.ddtCountTime, matls=r)
        for lab in (ML.ddtBurning, ML.ddtCriteria, ML.ddtDetonating, ML.ddtDetLocalTo, ML.jwlF, ML.jwlDelF,
                    ML.ddtSurfTemp, ML.ddtOnSurface):
            t.computes(lab, matls=r)
        return t

    def count_particles(self, patch, matls, old_dw, new_dw):
        """numPPC as Steady_Burn's; with the crack model also crackedEnough."""
        super().count_particles(patch, matls, old_dw, new_dw)
        if not self.use_cracks:
            return
        lv, b, r = patch.level, self.comp.ice.boxes(patch), self.react
        cracked = new_dw.allocate(ML.ddtCracked, r, patch)
        cracked[...] = 0.0
        cracked_cells(old_dw.get(M.pX, r, patch), old_dw.get(M.STATE["p.crackRad"][0], r, patch), lv.anchor, lv.dx,
                      np.array(patch.low_index(CC), np.int64), b.lo, b.hi, new_dw.get(I.press_equil_CC, 0, patch), cracked)

    def released_heat(self, patch):
        """J/kg the burned mass of each cell releases (E0 where it detonates, Qc + Qg where it burns)."""
        return self._heat.pop(id(patch))

    def burned_mass(self, patch, old_dw, new_dw, temps, vfs, mass_c, dt, burned):
        """DDT1's burn of every reactant cell (module docstring) into `burned`."""
        c, r = self.comp, self.react
        b, cc_low, node_low, _, n_lo, n_hi = c._geom(patch)
        n_lo, n_hi = symmetry_nodes(c, n_lo, n_hi)
        out = {}
        for lab in (ML.ddtBurning, ML.ddtCriteria, ML.ddtDetonating, ML.ddtDetLocalTo, ML.jwlF, ML.jwlDelF,
                    ML.ddtSurfTemp, ML.ddtOnSurface):
            out[lab] = new_dw.allocate(lab, r, patch)
            out[lab][...] = 0.0
        heat = np.zeros(burned.shape)
        cracked = new_dw.get(ML.ddtCracked, r, patch) if self.use_cracks else np.zeros(burned.shape)
        if self.use_induction:
            old = tuple(old_dw.get(lab, r, patch) for lab in (ML.ddtBurning, ML.ddtInductionTime, ML.ddtCountTime))
            ind, count = new_dw.allocate(ML.ddtInductionTime, r, patch), new_dw.allocate(ML.ddtCountTime, r, patch)
            ind[...] = 0.0
            count[...] = 0.0
        else:
            old = (burned, burned, burned)
            ind, count = np.zeros(burned.shape), np.zeros(burned.shape)
        ddt1_cells(new_dw.get(M.gMass, r, patch), node_low, cc_low, b.lo, b.hi, c.dims_i, patch.level.dx, n_lo, n_hi,
                   new_dw.get(ML.numPPC, r, patch), cracked, self.use_cracks, temps, vfs,
                   new_dw.get(I.press_equil_CC, 0, patch), new_dw.get(I.rho_CC, r, patch),
                   old_dw.get(I.rho_CC, self.prod, patch), new_dw.get(I.sp_vol_CC, r, patch), r, self.prod,
                   self.jwl, self.wsb, self.CC, self.Ec, self.R, EPSILON, TINY_RHO * b.vol, dt,
                   burned, heat, out[ML.ddtCriteria], out[ML.ddtDetonating], out[ML.ddtDetLocalTo], out[ML.jwlF],
                   out[ML.jwlDelF], out[ML.ddtSurfTemp], out[ML.ddtOnSurface], self.induction, *old, ind, count)
        out[ML.ddtBurning][...] = out[ML.ddtCriteria]
        sym_lo, sym_hi = c._sym(r)
        for lab in (ML.jwlF, ML.jwlDelF):           # Uintah's set_if_sym_BC
            copy_to_symmetry_extra_cells(out[lab], b, sym_lo, sym_hi)
        self._heat[id(patch)] = heat
