"""ICE boundary conditions: `<Grid><BoundaryConditions>` read per face and material, and applied.

Extra cells hold the boundary values of CC variables, as in Uintah:
  Dirichlet            extra cell = value
  Neumann              extra cell = first interior cell + value * dx (value: the
                       gradient along the outward normal; 0 = zero gradient)
  symmetry             scalars copied; the normal velocity component reflected; the
                       normal face velocity is zero
  computeFromDensity   (SpecificVol only) v = theta / rho in the extra cell
  FreeSlipWall         (Velocity only) the first interior cell's velocity with its normal
                       component zero; the normal face velocity is zero
Face velocities on a boundary face: Dirichlet sets the normal component, symmetry and
FreeSlipWall zero, Neumann keeps the value computed from the extra cells.
A `<BCType id="all">` applies to every material; Pressure is one field (material 0).
"""
from __future__ import annotations

import numpy as np
from numba import njit

from framework.gridspec import boundary_faces

NEUMANN, DIRICHLET, SYMMETRY, FROM_DENSITY, FREE_SLIP = 0, 1, 2, 3, 4
KINDS = {"Neumann": NEUMANN, "Dirichlet": DIRICHLET, "symmetry": SYMMETRY, "computeFromDensity": FROM_DENSITY,
         "FreeSlipWall": FREE_SLIP}
VARS = ("Pressure", "Velocity", "Temperature", "Density", "SpecificVol")
FACE_NAMES = ("x-", "x+", "y-", "y+", "z-", "z+")


def read_bcs(root, level, nmat):
    """{face: {var: [(kind, value) per material]}} for every physical face of the level."""
    grid = root.child("Grid", required=True)
    bcn = grid.child("BoundaryConditions")
    found = {}
    nodes = {}
    if bcn is not None:
        for side, face in boundary_faces(bcn, FACE_NAMES):
            table = found.setdefault(side, {})
            nodes[side] = face
            for bt in face.children("BCType"):
                _read_bctype(bt, table, nmat)
    out = {}
    for d in range(3):
        if level.collapsed[d] or level.periodic[d]:
            continue
        for s in range(2):
            name = FACE_NAMES[2 * d + s]
            table = found.get(name, {})
            where = nodes.get(name, bcn if bcn is not None else grid)
            face = {}
            for var in VARS:
                per = table.get(var, [None] * nmat)
                if var == "Pressure":
                    per = per[:1]
                for m, e in enumerate(per):
                    if e is None:
                        if "symmetry" in table:
                            per[m] = (SYMMETRY, None)
                        elif var == "SpecificVol":
                            per[m] = (FROM_DENSITY, None)
                        else:
                            raise where.error(f"face {name}: no boundary condition for {var} of material {m}; "
                                              'give <BCType id="..." label="' + var +
                                              '" var="Dirichlet|Neumann"> or a symmetry BCType')
                face[var] = per
            out[name] = face
    return out


def _read_bctype(bt, table, nmat):
    ident = bt.attr("id")
    label = bt.attr("label")
    kind = bt.attr("var", choices=tuple(KINDS))
    if ident == "all":
        mats = range(nmat)
    else:
        try:
            mats = [int(ident)]
        except ValueError:
            raise bt.error(f'id="{ident}" is not a material index or "all"') from None
        if not 0 <= mats[0] < nmat:
            raise bt.error(f"id={ident}: there are {nmat} ICE materials (0..{nmat - 1})")
    if kind == "symmetry":
        if bt.has("value"):
            bt.child("value").mark_used()
        table["symmetry"] = True
        for var in VARS:
            per = table.setdefault(var, [None] * nmat)
            for m in mats:
                per[m] = (SYMMETRY, None)
        return
    if label not in VARS:
        raise bt.error(f'label="{label}" is not supported; accepted: {", ".join(VARS)} (or var="symmetry")')
    if kind == "computeFromDensity" and label != "SpecificVol":
        raise bt.error('var="computeFromDensity" applies only to label="SpecificVol"')
    if label == "SpecificVol" and kind not in ("computeFromDensity",):
        raise bt.error('SpecificVol accepts only var="computeFromDensity"')
    if kind == "FreeSlipWall" and label != "Velocity":
        raise bt.error('var="FreeSlipWall" applies only to label="Velocity"')
    vtype = "vector" if label == "Velocity" else "float"
    # a fixed pressure, temperature or density on a face is a state of matter: positive
    positive = 0.0 if kind == "Dirichlet" and label in ("Pressure", "Temperature", "Density") else None
    value = bt.get("value", vtype, 0.0 if vtype == "float" else (0.0, 0.0, 0.0), above=positive)
    if label == "Pressure" and mats != [0] and ident != "all":
        raise bt.error('the pressure is one field: give its BCType with id="0"')
    per = table.setdefault(label, [None] * nmat)
    given = table.setdefault("given", set())
    for m in mats:
        if (label, m) in given:
            raise bt.error(f'a second <BCType label="{label}"> for material {m} on this face; accepted: one '
                           "condition per variable and material on a face")
        given.add((label, m))
        per[m] = (KINDS[kind], np.asarray(value, dtype=np.float64) if vtype == "vector" else float(value))


@njit(cache=True)
def _idx(d, e, a, b):
    """The (i, j, k) with index e along d and (a, b) along the next two directions (cyclic)."""
    if d == 0:
        return e, a, b
    if d == 1:
        return b, e, a
    return a, b, e


@njit(cache=True)
def bc_scalar(q, d, side, kind, value, dx, lo, hi, olo, ohi):
    """Fill the extra-cell layer of face (d, side) of a scalar CC array."""
    e = lo[d] - 1 if side == 0 else hi[d]
    n = lo[d] if side == 0 else hi[d] - 1
    add = value * dx if kind == 0 else 0.0
    d1, d2 = (d + 1) % 3, (d + 2) % 3
    for a in range(olo[d1], ohi[d1]):
        for b in range(olo[d2], ohi[d2]):
            ie = _idx(d, e, a, b)
            if kind == 1:
                q[ie] = value
            else:
                q[ie] = q[_idx(d, n, a, b)] + add


@njit(cache=True)
def bc_vector(q, d, side, kind, value, dx, lo, hi, olo, ohi):
    """Fill the extra-cell layer of a vector CC array (velocity)."""
    e = lo[d] - 1 if side == 0 else hi[d]
    n = lo[d] if side == 0 else hi[d] - 1
    d1, d2 = (d + 1) % 3, (d + 2) % 3
    for a in range(olo[d1], ohi[d1]):
        for b in range(olo[d2], ohi[d2]):
            ie = _idx(d, e, a, b)
            i_n = _idx(d, n, a, b)
            for c in range(3):
                if kind == 1:
                    q[ie[0], ie[1], ie[2], c] = value[c]
                elif kind == 2:
                    v = q[i_n[0], i_n[1], i_n[2], c]
                    q[ie[0], ie[1], ie[2], c] = -v if c == d else v
                elif kind == 4:
                    q[ie[0], ie[1], ie[2], c] = 0.0 if c == d else q[i_n[0], i_n[1], i_n[2], c]
                else:
                    q[ie[0], ie[1], ie[2], c] = q[i_n[0], i_n[1], i_n[2], c] + value[c] * dx


@njit(cache=True)
def bc_sp_vol_from_density(spv, vf, rho, d, side, lo, hi, olo, ohi):
    """computeFromDensity: v = theta / rho in the extra-cell layer of face (d, side)."""
    e = lo[d] - 1 if side == 0 else hi[d]
    d1, d2 = (d + 1) % 3, (d + 2) % 3
    for a in range(olo[d1], ohi[d1]):
        for b in range(olo[d2], ohi[d2]):
            ie = _idx(d, e, a, b)
            spv[ie] = vf[ie] / rho[ie]


@njit(cache=True)
def bc_face_velocity(uf, d, index, value):
    """Set every face of layer `index` (along d) of a face-velocity array to `value`."""
    sh = uf.shape
    for a in range(sh[(d + 1) % 3]):
        for b in range(sh[(d + 2) % 3]):
            uf[_idx(d, index, a, b)] = value


class BoundaryConditions:
    """The boundary conditions of one deck, applied to one patch's arrays."""

    def __init__(self, table, level):
        self.table = table
        self.level = level

    # `b` below is the patch's Boxes (tasks.py): interior and owned local ranges.
    def _faces(self, patch):
        for name in patch.boundary_faces:
            i = FACE_NAMES.index(name)
            yield name, i // 2, i % 2

    def scalar(self, patch, q, var, m, b, copy=False):
        """Temperature, Density or Pressure (m = 0) in the extra cells of one CC array.

        copy=True: zero-gradient copy whatever the condition (specific volume at t = 0).
        """
        for name, d, s in self._faces(patch):
            kind, value = self.table[name][var][m]
            if copy:
                kind, value = NEUMANN, 0.0
            v = 0.0 if value is None else value
            if kind == DIRICHLET:
                bc_scalar(q, d, s, 1, v, 0.0, b.lo, b.hi, b.olo, b.ohi)
            else:
                bc_scalar(q, d, s, 0, v if kind == NEUMANN else 0.0, self.level.dx[d], b.lo, b.hi, b.olo, b.ohi)

    def velocity(self, patch, q, m, b):
        for name, d, s in self._faces(patch):
            kind, value = self.table[name]["Velocity"][m]
            v = np.zeros(3) if value is None else value
            bc_vector(q, d, s, kind, v, self.level.dx[d], b.lo, b.hi, b.olo, b.ohi)

    def sp_vol(self, patch, spv, vf, rho, m, b):
        for name, d, s in self._faces(patch):
            bc_sp_vol_from_density(spv, vf, rho, d, s, b.lo, b.hi, b.olo, b.ohi)

    def face_velocity(self, patch, uf, d, m, flo, fhi):
        """Boundary faces of direction d: Dirichlet -> value[d], symmetry and FreeSlipWall -> 0."""
        for s, at in ((0, patch.at_low[d]), (1, patch.at_high[d])):
            if not at:
                continue
            kind, value = self.table[FACE_NAMES[2 * d + s]]["Velocity"][m]
            idx = flo[d] if s == 0 else fhi[d] - 1
            if kind == DIRICHLET:
                bc_face_velocity(uf, d, idx, float(value[d]))
            elif kind in (SYMMETRY, FREE_SLIP):
                bc_face_velocity(uf, d, idx, 0.0)
