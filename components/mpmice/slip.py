"""The slip exchange model's tasks in MPMICE (components/ice/slip_exchange.py has the model):
before the face velocities' exchange, the solid's surface cells and normals from its node
masses, the gas's mean free path, and the face exchange's K of each cell; the diagnostic
vel_CCTransposed. The exchange tasks themselves are ICE's, which read these.
"""
from __future__ import annotations

import numpy as np

from components.ice import labels as I
from components.ice import slip_exchange as SL
from components.mpm import labels as M
from framework.task import NEW, OLD, Task
from framework.variables import Ghost

G = Ghost.AROUND_CELLS


class SlipTasks:
    """Uintah's SlipExch::sched_PreExchangeTasks and the requires it adds to the exchange tasks."""

    def __init__(self, mpmice):
        self.c = mpmice
        self.model = mpmice.ice.slip

    def schedule_pre_exchange(self, sched):
        c, sl = self.c, self.model
        t = Task("ExchangeModel::ComputeSurfaceNormal", self.surface_normal, c.mpm_matls) \
            .requires(NEW, M.gMass, G, 1).computes(SL.surfaceNorm).computes(SL.isSurfaceCell, matls=[0])
        sched.add_task(t)
        sched.add_task(Task("SlipExch::computeMeanFreePath", self.mean_free_path, c.ice.ice_matls)
                       .requires(OLD, I.temp_CC).requires(OLD, I.sp_vol_CC).computes(SL.meanFreePath))
        sched.add_task(Task("SlipExch::faceCoefficients", self.face_coefficients, [0])
                       .requires(NEW, SL.isSurfaceCell).requires(NEW, SL.surfaceNorm, matls=[sl.solid])
                       .requires(NEW, SL.meanFreePath, matls=[sl.fluid])
                       .requires(NEW, I.vol_frac_CC, matls=[sl.solid]).computes(SL.slipK_CC))

    def face_requires(self, t):
        """The explicit face exchange reads the K of its faces' cells."""
        t.requires(NEW, SL.slipK_CC, G, 1, matls=[0])

    def cell_requires(self, t):
        sl = self.model
        t.requires(NEW, SL.isSurfaceCell, matls=[0]).requires(NEW, SL.surfaceNorm, matls=[sl.solid]) \
            .requires(NEW, SL.meanFreePath, matls=[sl.fluid])

    def schedule_diagnostics(self, sched):
        """vel_CCTransposed (only when saved): Q u of every material before the exchange."""
        sl = self.model
        sched.add_task(Task("SlipExch::vel_CCTransposed", self.transposed, self.c.all_matls)
                       .requires(NEW, I.mass_L_CC).requires(NEW, I.mom_L_CC).requires(NEW, SL.isSurfaceCell, matls=[0])
                       .requires(NEW, SL.surfaceNorm, matls=[sl.solid]).computes(SL.vel_CCTransposed))

    # -- task bodies --------------------------------------------------------------------------------
    def surface_normal(self, patch, matls, old_dw, new_dw):
        b, cc_low, node_low, dims, n_lo, n_hi = self.c._geom(patch)
        surf = new_dw.allocate(SL.isSurfaceCell, 0, patch, fill=0)
        for m in matls:
            norm = new_dw.allocate(SL.surfaceNorm, m, patch)
            one = surf if m == matls[0] else np.zeros_like(surf)
            SL.surface_cells(new_dw.get(M.gMass, m, patch), node_low, cc_low, b.lo, b.hi, dims, n_lo, n_hi,
                             np.asarray(patch.level.dx, np.float64), norm, one)
            surf |= one

    def mean_free_path(self, patch, matls, old_dw, new_dw):
        ice = self.c.ice
        for m in matls:
            SL.mean_free_path(old_dw.get(I.sp_vol_CC, m, patch), old_dw.get(I.temp_CC, m, patch), ice.cvs[m],
                              ice.gammas[m], new_dw.allocate(SL.meanFreePath, m, patch))

    def face_coefficients(self, patch, matls, old_dw, new_dw):
        sl, b = self.model, self.c.ice.boxes(patch)
        out = new_dw.allocate(SL.slipK_CC, 0, patch, fill=SL.K_FACE)
        SL.face_coefficients(new_dw.get(SL.isSurfaceCell, 0, patch), new_dw.get(SL.surfaceNorm, sl.solid, patch),
                             new_dw.get(SL.meanFreePath, sl.fluid, patch), new_dw.get(I.vol_frac_CC, sl.solid, patch),
                             np.asarray(patch.level.dx, np.float64), sl.a_v, sl.use_coeffs, b.olo, b.ohi, out)

    def transposed(self, patch, matls, old_dw, new_dw):
        sl = self.model
        surf = new_dw.get(SL.isSurfaceCell, 0, patch)
        norm = new_dw.get(SL.surfaceNorm, sl.solid, patch)
        for m in matls:
            out = new_dw.allocate(SL.vel_CCTransposed, m, patch)
            if sl.use_coeffs:
                SL.transposed_velocity(new_dw.get(I.mass_L_CC, m, patch), new_dw.get(I.mom_L_CC, m, patch), surf, norm,
                                       out)
