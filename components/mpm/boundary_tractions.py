"""The force, mean traction and contact area on domain faces: Uintah's `<boundary_traction_faces>`
reductions BndyForce_<face>, BndyTraction_<face> and BndyContactArea_<face> (SerialMPM's
computeContactArea and the end of its computeInternalForce), and AccStrainEnergy.

On each listed face (xminus ... zplus) of the domain, over the face's nodes i and the
materials that are not rigid, at the start of the step:

  BndyForce    = -sum_i f_int,i          (pushing on the wall counts positive)
  BndyTraction = sum_i sigma_i . n A_i / A,    sigma_i = sum_p S_ip sigma_p V_p / V_i,
                                               A_i = 2 V_i / h,  A = sum_i A_i (all materials)
  BndyContactArea = BndyForce_d / BndyTraction_d where BndyTraction_d^2 > 1e-12, else A

with f_int the internal force before the symmetry conditions (with artificial viscosity, of
sigma - q I; under MPMICE with the pressure), V_i the nodal volume, n the outward normal, d
its direction and h the cell width along it; A_i is twice the nodal volume over h because a
face node gathers volume from one side only. Uintah's per-rank ratio for the contact area is
taken over the whole level here (the same on one rank). They are output only: the tasks are
scheduled when the deck saves one of them.

AccStrainEnergy (a <save> turns it on, as in Uintah): the sum over the steps of Uintah's
StrainEnergy, which is the step's increment for the rate models (hypo-elastic, elastic-plastic
...) and the total for the hyperelastic ones; 0 at the start. (pysus's StrainEnergy is the
total strain energy for every model: for the rate models it is Uintah's AccStrainEnergy.)
"""
from __future__ import annotations

import numpy as np

from framework.task import NEW, OLD, Task
from framework.variables import Ghost, VarType

from . import kernels, transfer
from . import labels as L

NC = VarType.NC
FACE_NAMES = L.BOUNDARY_FACES       # Uintah's Patch::getFaceName order: xminus, xplus, yminus ...
_PER_FACE = 7                       # force (3), traction before the division by A (3), A


def read_traction_faces(mpm, text, level):
    """The face indices (0..5) of `<boundary_traction_faces>[zminus, zplus]</...>`."""
    if mpm is None or not mpm.has("boundary_traction_faces"):
        return []
    node = mpm.child("boundary_traction_faces")
    t = text.strip()
    if not (t.startswith("[") and t.endswith("]")):
        raise node.error(f"'{t}' is not a list; accepted: [face, ...] of {', '.join(FACE_NAMES)}")
    faces = []
    for name in t[1:-1].replace(",", " ").split():
        if name not in FACE_NAMES:
            raise node.error(f"unknown face '{name}'; accepted: {', '.join(FACE_NAMES)}")
        f = FACE_NAMES.index(name)
        if level.collapsed[f // 2]:
            raise node.error(f"face {name}: the grid has one cell along {'xyz'[f // 2]}, where pysus holds one "
                             "layer of nodes and no face of nodes to sum over; accepted: faces of the directions "
                             "with more than one cell")
        if f not in faces:
            faces.append(f)
    return faces


def saved_face_labels(faces, saved):
    """Whether the deck saves any of the listed faces' reductions."""
    return any(lab.name in saved for f in faces for lab in (L.BndyForce[f], L.BndyTraction[f],
                                                            L.BndyContactArea[f]))


class BoundaryTractionTasks:
    """Mixed into the MPM component: needs self.level, self.materials, self.kind, self.act, self.ng,
    self._lp, self.size_labels and self.traction_faces."""

    def schedule_boundary_tractions(self, sched):
        """The face sums after the internal force is final (MPMICE adds the pressure's part
        before computeAndIntegrateAcceleration), then the reductions saved."""
        if not (self.traction_faces and saved_face_labels(self.traction_faces, getattr(sched, "output_labels", ()))):
            return
        t = Task("MPM::computeBoundaryFaceSums", self.boundary_face_sums, self.matls).requires(NEW, L.gIntForce)
        for lab in [L.pX, L.pVolume, L.pStress] + self.size_labels():
            t.requires(OLD, lab, Ghost.AROUND_NODES, self.ng)
        sched.add_task(t.computes(L.BoundaryFaceSums))
        t = Task("MPM::computeBoundaryTractions", self.boundary_tractions, self.matls).requires(NEW, L.BoundaryFaceSums)
        for f in self.traction_faces:
            t.computes(L.BndyForce[f]).computes(L.BndyTraction[f]).computes(L.BndyContactArea[f])
        sched.add_task(t)

    def boundary_face_sums(self, patch, matls, old_dw, new_dw):
        """Per listed face on this patch: -sum f_int, sum sigma_i . n A_i and sum A_i over the
        face's nodes (the module's docstring)."""
        lv = self.level
        alo, ahi = patch.alloc(NC)
        pad = np.array([self.ng + 2 if self.dims[d] else 0 for d in range(3)])
        shape = tuple(np.array(ahi) - np.array(alo) + 2 * pad)
        base = np.array(alo) - pad                  # global index of the padded arrays' [0, 0, 0]
        kind = transfer.INTERPOLATORS[self.kind]
        own = patch.owned(NC)
        inner = lv.interior_box(NC)
        sums = np.zeros(6 * _PER_FACE)
        for m in matls:
            px = old_dw.get(L.pX, m, patch)
            gvol = np.zeros(shape)
            gsv = np.zeros(shape + (3, 3))           # sum S sigma_p V_p
            kernels.p2g_stress(kind, self.act, px, old_dw.get(L.pVolume, m, patch), old_dw.get(L.pStress, m, patch),
                               self._lp(old_dw, m, patch, len(px)), lv.anchor, lv.dx, base, gvol, gsv)
            gvol += 1e-200                           # Uintah's nodal volume starts at d_SMALL_NUM_MPM
            rigid = self.materials[m].is_rigid
            fint = None if rigid else new_dw.get(L.gIntForce, m, patch)
            for f in self.traction_faces:
                d, upper = f // 2, f % 2
                if not (patch.at_high if upper else patch.at_low)[d]:
                    continue                         # an interior or periodic patch face
                lo, hi = [max(a, b) for a, b in zip(own[0], inner[0])], [min(a, b) for a, b in zip(own[1], inner[1])]
                lo[d] = inner[1][d] - 1 if upper else 0
                hi[d] = lo[d] + 1
                face = tuple(slice(l - b, h - b) for l, h, b in zip(lo, hi, base))
                area = 2.0 * gvol[face] / lv.dx[d]
                s = sums[_PER_FACE * f:_PER_FACE * (f + 1)]
                s[6] += area.sum()
                if rigid:
                    continue
                fl = patch.low_index(NC)
                s[0:3] -= fint[tuple(slice(l - b, h - b) for l, h, b in zip(lo, hi, fl))].reshape(-1, 3).sum(axis=0)
                normal = 1.0 if upper else -1.0
                stress = gsv[face] / gvol[face][..., None, None]
                s[3:6] += ((stress[..., :, d] * normal) * area[..., None]).reshape(-1, 3).sum(axis=0)
        new_dw.put_reduction(L.BoundaryFaceSums, sums)

    def boundary_tractions(self, patch, matls, old_dw, new_dw):
        """BndyForce, BndyTraction = the traction sum / A, BndyContactArea: the level's
        totals, put by the level's first patch."""
        sums = np.asarray(new_dw.get_reduction(L.BoundaryFaceSums)).reshape(6, _PER_FACE)
        first = patch.id == min(p.id for p in self.level.patches)
        for f in self.traction_faces:
            force, traction, cell_area = sums[f, 0:3], sums[f, 3:6].copy(), sums[f, 6]
            if cell_area > 0.0:
                traction /= cell_area
            d = f // 2
            area = force[d] / traction[d] if traction[d] * traction[d] > 1e-12 else cell_area
            scale = 1.0 if first else 0.0
            new_dw.put_reduction(L.BndyForce[f], force * scale)
            new_dw.put_reduction(L.BndyTraction[f], traction * scale)
            new_dw.put_reduction(L.BndyContactArea[f], area * scale)


def schedule_acc_strain_energy(component, sched, initialize=False):
    """AccStrainEnergy when the deck saves it (component.saves_acc_energy): 0 at
    initialization, then the old value plus Uintah's StrainEnergy of the step (Uintah's
    computeAccStrainEnergy)."""
    if not component.saves_acc_energy:
        return
    if initialize:
        sched.add_task(Task("MPM::initializeAccStrainEnergy", _zero_acc_strain_energy, component.matls)
                       .computes(L.AccStrainEnergy))
        return
    sched.add_task(Task("MPM::computeAccStrainEnergy", _acc_strain_energy, component.matls)
                   .requires(OLD, L.AccStrainEnergy).requires(NEW, L.StepStrainEnergy).computes(L.AccStrainEnergy))


def _zero_acc_strain_energy(patch, matls, old_dw, new_dw):
    new_dw.put_reduction(L.AccStrainEnergy, 0.0)


def _acc_strain_energy(patch, matls, old_dw, new_dw):
    """A max reduction (as Uintah's): every patch puts the same level total."""
    new_dw.put_reduction(L.AccStrainEnergy, old_dw.get_reduction(L.AccStrainEnergy)
                         + new_dw.get_reduction(L.StepStrainEnergy))
