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
  <BCType id="all|N" var="Neumann"   label="Temperature"><value>g</value></BCType>
      (likewise, each node of the face and beyond takes the temperature of its inward
      neighbour less g dx, as Uintah's MPMBoundCond)
  <BCType label="Pressure|Density|SpecificVol">: ICE's conditions, read and not applied
      (Uintah's MPM sets only Velocity, Symmetric and Temperature conditions), with a note
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

import sys

import numpy as np

from framework.grid import FACES
from framework.gridspec import boundary_faces, sub_faces
from framework.scheduler.comm import world_rank
from framework.variables import VarType

from . import kernels


ICE_LABELS = ("Pressure", "Density", "SpecificVol")


def _note(bc, text):
    """A one-line note on a read <BCType> that is not applied (rank 0 prints it)."""
    if world_rank() == 0:
        print(f"pysus: note: {bc.filename}:{bc.line}: {text}", file=sys.stderr)


def _periodic_note(bc, side):
    """A <BCType> on a periodic face is read and not applied: Uintah applies conditions on faces
    without a neighbour only, and a periodic face has one."""
    _note(bc, f"face {side} is periodic; its <BCType> is not applied (as in Uintah)")


class GridBCs:
    temperature_items = ()
    # GIMP and CPDI reach the extra nodes: there a symmetry plane mirrors the velocity of the node
    # as far inside (normal component negated), as Uintah's MPMBoundCond for those interpolators
    mirror_extra = False

    def __init__(self, root, level, nmat):
        self.items = []          # (d, side, comps mask, value, materials, where)
        self.temperature_items = []      # (d, side, neumann, value, materials, where)
        grid = root.child("Grid")
        bcs = grid.child("BoundaryConditions") if grid is not None else None
        if bcs is None:
            return
        faces = [(side, None, face) for side, face in boundary_faces(bcs, FACES)] + sub_faces(bcs, FACES, level)
        for side, geom, face in faces:
            d, s = FACES.index(side) // 2, FACES.index(side) % 2
            given = {"Velocity": set(), "Symmetric": set(), "Temperature": set()}
            for bc in face.children("BCType"):
                ident = bc.attr("id")
                var = bc.attr("var", choices=("Dirichlet", "symmetry", "Neumann"))
                label = bc.attr("label", choices=("Velocity", "Symmetric", "Temperature") + ICE_LABELS)
                if label in ICE_LABELS:
                    _materials(bc, ident, nmat, strict=False)
                    if bc.has("value"):
                        bc.get("value", "float")
                    _note(bc, f'<BCType label="{label}"> is read and not applied: Uintah\'s MPM applies only '
                              "Velocity, Symmetric and Temperature conditions")
                    continue
                mats = _materials(bc, ident, nmat)
                kind = label                  # Uintah keeps a Velocity and a Symmetric condition apart
                if given[kind] & set(mats):
                    raise bc.error(f"a second {kind} <BCType> for material {min(given[kind] & set(mats))} on this "
                                   "face; accepted: one condition of each label per material on a face")
                given[kind] |= set(mats)
                if label == "Temperature":
                    if var not in ("Dirichlet", "Neumann"):
                        raise bc.error(f'var="{var}" label="Temperature": accepted: var="Dirichlet" or "Neumann"')
                    value = bc.get("value", "float")
                    if level.periodic[d]:
                        _periodic_note(bc, side)
                        continue
                    self.temperature_node = bc
                    if not level.collapsed[d]:
                        self.temperature_items.append((d, s, var == "Neumann", value, mats, geom))
                    continue
                if (var == "symmetry") != (label == "Symmetric"):
                    raise bc.error('accepted: var="Dirichlet" or "Neumann" label="Velocity", '
                                   'or var="symmetry" label="Symmetric"')
                if var == "Neumann":
                    bc.get("value", "vector", (0.0, 0.0, 0.0))       # read: a free face has no value to set
                    continue
                if var == "symmetry":
                    if geom is not None:
                        raise bc.error('var="symmetry" on a sub-face is not supported; accepted: Dirichlet, '
                                       "Neumann (symmetry acts on a whole <Face side>)")
                    comps = np.zeros(3, np.bool_)
                    comps[d] = True
                    value = np.zeros(3)
                else:
                    comps = np.ones(3, np.bool_)
                    value = np.array(bc.get("value", "vector"), float)
                if level.periodic[d]:
                    _periodic_note(bc, side)
                    continue
                # a collapsed direction's one node layer is that face's nodes (Uintah's one cell
                # has both faces' nodes): a Dirichlet velocity there holds the material's every node
                if not level.collapsed[d] or var == "Dirichlet":
                    self.items.append((d, s, comps, value, mats, geom))
        # Uintah sets every face's Velocity conditions, then the Symmetric ones
        self.items.sort(key=lambda item: bool(item[2].sum() == 1))      # symmetric: one component
        self._place_sub_faces(faces, nmat)

    def _place_sub_faces(self, faces, nmat):
        """Turn each item's sub-face (or None) into where = (the sub-face, None) or, for a side's
        condition, (None, the sub-faces of that side that name the material): the nodes of a
        sub-face take its conditions, the side's the rest (per material, as Uintah: a sub-face
        exists for the materials its BCTypes name). where = None: the whole face."""
        named = {}
        for side, geom, face in faces:
            if geom is not None:
                ms = set()
                for bc in face.children("BCType"):
                    ms |= set(_materials(bc, bc.attr("id"), nmat, strict=False))
                named[geom] = ms
        self.sub_faces = list(named)
        self._masks = {}
        self._apply_ops = {}            # (patch id, material, symmetric_only, shape, halo, mirror_extra): apply's work

        def place(items, nvals):
            out = []
            for item in items:
                head, mats, geom = item[:nvals], item[nvals], item[nvals + 1]
                if geom is not None:
                    out.append(head + (mats, (geom, ())))
                    continue
                d, s = item[0], item[1]
                if not any((g.d, g.s) == (d, s) for g in named):
                    out.append(head + (mats, None))
                    continue
                for m in mats:
                    cut = tuple(g for g, ms in named.items() if (g.d, g.s) == (d, s) and m in ms)
                    out.append(head + ((m,), (None, cut) if cut else None))
            return out

        self.items = place(self.items, 4)
        self.temperature_items = place(self.temperature_items, 4)

    def _where(self, patch, where, d, lo, hi):
        """Which nodes of the local box [lo, hi) (the face's nodes and the extra nodes beyond) `where`
        selects, by the position of the face node they share: inside its sub-face, or outside
        every sub-face it cuts out."""
        geom, cut = where
        base = patch.low_index(VarType.NC)
        key = (patch.id, d, geom, cut, tuple(lo), tuple(hi), base)
        mask = self._masks.get(key)
        if mask is None:
            lv = patch.level
            axes = [lv.anchor[c] + (np.arange(lo[c], hi[c]) + base[c]) * lv.dx[c] for c in range(3)]
            pts = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1)
            g0 = geom if geom is not None else cut[0]
            pts[..., d] = (lv.upper if g0.s else lv.anchor)[d]          # the face node above each node
            mask = geom.inside(pts) if geom is not None else np.ones(pts.shape[:3], np.bool_)
            for g in cut:
                mask &= ~g.inside(pts)
            self._masks[key] = mask
        return mask

    def has_symmetric(self, patch, matl):
        """Whether a symmetry condition of this material lies on a face `patch` touches."""
        return any(matl in mats and comps.sum() == 1 and (patch.at_high if s else patch.at_low)[d]
                   for d, s, comps, value, mats, where in self.items)

    def apply_symmetric(self, patch, matl, gvel):
        """The symmetry conditions of this material on g.velocity (normal component 0)."""
        self.apply(patch, matl, gvel, np.empty_like(gvel), gvel, 1.0, symmetric_only=True)

    def apply(self, patch, matl, gvs, gacc, gvel, dt, symmetric_only=False):
        """Apply every condition of this material on the faces `patch` touches."""
        if not self.items:
            return
        key = (patch.id, matl, symmetric_only, gvs.shape, patch.level.halo[VarType.NC], self.mirror_extra)
        ops = self._apply_ops.get(key)
        if ops is None:
            ops = self._apply_ops[key] = self._ops(patch, matl, gvs.shape, symmetric_only)
        for d, lo, hi, comps, value, mirrors, sl, mask in ops:
            if mask is None:
                kernels.velocity_bc(gvs, gacc, gvel, dt, lo, hi, comps, value)
                for sl_e, sl_s in mirrors:
                    # extra node beyond the face takes the velocity of the node as far inside, its d
                    # component negated (Uintah's Symmetric condition for GIMP and CPDI)
                    v = gvs[sl_s].copy()
                    v[..., d] = -v[..., d]
                    gvs[sl_e] = v
                    gacc[sl_e] = (v - gvel[sl_e]) / dt
                continue
            vs, acc, v = gvs[sl], gacc[sl], gvel[sl]
            for c in comps:     # velocity_bc on the selected nodes
                vs[..., c][mask] = value[c]
                acc[..., c][mask] = (value[c] - v[..., c][mask]) / dt

    def _ops(self, patch, matl, shape, symmetric_only):
        """apply's work on one patch and material for arrays of this shape, kept (per halo):
        per condition its direction, its node box [lo, hi) and components for velocity_bc with the
        (extra node, mirrored node) slices of a symmetry face (mirror_extra), or the box's slices
        and the node mask of a sub-face with the components it sets."""
        lo_all, hi_all = (0, 0, 0), shape[:3]
        own_lo, own_hi = patch.owned_local(VarType.NC)
        base = patch.low_index(VarType.NC)
        ops = []
        for d, s, comps, value, mats, where in self.items:
            if matl not in mats or not (patch.at_high if s else patch.at_low)[d]:
                continue
            if symmetric_only and comps.all():          # a Dirichlet velocity (all components)
                continue
            if where is not None and not _on_level_face(patch, d, s):
                if where[0] is not None:                  # a sub-face lies on the level's outer face
                    continue
                where = None
            lo = list(own_lo)
            hi = list(own_hi)
            face = patch.face_index(d, s) - base[d]
            if s == 0:
                hi[d] = face + 1                           # face node and the extra nodes below
            else:
                lo[d] = face                               # face node and the extra nodes above
            lo = np.maximum(lo, lo_all)
            hi = np.minimum(hi, hi_all)
            if where is None:
                mirrors = self._mirrors(shape, d, s, lo, hi, face) \
                    if self.mirror_extra and comps.sum() == 1 and not value.any() else []
                ops.append((d, np.asarray(lo, np.int64), np.asarray(hi, np.int64), comps, value, mirrors, None, None))
                continue
            sl = tuple(slice(a, b) for a, b in zip(lo, hi))
            ops.append((d, lo, hi, list(np.flatnonzero(comps)), value, None, sl, self._where(patch, where, d, lo, hi)))
        return ops

    @staticmethod
    def _mirrors(shape, d, s, lo, hi, face):
        """(extra node, node as far inside) slices of the extra nodes e beyond the face node."""
        out = []
        for e in (range(lo[d], face) if s == 0 else range(face + 1, hi[d])):
            src = 2 * face - e
            if not 0 <= src < shape[d]:
                continue
            out.append((tuple(slice(lo[c], hi[c]) if c != d else e for c in range(3)),
                        tuple(slice(lo[c], hi[c]) if c != d else src for c in range(3))))
        return out

    def _face_nodes(self, patch, d, s, shape, ghosts=False):
        """The slices of a patch's node array on face (d, s): the face nodes and the extra
        nodes beyond them, within the patch's owned nodes (ghosts: its every node)."""
        own_lo, own_hi = ((0, 0, 0), shape[:3]) if ghosts else patch.owned_local(VarType.NC)
        base = patch.low_index(VarType.NC)
        lo, hi = list(own_lo), list(own_hi)
        if s == 0:
            hi[d] = patch.face_index(d, s) - base[d] + 1
        else:
            lo[d] = patch.face_index(d, s) - base[d]
        lo = np.maximum(lo, 0)
        hi = np.minimum(hi, shape[:3])
        return tuple(slice(a, b) for a, b in zip(lo, hi))

    def apply_temperature(self, patch, matl, temperature, ghosts=False):
        """Set the temperature conditions of this material on the faces `patch` touches (ghosts:
        also on its ghost nodes along the face, as their owner sets them)."""
        for d, s, neumann, value, mats, where in self.temperature_items:
            if where is not None and not _on_level_face(patch, d, s):
                if where[0] is not None:
                    continue
                where = None
            if matl in mats and (patch.at_high if s else patch.at_low)[d]:
                sl = self._face_nodes(patch, d, s, temperature.shape, ghosts)
                mask = None if where is None else self._where(patch, where, d, [x.start for x in sl],
                                                              [x.stop for x in sl])
                if not neumann:
                    if mask is None:
                        temperature[sl] = value
                    else:
                        temperature[sl][mask] = value
                    continue
                self._neumann(temperature, sl, mask, d, s, value * patch.level.dx[d])

    @staticmethod
    def _neumann(T, sl, mask, d, s, drop):
        """T = T(inward neighbour) - drop on the face's node layer, then on the extra node layer
        beyond it (from the face node just set), as Uintah's MPMBoundCond."""
        lo, hi = sl[d].start, sl[d].stop
        face = hi - 1 if s == 0 else lo
        inward = 1 if s == 0 else -1
        for i in [face] + [i for i in range(lo, hi) if i != face]:
            src = T[tuple(sl[:d]) + (i + inward,) + tuple(sl[d + 1:])]
            dst = tuple(sl[:d]) + (i,) + tuple(sl[d + 1:])
            new = src - drop
            if mask is None:
                T[dst] = new
            else:
                m = np.take(mask, i - lo, axis=d)
                T[dst] = np.where(m, new, T[dst])

    def symmetric_normal(self, patch, normal):
        """Remove the component into the face from a nodal normal on every symmetry face of
        material 0 (Uintah's "Symmetric" condition on g.normAlphaToBeta)."""
        for d, s, comps, value, mats, where in self.items:
            if 0 not in mats or comps.sum() != 1 or not (patch.at_high if s else patch.at_low)[d]:
                continue
            normal[self._face_nodes(patch, d, s, normal.shape) + (d,)] = 0.0


def _on_level_face(patch, d, s):
    """Whether the boundary face (d, s) of a patch lies on the level's outer face (a sub-face's
    plane); not so for a face on a hole of a level that is not one box."""
    return patch.face_index(d, s) == (patch.level.ncells[d] if s else 0)


def _materials(bc, ident, nmat, strict=True):
    """The material indices of a BCType's id ("all" or one index); strict=False drops an index
    that is not one of these nmat materials (an ICE material in an MPMICE deck)."""
    if ident == "all":
        return tuple(range(nmat))
    try:
        m = int(ident)
    except ValueError:
        raise bc.error(f'id="{ident}": accepted: all or a material index') from None
    if not 0 <= m < nmat:
        if not strict:
            return ()
        raise bc.error(f'id="{ident}": there are {nmat} MPM materials')
    return (m,)
