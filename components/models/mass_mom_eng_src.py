"""Uintah's mass_momentum_energy_src model for ICE: fans and heaters that hold a region's
velocity or temperature at a given value.

    <Models><Model type="mass_momentum_energy_src"><MassMomEng_src>
      <material> name </material>
      <sources>
        <geom_object> pieces
          <algorithm type="fixedPrimitiveValues">
            <velocity_src> [u, v, w] </velocity_src>   <density_src> 0 </density_src>
            <temperature_src> K </temperature_src>
            <timeStart> s </timeStart>  <timeStop> s </timeStop>      (default: always)
          </algorithm>
        </geom_object> ...
      </sources>
    </MassMomEng_src></Model></Models>

Each step, after the equilibration pressure (Uintah's ICE::computeModelSources), every cell of
the material with a low or high corner inside a region and volume fraction above 0.001 gets
the momentum source modelMom_src = m_old (theta u_src - u_old) (a non-zero <velocity_src>) and
the energy source modelEng_src = m_old cv (theta T_src - T_old) (a non-zero <temperature_src>),
m_old = rho_CC V at the start of the step: the Lagrangian state (ICE::computeLagrangianValues,
which adds them) starts from u_src and T_src there. The sums over those cells are the
reductions TotalMom_src and TotalEng_src (TotalMass_src: 0). A region acts while
timeStart <= t <= timeStop (t at the start of the step).
A <density_src> other than 0 (a mass source, which also enters the pressure equation) is not
available.
"""
from __future__ import annotations

import numpy as np

from components.ice import labels as I
from framework import labels as L
from framework.problemspec import Param
from framework.task import NEW, OLD, Task
from framework.variables import VarType

from . import labels as ML
from .simple_burn import _material

ALGORITHM = {
    "velocity_src": Param("vector"),
    "density_src": Param("float"),
    "temperature_src": Param("float"),
    "timeStart": Param("float", 0.0),
    "timeStop": Param("float", 9e99),
}
# the smallest volume fraction of the material that a region acts on (Uintah's)
MIN_VOL_FRAC = 0.001


class Region:
    """One <sources><geom_object>: its piece and its fixedPrimitiveValues."""

    def __init__(self, node, geo):
        self.piece = geo.read_object(node)
        algo = node.child("algorithm", required=True)
        algo.attr("type", choices=("fixedPrimitiveValues",))
        p = algo.read(ALGORITHM)
        self.velocity = np.array(p["velocity_src"], dtype=np.float64)
        self.temperature = p["temperature_src"]
        if p["density_src"] != 0.0:
            raise algo.child("density_src").error("a mass source (<density_src> other than 0) is not available; "
                                                  "accepted: 0")
        self.start, self.stop = p["timeStart"], p["timeStop"]


class MassMomEngSrc:
    """One <Model type="mass_momentum_energy_src">: its material and source regions."""

    def __init__(self, node, ice, geo):
        self.ice = ice
        mme = node.child("MassMomEng_src", required=True)
        self.matl = _material(mme, "material", ice.material_names())
        srcs = mme.child("sources", required=True)
        self.regions = [Region(go, geo) for go in srcs.children("geom_object")]
        if not self.regions:
            raise srcs.error("no source region (<geom_object>); accepted: one or more")
        self._masks = {}

    # -- scheduling (the ICE component calls these) ----------------------------------------------
    def schedule_sources(self, sched):
        sched.add_task(Task("MassMomEng_src::computeModelSources", self.sources_task, [self.matl])
                       .requires(OLD, L.simTime).requires(OLD, I.rho_CC).requires(OLD, I.vel_CC)
                       .requires(OLD, I.temp_CC).requires(NEW, I.vol_frac_CC)
                       .computes(ML.modelMom_src).computes(ML.modelEng_src)
                       .computes(ML.totalMass_src).computes(ML.totalMom_src).computes(ML.totalEng_src))

    def lagrangian_requires(self, t):
        """What ICE::computeLagrangianValues reads to add the sources."""
        t.requires(NEW, ML.modelMom_src, matls=[self.matl]).requires(NEW, ML.modelEng_src, matls=[self.matl])

    # -- tasks -----------------------------------------------------------------------------------
    def sources_task(self, patch, matls, old_dw, new_dw):
        """modelMom_src, modelEng_src in the patch's cells (extra cells included) and their sums."""
        b = self.ice.boxes(patch)
        m = self.matl
        t = float(old_dw.get_reduction(L.simTime))
        own = tuple(slice(l, h) for l, h in zip(b.olo, b.ohi))
        mass = old_dw.get(I.rho_CC, m, patch)[own] * b.vol
        vf = new_dw.get(I.vol_frac_CC, m, patch)[own]
        vel, temp = old_dw.get(I.vel_CC, m, patch)[own], old_dw.get(I.temp_CC, m, patch)[own]
        mom = new_dw.allocate(ML.modelMom_src, m, patch)
        eng = new_dw.allocate(ML.modelEng_src, m, patch)
        mom_o, eng_o = mom[own], eng[own]
        cv = self.ice.cvs[m]
        totals = np.zeros(3)
        total_eng = 0.0
        for n, region in enumerate(self.regions):
            if not region.start <= t <= region.stop:
                continue
            hit = self._mask(patch, n, region) & (vf > MIN_VOL_FRAC)
            if not hit.any():
                continue
            mh = mass[hit]
            if region.velocity.any():
                mom_o[hit] += region.velocity * mh[:, None] * vf[hit][:, None] - vel[hit] * mh[:, None]
            if region.temperature != 0.0:
                eng_o[hit] += region.temperature * mh * cv * vf[hit] - cv * temp[hit] * mh
            totals += mom_o[hit].sum(axis=0)
            total_eng += float(eng_o[hit].sum())
        new_dw.put_reduction(ML.totalMass_src, 0.0)
        new_dw.put_reduction(ML.totalMom_src, totals)
        new_dw.put_reduction(ML.totalEng_src, total_eng)

    def add_lagrangian(self, patch, m, mass_L, mom_L, eng_L, old_dw, new_dw):
        """ICE::computeLagrangianValues with model sources (interior cells): (m u)_L += modelMom_src,
        (m e)_L += modelEng_src, the energy kept at least tiny_rho V cv T_old (Uintah's floor)."""
        if m != self.matl:
            return
        b = self.ice.boxes(patch)
        sl = tuple(slice(l, h) for l, h in zip(b.lo, b.hi))
        mom_L[sl] += new_dw.get(ML.modelMom_src, m, patch)[sl]
        eng = eng_L[sl]
        eng += new_dw.get(ML.modelEng_src, m, patch)[sl]
        floor = self.ice.materials[m].tiny_rho * b.vol * self.ice.cvs[m] * old_dw.get(I.temp_CC, m, patch)[sl]
        np.maximum(eng, floor, out=eng)

    def _mask(self, patch, n, region):
        """Whether a cell's low or high corner lies in region n, over the patch's own cells
        (extra cells included; cached per patch)."""
        key = (patch.id, n)
        if key not in self._masks:
            lo, hi = patch.owned(VarType.CC)
            xs = patch.level.node_positions((lo, hi))
            dx = patch.level.dx
            corners = []
            for shift in (0.0, 1.0):
                X, Y, Z = np.meshgrid(*(x + shift * d for x, d in zip(xs, dx)), indexing="ij")
                corners.append(region.piece.inside(np.stack([X.ravel(), Y.ravel(), Z.ravel()], axis=1)))
            self._masks[key] = (corners[0] | corners[1]).reshape(tuple(np.array(hi) - np.array(lo)))
        return self._masks[key]
