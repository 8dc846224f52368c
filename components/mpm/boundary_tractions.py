"""The force, mean traction and contact area on domain faces: Uintah's `<boundary_traction_faces>`
reductions BndyForce_<face>, BndyTraction_<face> and BndyContactArea_<face> (SerialMPM's
computeContactArea and the end of its computeInternalForce), and AccStrainEnergy.

On each listed face (xminus ... zplus) of the domain, over the face's nodes i at the start of
the step:

  BndyContactCellArea = A = sum_i A_i over all materials,   A_i = 2 V_i / h
  BndyForce    = -sum_i f_int,i                     (pushing on the wall counts positive)
  BndyTraction = sum_i sigma_i . n A_i / A,          sigma_i = sum_p S_ip sigma_p V_p / V_i
  BndyContactArea = BndyForce_d / BndyTraction_d where BndyTraction_d^2 > 1e-12, else A

the force and traction over the materials that are not rigid, f_int the internal force before
the symmetry conditions (with artificial viscosity of sigma - q I; under MPMICE with the
pressure), V_i the nodal volume, n the outward normal, d its direction and h the cell width
along it; A_i is twice the nodal volume over h because a face node gathers volume from one side
only. As in Uintah, the three are summed over the patches, each patch taking the ratio of its
own force and traction for the contact area (or A): on a level of N patches that is about N
times the contact area (sus gives the same). They are output only: the tasks are scheduled
when the deck saves one of them, and g.volume is then computed.

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
_SMALL = 1e-200                     # Uintah's nodal volume starts at d_SMALL_NUM_MPM


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


def saves_face_labels(faces, saved):
    """Whether the deck saves any of the listed faces' reductions."""
    return any(lab.name in saved for f in faces
               for lab in (L.BndyForce[f], L.BndyTraction[f], L.BndyContactArea[f], L.BndyContactCellArea[f]))


class BoundaryTractionTasks:
    """Mixed into the MPM component: needs self.level, self.materials, self.kind, self.act, self.ng,
    self.dims, self._lp, self.size_labels and self.traction_faces."""

    def schedule_boundary_tractions(self, sched):
        """The nodal area of the faces, then force, traction and contact area, after the
        internal force is final (MPMICE adds the pressure's part before
        computeAndIntegrateAcceleration)."""
        if not self.saves_tractions:
            return
        t = Task("MPM::computeContactArea", self.contact_cell_area, self.matls).requires(NEW, L.gVolume)
        for f in self.traction_faces:
            t.computes(L.BndyContactCellArea[f])
        sched.add_task(t)
        t = Task("MPM::computeBoundaryTractions", self.boundary_tractions, self.matls) \
            .requires(NEW, L.gIntForce).requires(NEW, L.gVolume)
        for lab in [L.pX, L.pVolume, L.pStress] + self.size_labels():
            t.requires(OLD, lab, Ghost.AROUND_NODES, self.ng)
        for f in self.traction_faces:
            t.requires(NEW, L.BndyContactCellArea[f])
            t.computes(L.BndyForce[f]).computes(L.BndyTraction[f]).computes(L.BndyContactArea[f])
        sched.add_task(t)

    def _face_slices(self, patch, f, base):
        """Slices of the patch's nodes on face f in an array whose [0, 0, 0] is global node
        `base`; None where the patch's side is not on the domain's face (inside, periodic)."""
        d, upper = f // 2, f % 2
        if not (patch.at_high if upper else patch.at_low)[d]:
            return None
        lo, hi = (list(x) for x in patch.interior_box(NC))
        lo[d] = patch.face_index(d, upper)
        hi[d] = lo[d] + 1
        return tuple(slice(l - b, h - b) for l, h, b in zip(lo, hi, base))

    def contact_cell_area(self, patch, matls, old_dw, new_dw):
        """BndyContactCellArea_<face> = sum over the face's nodes and all materials of 2 V_i / h."""
        base = patch.low_index(NC)
        for f in self.traction_faces:
            face = self._face_slices(patch, f, base)
            area = 0.0
            if face is not None:
                for m in matls:
                    area += 2.0 * (new_dw.get(L.gVolume, m, patch)[face] + _SMALL).sum() / self.level.dx[f // 2]
            new_dw.put_reduction(L.BndyContactCellArea[f], area)

    def boundary_tractions(self, patch, matls, old_dw, new_dw):
        """This patch's part of BndyForce, BndyTraction and BndyContactArea (the module's
        docstring): sums over its face nodes and the materials that are not rigid."""
        lv = self.level
        alo, ahi = patch.alloc(NC)
        pad = np.array([self.ng + 2 if self.dims[d] else 0 for d in range(3)])
        shape = tuple(np.array(ahi) - np.array(alo) + 2 * pad)
        base = np.array(alo) - pad                  # global index of the padded arrays' [0, 0, 0]
        kind = transfer.INTERPOLATORS[self.kind]
        force = {f: np.zeros(3) for f in self.traction_faces}
        traction = {f: np.zeros(3) for f in self.traction_faces}
        faces = {f: (self._face_slices(patch, f, base), self._face_slices(patch, f, patch.low_index(NC)))
                 for f in self.traction_faces}
        for m in matls:
            if self.materials[m].is_rigid or all(face is None for face, _ in faces.values()):
                continue
            px = old_dw.get(L.pX, m, patch)
            gsv = np.zeros(shape + (3, 3))           # sum S sigma_p V_p
            kernels.p2g_stress(kind, self.act, px, old_dw.get(L.pVolume, m, patch), old_dw.get(L.pStress, m, patch),
                               self._lp_read_only(old_dw, m, patch, len(px)), lv.anchor, lv.dx, base, np.zeros(shape),
                               gsv)
            gvol = new_dw.get(L.gVolume, m, patch)
            fint = new_dw.get(L.gIntForce, m, patch)
            for f, (face, own) in faces.items():
                if face is None:
                    continue
                d, normal = f // 2, (1.0 if f % 2 else -1.0)
                vol = gvol[own] + _SMALL
                area = 2.0 * vol / lv.dx[d]
                stress = gsv[face] / vol[..., None, None]
                force[f] -= fint[own].reshape(-1, 3).sum(axis=0)
                traction[f] += ((stress[..., :, d] * normal) * area[..., None]).reshape(-1, 3).sum(axis=0)
        for f in self.traction_faces:
            cell_area = new_dw.get_reduction(L.BndyContactCellArea[f])
            if cell_area > 0.0:
                traction[f] /= cell_area
            d = f // 2
            contact = force[f][d] / traction[f][d] if traction[f][d] * traction[f][d] > 1e-12 else cell_area
            new_dw.put_reduction(L.BndyForce[f], force[f])
            new_dw.put_reduction(L.BndyTraction[f], traction[f])
            new_dw.put_reduction(L.BndyContactArea[f], contact)


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
