"""Grid velocity boundary conditions of MPM from `<Grid><BoundaryConditions>`.

Accepted per `<Face side="x-|x+|y-|y+|z-|z+">`:
  <BCType id="all|N" var="Dirichlet" label="Velocity"><value>[u,v,w]</value></BCType>
  <BCType id="all|N" var="symmetry"  label="Symmetric"/>   (normal velocity zero)
  <BCType id="all|N" var="Neumann"   label="Velocity">       (free: Uintah's MPMBoundCond
                                                              applies nothing for it)
  <BCType id="all|N" var="Dirichlet" label="Temperature"><value>T</value></BCType>
      (with heat conduction, thermal.py: g.temperature takes T on those nodes after
      particles -> grid, and the nodal rate there becomes (T - the interpolated
      temperature)/dt, as Uintah's integrateTemperatureRate)
They are applied to g.velocity_star on the face's nodes and on the extra-cell nodes
beyond it, after the acceleration is integrated, and the acceleration there is
recomputed as (v* - v)/dt, as Uintah's setGridBoundaryConditions. The symmetry
conditions also act on g.velocity as soon as the particles have been interpolated to
the grid (apply_symmetric, as Uintah's interpolateParticlesToGrid), so a symmetry
plane's nodes get no normal acceleration to hand back to the particles. Faces of collapsed
directions (2D, 1D) hold no nodes of their own and need nothing. A face without a
condition is left free (traction-free).
"""
from __future__ import annotations

import numpy as np

from framework.grid import FACES
from framework.gridspec import boundary_faces
from framework.variables import VarType

from . import kernels


class GridBCs:
    temperature_items = ()

    def __init__(self, root, level, nmat):
        self.items = []          # (d, side, comps mask, value, materials)
        self.temperature_items = []      # (d, side, value, materials)
        grid = root.child("Grid")
        bcs = grid.child("BoundaryConditions") if grid is not None else None
        if bcs is None:
            return
        for side, face in boundary_faces(bcs, FACES):
            d, s = FACES.index(side) // 2, FACES.index(side) % 2
            given = {"Velocity": set(), "Temperature": set()}
            for bc in face.children("BCType"):
                ident = bc.attr("id")
                var = bc.attr("var", choices=("Dirichlet", "symmetry", "Neumann"))
                label = bc.attr("label", choices=("Velocity", "Symmetric", "Temperature"))
                if ident == "all":
                    mats = tuple(range(nmat))
                else:
                    try:
                        mats = (int(ident),)
                    except ValueError:
                        raise bc.error(f'id="{ident}": accepted: all or a material index') from None
                    if not 0 <= mats[0] < nmat:
                        raise bc.error(f'id="{ident}": there are {nmat} MPM materials')
                kind = "Temperature" if label == "Temperature" else "Velocity"
                if given[kind] & set(mats):
                    raise bc.error(f"a second {kind} <BCType> for material {min(given[kind] & set(mats))} on this "
                                   "face; accepted: one condition per material on a face")
                given[kind] |= set(mats)
                if label == "Temperature":
                    if var != "Dirichlet":
                        raise bc.error(f'var="{var}" label="Temperature": accepted: var="Dirichlet"')
                    if level.periodic[d]:
                        raise bc.error(f"face {side} is periodic; it takes no boundary condition")
                    value = bc.get("value", "float")
                    self.temperature_node = bc
                    if not level.collapsed[d]:
                        self.temperature_items.append((d, s, value, mats))
                    continue
                if (var == "symmetry") != (label == "Symmetric"):
                    raise bc.error('accepted: var="Dirichlet" or "Neumann" label="Velocity", '
                                   'or var="symmetry" label="Symmetric"')
                if var == "Neumann":
                    bc.get("value", "vector", (0.0, 0.0, 0.0))       # read: a free face has no value to set
                    continue
                if var == "symmetry":
                    comps = np.zeros(3, np.bool_)
                    comps[d] = True
                    value = np.zeros(3)
                else:
                    comps = np.ones(3, np.bool_)
                    value = np.array(bc.get("value", "vector"), float)
                if level.periodic[d]:
                    raise bc.error(f"face {side} is periodic; it takes no boundary condition")
                if not level.collapsed[d]:
                    self.items.append((d, s, comps, value, mats))

    def apply_symmetric(self, patch, matl, gvel):
        """The symmetry conditions of this material on g.velocity (normal component 0)."""
        self.apply(patch, matl, gvel, np.empty_like(gvel), gvel, 1.0, symmetric_only=True)

    def apply(self, patch, matl, gvs, gacc, gvel, dt, symmetric_only=False):
        """Apply every condition of this material on the faces `patch` touches."""
        if not self.items:
            return
        lo_all, hi_all = (0, 0, 0), gvs.shape[:3]
        own_lo, own_hi = patch.owned_local(VarType.NC)
        inner = patch.level.interior_box(VarType.NC)
        base = patch.low_index(VarType.NC)
        for d, s, comps, value, mats in self.items:
            if matl not in mats or not (patch.at_high if s else patch.at_low)[d]:
                continue
            if symmetric_only and comps.all():          # a Dirichlet velocity (all components)
                continue
            lo = list(own_lo)
            hi = list(own_hi)
            if s == 0:
                hi[d] = inner[0][d] - base[d] + 1          # face node and the extra nodes below
            else:
                lo[d] = inner[1][d] - 1 - base[d]          # face node and the extra nodes above
            lo = np.maximum(lo, lo_all)
            hi = np.minimum(hi, hi_all)
            kernels.velocity_bc(gvs, gacc, gvel, dt, np.asarray(lo, np.int64), np.asarray(hi, np.int64),
                                comps, value)

    def _face_nodes(self, patch, d, s, shape):
        """The slices of a patch's node array on face (d, s): the face nodes and the extra
        nodes beyond them, within the patch's owned nodes."""
        own_lo, own_hi = patch.owned_local(VarType.NC)
        inner = patch.level.interior_box(VarType.NC)
        base = patch.low_index(VarType.NC)
        lo, hi = list(own_lo), list(own_hi)
        if s == 0:
            hi[d] = inner[0][d] - base[d] + 1
        else:
            lo[d] = inner[1][d] - 1 - base[d]
        lo = np.maximum(lo, 0)
        hi = np.minimum(hi, shape[:3])
        return tuple(slice(a, b) for a, b in zip(lo, hi))

    def apply_temperature(self, patch, matl, temperature):
        """Set the Dirichlet temperatures of this material on the faces `patch` touches."""
        for d, s, value, mats in self.temperature_items:
            if matl in mats and (patch.at_high if s else patch.at_low)[d]:
                temperature[self._face_nodes(patch, d, s, temperature.shape)] = value

    def symmetric_normal(self, patch, normal):
        """Remove the component into the face from a nodal normal on every symmetry face of
        material 0 (Uintah's "Symmetric" condition on g.normAlphaToBeta)."""
        for d, s, comps, value, mats in self.items:
            if 0 not in mats or comps.sum() != 1 or not (patch.at_high if s else patch.at_low)[d]:
                continue
            normal[self._face_nodes(patch, d, s, normal.shape) + (d,)] = 0.0
