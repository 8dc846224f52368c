"""ICE boundary conditions: `<Grid><BoundaryConditions>` read per face and material, and applied.

Extra cells hold the boundary values of CC variables, as in Uintah:
  Dirichlet            extra cell = value
  Neumann              extra cell = first interior cell - value * dx on every face, as
                       Uintah's setNeumannBC_CC (value: the gradient along the inward
                       normal; 0 = zero gradient)
  symmetry             scalars copied; the normal velocity component reflected; the
                       normal face velocity is zero
  computeFromDensity   (SpecificVol only) v = theta / rho in the extra cell
  FreeSlipWall         (Velocity only) the first interior cell's velocity with its normal
                       component zero; the normal face velocity is zero
  powerLawProfile,     (Velocity only) Uintah's inlet profiles (CustomBCs/inletVelocity.cc)
  logLawProfile        u_n = U (h/H)^n or u_* / kappa ln(h / z0) at the cell's height h
                       above the domain floor, in the extra cells and on the face; their
                       parameters in <BoundaryConditions><inletVelocity> (InletProfile)
  LODI                 (Pressure, Velocity, Temperature, Density) Uintah's characteristic
                       non-reflecting face, its parameters in <BoundaryConditions><LODI>
                       (lodi.py); these kernels leave its extra cells alone
Face velocities on a boundary face: Dirichlet sets the normal component, symmetry and
FreeSlipWall zero, Neumann keeps the value computed from the extra cells.
A `<BCType id="all">` applies to every material; Pressure is one field (material 0). A model's
transported scalar (label scalar-f, components/models/passive_scalar.py) takes Dirichlet or
Neumann on every face (a symmetry face: zero gradient).
"""
from __future__ import annotations

import numpy as np
from numba import njit

from framework.gridspec import boundary_faces, sub_faces
from framework.variables import VarType

CC = VarType.CC

from .lodi import LODI_KIND, LodiInputs
from .specific_heat import cv_at

NEUMANN, DIRICHLET, SYMMETRY, FROM_DENSITY, FREE_SLIP, POWER_LAW, LOG_LAW = 0, 1, 2, 3, 4, 5, 6
LODI = LODI_KIND
KINDS = {"Neumann": NEUMANN, "Dirichlet": DIRICHLET, "symmetry": SYMMETRY, "computeFromDensity": FROM_DENSITY,
         "FreeSlipWall": FREE_SLIP, "powerLawProfile": POWER_LAW, "logLawProfile": LOG_LAW, "LODI": LODI}
LODI_VARS = ("Pressure", "Velocity", "Temperature", "Density")
INLET = (POWER_LAW, LOG_LAW)
VARS = ("Pressure", "Velocity", "Temperature", "Density", "SpecificVol")
FACE_NAMES = ("x-", "x+", "y-", "y+", "z-", "z+")
_UNSET = object()


class InletProfile:
    """<BoundaryConditions><inletVelocity>: the parameters of the powerLaw/logLaw inlet profiles
    (Uintah's read_inletVel_BC_inputs): vertical direction, exponent n, the profile's height H
    (<maxHeight>, default the domain's height), roughness z0, von Karman constant, material."""

    def __init__(self, node, level, material_names, n_before):
        node.attr("type", default="", choices=("", "powerLawProfile", "logLawProfile"))
        self.vdir = node.get("verticalDirection", "int", at_least=0)
        if self.vdir > 2:
            raise node.child("verticalDirection").error("verticalDirection must be 0, 1 or 2 (x, y, z)")
        self.exponent = node.get("exponent", "float", 0.0)
        self.roughness = node.get("roughness", "float", 0.0, at_least=0.0)
        self.von_karman = node.get("vonKarmanConstant", "float", 0.4, above=0.0)
        floor, top = level.anchor[self.vdir], level.upper[self.vdir]
        self.height = node.get("maxHeight", "float", top - floor) - floor
        self.floor, self.top = floor, top
        mn = node.child("material", required=True)
        name = mn.text().strip().replace('"', "")
        if name not in material_names:
            raise mn.error(f"no ICE material named '{name}'; accepted: {', '.join(material_names)}")
        self.matl = n_before + material_names.index(name)

    def params(self):
        return np.array([self.floor, self.top, self.height, self.exponent, self.roughness, self.von_karman])


@njit(cache=True)
def inlet_profile(kind, value, h, p, out):
    """Uintah's set_inletVelocity_BC at height h: out = value with its component n (out's last
    index, the face normal) from the profile; 0 outside the domain's height. p = params()."""
    floor, top, height, n, z0, kappa = p[0], p[1], p[2], p[3], p[4], p[5]
    nd = out.shape[0] - 1
    if kind == 5:
        ratio = min(max((h - floor) / height, 0.0), 1.0)
        out[nd] = value * ratio ** n if floor < h < height else value
    else:
        out[nd] = value / kappa * np.log((h - floor) / z0)
    if h < floor or h > top:
        out[nd] = 0.0
        return False
    return True


@njit(cache=True)
def bc_inlet(q, d, side, kind, value, vdir, p, anchor, dx, lo, hi, olo, ohi, sel, want):
    """Fill the extra-cell layer of face (d, side) of vel_CC with an inlet profile (the cells
    where sel is `want`: see _skip)."""
    e = lo[d] - 1 if side == 0 else hi[d]
    d1, d2 = (d + 1) % 3, (d + 2) % 3
    ijk = np.zeros(3, dtype=np.int64)
    u = np.zeros(1)
    for a in range(olo[d1], ohi[d1]):
        for b in range(olo[d2], ohi[d2]):
            if _skip(sel, a, b, want):
                continue
            ijk[d], ijk[d1], ijk[d2] = e, a, b
            h = anchor[vdir] + (ijk[vdir] - lo[vdir] + 0.5) * dx[vdir]
            inside = inlet_profile(kind, value[d], h, p, u)
            for c in range(3):
                q[ijk[0], ijk[1], ijk[2], c] = (value[c] if inside else 0.0) if c != d else u[0]


@njit(cache=True)
def bc_inlet_face(uf, d, index, kind, value, vdir, p, anchor, dx, f0, sel, want):
    """The normal face velocity of an inlet face (layer `index` along d) from the profile at
    each face's height; f0: the global index of uf[0, 0, 0] along vdir."""
    sh = uf.shape
    u = np.zeros(1)
    ijk = np.zeros(3, dtype=np.int64)
    for a in range(sh[(d + 1) % 3]):
        for b in range(sh[(d + 2) % 3]):
            if _skip(sel, a, b, want):
                continue
            ijk[d], ijk[(d + 1) % 3], ijk[(d + 2) % 3] = index, a, b
            h = anchor[vdir] + (ijk[vdir] + f0 + 0.5) * dx[vdir]
            inlet_profile(kind, value, h, p, u)
            uf[ijk[0], ijk[1], ijk[2]] = u[0]


@njit(cache=True)
def lagrangian_face_primitives(mass, mom, eng, cv, vel, temp, d, side, lo, hi, olo, ohi):
    """u = (m u)/m and T = (m e)/(m cv) in the extra-cell layer of face (d, side) and the first
    interior layer next to it: what the face's conditions read and overwrite."""
    d1, d2 = (d + 1) % 3, (d + 2) % 3
    for e in ((lo[d] - 1, lo[d]) if side == 0 else (hi[d], hi[d] - 1)):
        for a in range(olo[d1], ohi[d1]):
            for b in range(olo[d2], ohi[d2]):
                i, j, k = _idx(d, e, a, b)
                m = mass[i, j, k]
                temp[i, j, k] = eng[i, j, k] / (m * cv_at(cv, i, j, k))
                for c in range(3):
                    vel[i, j, k, c] = mom[i, j, k, c] / m


@njit(cache=True)
def lagrangian_face_conserved(mass, vel, temp, cv, mom, eng, d, side, lo, hi, olo, ohi):
    """m u and m cv T in the extra-cell layer of face (d, side)."""
    e = lo[d] - 1 if side == 0 else hi[d]
    d1, d2 = (d + 1) % 3, (d + 2) % 3
    for a in range(olo[d1], ohi[d1]):
        for b in range(olo[d2], ohi[d2]):
            i, j, k = _idx(d, e, a, b)
            m = mass[i, j, k]
            eng[i, j, k] = temp[i, j, k] * cv_at(cv, i, j, k) * m
            for c in range(3):
                mom[i, j, k, c] = vel[i, j, k, c] * m


@njit(cache=True)
def lagrangian_extra_cells_faces(mass, mom, eng, cv, vel, temp, faces, vkind, vval, tkind, tval, dx, lo, hi, olo, ohi):
    """BoundaryConditions.lagrangian_extra_cells in one call for faces (rows d, side) whose
    velocity kinds bc_vector applies (vkind, values vval) and whose temperature is Dirichlet
    (tkind 1, tval the value), a gradient (tkind 0, tval the Neumann value, 0 on a symmetry
    face) or left alone (-1), in the order of the rows."""
    n = faces.shape[0]
    for f in range(n):
        lagrangian_face_primitives(mass, mom, eng, cv, vel, temp, faces[f, 0], faces[f, 1], lo, hi, olo, ohi)
    for f in range(n):
        d = faces[f, 0]
        bc_vector(vel, d, faces[f, 1], vkind[f], vval[f], dx[d], lo, hi, olo, ohi)
    for f in range(n):
        if tkind[f] >= 0:
            d = faces[f, 0]
            bc_scalar(temp, d, faces[f, 1], tkind[f], tval[f], dx[d], lo, hi, olo, ohi)
    for f in range(n):
        lagrangian_face_conserved(mass, vel, temp, cv, mom, eng, faces[f, 0], faces[f, 1], lo, hi, olo, ohi)


@njit(cache=True)
def bc_hydrostatic(press, sp_vol, d, side, dirichlet, g, origin, anchor, dx, lo, hi, olo, ohi, sel, want):
    """The hydrostatic term of one face's extra-cell layer (BoundaryConditions.hydrostatic_pressure);
    origin: the position of the patch's first interior cell's low corner."""
    e = lo[d] - 1 if side == 0 else hi[d]
    n = lo[d] if side == 0 else hi[d] - 1
    d1, d2 = (d + 1) % 3, (d + 2) % 3
    sign = -1.0 if side == 0 else 1.0
    for a in range(olo[d1], ohi[d1]):
        for b in range(olo[d2], ohi[d2]):
            if _skip(sel, a, b, want):
                continue
            ie = _idx(d, e, a, b)
            if dirichlet:
                corr = 0.0
                for c in range(3):
                    x = origin[c] + (ie[c] - lo[c] + 0.5) * dx[c]
                    corr += g[c] * (x - (anchor[c] + 0.5 * dx[c]))
                press[ie] += corr / sp_vol[ie]
            else:
                rho = 0.5 * (1.0 / sp_vol[ie] + 1.0 / sp_vol[_idx(d, n, a, b)])
                press[ie] += g[d] * sign * dx[d] * rho


def read_bcs(root, level, nmat, material_names=(), n_before=0, scalars=None, gravity=(0.0, 0.0, 0.0)):
    """{face: {var: [(kind, value) per material]}} for every physical face of the level, the
    inlet profiles' parameters (an InletProfile, or None) under the key "inletVelocity" and the
    LODI parameters (a LodiInputs, or None) under "LODI".
    scalars: {label: material} of the models' transported scalars (scalar-f ...): Dirichlet or
    Neumann on every face for that material (or a symmetry face), as Uintah's is_BC_specified."""
    scalars = scalars or {}
    grid = root.child("Grid", required=True)
    bcn = grid.child("BoundaryConditions")
    found = {}
    nodes = {}
    if bcn is not None:
        for side, face in boundary_faces(bcn, FACE_NAMES):
            table = found.setdefault(side, {})
            nodes[side] = face
            for bt in face.children("BCType"):
                _read_bctype(bt, table, nmat, scalars)
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
            for var, sm in scalars.items():
                per = table.get(var, [None] * nmat)
                if per[sm] is None:
                    if "symmetry" not in table:
                        raise where.error(f"face {name}: no boundary condition for {var} of material {sm}; give "
                                          f'<BCType id="{sm}" label="{var}" var="Dirichlet|Neumann"> or a '
                                          "symmetry BCType")
                    per[sm] = (SYMMETRY, None)
                face[var] = per
            out[name] = face
    out["subfaces"] = _read_sub_faces(bcn, level, out, nmat, scalars) if bcn is not None else {}
    used = any(e is not None and e[0] in INLET for t in found.values() for k, per in t.items()
               if k != "lodi_nodes" and isinstance(per, list) for e in per)
    used = used or any(e is not None and e[0] in INLET for parts in out["subfaces"].values() for p in parts
                       for e in p.table["Velocity"])
    out["inletVelocity"] = None
    if used:
        node = bcn.child("inletVelocity")
        if node is None:
            raise bcn.error('a powerLawProfile or logLawProfile velocity condition needs '
                            '<inletVelocity type="..."> with its parameters in <BoundaryConditions>')
        out["inletVelocity"] = InletProfile(node, level, list(material_names), n_before)
    elif bcn is not None and bcn.has("inletVelocity"):
        bcn.child("inletVelocity").mark_used()
    out["LODI"] = _read_lodi(bcn, found, out, level, material_names, n_before, gravity)
    return out


class SubFaceBCs:
    """The conditions of one `<Face circle|rectangle|annulus>` (framework.gridspec.SubFace):
    table {var: [(kind, value) or None per material]}, None for a material that none of its
    BCTypes names (id="all" names every one): that material keeps the side's conditions there,
    as in Uintah, where a sub-face exists only for the materials of its BCTypes."""

    def __init__(self, geom, table):
        self.geom, self.table = geom, table

    def covers(self, m):
        return self.table["Velocity"][m] is not None


def _read_sub_faces(bcn, level, out, nmat, scalars):
    """{side: [SubFaceBCs]} of the level's physical faces. Each material a sub-face names needs
    all its conditions there (SpecificVol defaults to computeFromDensity), Dirichlet or
    Neumann (Velocity: also the inlet profiles, FreeSlipWall); symmetry and LODI act on a
    whole side."""
    subs = {}
    for side, geom, face in sub_faces(bcn, FACE_NAMES, level):
        if side not in out:
            raise face.error(f"face {side} is periodic or has one cell; it takes no boundary condition")
        table = {}
        for bt in face.children("BCType"):
            kind = bt.attr("var", choices=tuple(KINDS))
            if kind in ("symmetry", "LODI"):
                raise bt.error(f'var="{kind}" on a sub-face is not supported; accepted: Dirichlet, Neumann '
                               "(symmetry and LODI act on a whole <Face side>)")
            _read_bctype(bt, table, nmat, scalars)
        named = {m for var, per in table.items() if var not in ("given", "lodi_nodes") for m, e in enumerate(per)
                 if e is not None}
        if not named:
            raise face.error("a sub-face without a <BCType>; accepted: the conditions of the materials it names")
        per_var = {}
        for var in VARS + tuple(scalars):
            per = table.get(var, [None] * nmat)
            if var == "Pressure":
                per = per[:1]
            for m in named:
                if var == "Pressure" and m != 0 or var in scalars and m != scalars[var]:
                    continue
                if per[m] is None:
                    if var == "SpecificVol":
                        per[m] = (FROM_DENSITY, None)
                        continue
                    raise face.error(f"sub-face {geom.kind} on {side}: no boundary condition for {var} of material "
                                     f"{m}; give <BCType id=\"{m}\" label=\"{var}\" var=\"Dirichlet|Neumann\">")
            per_var[var] = per
        subs.setdefault(side, []).append(SubFaceBCs(geom, per_var))
    return subs


def _read_lodi(bcn, found, out, level, material_names, n_before, gravity):
    """The <LODI> block when a face of the level uses var="LODI" (Uintah's read_LODI_BC_inputs:
    every LODI BCType names the block's material); without LODI faces the block is ignored."""
    nodes = [bt for t in found.values() for bt in t.get("lodi_nodes", ())]
    if not nodes:
        if bcn is not None and bcn.has("LODI"):
            bcn.child("LODI").mark_used()
        return None
    node = bcn.child("LODI")
    if node is None:
        raise nodes[0].error('var="LODI" needs a <LODI> block in <BoundaryConditions> (press_infinity, sigma, '
                             "Li_scale, material)")
    lodi = LodiInputs(node, level, list(material_names), n_before, gravity)
    for bt in nodes:
        if bt.attr("label") != "Pressure" and int(bt.attr("id")) != lodi.matl:
            raise bt.error(f'a LODI condition is for the <LODI> block\'s material: give id="{lodi.matl}"')
    lodi.faces = [name for name in FACE_NAMES if name in out
                  and any(e is not None and e[0] == LODI for var in LODI_VARS for e in out[name][var])]
    return lodi


def _read_bctype(bt, table, nmat, scalars):
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
    if kind == "LODI":
        if label not in LODI_VARS:
            raise bt.error(f'var="LODI" is not accepted for label="{label}"; accepted: label={", ".join(LODI_VARS)}')
        if ident == "all":
            raise bt.error('var="LODI" needs the id of the <LODI> block\'s ICE material, not id="all" (as Uintah)')
        table.setdefault("lodi_nodes", []).append(bt)
    if kind == "symmetry":
        if bt.has("value"):
            bt.child("value").mark_used()
        table["symmetry"] = True
        for var in VARS + tuple(scalars):
            per = table.setdefault(var, [None] * nmat)
            for m in mats:
                per[m] = (SYMMETRY, None)
        return
    if label not in VARS and label not in scalars:
        more = "".join(f", {s}" for s in scalars)
        raise bt.error(f'label="{label}" is not supported; accepted: {", ".join(VARS)}{more} (or var="symmetry")'
                       + ("" if scalars or not label.startswith("scalar-") else
                          '; a scalar-<name> label needs a <Models><Model type="PassiveScalar"> with that scalar'))
    if label in scalars and kind not in ("Dirichlet", "Neumann"):
        raise bt.error(f'{label} accepts var="Dirichlet" or "Neumann" (or a symmetry BCType)')
    if kind == "computeFromDensity" and label != "SpecificVol":
        raise bt.error('var="computeFromDensity" applies only to label="SpecificVol"')
    if label == "SpecificVol" and kind not in ("computeFromDensity",):
        raise bt.error('SpecificVol accepts only var="computeFromDensity"')
    if kind in ("FreeSlipWall", "powerLawProfile", "logLawProfile") and label != "Velocity":
        raise bt.error(f'var="{kind}" applies only to label="Velocity"')
    if kind in ("powerLawProfile", "logLawProfile") and ident == "all":
        raise bt.error(f'var="{kind}" needs the ICE material\'s id, not id="all" (as Uintah)')
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
def _skip(sel, a, b, want):
    """Cell (a, b) of a face layer is not one of the part being set: sel holds each cell's part
    of the face (0 the side, k the k-th sub-face; BoundaryConditions._parts); an empty sel
    selects every cell."""
    return sel.shape[0] > 0 and sel[a, b] != want


ALL_CELLS = np.zeros((0, 0), dtype=np.int64)


@njit(cache=True)
def _all_cells():
    """(ALL_CELLS, 0) typed as a run's Python calls pass them (a writable array, an int64):
    the global and the literal 0 would compile the *_part kernels a second time."""
    return np.empty((0, 0), dtype=np.int64), np.int64(0)


@njit(cache=True)
def bc_scalar(q, d, side, kind, value, dx, lo, hi, olo, ohi):
    """Fill the extra-cell layer of face (d, side) of a scalar CC array."""
    sel, want = _all_cells()
    bc_scalar_part(q, d, side, kind, value, dx, lo, hi, olo, ohi, sel, want)


@njit(cache=True)
def bc_scalar_part(q, d, side, kind, value, dx, lo, hi, olo, ohi, sel, want):
    """bc_scalar on the cells of one part of the face (see _skip)."""
    e = lo[d] - 1 if side == 0 else hi[d]
    n = lo[d] if side == 0 else hi[d] - 1
    add = -value * dx if kind == 0 else 0.0
    d1, d2 = (d + 1) % 3, (d + 2) % 3
    for a in range(olo[d1], ohi[d1]):
        for b in range(olo[d2], ohi[d2]):
            if _skip(sel, a, b, want):
                continue
            ie = _idx(d, e, a, b)
            if kind == 1:
                q[ie] = value
            else:
                q[ie] = q[_idx(d, n, a, b)] + add


@njit(cache=True)
def bc_vector(q, d, side, kind, value, dx, lo, hi, olo, ohi):
    """Fill the extra-cell layer of a vector CC array (velocity)."""
    sel, want = _all_cells()
    bc_vector_part(q, d, side, kind, value, dx, lo, hi, olo, ohi, sel, want)


@njit(cache=True)
def bc_vector_part(q, d, side, kind, value, dx, lo, hi, olo, ohi, sel, want):
    """bc_vector on the cells of one part of the face (see _skip)."""
    e = lo[d] - 1 if side == 0 else hi[d]
    n = lo[d] if side == 0 else hi[d] - 1
    d1, d2 = (d + 1) % 3, (d + 2) % 3
    for a in range(olo[d1], ohi[d1]):
        for b in range(olo[d2], ohi[d2]):
            if _skip(sel, a, b, want):
                continue
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
                    q[ie[0], ie[1], ie[2], c] = q[i_n[0], i_n[1], i_n[2], c] - value[c] * dx


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
    sel, want = _all_cells()
    bc_face_velocity_part(uf, d, index, value, sel, want)


@njit(cache=True)
def bc_face_velocity_part(uf, d, index, value, sel, want):
    """bc_face_velocity on the faces of one part of the domain face (see _skip)."""
    sh = uf.shape
    for a in range(sh[(d + 1) % 3]):
        for b in range(sh[(d + 2) % 3]):
            if _skip(sel, a, b, want):
                continue
            uf[_idx(d, index, a, b)] = value


class BoundaryConditions:
    """The boundary conditions of one deck, applied to one patch's arrays."""

    def __init__(self, table, level):
        self.inlet = table.pop("inletVelocity", None)
        self._extra_cell_plans = {}     # (patch id, material): lagrangian_extra_cells_faces's arguments
        self._work = (np.empty(0), np.empty(0))         # u and T work buffers of lagrangian_extra_cells
        self.lodi = table.pop("LODI", None)
        self.subfaces = table.pop("subfaces", {})
        self._sel = {}                  # (patch id, face, sub-faces, array box): each boundary cell's part
        self._scalar_calls = {}         # (patch id, variable, material, Boxes, copy, dims): scalar()'s kernel calls
        self._velocity_parts = {}       # (patch id, material, Boxes, dims): velocity()'s conditions per face
        self._face_velocity_parts = {}  # (patch id, direction, material, halo): face_velocity()'s
        self.table = table
        self.level = level

    # `b` below is the patch's Boxes (tasks.py): interior and owned local ranges.
    def _faces(self, patch):
        for name in patch.boundary_faces:
            i = FACE_NAMES.index(name)
            yield name, i // 2, i % 2

    def _parts(self, patch, name, var, m, vt=CC):
        """[(kind, value, sel, want)]: the conditions of var for material m on face `name`, each
        with the cells it sets (see _skip; sel indexed like an array of type vt): the side's on
        every cell, or, with sub-faces that name m, the side's on the cells outside them and each
        sub-face's on its own cells."""
        side = self.table[name][var][m]
        subs = tuple(k for k, sf in enumerate(self.subfaces.get(name, ())) if sf.table[var][m] is not None)
        if not subs:
            return ((side[0], side[1], ALL_CELLS, 0),)
        key = (patch.id, name, subs, vt, patch.low_index(vt), patch.alloc_shape(vt))   # halos differ, change
        sel = self._sel.get(key)
        if sel is None:
            sel = self._sel[key] = self.face_parts(patch, name, subs, vt)
        parts = [(side[0], side[1], sel, 0)]
        for k in subs:
            kind, value = self.subfaces[name][k].table[var][m]
            parts.append((kind, value, sel, k + 1))
        return parts

    def face_parts(self, patch, name, subs=None, vt=CC):
        """Per boundary cell of face `name` of this patch (indexed by the two tangential local
        indices of an array of type vt: CC, or the face's own SFC type): 0 on the side, k + 1
        inside sub-face k (of subs, the sub-faces considered; the last one that holds a cell
        takes it, as Uintah applies its sub-faces in deck order)."""
        subfaces = self.subfaces.get(name, ())
        subs = range(len(subfaces)) if subs is None else subs
        low, shape = patch.low_index(vt), patch.alloc_shape(vt)
        sel = None
        for k in subs:
            inside = subfaces[k].geom.cells(self.level, low, shape)
            sel = np.zeros(inside.shape, np.int64) if sel is None else sel
            sel[inside] = k + 1
        return sel

    def scalar(self, patch, q, var, m, b, copy=False, dims=(True, True, True)):
        """Temperature, Density, Pressure (m = 0) or a model's scalar (scalar-f) in the extra cells
        of one CC array (of the faces of the directions where dims is true).

        copy=True: zero-gradient copy whatever the condition (specific volume at t = 0).
        """
        key = (patch.id, var, m, b, copy, tuple(dims))
        calls = self._scalar_calls.get(key)
        if calls is None:
            calls = self._scalar_calls[key] = self._scalar_plan(patch, var, m, b, copy, dims)
        for d, s, kind, v, dx, lo, hi, olo, ohi, sel, want in calls:
            bc_scalar_part(q, d, s, kind, v, dx, lo, hi, olo, ohi, sel, want)

    def _scalar_plan(self, patch, var, m, b, copy, dims):
        """The bc_scalar_part calls of scalar() but its array, kept per patch, variable, material
        and Boxes: a task fills a dozen arrays' extra cells a step."""
        calls = []
        for name, d, s in self._faces(patch):
            if not dims[d]:
                continue
            parts = ((NEUMANN, 0.0, ALL_CELLS, 0),) if copy else self._parts(patch, name, var, m)
            for kind, value, sel, want in parts:
                if kind == LODI:        # lodi.py sets these extra cells (none at t = 0)
                    continue
                v = 0.0 if value is None else value
                if kind == DIRICHLET:
                    calls.append((d, s, 1, v, 0.0, b.lo, b.hi, b.olo, b.ohi, sel, want))
                else:
                    calls.append((d, s, 0, v if kind == NEUMANN else 0.0, self.level.dx[d], b.lo, b.hi, b.olo, b.ohi,
                                  sel, want))
        return calls

    def velocity(self, patch, q, m, b, initial=False, dims=(True, True, True)):
        """vel_CC's extra cells (of the faces of the directions where dims is true). initial: at
        t = 0 the inlet profiles leave them as the initialization made them (Uintah sets those
        only from the first step)."""
        lv = self.level
        key = (patch.id, m, b, tuple(dims))
        parts = self._velocity_parts.get(key)
        if parts is None:
            parts = self._velocity_parts[key] = [
                (d, s, kind, np.zeros(3) if value is None else value, sel, want)
                for name, d, s in self._faces(patch) if dims[d]
                for kind, value, sel, want in self._parts(patch, name, "Velocity", m) if kind != LODI]
        for d, s, kind, v, sel, want in parts:
            if kind in INLET:
                if not initial:
                    ip = self.inlet
                    bc_inlet(q, d, s, kind, v, ip.vdir, ip.params(), lv.anchor + np.array(patch.lo) * lv.dx,
                             lv.dx, b.lo, b.hi, b.olo, b.ohi, sel, want)
                continue
            bc_vector_part(q, d, s, kind, v, lv.dx[d], b.lo, b.hi, b.olo, b.ohi, sel, want)

    def hydrostatic_pressure(self, patch, press, sp_vol, g, b):
        """Uintah's HydrostaticPressureAdjustment of press_CC's extra cells (after the first
        step): on a Neumann or symmetry face normal to gravity the extra cell adds
        g.n dx (rho_in + rho_ec) / 2; on a Dirichlet face rho_ec g.(x_ec - x_ref), x_ref the
        centre of cell 0. rho: the surrounding material's 1 / sp_vol."""
        lv = self.level
        origin = lv.anchor + np.array(patch.lo) * lv.dx
        for name, d, s in self._faces(patch):
            for kind, _, sel, want in self._parts(patch, name, "Pressure", 0):
                if kind in (NEUMANN, SYMMETRY) and g[d] != 0.0:
                    bc_hydrostatic(press, sp_vol, d, s, 0, g, origin, lv.anchor, lv.dx, b.lo, b.hi, b.olo, b.ohi,
                                   sel, want)
                elif kind == DIRICHLET:
                    bc_hydrostatic(press, sp_vol, d, s, 1, g, origin, lv.anchor, lv.dx, b.lo, b.hi, b.olo, b.ohi,
                                   sel, want)

    def lagrangian_extra_cells(self, patch, mass, mom, eng, cv, m, b, dims):
        """Uintah's addExchangeToMomentumAndEnergy at the boundary: u and T from the Lagrangian
        (exchanged) m u and m e, every face's Velocity and Temperature conditions on them, then
        m u and m cv T in the extra cells (mom, eng modified there only; the interior keeps its
        values). An open face's extra cell thus holds this step's interior velocity, not the
        old one. The faces of directions with one cell (dims[d] false) are left alone: nothing
        is advected through them, and in a 2D run with extra cells in z they are whole planes."""
        plan = self._extra_cell_plans.get((patch.id, m), _UNSET)
        if plan is _UNSET:
            plan = self._extra_cell_plans[(patch.id, m)] = self._extra_cell_plan(patch, m, dims)
        if plan is None:                        # no such face
            return
        if self._work[0].size < mom.size:      # one pair of buffers for all patches, grown as needed
            self._work = (np.empty(mom.size), np.empty(eng.size))
        vel, temp = self._work[0][:mom.size].reshape(mom.shape), self._work[1][:eng.size].reshape(eng.shape)
        if plan is False:                       # an inlet profile or a sub-face: the general path
            faces = [(d, s) for _, d, s in self._faces(patch) if dims[d]]
            for d, s in faces:
                lagrangian_face_primitives(mass, mom, eng, cv, vel, temp, d, s, b.lo, b.hi, b.olo, b.ohi)
            self.velocity(patch, vel, m, b, dims=dims)
            self.scalar(patch, temp, "Temperature", m, b, dims=dims)
            for d, s in faces:
                lagrangian_face_conserved(mass, vel, temp, cv, mom, eng, d, s, b.lo, b.hi, b.olo, b.ohi)
            return
        lagrangian_extra_cells_faces(mass, mom, eng, cv, vel, temp, *plan, self.level.dx, b.lo, b.hi, b.olo, b.ohi)

    def _extra_cell_plan(self, patch, m, dims):
        """lagrangian_extra_cells_faces's face rows, kinds and values for one patch and material;
        None without faces, False with an inlet-profile face or a sub-face."""
        rows, vk, vv, tk, tv = [], [], [], [], []
        for name, d, s in self._faces(patch):
            if not dims[d]:
                continue
            if self.subfaces.get(name):
                return False
            kind, value = self.table[name]["Velocity"][m]
            if kind in INLET or kind == LODI:
                return False
            rows.append((d, s))
            vk.append(kind)
            vv.append(np.zeros(3) if value is None else np.asarray(value, dtype=np.float64))
            kind, value = self.table[name]["Temperature"][m]
            v = 0.0 if value is None else value
            tk.append(-1 if kind == LODI else (1 if kind == DIRICHLET else 0))
            tv.append(v if kind in (DIRICHLET, NEUMANN) else 0.0)
        if not rows:
            return None
        return (np.array(rows, dtype=np.int64), np.array(vk, dtype=np.int64), np.array(vv),
                np.array(tk, dtype=np.int64), np.array(tv))

    def sp_vol(self, patch, spv, vf, rho, m, b):
        for name, d, s in self._faces(patch):
            bc_sp_vol_from_density(spv, vf, rho, d, s, b.lo, b.hi, b.olo, b.ohi)

    def face_velocity(self, patch, uf, d, m, flo, fhi):
        """Boundary faces of direction d: Dirichlet -> value[d], symmetry and FreeSlipWall -> 0."""
        vt = (VarType.SFCX, VarType.SFCY, VarType.SFCZ)[d]
        key = (patch.id, d, m, patch.level.halo[vt])       # the sub-faces' cells depend on the halo
        parts = self._face_velocity_parts.get(key)
        if parts is None:
            parts = self._face_velocity_parts[key] = [
                (s, part) for s, at in ((0, patch.at_low[d]), (1, patch.at_high[d])) if at
                for part in self._parts(patch, FACE_NAMES[2 * d + s], "Velocity", m, vt)]
        for s, (kind, value, sel, want) in parts:
            idx = flo[d] if s == 0 else fhi[d] - 1
            if kind == DIRICHLET:
                bc_face_velocity_part(uf, d, idx, float(value[d]), sel, want)
            elif kind in (SYMMETRY, FREE_SLIP):
                bc_face_velocity_part(uf, d, idx, 0.0, sel, want)
            elif kind in INLET:
                ip, lv = self.inlet, self.level
                bc_inlet_face(uf, d, idx, kind, float(value[d]), ip.vdir, ip.params(), lv.anchor, lv.dx,
                              int(patch.low_index(vt)[ip.vdir]), sel, want)
