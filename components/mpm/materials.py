"""MPM materials from `<MaterialProperties><MPM><material>` and their particles.

A material has a density, a constitutive model (one of MODELS), thermal properties
(conductivity and specific heat: used by heat conduction and the MPMICE heat exchange,
thermal.py) and geometry objects that fill it with
particles: `res` particles per cell per direction (one in a collapsed direction),
`velocity`, `temperature` and, with `<withColor>`, `color`. Where two objects of one
material overlap, each makes its particles there, as Uintah's ParticleCreator (Uintah's
extrudeRT stacks its objects, to be moved in one colour at a time: insert_particles.py).
"""
from __future__ import annotations

import dataclasses
import importlib
import sys

import numpy as np

from framework.geometry import GeometryReader, Null, SmoothCylinder
from framework.problemspec import Param
from framework.scheduler.comm import world_rank

from .constitutive import damage

# deck name -> module under components.mpm.constitutive
MODELS = {
    "comp_neo_hook": "comp_neo_hook",
    "comp_mooney_rivlin": "comp_mooney_rivlin",
    "hypo_elastic": "hypo_elastic",
    "elastic_plastic": "elastic_plastic",
    "elastic_plastic_hp": "elastic_plastic_hp",
    "rigid": "rigid",
    "ideal_gas_fluid": "ideal_gas_fluid",
    "membrane": "membrane",
    "visco_scram": "visco_scram",
    "comp_neo_hook_plastic": "comp_neo_hook_plastic",
    "UCNH": "ucnh",
    "UCNHVar": "ucnh_var",
    "jwlpp_mpm": "jwlpp_mpm",
    "ArenaSoil": "arena_soil",
}

# models whose stress needs only F (their velocity gradient need not be stored)
NO_L = ("comp_neo_hook", "comp_mooney_rivlin", "rigid", "comp_neo_hook_plastic", "UCNH", "UCNHVar", "jwlpp_mpm")

# models with state per particle: the carried particle label holding it (one name), or the
# labels (a tuple: the model's update gets tuples of old and new arrays in that order)
STATE = {"elastic_plastic": "p.plasticStrain", "ideal_gas_fluid": "p.internalEnergy",
         "visco_scram": ("p.pStatedata_vs", "p.crackRad", "p.tempPrevious"),
         "comp_neo_hook_plastic": ("p.plasticStrain", "p.bElBar"), "UCNH": ("p.plasticStrain", "p.bElBar")}


MATERIAL = {
    "density": Param("float", doc="reference mass density (kg/m^3)", above=0.0),
    "thermal_conductivity": Param("float", 0.0, doc="W/(m K) (thermal.py)", at_least=0.0),
    "specific_heat": Param("float", 0.0, doc="J/(kg K) (thermal.py, MPMICE exchange)", at_least=0.0),
    "C_p": Param("float", 0.0, doc="J/(kg K), Uintah's constant-pressure specific heat; read, no model uses it",
                 at_least=0.0),
    "room_temp": Param("float", 294.0, doc="K; read, no thermal model uses it", above=0.0),
    "melt_temp": Param("float", 1e30, doc="K; read, no thermal model uses it", above=0.0),
    "is_rigid": Param("bool", False, doc="rigid body for <contact type=rigid>"),
    "is_force_transmitting_material": Param("bool", False, doc="Uintah's force-transmitting rigid material: "
                                            "moves as one body under the sum of its external and contact forces"),
    "includeFlowWork": Param("bool", False, doc="read, MPMICE only"),
}

GEOM = {
    "res": Param("ivector", doc="particles per cell in each direction", at_least=1),
    "velocity": Param("vector", (0.0, 0.0, 0.0)),
    "temperature": Param("float", 294.0, doc="K; initial p.temperature (thermal.py); 0 as Uintah allows",
                         at_least=0.0),
    "numLevelsParticleFilling": Param("int", 0, doc="|n| > 1: Uintah's recursive filling of the object's "
                                      "surface cells with particles of half the spacing, n - 1 times "
                                      "(fill_levels); n < 0 first removes the particles that stick out"),
    "cut_cell_particles": Param("bool", False, doc="pysus: a particle whose lattice sub-cell the object's "
                                "surface cuts holds the part inside, with that part's volume, mass and "
                                "centroid (cut_cells), so that the particles hold the object's volume; "
                                "Uintah's (false): a particle where the sub-cell's centre is inside, with "
                                "the whole sub-cell's volume"),
}

LATTICE_BITS = 40       # a lattice particle's ID: object number << 40, then its lattice index


def model_kind(cm):
    """The model Uintah builds for a <constitutive_model>: its type, with Uintah's two renames
    (elastic_plastic with a <flow_model> is elastic_plastic_hp; comp_neo_hook with
    <usePlasticity> is UCNH)."""
    kind = cm.attr("type")
    if kind == "elastic_plastic" and cm.has("flow_model"):
        return "elastic_plastic_hp"
    if kind == "comp_neo_hook" and cm.get("usePlasticity", "bool", False):
        return "UCNH"
    return kind


def _read_affine(g):
    """Uintah's <affineTransformation_A0|A1|A2> (the rows of A) and <affineTransformation_b>: the
    particles laid on the lattice inside the piece are moved to A x + b and their domains turned
    and stretched by A (conforming particles for CPDI); None when the object has none."""
    tags = ("affineTransformation_A0", "affineTransformation_A1", "affineTransformation_A2", "affineTransformation_b")
    if not any(g.has(t) for t in tags):
        return None
    rows = [g.get(t, "vector", tuple(np.eye(3)[k])) for k, t in enumerate(tags[:3])]
    A = np.array(rows, float)
    if abs(np.linalg.det(A)) < 1e-12:
        raise g.child(next(t for t in tags if g.has(t))).error("the affine transformation's A is singular")
    return A, np.array(g.get(tags[3], "vector", (0.0, 0.0, 0.0)), float)


# accepted ranges (above, at_least) of constitutive-model tags: moduli of a deforming solid
# have a positive bulk modulus (none gives no or an imaginary wave speed), shear >= 0, gamma > 1
MODEL_RANGES = {"bulk_modulus": (0.0, None), "shear_modulus": (None, 0.0), "K": (0.0, None), "G": (None, 0.0),
                "yield_stress": (0.0, None), "hardening_modulus": (None, 0.0), "gamma": (1.0, None),
                "viscosity": (None, 0.0), "specific_heat": (None, 0.0), "he_constant_1": (None, 0.0),
                "he_constant_2": (None, 0.0), "alpha": (None, 0.0)}


def read_model_params(cm, model, kind):
    """The Params of a model without sub-model nodes (no read_params) from its <constitutive_model>
    node cm of type `kind`: a tag per field, each checked against MODEL_RANGES (a rigid model's
    moduli act nowhere: any finite number); an unknown field is an input error."""
    fields = dataclasses.fields(model.Params)
    values = {}
    for f in fields:
        c = cm.child(f.name)
        if c is not None:
            kind_of = "bool" if f.type in (bool, "bool") else "float"
            above, at_least = MODEL_RANGES.get(f.name, (None, None)) if kind != "rigid" else (None, None)
            values[f.name] = (c.text() if f.name == "formulation"
                              else str(c.value(kind_of, above=above, at_least=at_least)))
    try:
        return model.Params.from_ups(values)
    except KeyError as e:
        raise cm.error(f"{e.args[0]}; accepted: {', '.join('<%s>' % f.name for f in fields)}") from None


class Material:
    """One MPM material: properties, constitutive model module + params, geometry."""

    collapsed_layers = False    # <res> layers along a collapsed axis too (lattice_res)

    def __init__(self, node, index, geom_reader, with_color):
        self.index = index
        self.node = node
        self.damage = None                    # damage.py: <damage_model> beside the constitutive model
        self.name = node.attr("name", default=f"mpm{index}")
        props = node.read(MATERIAL)
        self.props = props                      # what a model's read_params takes beside its node
        self.density = props["density"]
        if self.density <= 0:
            raise node.child("density").error("density must be positive")
        self.is_rigid = props["is_rigid"]
        self.is_ftm = props["is_force_transmitting_material"]
        self.conductivity = props["thermal_conductivity"]
        self.specific_heat = props["specific_heat"]
        if self.conductivity < 0 or self.specific_heat < 0:
            raise node.error("<thermal_conductivity> and <specific_heat> must not be negative")
        cm = node.child("constitutive_model", required=True)
        kind = cm.attr("type")
        if kind not in MODELS:
            raise cm.error(f'constitutive_model type="{kind}" is not supported; accepted: '
                           f"{', '.join(MODELS)}")
        kind = model_kind(cm)
        if kind in ("comp_neo_hook", "comp_neo_hook_plastic", "UCNH") and cm.get("useInitialStress", "bool", False):
            raise cm.child("useInitialStress").error("<useInitialStress> true (UCNH's initial pressure from "
                                                     "<initial_pressure>) is not implemented; accepted: false")
        uniform_yield = None                  # UCNH's yield_distrib uniform: (yield_range, yield_seed)
        if kind in ("comp_neo_hook", "comp_neo_hook_plastic", "UCNH") and cm.has("yield_distrib"):
            if cm.get("yield_distrib", "str", choices=("constant", "uniform")) == "uniform":
                uniform_yield = (cm.get("yield_range", at_least=0.0), cm.get("yield_seed", "int", 0))
        self.model_name = kind
        self.model = importlib.import_module(f"components.mpm.constitutive.{MODELS[kind]}")
        if getattr(self.model, "USES_COLOR", False) and not with_color:
            raise cm.error(f'constitutive_model type="{kind}" reads p.color: it needs <MPM><withColor>true'
                           '</withColor>')
        if hasattr(self.model, "read_params"):        # sub-model nodes (elastic_plastic_hp, UCNHVar)
            params = self.model.read_params(cm, node, props)
            if kind in damage.MODELS or kind == "jwlpp_mpm":     # jwlpp_mpm: an <erosion> alone is read
                self._read_damage(node, cm, kind)
            self._finish(node, props, params, kind, with_color, geom_reader)
            return
        self.params = read_model_params(cm, self.model, kind)
        unread = [cm.child(t) for t in getattr(self.model, "UINTAH_UNREAD", ()) if cm.has(t)]
        if unread and world_rank() == 0:
            print(f"pysus: note: {cm.filename}:{unread[0].line}: {', '.join('<%s>' % c.tag for c in unread)} "
                  f"of {kind} have no effect (Uintah's model does not read them either)", file=sys.stderr)
        if hasattr(self.model, "MATERIAL_PROPERTIES"):    # visco_scram: rho c_v of its heating
            self.params = dataclasses.replace(self.params, **{k: props[k] for k in self.model.MATERIAL_PROPERTIES})
            if props["specific_heat"] <= 0.0:
                raise node.error(f'constitutive_model type="{kind}" heats the particles by its dissipation over '
                                 "rho c_v: it needs the material's <specific_heat> > 0")
        if uniform_yield and self.params.usePlasticity:
            self.params = dataclasses.replace(self.params, yield_uniform=True, yield_range=uniform_yield[0],
                                              yield_seed=uniform_yield[1])
        if hasattr(self.model, "read_failure"):       # elastic_plastic: <damage_model>, <erosion>
            self.params = self.model.read_failure(self.params, node, cm)
        else:
            self._read_damage(node, cm, kind)
        self._finish(node, props, self.params, kind, with_color, geom_reader)

    def _read_damage(self, node, cm, kind):
        """Uintah's damage model beside the constitutive model, and its erosion (damage.py); an
        <erosion> without a damage model does nothing, as in Uintah (no particle localizes)."""
        if not node.has("damage_model"):
            if node.has("erosion"):
                damage.read_erosion(node.child("erosion"))
            return
        if kind not in damage.MODELS:
            raise node.child("damage_model").error(
                f"a <damage_model> of a {kind} material is not implemented; accepted with the "
                f"constitutive models {', '.join(damage.MODELS)}")
        self.damage = damage.read(node, cm)

    def _finish(self, node, props, params, kind, with_color, geom_reader):
        """The model's params, its flags and the geometry objects."""
        self.params = params
        cm = node.child("constitutive_model")
        self.increment_energy = self.model.ENERGY_IS_INCREMENT
        self.uses_L = kind not in NO_L       # the model reads the velocity gradient
        st = getattr(self.model, "STATE", STATE.get(kind))
        if hasattr(self.model, "state_of"):       # state that depends on the deck (Maxwell elements)
            st = self.model.state_of(self.params)
        if not getattr(self.params, "usePlasticity", True):
            st = None                         # UCNH without plasticity: comp_neo_hook, no state
        self.state = st                       # the model's state label name(s), or None
        self.state_names = (st,) if isinstance(st, str) else tuple(st or ())
        if self.damage is not None:           # the damage model's state follows the model's
            self.model = damage.Damaged(self.model, len(self.state_names), self.damage,
                                        kind in damage.NO_ENERGY_WHEN_LOCALIZED)
            self.state_names += self.damage.STATE
            self.state = self.state_names
        # the erosion (damage.EROSION code) of a damage model, or of a model that localizes its
        # particles itself (elastic_plastic_hp); it needs the step's start time, and most erode F
        if self.damage is not None:
            self.erosion = getattr(self.damage, "erosion", 0)
        else:
            self.erosion = getattr(self.params, "erosion", 0) if getattr(self.model, "LOCALIZES", False) else 0
        self.erodes_F = self.erosion in (1, 2, 3)
        self.needs_time = self.damage is not None or self.erosion != 0
        self.uses_temperature = getattr(self.model, "USES_TEMPERATURE", False)     # p.temperature as an argument
        self.needs_temperature = getattr(self.model, "NEEDS_TEMPERATURE", False)   # p.temperature / p.dTdt in the state
        self.max_delT = getattr(self.model, "MAX_DELT", np.inf)
        # V = m J / volume_density: the density over the initial J (Uintah's V_old J/J_old, where
        # a model starts from F != I with the geometric volume: jwlpp_mpm's initial pressure)
        self.volume_density = self.density * getattr(self.model, "initial_J", lambda params: 1.0)(self.params)
        if kind == "ideal_gas_fluid":
            # e0 = c_v T: the model's <specific_heat>, else the material's
            self.cv = self.params.specific_heat or props["specific_heat"]
            if self.cv <= 0:
                raise cm.error("ideal_gas_fluid needs <specific_heat> > 0 (in the model or the material): "
                               "the initial specific internal energy is specific_heat * <temperature>")
        self.objects = []
        self.is_membrane = kind == "membrane"
        for g in node.children("geom_object"):
            if self.is_membrane:
                self.objects.append(read_membrane_object(g, with_color))
                continue
            piece = geom_reader.read_object(g)
            spec = g.read(GEOM)
            if any(r < 1 for r in spec["res"]):
                raise g.child("res").error("res must be at least 1 in every direction")
            spec["color"] = g.get("color", "float", 0.0) if with_color else None
            if not with_color and g.has("color"):
                raise g.child("color").error("<color> needs <MPM><withColor>true</withColor>")
            spec["piece"] = piece
            spec["node"] = g
            spec["smooth"] = isinstance(piece, SmoothCylinder)
            if spec["smooth"] and abs(spec["numLevelsParticleFilling"]) > 1:
                raise g.child("numLevelsParticleFilling").error(
                    "a <smoothcyl> lays its own particles: accepted numLevelsParticleFilling -1 .. 1 with it")
            spec["affine"] = _read_affine(g)
            if spec["affine"] is not None and abs(spec["numLevelsParticleFilling"]) > 1:
                raise g.child("numLevelsParticleFilling").error(
                    "the filling of an affine-transformed object is not implemented; accepted: -1 .. 1")
            if spec["cut_cell_particles"]:
                for other, why in ((f"numLevelsParticleFilling {spec['numLevelsParticleFilling']}",
                                    abs(spec["numLevelsParticleFilling"]) > 1),
                                   ("a <smoothcyl>", spec["smooth"]),
                                   ("an affine transformation", spec["affine"] is not None)):
                    if why:
                        raise g.child("cut_cell_particles").error(
                            f"cut_cell_particles lays the lattice's particles itself: accepted with neither "
                            f"numLevelsParticleFilling beyond -1 .. 1, a <smoothcyl> nor an affine transformation "
                            f"(this object has {other})")
            self.objects.append(spec)
        if not self.objects:
            raise node.error("a material needs at least one <geom_object>")
        self._check_smooth(node)

    def _check_smooth(self, node):
        """A <smoothcyl> lays its own particles only as the lone piece of its <geom_object>, and
        Uintah's FileGeomPieceParticleCreator takes a material whose pieces are all such (a
        smoothcyl inside <union> etc. is filled on the lattice like any piece)."""
        smooth = [o for o in self.objects if o.get("smooth")]
        if not smooth:
            bare = [c for o in self.objects if "node" in o for c in o["node"].children("smoothcyl")]
            if bare:
                raise bare[0].error("a <smoothcyl> that lays its own particles must be the only piece of its "
                                    "<geom_object> (Uintah's particle creator for it reads one piece)")
            return
        if len(smooth) != len(self.objects):
            other = next(o for o in self.objects if not o.get("smooth"))
            raise other["node"].error("a material with a <smoothcyl> object takes only <smoothcyl> objects "
                                      "(Uintah: file geometry pieces can't be mixed with other geometry types "
                                      "in a single material)")

    def initial_state(self, d):
        """The model state of new particles: plastic strain 0; ideal gas: the specific
        internal energy e = specific_heat * <temperature> of the geometry object; membrane:
        (unit tangent, thickness) from the chain; the models with an initial_state
        (visco_scram, elastic_plastic_hp, comp_neo_hook_plastic): their tuple (elastic_plastic_hp
        also gets Uintah's order of creation, for its random initial porosity)."""
        drawn = getattr(self.params, "yield_uniform", False)      # UCNH's p.yieldStress
        draw = None
        if drawn or getattr(self.damage, "random", False):
            draw = (self.uintah_creation_order(d), uintah_patch_id(d["patch"]))
        if self.damage is not None:
            return self.model.initial_state(self.params, len(d["id"]), d["temp"], color=d["color"], draw=draw)
        if getattr(self.params, "draws_initial_state", False):
            return self.model.initial_state(self.params, len(d["id"]), d["temp"],
                                            creation_order=self.uintah_creation_order(d))
        if self.state_names and hasattr(self.model, "initial_state"):
            if drawn:
                return self.model.initial_state(self.params, len(d["id"]), d["temp"], draw=draw)
            return self.model.initial_state(self.params, len(d["id"]), d["temp"])
        if self.model_name == "ideal_gas_fluid":
            return self.cv * d["temp"]
        if self.is_membrane:
            return d["tangent"], d["thickness"]
        return np.zeros(len(d["id"]))

    # -- particles -------------------------------------------------------------------
    @property
    def draws(self):
        """Whether the particles get random values of their own (failure stresses, yield
        stresses, porosities drawn in Uintah's order of creation)."""
        return bool(getattr(self.params, "yield_uniform", False) or getattr(self.damage, "random", False)
                    or getattr(self.params, "porosity_gauss", False))

    def lattice_res(self, obj, lv):
        """Particles per cell of a lattice object along each axis: its <res>, one along a
        collapsed axis, where Uintah's res layers would be copies of each other (their summed
        mass moves as one), unless collapsed_layers: a deck whose particles draw values of their
        own gets Uintah's layers, whose draws differ (MPM.problem_setup)."""
        return np.array([1 if lv.collapsed[d] and not self.collapsed_layers else obj.get("res", (1, 1, 1))[d]
                         for d in range(3)])

    def create(self, patch, obj_base, pressure=None, surface=False, axisymmetric=False):
        """Particles of this material in one patch: dict of arrays sorted by ID.

        IDs: object number (global over all materials, `obj_base` + k) times 2^40 plus
        the index of the particle's sub-cell on the level-wide lattice of that object,
        so they do not depend on the patch layout. With pressure BCs (pressure.py), "lcid"
        is p.loadCurveID of the particles on a loaded surface; with surface, "surf" is
        p.surface (1: a neighbour one particle spacing away along an active direction is
        outside the object, Uintah's checkForSurface). Axisymmetric: x is r and a particle's
        volume (and mass) is that of its ring per radian, r dx dy / (res_x res_y), as Uintah's
        ParticleCreator."""
        lv = patch.level
        out = []
        for k, obj in enumerate(self.objects):
            if "chain" in obj:
                out.append(membrane_points(obj, patch, obj_base + k, axisymmetric))
                if surface:
                    out[-1]["surf"] = np.ones(len(out[-1]["x"]))      # a membrane is all surface
                continue
            if isinstance(obj["piece"], Null):
                continue              # Uintah: its box is a point, so no particles
            res = self.lattice_res(obj, lv)
            if obj.get("smooth"):
                out.append(smooth_points(obj, patch, obj_base + k, res, pressure, self.index))
                if surface:
                    out[-1]["surf"] = on_surface(out[-1]["x"], obj["piece"], lv.dx / res,
                                                 ~np.asarray(lv.collapsed)).astype(float)
                continue
            if obj.get("cut_cell_particles"):
                sub, x, fraction = cut_cells(obj["piece"], patch, res)
                out.append(self._lattice_particles(obj, patch, obj_base + k, res, 0, sub, x, pressure, surface,
                                                   axisymmetric))
                out[-1]["vol"] = out[-1]["vol"] * fraction     # axisymmetric: r_centroid * area, Pappus
                continue
            for level, sub, x in fill_levels(obj["piece"], patch, res, obj.get("numLevelsParticleFilling", 0)):
                out.append(self._lattice_particles(obj, patch, obj_base + k, res, level, sub, x, pressure,
                                                   surface, axisymmetric))
        if not out:
            out.append(dict(x=np.empty((0, 3)), id=np.empty(0, np.int64), vol=np.empty(0), temp=np.empty(0),
                            lcid=np.empty((0, 3)), vel=np.empty((0, 3)), size=np.empty((0, 3)),
                            color=np.empty(0), **({"surf": np.empty(0)} if surface else {})))
        for o in out:       # the size matrix's columns: the half-vectors of the particle's domain
            if "size_matrix" not in o:
                o["size_matrix"] = o["size"][:, :, None] * np.eye(3)
        data = {key: np.concatenate([o[key] for o in out]) for key in out[0]}
        order = np.argsort(data["id"], kind="stable")
        data = {key: np.ascontiguousarray(v[order]) for key, v in data.items()}
        data["mass"] = self.density * data["vol"]
        data["patch"], data["obj_base"] = patch, obj_base
        return data

    def _lattice_particles(self, obj, patch, obj_id, res, level, sub, x, pressure, surface, axisymmetric):
        """The particles of one lattice object at fill level `level` (0: the <res> lattice; k > 0:
        2^k times finer, Uintah's filling of the surface cells): IDs, volumes, sizes, the rest."""
        lv = patch.level
        fine = 0.5 ** level
        std = np.diag(1.0 / res)                 # Uintah's p.size in cells
        if obj.get("affine") is not None:        # moved, kept where the patch owns them (as Uintah)
            A, b = obj["affine"]
            x = x @ A.T + b
            cell = np.floor((x - lv.anchor) / lv.dx).astype(np.int64)
            mine = np.all((cell >= patch.lo) & (cell < patch.hi), axis=1)
            x, sub, std = x[mine], sub[mine], A @ std
        nsub = np.array(lv.ncells) * res * 2 ** level
        ids = (obj_id << LATTICE_BITS) + level_offset(lv.ncells, res, level) + sub[:, 0] + nsub[0] * (
            sub[:, 1] + nsub[1] * sub[:, 2])
        n = len(x)
        dx = np.asarray(lv.dx, float)
        if obj.get("affine") is None:
            vol = (x[:, 0] * (lv.dx[0] / res[0]) * (lv.dx[1] / res[1]) if axisymmetric
                   else np.full(n, float(np.prod(lv.dx / res))))
        else:                                    # Uintah's volumes of the turned domains
            vol = (x[:, 0] * (std[0, 0] * std[1, 1] - std[0, 1] * std[1, 0]) * dx[0] * dx[1] if axisymmetric
                   else np.full(n, float(np.linalg.det(std) * np.prod(dx))))
        if level:                                # axisymmetric: per radian, fine in r and z only (Uintah's)
            vol = vol * (fine ** 2 if axisymmetric else fine ** 3)
        dxpp = lv.dx / res * fine
        d = dict(x=x, id=ids.astype(np.int64), vol=vol, temp=np.full(n, obj["temperature"]),
                 lcid=pressure.flag(x, obj["piece"], dxpp, self.index) if pressure else np.zeros((n, 3)),
                 vel=np.tile(np.asarray(obj["velocity"], float), (n, 1)),
                 size=np.tile(0.5 * lv.dx / res * fine, (n, 1)),
                 size_matrix=np.broadcast_to(0.5 * fine * dx[:, None] * std, (n, 3, 3)).copy(),
                 color=np.full(n, obj["color"] if obj["color"] is not None else 0.0))
        if surface:
            d["surf"] = on_surface(x, obj["piece"], dxpp, ~np.asarray(lv.collapsed)).astype(float)
        return d

    def uintah_creation_order(self, d):
        """The indices of a patch's particles (create's dict d, sorted by ID) in the order
        Uintah's ParticleCreator makes them: object by object, the cells x fastest, then each
        cell's particles by fill level and, within one, with the z lattice index fastest (its
        loops ix, iy, iz)."""
        lv = d["patch"].level
        ids = d["id"]
        k = (ids >> LATTICE_BITS) - d["obj_base"]
        lattice = ids & ((1 << LATTICE_BITS) - 1)
        objs = np.unique(k)
        level = np.zeros(len(ids), np.int64)
        res = np.empty((len(ids), 3), np.int64)
        for o in objs:
            sel = k == o
            obj = self.objects[o]
            r = self.lattice_res(obj, lv).astype(np.int64)
            nlev = max(abs(obj.get("numLevelsParticleFilling", 0)), 1)
            offsets = np.array([level_offset(lv.ncells, r, j) for j in range(nlev)], np.int64)
            level[sel] = np.searchsorted(offsets, lattice[sel], side="right") - 1
            lattice[sel] -= offsets[level[sel]]
            res[sel] = r
        res = res << level[:, None]
        nsub = np.array(lv.ncells, np.int64) * res
        sub = np.stack([lattice % nsub[:, 0], (lattice // nsub[:, 0]) % nsub[:, 1],
                        lattice // (nsub[:, 0] * nsub[:, 1])], axis=1)
        cell, ip = sub // res, sub % res
        return np.lexsort((ip[:, 2], ip[:, 1], ip[:, 0], level, cell[:, 0], cell[:, 1], cell[:, 2],
                           k)).astype(np.int64)


def level_offset(ncells, res, level):
    """Where the lattice indices of fill level `level` start in an object's IDs: after those of
    the coarser levels (level j has ncells * res * 2^j sub-cells)."""
    return sum(int(np.prod(np.asarray(ncells, np.int64) * np.asarray(res, np.int64) * 2 ** j))
               for j in range(level))


def _flat(sub, n):
    """Linear indices of lattice indices sub (m, 3) on a lattice of n sub-cells, x fastest."""
    return sub[:, 0] + n[0] * (sub[:, 1] + n[1] * sub[:, 2])


def lattice_positions(anchor, dx, r, sub):
    """The points of a lattice of r per cell (sub-cell indices sub, (n, 3)) with Uintah's
    ParticleCreator arithmetic: (anchor + dx c) + dxpp/2 + dxpp i, c the cell, i the index in
    it, dxpp = dx / r. The same points as anchor + (sub + 1/2) dx / r, but rounded as Uintah's:
    a point an ulp off sits on the other side of a GIMP piece's bound (a weight of 1e-32
    instead of 0), which decides friction_LR's prominence there."""
    anchor, dx = np.asarray(anchor, float), np.asarray(dx, float)
    cell, idx = np.divmod(sub, r)
    dxpp = dx / r
    return ((anchor + dx * cell) + dxpp * 0.5) + dxpp * idx


CUT_SAMPLES = 8         # samples per active direction in a cut sub-cell (cut_cells)


def _patch_lattice(patch, r):
    """Sub-cell indices (n, 3) of a patch's lattice of r per cell, x fastest, and their points."""
    lv = patch.level
    axes = [np.arange(patch.lo[d] * r[d], patch.hi[d] * r[d]) for d in range(3)]
    I, J, K = np.meshgrid(*axes, indexing="ij")
    sub = np.stack([I.ravel(order="F"), J.ravel(order="F"), K.ravel(order="F")], axis=1)
    return sub, lattice_positions(lv.anchor, lv.dx, r, sub)


def cut_cells(piece, patch, res, chunk=1 << 15):
    """The <res> lattice's sub-cells of a patch that hold part of `piece`: (sub-cell index (n, 3),
    position (n, 3), volume fraction (n,)). A sub-cell whose centre and corners are all inside is
    whole (fraction 1, at its centre, the lattice point); one the surface cuts (some of its centre
    and corners inside, some not) is sampled at CUT_SAMPLES points per active direction and
    holds the inside part's fraction at that part's centroid, which lies in the sub-cell (the
    lattice point where every sample is inside). The particles then hold the object's volume to
    the sampling's resolution where the lattice's centres hold it to a sub-cell per surface cell
    (the pressurized cylinder's eq. 43 error: docs/MPMICE.md). `chunk` sub-cells at a time."""
    lv = patch.level
    sub, x = _patch_lattice(patch, res)
    h = np.asarray(lv.dx, float) / res
    act = ~np.asarray(lv.collapsed)
    signs = np.array([[a, b, c] for a in (-0.5, 0.5) for b in (-0.5, 0.5) for c in (-0.5, 0.5)])
    corners = np.unique(signs * act, axis=0) * h
    offsets = [((np.arange(CUT_SAMPLES) + 0.5) / CUT_SAMPLES - 0.5) * h[d] if act[d] else np.zeros(1)
               for d in range(3)]
    samples = np.stack(np.meshgrid(*offsets, indexing="ij"), axis=-1).reshape(-1, 3)
    active = np.nonzero(act)[0]
    fraction = np.zeros(len(x))
    pos = x.copy()
    for a in range(0, len(x), chunk):
        xs = x[a:a + chunk]
        centre = piece.inside(xs)
        corner_in = piece.inside((xs[:, None, :] + corners[None]).reshape(-1, 3)).reshape(len(xs), len(corners))
        whole = centre & corner_in.all(axis=1)
        fraction[a:a + chunk] = whole
        cut = np.nonzero((centre | corner_in.any(axis=1)) & ~whole)[0]
        step = max(1, chunk // len(samples))           # sub-cells sampled at a time
        for c in range(0, len(cut), step):
            idx = a + cut[c:c + step]
            pts = x[idx, None, :] + samples[None]
            inside = piece.inside(pts.reshape(-1, 3)).reshape(len(idx), len(samples))
            count = inside.sum(axis=1)
            fraction[idx] = count / len(samples)
            part = (count > 0) & (count < len(samples))     # every sample inside: the lattice point stays
            centroid = (pts[part] * inside[part, :, None]).sum(axis=1) / count[part, None]
            pos[idx[part][:, None], active[None, :]] = centroid[:, active]      # collapsed axes keep theirs
    keep = fraction > 0.0
    return sub[keep], pos[keep], fraction[keep]


def fill_levels(piece, patch, res, fill):
    """The lattice points of a patch inside `piece`, per fill level: [(level, sub-cell index (n, 3)
    on that level's lattice, position (n, 3))]. Level 0 is the <res> lattice. With |fill| > 1
    (Uintah's numLevelsParticleFilling), levels 1 .. |fill| - 1 each halve the spacing (in every
    direction, a collapsed one too, as Uintah) and add the points inside the piece that no
    particle of a coarser level covers; fill < 0 first removes, at each level, the particles a
    corner of whose would-be children (+-dx/4 of the current spacing) lies outside the piece."""
    lv = patch.level
    out = []
    for level in range(max(abs(fill), 1)):
        r = res * 2 ** level
        sub, x = _patch_lattice(patch, r)
        inside = piece.inside(x)
        sub, x = sub[inside], x[inside]
        if level:
            if fill < 0:            # the coarser particles that stick out go
                h = lv.dx / (res * 2 ** (level - 1))
                corners = np.array([[a, b, c] for a in (-1, 1) for b in (-1, 1) for c in (-1, 1)], float)
                for j, (lev, s, xs) in enumerate(out):
                    pts = xs[:, None, :] + 0.25 * corners[None, :, :] * h
                    keep = piece.inside(pts.reshape(-1, 3)).reshape(len(xs), 8).all(axis=1)
                    out[j] = (lev, s[keep], xs[keep])
            covered = np.zeros(len(sub), bool)
            for lev, s, _ in out:   # inside a coarser particle's domain
                n = np.array(lv.ncells, np.int64) * res * 2 ** lev
                covered |= np.isin(_flat(sub // 2 ** (level - lev), n), _flat(s, n))
            sub, x = sub[~covered], x[~covered]
        out.append((level, sub, x))
    return out


# -- membrane strings (004 sec. 3.2) ------------------------------------------------------
MEMBRANE = {
    "spacing": Param("float", doc="distance between consecutive membrane points (m)", above=0.0),
    "thickness": Param("float", doc="membrane thickness h (m): point volume = spacing * h * depth", above=0.0),
    "closed": Param("bool", True, doc="the last vertex joins the first"),
}


def uintah_patch_id(patch):
    """The ID Uintah gives this patch of a one-level grid: its Grid loops over the layout with z
    fastest, where pysus numbers x fastest."""
    i, j, k = patch.index
    _, ny, nz = patch.level.layout
    return (i * ny + j) * nz + k


def read_membrane_object(g, with_color):
    """A membrane material's <geom_object>: <membrane_polygon> with <vertex>[x,y,z]</vertex>
    (two or more, in order along the membrane), <spacing>, <thickness>, <closed>; plus the
    usual <velocity>, <temperature> (and <color>). The points are laid along the polygon at
    the spacing (the polygon's length divided evenly), numbered consecutively: their IDs
    follow the chain, and the unit tangent of each comes from its neighbours (004 sec. 3.2)."""
    mp = g.child("membrane_polygon", required=True)
    spec = mp.read(MEMBRANE)
    verts = np.array([v.value("vector") for v in mp.children("vertex")], float)
    if len(verts) < 2:
        raise mp.error("a <membrane_polygon> needs at least two <vertex>")
    if spec["spacing"] <= 0 or spec["thickness"] <= 0:
        raise mp.error("<spacing> and <thickness> must be positive")
    ring = np.vstack([verts, verts[:1]]) if spec["closed"] else verts
    seg = np.linalg.norm(np.diff(ring, axis=0), axis=1)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    n = max(2, int(round(s[-1] / spec["spacing"])))
    ds = s[-1] / n if spec["closed"] else s[-1] / (n - 1)
    sp = (np.arange(n) + (0.5 if spec["closed"] else 0.0)) * ds
    x = np.stack([np.interp(sp, s, ring[:, d]) for d in range(3)], axis=1)
    from .constitutive.membrane import chain_tangents
    t = np.empty_like(x)
    chain_tangents(x, spec["closed"], t)
    if g.has("res"):          # not used by membranes
        g.child("res").mark_used()
    return dict(chain=x, tangent=t, ds=ds, thickness=spec["thickness"], closed=spec["closed"], node=mp,
                velocity=g.get("velocity", "vector", (0.0, 0.0, 0.0)),
                temperature=g.get("temperature", "float", 294.0, at_least=0.0),
                color=g.get("color", "float", 0.0) if with_color else None)


def smooth_points(obj, patch, obj_id, res, pressure, matl):
    """The particles of a <smoothcyl> object that lie in the patch's cells (Uintah's
    FileGeomPieceParticleCreator): positions and volumes from SmoothCylinder.points, mass =
    density * volume; IDs obj_id * 2^40 + the index in the piece's list; size_matrix the
    half-vectors of each particle's domain, half its ring sector's edges (Uintah's p.size
    matrix times the cell size). A point outside the
    level (extra cells included) is an error, as Uintah's."""
    lv = patch.level
    x, vol, size = obj["piece"].cached_points(lv.dx)
    extra = np.asarray(lv.extra) * lv.dx
    lo, hi = lv.anchor - extra, lv.upper + extra
    bad = np.nonzero(np.any((x < lo) | (x > hi), axis=1))[0]
    if len(bad):
        raise obj["node"].error(f"the <smoothcyl>'s particle at {_fmt(x[bad[0]])} lies outside the domain "
                                f"{_fmt(lo)} to {_fmt(hi)} (extra cells included)")
    cell = np.floor((x - lv.anchor) / lv.dx).astype(np.int64)
    idx = np.nonzero(np.all((cell >= patch.lo) & (cell < patch.hi), axis=1))[0]
    x, n = x[idx], len(idx)
    dxpp = lv.dx / res
    return dict(x=x, id=(obj_id * (1 << 40) + idx).astype(np.int64), vol=vol[idx],
                temp=np.full(n, obj["temperature"]),
                lcid=pressure.flag(x, obj["piece"], dxpp, matl) if pressure else np.zeros((n, 3)),
                vel=np.tile(np.asarray(obj["velocity"], float), (n, 1)),
                size=np.tile(0.5 * dxpp, (n, 1)),
                size_matrix=0.5 * size[idx],
                color=np.full(n, obj["color"] if obj["color"] is not None else 0.0))


def _fmt(v):
    return "[" + ", ".join(f"{a:g}" for a in v) + "]"


def on_surface(x, piece, dxpp, active):
    """Points whose neighbour one spacing away along an active direction lies outside piece."""
    surface = np.zeros(len(x), bool)
    for d in range(3):
        if active[d]:
            for sgn in (-1.0, 1.0):
                y = x.copy()
                y[:, d] += sgn * dxpp[d]
                surface |= ~piece.inside(y)
    return surface


def membrane_points(obj, patch, obj_id, axisymmetric=False):
    """The membrane points of one polygon that lie in the patch's cells (IDs: obj_id * 2^40 +
    the index along the chain); volume = spacing * thickness * the cell depth in a collapsed
    direction (2D: the membrane is a surface extruded out of the plane); axisymmetric: the
    polygon is a meridian and the volume is that of its ring per radian, r * spacing * thickness."""
    lv = patch.level
    x = obj["chain"]
    cell = np.floor((x - lv.anchor) / lv.dx).astype(np.int64)
    inp = np.ones(len(x), bool)
    for d in range(3):
        if not lv.collapsed[d]:
            inp &= (cell[:, d] >= patch.lo[d]) & (cell[:, d] < patch.hi[d])
    idx = np.nonzero(inp)[0]
    n = len(idx)
    if axisymmetric:
        vol = obj["ds"] * obj["thickness"] * x[idx, 0]
    else:
        depth = float(np.prod([lv.dx[d] for d in range(3) if lv.collapsed[d]])) if any(lv.collapsed) else 1.0
        vol = np.full(n, obj["ds"] * obj["thickness"] * depth)
    return dict(x=x[idx], id=(obj_id * (1 << 40) + idx).astype(np.int64), vol=vol,
                temp=np.full(n, obj["temperature"]), lcid=np.zeros((n, 3)),
                vel=np.tile(np.asarray(obj["velocity"], float), (n, 1)),
                size=np.tile(0.5 * lv.dx / 2, (n, 1)),
                color=np.full(n, obj["color"] if obj["color"] is not None else 0.0),
                tangent=obj["tangent"][idx], thickness=np.full(n, obj["thickness"]))
