"""EFEM materials and settings as a deck gives them.

`<MaterialProperties><EFEM><material name="...">`: a solid has <youngs_modulus> and
<poissons_ratio> (Hooke's law, plane strain, eq. 21), a fluid <dynamic_viscosity>
(Newtonian shear, eq. 19); both have <density> and one or more <geom_object>s with the
framework's geometry pieces, <res> (samples per cell and direction for the initial volume
fraction) and <velocity>. Materials fill the cells in deck order: a later material takes
at most what the earlier ones left free, so a body listed before the fluid sits in it.

`<EFEM>` holds the scheme's settings and `<BoundaryConditions>`: one `<Face side="x-"
type="wall|slip|inflow|outflow"/>` per domain face (default: wall = no-slip on every
face); an inflow names its fluid, `material="water"`, and its `<velocity>`.
"""
from __future__ import annotations

import numpy as np

from framework.problemspec import Param

from .kernels import INFLOW, WALL_NONE, WALL_NOSLIP, WALL_SLIP

MATERIAL = {
    "density": Param("float", above=0.0),
    "youngs_modulus": Param("float", None, above=0.0),
    "poissons_ratio": Param("float", None, at_least=0.0),
    "dynamic_viscosity": Param("float", None, at_least=0.0),
}
GEOM = {
    "res": Param("ivector", (2, 2, 1), at_least=1),
    "velocity": Param("vector", (0.0, 0.0, 0.0)),
}
SETTINGS = {
    "cfl": Param("float", 0.25, above=0.0),
    "hourglass_damping": Param("float", 0.05, at_least=0.0),
    "hourglass_stiffness": Param("float", 1.0, at_least=0.0),
    "damping": Param("float", 0.0, at_least=0.0),
    "fill_min": Param("float", 0.05, above=0.0),
    "slide_condition": Param("bool", False),
    "solid_min": Param("float", 0.1, at_least=0.0),
    "volume_correction": Param("float", 0.25, at_least=0.0),
    "fill_correction": Param("float", 0.1, at_least=0.0),
    "volume_fraction_limiter": Param("str", "vanleer", choices=("vanleer", "superbee")),
    "stress_remap": Param("str", "upwind", choices=("upwind", "muscl")),
}
SOLVER = {
    "tolerance": Param("float", 1e-10, above=0.0),
    "max_iterations": Param("int", 1000, at_least=1),
    "preconditioner": Param("str", "mg", choices=("mg", "jacobi", "none")),
}
WALLS = {"wall": WALL_NOSLIP, "slip": WALL_SLIP, "inflow": INFLOW, "outflow": WALL_NONE}
SIDES = ("x-", "x+", "y-", "y+")


class Material:
    """One material: density, its law and the geometry objects that place it at t = 0."""

    def __init__(self, name, props, objects, node):
        self.name = name
        self.density = props["density"]
        self.solid = props["youngs_modulus"] is not None
        self.objects = objects            # [(piece, {res, velocity})]
        if self.solid:
            E, nu = props["youngs_modulus"], props["poissons_ratio"]
            self.mu = E / (2.0 * (1.0 + nu))
            self.lam = E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu))
            self.viscosity = 0.0
        else:
            self.mu = self.lam = 0.0
            self.viscosity = props["dynamic_viscosity"]

    def wave_speed(self):
        """Plane-strain dilatational wave speed sqrt((lambda + 2 mu) / rho) (0 for a fluid)."""
        return float(np.sqrt((self.lam + 2.0 * self.mu) / self.density))


def read_material(node, geo, index):
    """A <material>: solid (E, nu) or fluid (mu), refused with one line if neither or both."""
    name = node.attr("name", default=f"material{index}")
    props = node.read(MATERIAL)
    solid = props["youngs_modulus"] is not None or props["poissons_ratio"] is not None
    fluid = props["dynamic_viscosity"] is not None
    if solid and fluid:
        raise node.child("dynamic_viscosity").error(
            "a material is a solid (<youngs_modulus>, <poissons_ratio>) or a fluid (<dynamic_viscosity>), not both")
    if not solid and not fluid:
        raise node.error("missing the material law; accepted: <youngs_modulus> and <poissons_ratio> (a solid) "
                         "or <dynamic_viscosity> (a fluid)")
    if solid:
        for tag in ("youngs_modulus", "poissons_ratio"):
            if props[tag] is None:
                raise node.error(f"missing required tag <{tag}> (a solid has <youngs_modulus> and <poissons_ratio>)")
        if not props["poissons_ratio"] < 0.5:
            raise node.child("poissons_ratio").error(
                f"value '{props['poissons_ratio']:g}' is out of range; accepted: 0 <= poissons_ratio < 0.5")
    objects = []
    for go in node.children("geom_object"):
        objects.append((geo.read_object(go), go.read(GEOM)))
    if not objects:
        raise node.error("material has no <geom_object> (its initial place)")
    return Material(name, props, objects, node)


class Boundaries:
    """Per domain face [x-, x+, y-, y+, z-, z+]: the kind (kernels.WALL_*, INFLOW), an inflow's
    velocity and material, and whether the pressure is 0 on it (outflow)."""

    def __init__(self):
        self.walls = np.full(6, WALL_NOSLIP, dtype=np.int64)
        self.velocity = np.zeros((6, 2))
        self.material = np.zeros(6, dtype=np.int64)
        self.open = np.zeros(6, dtype=np.int64)


def read_boundaries(efem, materials):
    """<EFEM><BoundaryConditions>: one <Face side="x-" type="wall|slip|inflow|outflow"> per side
    (wall by default); an inflow names its fluid (material="...") and <velocity>."""
    b = Boundaries()
    bcs = efem.child("BoundaryConditions") if efem is not None else None
    if bcs is None:
        return b
    seen = {}
    names = [m.name for m in materials]
    for face in bcs.children("Face"):
        side = face.attr("side", choices=SIDES)
        if side in seen:
            raise face.error(f'<Face side="{side}"> given twice (first at line {seen[side]}); accepted: one per side')
        seen[side] = face.line
        f = SIDES.index(side)
        kind = face.attr("type", choices=tuple(WALLS))
        b.walls[f] = WALLS[kind]
        b.open[f] = int(kind == "outflow")
        if kind != "inflow":
            continue
        name = face.attr("material", choices=tuple(names))
        m = names.index(name)
        if materials[m].solid:
            raise face.error(f'an inflow brings a fluid; material "{name}" is a solid')
        v = face.get("velocity", "vector")
        b.velocity[f] = v[:2]
        b.material[f] = m
    return b
