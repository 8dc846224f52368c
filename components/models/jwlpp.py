"""Uintah's JWLpp: the JWL++ reactive flow of an ICE explosive into ICE products (Souers et al.).

    <Model type="JWLpp"><JWLpp>
      <fromMaterial> reactant </fromMaterial>  <toMaterial> product </toMaterial>   (ICE materials)
      <G> 1/(s Pa^b) </G>  <b> </b>  <rho0> kg/m^3 </rho0>  <E0> J/kg </E0>
      <ThresholdPressure> Pa </ThresholdPressure>  <ThresholdVolFrac> 0.01 </ThresholdVolFrac>
    </JWLpp></Model>

In a cell where the equilibration pressure p exceeds ThresholdPressure and the reactant's volume
fraction ThresholdVolFrac, the reacted fraction F = rho_product / (rho_reactant + rho_product)
(cell densities, mass / V) grows by dF = dt G p^b (1 - F) (for F < 0.99), and

    m_burned = min(dF (m_reactant + m_product), m_reactant, 0.2 rho0 V)

moves from reactant to product with the reactant's velocity, its energy cv T and E0 per kg, and
the volume m_burned v_reactant (all reactant values of the step's start, as Uintah's). Sources
of both materials enter ICE's Lagrangian mass, momentum, energy and specific volume (Uintah's
modelMass_src ... modelVol_src), and the pressure takes Uintah's term of eq. 9,
sum_m m_src,m v_m / (V sum_m theta_m kappa_m) (delP_MassX). Outputs: F, delF (per cell),
totalMassBurned, totalHeatReleased (burned E0).
"""
from __future__ import annotations

import numpy as np
from numba import njit

from components.ice import labels as I
from framework import labels as FL
from framework.problemspec import Param
from framework.task import NEW, OLD, Task
from framework.variables import VarType

from . import labels as ML
from .simple_burn import IceSources, _material, copy_to_symmetry_extra_cells

CC = VarType.CC
TABLE = {
    "G": Param("float", doc="rate constant, 1/(s Pa^b)", at_least=0.0),
    "b": Param("float", doc="pressure exponent"),
    "rho0": Param("float", doc="kg/m^3: the burn per step is at most 0.2 rho0 V", above=0.0),
    "E0": Param("float", doc="J/kg released"),
    "ThresholdPressure": Param("float", doc="Pa"),
    "ThresholdVolFrac": Param("float", 0.01, doc="the reactant's volume fraction above which a cell reacts"),
}


@njit(cache=True)
def jwlpp_cells(press, vf_r, rho_r, rho_p, lo, hi, vol, p_thresh, vf_thresh, G, b, rho0, dt, F, dF, burned):
    """JWL++'s burn of each cell over [lo, hi) (module docstring); F and dF are Uintah's outputs."""
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                p = press[i, j, k]
                if not (p > p_thresh and vf_r[i, j, k] > vf_thresh):
                    continue
                f = rho_p[i, j, k] / (rho_r[i, j, k] + rho_p[i, j, k])
                d = 0.0
                if 0.0 <= f < 0.99:
                    d = G * p ** b * (1.0 - f)
                d *= dt
                dF[i, j, k] = d
                F[i, j, k] = f
                m_r = rho_r[i, j, k] * vol
                mb = min(d * (rho_p[i, j, k] * vol + m_r), m_r)
                burned[i, j, k] = min(mb, 0.2 * rho0 * vol)      # JWL++'s 20 % limit per step


@njit(cache=True)
def mass_exchange_pressure(burned, v_r, v_p, vfs, sps, css, lo, hi, vol, press):
    """001 eq. 9's reaction term as Uintah's: p += m_burned (v_product - v_reactant) / (V sum theta kappa)."""
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                mb = burned[i, j, k]
                if mb == 0.0:
                    continue
                ks = 0.0
                for m in range(len(vfs)):
                    c = css[m][i, j, k]
                    ks += vfs[m][i, j, k] * sps[m][i, j, k] / (c * c)
                press[i, j, k] += mb * (v_p[i, j, k] - v_r[i, j, k]) / vol / ks


class JWLpp(IceSources):
    name = "JWLpp"

    def __init__(self, node, comp, root):
        self.comp = comp
        jw = node.child("JWLpp", required=True)
        names = comp.material_names()
        self.react = _material(jw, "fromMaterial", names)
        self.prod = _material(jw, "toMaterial", names)
        for tag, m in (("fromMaterial", self.react), ("toMaterial", self.prod)):
            if m in comp.mpm_matls:
                raise jw.child(tag).error(f"<{tag}> must be an ICE material here (JWLpp of an MPM reactant "
                                          "is not implemented)")
        p = jw.read(TABLE)
        self.G, self.b, self.rho0, self.E0 = p["G"], p["b"], p["rho0"], p["E0"]
        self.p_thresh, self.vf_thresh = p["ThresholdPressure"], p["ThresholdVolFrac"]
        self.cv_react = comp.ice.materials[self.react].cv

    # -- scheduling ----------------------------------------------------------------------------
    def tasks_after(self):
        return [("MPMICE::computeEquilibrationPressure", self._sources_task),
                ("ICE::computeDelPressAndUpdatePressCC", self._pressure_task),
                ("ICE::computeLagrangianValues", self._lagrangian_task),
                ("ICE::computeLagrangianSpecificVolume", self._volume_task)]

    def _sources_task(self):
        r, g, both = [self.react], [self.prod], [self.react, self.prod]
        t = Task("JWLpp::computeModelSources", self.compute_sources, both).requires(OLD, FL.delT) \
            .requires(OLD, I.rho_CC).requires(OLD, I.temp_CC, matls=r).requires(OLD, I.vel_CC, matls=r) \
            .requires(NEW, I.sp_vol_CC, matls=r).requires(NEW, I.vol_frac_CC, matls=r) \
            .requires(NEW, I.press_equil_CC, matls=[0]).computes(ML.jwlF, matls=r).computes(ML.jwlDelF, matls=r) \
            .computes(ML.totalMassBurned).computes(ML.totalHeatReleased)
        for lab in (ML.modelMass_src, ML.modelMom_src, ML.modelEng_src, ML.modelVol_src):
            t.computes(lab)
        return t

    def _pressure_task(self):
        c = self.comp
        return Task("JWLpp::addPressureSource", self.pressure_source, c.all_matls) \
            .requires(NEW, ML.modelMass_src, matls=[self.prod]).requires(NEW, I.vol_frac_CC) \
            .requires(NEW, I.sp_vol_CC).requires(NEW, I.speedSound_CC).modifies(I.press_CC, matls=[0])

    def _lagrangian_task(self):
        return Task("JWLpp::addLagrangianSources", self.lagrangian_sources, [self.react, self.prod]) \
            .requires(NEW, ML.modelMass_src).requires(NEW, ML.modelMom_src).requires(NEW, ML.modelEng_src) \
            .modifies(I.mass_L_CC).modifies(I.mom_L_CC).modifies(I.int_eng_L_CC)

    def _volume_task(self):
        return Task("JWLpp::addVolumeSource", self.volume_source, [self.react, self.prod]) \
            .requires(NEW, ML.modelMass_src).requires(NEW, ML.modelVol_src).requires(NEW, I.sp_vol_CC) \
            .modifies(I.sp_vol_L_CC)

    def volume_sources_requires(self, t):
        t.requires(NEW, ML.modelVol_src, matls=[self.react, self.prod])

    def volume_sources(self, patch, new_dw):
        """{material: the volume it gains this step} (Uintah's modelVol_src)."""
        return {m: new_dw.get(ML.modelVol_src, m, patch) for m in (self.react, self.prod)}

    def mass_exchange_requires(self, t, dw):
        """What mass_exchange_term reads (semi-implicit ICE's eq. P)."""
        t.requires(dw, ML.modelMass_src, matls=[self.prod]).requires(dw, I.sp_vol_CC, matls=[self.react, self.prod])

    def mass_exchange_term(self, patch, dw):
        """Uintah's implicit massExchTerm per cell, sum_m m_src,m v_m / V."""
        ms = dw.get(ML.modelMass_src, self.prod, patch)
        return ms * (dw.get(I.sp_vol_CC, self.prod, patch) - dw.get(I.sp_vol_CC, self.react, patch)) \
            / self.comp.ice.boxes(patch).vol

    # -- task bodies -----------------------------------------------------------------------------
    def compute_sources(self, patch, matls, old_dw, new_dw):
        c, r, g = self.comp, self.react, self.prod
        b = c.ice.boxes(patch)
        dt = old_dw.get_reduction(FL.delT)
        F = new_dw.allocate(ML.jwlF, r, patch)
        dF = new_dw.allocate(ML.jwlDelF, r, patch)
        F[...] = 0.0
        dF[...] = 0.0
        burned = np.zeros(patch.alloc_shape(CC))
        jwlpp_cells(new_dw.get(I.press_equil_CC, 0, patch), new_dw.get(I.vol_frac_CC, r, patch),
                    old_dw.get(I.rho_CC, r, patch), old_dw.get(I.rho_CC, g, patch), b.lo, b.hi, b.vol,
                    self.p_thresh, self.vf_thresh, self.G, self.b, self.rho0, dt, F, dF, burned)
        sym_lo, sym_hi = c._sym(r)
        for a in (F, dF):                       # Uintah's set_if_sym_BC
            copy_to_symmetry_extra_cells(a, b, sym_lo, sym_hi)
        vel, temp, v_r = old_dw.get(I.vel_CC, r, patch), old_dw.get(I.temp_CC, r, patch), new_dw.get(I.sp_vol_CC, r, patch)
        for m, sign in ((r, -1.0), (g, 1.0)):
            new_dw.allocate(ML.modelMass_src, m, patch)[...] = sign * burned
            new_dw.allocate(ML.modelMom_src, m, patch)[...] = sign * burned[..., None] * vel
            new_dw.allocate(ML.modelEng_src, m, patch)[...] = sign * burned * self.cv_react * temp \
                + (burned * self.E0 if m == g else 0.0)
            new_dw.allocate(ML.modelVol_src, m, patch)[...] = sign * burned * v_r
        total = float(burned.sum())
        new_dw.put_reduction(ML.totalMassBurned, total)
        new_dw.put_reduction(ML.totalHeatReleased, total * self.E0)

    def pressure_source(self, patch, matls, old_dw, new_dw):
        c = self.comp
        b = c.ice.boxes(patch)
        get = lambda lab: tuple(new_dw.get(lab, m, patch) for m in matls)
        press = new_dw.get_modifiable(I.press_CC, 0, patch)
        mass_exchange_pressure(new_dw.get(ML.modelMass_src, self.prod, patch), new_dw.get(I.sp_vol_CC, self.react, patch),
                               new_dw.get(I.sp_vol_CC, self.prod, patch), get(I.vol_frac_CC), get(I.sp_vol_CC),
                               get(I.speedSound_CC), b.lo, b.hi, b.vol, press)
        c.ice.bcs.scalar(patch, press, "Pressure", 0, b)
