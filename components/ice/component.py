"""The ICE component: multi-material, cell-centred, compressible Eulerian flow.

`<SimulationComponent type="ice">`. Reads Uintah's tags (`<CFD>`, `<PhysicalConstants>`,
`<MaterialProperties><ICE>`, `<exchange_properties>`, `<Grid><BoundaryConditions>`) and
schedules one timestep as the tasks of paper 000 sec. 3.3, steps 2-12 (tasks.py).
Physics a deck does not call for is not scheduled: the exchange tasks need two or
more materials with a non-zero coefficient; the viscous and heat-conduction tasks a
non-zero <dynamic_viscosity> (or <dynamicViscosityModels>: Sutherland, SpongeLayer) /
<thermal_conductivity>; gravity enters only when non-zero.
The viscous task (ICE::viscousShearStress, kernels.viscous_stress_source) adds the
divergence of the full Newtonian stress tau = mu (grad v + grad v^T) - 2/3 mu div v I,
computed on the faces as Uintah's computeTauX/Y/Z from its velTau_CC (the extra cells on
the domain's faces hold 2 v_boundary - v_interior, so a wall sits on the boundary face), to
the momentum; like Uintah's ICE it adds no viscous heating to the energy. With gravity, the
<isSurroundingMatl> material's rho_micro sets Uintah's hydrostatic pressure: press_CC at t = 0
(rho_micro g.(x - x_0)) and the pressure's extra cells on every later step (bc.py). The face stresses
tau_X_FC, tau_Y_FC, tau_Z_FC are computed only when a deck saves them. Heat conduction: div(theta k grad T) (eq. 9).
"""
from __future__ import annotations

import sys

import numpy as np

from components.models import MODELS as REACTIONS
from components.models.ice_models import read_ice_models
from framework import labels as L
from framework.component import Component, register
from framework.geometry import GeometryReader
from framework.problemspec import Param
from framework.scheduler.comm import world_rank
from framework.task import NEW, OLD, Task
from framework.variables import Ghost

from . import labels as I
from .advection import EXTREMA, VAN_LEER
from .bc import BoundaryConditions, read_bcs
from .custom_init import CustomInitialization
from .turbulence import read_turbulence
from .eos import IDEAL_GAS, MAX_PARAMS, THOMSEN_HARTKA, eos_press_eos, make_eos
from .implicit import ImplicitICE
from .lodi import LodiTasks
from .specific_heat import read_specific_heat_model
from .slip_exchange import read_slip
from .tasks import IceTasks

G = Ghost.AROUND_CELLS
# Face arrays are read with one ghost layer: a patch's upper faces belong to its
# neighbour, and the halo is what makes them part of the stored array.

EOS_TAGS = {"ideal_gas": (), "Murnaghan": ("K", "n", "rho0", "P0"), "JWL": ("A", "B", "R1", "R2", "om", "rho0"),
            "JWLC": ("A", "B", "C", "R1", "R2", "om", "rho0"), "Stiffened_gas": ("Pinf",),
            "Thomsen_Hartka_water": ("a", "b", "co", "ko", "To", "L", "vo"), "TST": ("a", "b", "u", "w", "Gamma")}
EOS_POSITIVE = ("K", "rho0")      # a bulk modulus and a reference density are positive
MATERIAL = {
    "dynamic_viscosity": Param("float", 0.0, at_least=0.0),
    "thermal_conductivity": Param("float", 0.0, at_least=0.0),
    "specific_heat": Param("float", above=0.0),
    "gamma": Param("float", above=0.0),     # > 1 where the EOS uses it (_read_material)
    "tiny_rho": Param("float", 1e-12, above=0.0),
    "isSurroundingMatl": Param("bool", False),
}
GEOM = {
    "res": Param("ivector", (2, 2, 2), at_least=1),
    "velocity": Param("vector"),
    "temperature": Param("float", above=0.0),
    "density": Param("float", above=0.0),
    "pressure": Param("float", above=0.0),
    "volumeFraction": Param("float", -1.0),
}


class Material:
    """One ICE material: EOS, constants and its initial geometry objects."""

    def __init__(self, name, eos, props, objects):
        self.name = name
        self.eos = eos
        self.cv = props["specific_heat"]
        self.gamma = props["gamma"]
        self.viscosity = props["dynamic_viscosity"]
        self.conductivity = props["thermal_conductivity"]
        self.tiny_rho = props["tiny_rho"]
        self.is_surrounding = props["isSurroundingMatl"]
        self.objects = objects          # [(piece, {res, velocity, temperature, density, pressure})]
        self.cv_model = None            # <SpecificHeatModel> (specific_heat.py)


LIMITERS = {"vanLeer": VAN_LEER, "BarthJespersen": EXTREMA}    # <advection limiter="...">


@register("ice")
class ICE(ImplicitICE, LodiTasks, IceTasks, Component):
    """Uintah's ICE: equilibration pressure, face velocities, Lagrangian step, exchange, advection."""

    holes_ok = True      # explicit ICE with side conditions only (_check_holes)

    # MPMICE hook: number of (MPM) materials before ICE's in the global material index
    # space; exchange coefficients and boundary-condition ids are read for all of them
    n_before = 0
    source_models, tracers = [], []      # <Models> of ICE alone (problem_setup)
    caloric = {}                         # {material: the model owning its caloric EOS} (gasCombustion)
    var_K = var_H = False                 # <CoefficientModel> linearVariation (problem_setup)
    open_faces_default = False           # MPMICE hook: openFaceTransfers unless the deck says

    @property
    def delp_vol_frac_ghost(self):
        """Ghost layers of vol_frac_CC that computeDelPressAndUpdatePressCC reads: Uintah's limiter
        (second order, BarthJespersen) reconstructs the donors' fractions from their neighbours."""
        return 2 if self.second_order and self.limiter == EXTREMA else 1

    def problem_setup(self, root, level):
        self.level = level
        self.dims = np.array([not c for c in level.collapsed])
        cfd = root.child("CFD", required=True)
        self.cfl = cfd.get("cfl", "float", above=0.0)
        ice = cfd.child("ICE", required=True)
        adv = ice.child("advection", required=True)
        self.second_order = adv.attr("type", choices=("FirstOrder", "SecondOrder")) == "SecondOrder"
        # the second-order limiter: "vanLeer", the slope along the face normal (pysus), or
        # "BarthJespersen", Uintah's SecondOrderAdvector: the gradient limited by the face
        # neighbours' extrema at the cell's vertices, evaluated at the outflow slab's centroid
        limiter = adv.attr("limiter", default="vanLeer", choices=LIMITERS)
        self.limiter = LIMITERS[limiter]
        # Uintah's flags (AdvectionFactory: either name); with BarthJespersen false reconstructs
        # the totals m q instead of the specific values q
        self.compatible_fluxes = adv.attr("useCompatibleFluxes", "bool", adv.attr("compatibleFluxes", "bool", True))
        # pysus extension (not in Uintah): transverse (corner) terms of the second-order
        # face values, second order in time for oblique flow; off = Uintah's scheme (for
        # vanLeer: BarthJespersen always has Uintah's own, the slab centroid's offset)
        self.transverse = adv.attr("transverseTerms", "bool", False) and self.second_order
        # pysus extension: the advection carries m (e + |u|^2/2) as well and takes
        # e = E/m - |u|^2/2, so the kinetic energy that the limited advection of mass and
        # momentum destroys (at shocks, contacts) becomes heat instead of being lost; the
        # Lagrangian phase stays Uintah's. On by default for ICE alone (MPMICE: on request);
        # "false" with limiter="BarthJespersen" is Uintah's SecondOrderAdvector
        self.dissipation_heating = adv.attr("dissipationHeating", "bool", self.n_before == 0)
        # pysus extension under MPMICE (the default with prescribed solids, rmpmice): the fluid a
        # solid's particles displace from a cell they advance through crosses the face as open as
        # the neighbour (docs/MPMICE.md, step 12; nothing changes where the particles are at rest
        # or the fluid is as dense per open volume as its neighbour's); "false" is Uintah's
        # advection, the face velocities' fluxes
        self.open_faces = adv.attr("openFaceTransfers", "bool", self.open_faces_default)
        self.max_iter = ice.get("max_iteration_equilibration", "int", 100, at_least=1)
        # Uintah's <ClampSpecificVolume>: the Lagrangian m v kept >= tiny_rho V v (MPMICE too)
        self.clamp_sp_vol = ice.get("ClampSpecificVolume", "bool", False)
        self.save_sp_vol_src = False     # sp_vol_src_CC: set at scheduling when a deck saves it
        # pysus extension: advect a conservative total energy and take e = E/m - |u|^2/2,
        # so that mass, momentum and total energy are conserved to round-off on closed
        # domains (Uintah's ICE, the default, advects internal energy: see tasks.py)
        self.conserve_energy = ice.get("conserveTotalEnergy", "bool", False)
        self._conserve_node = ice.child("conserveTotalEnergy")
        pc = root.child("PhysicalConstants", required=True)
        self.gravity = np.array(pc.get("gravity", "vector"), dtype=np.float64)
        self.reference_pressure = pc.get("reference_pressure", "float", 101325.0, at_least=0.0)
        self.use_gravity = bool(np.any(self.gravity != 0.0))
        mp = root.child("MaterialProperties", required=True)
        icen = mp.child("ICE", required=True)
        geo = getattr(root, "_geometry_reader", None) or GeometryReader(level)   # MPMICE shares one
        self.n_all = self.n_before + len(icen.children("material"))     # every material of the problem
        self.materials = [self._read_material(m, geo) for m in icen.children("material")]
        if not self.materials:
            raise icen.error("no <material>: ICE needs at least one")
        n = len(self.materials)
        self.var_K, self.var_H = self._read_coefficient_model(mp.child("exchange_properties"), self.n_before + n)
        self.K, self.H = self._read_exchange(mp.child("exchange_properties"), self.n_before + n,
                                             skip=("heat",) if self.var_H else ())
        self.exchange = n > 1 and bool(np.any(self.K) or np.any(self.H) or self.var_K or self.var_H)
        self.slip = read_slip(mp.child("exchange_properties"), self.n_before + n, self.n_before)
        self.exchange = self.exchange or self.slip is not None
        # Uintah's hydrostatic pressure (gravity): initial press_CC and the pressure's extra cells
        # from the <isSurroundingMatl> material's rho_micro; ICE alone (MPMICE: not yet)
        surr = [m for m, mat in enumerate(self.materials) if mat.is_surrounding]
        self.surrounding = surr[-1] if surr else None
        apply_hydro = ice.get("applyHydrostaticPressure", "bool", True)
        self.hydrostatic = self.use_gravity and apply_hydro and self.n_before == 0
        if self.hydrostatic and self.surrounding is None:
            raise icen.error("with gravity, one ICE material needs <isSurroundingMatl> true </isSurroundingMatl> "
                             "(the background material of the hydrostatic pressure, as Uintah); or give "
                             "<CFD><ICE><applyHydrostaticPressure> false")
        # <Models>: Uintah's PassiveScalar, mass_momentum_energy_src and TracerParticles (MPMICE:
        # PassiveScalar; it reads its reaction models itself)
        models = read_ice_models(root, self, geo, () if self.n_before == 0 else tuple(REACTIONS))
        self.scalars, self.source_models, self.tracers = models.scalars, models.sources, models.tracers
        self.bcs = BoundaryConditions(read_bcs(root, level, self.n_before + n, self.material_names(), self.n_before,
                                               {s.name: s.matl for s in self.scalars}, self.gravity), level)
        self.lodi = self.bcs.lodi
        self.codes = np.array([m.eos.code for m in self.materials], dtype=np.int64)
        if self.conserve_energy and n > 1 and np.any(self.codes != IDEAL_GAS):
            # the equilibration (eq. 13) changes each material's rho_micro at fixed T; with
            # e = cv T + e_c(rho_micro) that changes the cold energy e_c, so total energy would
            # not be conserved: several materials must all be ideal gases (e_c = 0)
            raise self._conserve_node.error("<conserveTotalEnergy> with several materials needs ideal gases "
                                            "only (any EOS is accepted for one material)")
        if self.conserve_energy and np.any(self.codes == THOMSEN_HARTKA):
            # its energy is not cv T plus a cold energy of rho alone (the T-dependence is not linear)
            raise self._conserve_node.error("<conserveTotalEnergy> is not available with the "
                                            "Thomsen_Hartka_water EOS")
        self.params = np.array([m.eos.params() for m in self.materials]).reshape(n, MAX_PARAMS)
        self.cvs = np.array([m.cv for m in self.materials])
        # ICE alone with ideal gases only: eq. 13 has a closed form (kernels.equilibrate_ideal)
        self.all_ideal = self.n_before == 0 and n > 1 and bool(np.all(self.codes == IDEAL_GAS))
        self.gammas = np.array([m.gamma for m in self.materials])
        self.matls = list(range(n))
        self.viscous = any(m.viscosity > 0 or m.viscosity_models for m in self.materials)
        self.conduction = any(m.conductivity > 0 for m in self.materials)
        self._geom_cache = {}
        ci = ice.child("customInitialization")
        self.custom_init = CustomInitialization(ci, level) if ci is not None else None
        self.custom_profiles = [self.custom_init.resolve(m) for m in self.materials] if ci is not None else None
        if self.custom_init is not None and self.custom_init.vortices is not None and n > 1:
            raise ci.child("vortices").error("<vortices> is available with one ICE material only "
                                             f"(this deck has {n})")
        # <turbulence>: Uintah's Smagorinsky or Germano subgrid-scale viscosity (turbulence.py)
        self.turbulence = read_turbulence(ice, self)
        if self.turbulence is not None and self.n_before:
            raise ice.child("turbulence").error("<turbulence> is available for ICE alone, not in MPMICE")
        self.read_timestep_control(ice)
        # <ImplicitSolver>: semi-implicit pressure (implicit.py); absent = explicit ICE
        self.read_implicit(ice, root)
        if level.holes:
            self._check_holes(root)
        if self.lodi is not None:
            self._check_lodi(n)
        self.cv_matls = [m for m, mat in enumerate(self.materials) if mat.cv_model is not None]
        if self.cv_matls:
            self._check_cv_models(n)
        # a model owning a material's caloric EOS (gasCombustion): cv and gamma per cell, ICE
        # carrying its sensible energy (tasks.py: _carrier_cv)
        self.caloric = {mod.matl: mod for mod in self.source_models if getattr(mod, "owns_caloric_eos", False)}
        for mod in self.caloric.values():
            mod.check(self)
        self.cv_matls = sorted(set(self.cv_matls) | set(self.caloric))

    def _check_cv_models(self, n):
        """<SpecificHeatModel> is available for explicit ICE alone with one material and no LODI
        faces (Uintah's also with several, implicit and LODI)."""
        where = self.materials[self.cv_matls[0]].cv_model.node
        if n > 1:
            raise where.error(f"<SpecificHeatModel> is available with one ICE material; this deck has {n}")
        if self.implicit:
            raise where.error("<SpecificHeatModel> is available with explicit ICE only (no <ImplicitSolver>)")
        if self.lodi is not None:
            raise where.error("<SpecificHeatModel> is not available with LODI boundaries")

    def _check_holes(self, root):
        """A level whose <Box>es do not fill one box: explicit ICE with the conditions of whole
        sides (those are what was tested: tests/ice/test_l_shaped.py)."""
        what = ("<ImplicitSolver>" if self.implicit else "LODI conditions" if self.lodi is not None
                else "sub-faces (circle, rectangle, annulus)" if any(self.bcs.subfaces.values())
                else "<turbulence>" if self.turbulence is not None
                else "<Models>" if (self.scalars or self.source_models or self.tracers) else None)
        if what is not None:
            raise root.child("Grid").child("Level").error(
                f"{what} on a level whose <Box>es do not fill one rectangular box is not supported; accepted "
                "there: explicit ICE with <Face side> conditions")

    def _check_lodi(self, n):
        """LODI faces are available for explicit ICE alone with one material (Uintah's also with
        several, and in implicit ICE and MPMICE)."""
        where = self.lodi.node
        if self.n_before:
            raise where.error("LODI boundaries are available for ICE alone, not in MPMICE")
        if n > 1:
            raise where.error(f"LODI boundaries are available with one ICE material; this deck has {n}")
        if self.implicit:
            raise where.error("LODI boundaries are available with explicit ICE only (no <ImplicitSolver>)")
        if self.conserve_energy:
            raise self._conserve_node.error("<conserveTotalEnergy> is not available with LODI boundaries")

    def material_names(self):
        return [m.name for m in self.materials]

    def read_timestep_control(self, ice):
        """<TimeStepControl> as Uintah reads it (both tags required when the block is there);
        without it the explicit delT is Uintah's default, aggressive with knob 1."""
        tsc = self.timestep_control = ice.child("TimeStepControl")
        self.conservative_dt, self.knob, self.knob_diffusion = False, 1.0, 1.0
        if tsc is not None:
            self.conservative_dt = tsc.get("Scheme_for_delT_calc", "str",
                                           choices=("aggressive", "conservative")) == "conservative"
            self.knob = tsc.get("knob_for_speedSound", "float")
            if not 0.0 <= self.knob <= 1.0:
                raise tsc.child("knob_for_speedSound").error("knob_for_speedSound must be between 0 and 1")
            if tsc.has("knob_for_diffusion"):
                self.knob_diffusion = tsc.get("knob_for_diffusion", "float")
                if not self.knob_diffusion >= 0.0:
                    raise tsc.child("knob_for_diffusion").error("knob_for_diffusion must be >= 0")
        # pysus extension: the CFL limit counts only directions with more than one cell
        # (Uintah also counts the one-cell directions' spacing, which can set a 1D run's step)
        self.delt_active_dirs_only = ice.get("delT_activeDirectionsOnly", "bool", False)
        # pysus extension: in a cell where a material's volume fraction is below this, its sound
        # speed does not limit the step (Uintah's counts every material in every cell, so that a
        # hot trace of gas inside a solid can set it); its velocity still does
        self.delt_trace_vol_frac = ice.get("delT_traceVolFrac", "float", 0.0)
        if not 0.0 <= self.delt_trace_vol_frac < 1.0:
            raise ice.child("delT_traceVolFrac").error(
                f"value '{self.delt_trace_vol_frac:g}' is out of range; accepted: 0 <= value < 1 (a volume "
                "fraction below which a material's sound speed does not limit the time step; 0: every material's does)")

    def schedule_sp_vol_src(self, t, sched):
        """computeLagrangianSpecificVolume also computes sp_vol_src_CC when a deck saves it."""
        self.save_sp_vol_src = I.sp_vol_src_CC.name in getattr(sched, "output_labels", ())
        if self.save_sp_vol_src:
            t.computes(I.sp_vol_src_CC)

    def _read_material(self, node, geo):
        name = node.attr("name", default=f"ice{len(getattr(self, 'materials', []))}")
        props = node.read(MATERIAL)
        en = node.child("EOS", required=True)
        etype = en.attr("type", choices=tuple(EOS_TAGS))
        if etype in ("ideal_gas", "Stiffened_gas") and not props["gamma"] > 1.0:
            # c^2 = gamma (gamma - 1) cv T: gamma = 1 has no sound speed
            raise node.child("gamma").error(f"value '{props['gamma']:g}' is out of range; accepted: a finite "
                                            f"number > 1 (the {etype} EOS)")
        eos = make_eos(etype, {t: en.get(t, "float", above=0.0 if t in EOS_POSITIVE else None)
                               for t in EOS_TAGS[etype]})
        jc = en.child("C") if etype == "JWL" else None
        if jc is not None:
            # Uintah's JWL reads A, B, R1, R2, om, rho0 only (JWLC's third term is <C>)
            jc.mark_used()
            print(f"pysus: note: {jc.filename}:{jc.line}: <C> of the JWL EOS has no effect (Uintah's JWL "
                  f"does not read it either; <C> belongs to JWLC)", file=sys.stderr)
        gc = en.child("gas_constant") if etype == "ideal_gas" else None
        if gc is not None:
            # Uintah's IdealGas reads no tags: R follows from cv and gamma, R = (gamma - 1) cv
            gc.mark_used()
            print(f"pysus: note: {gc.filename}:{gc.line}: <gas_constant> of the ideal_gas EOS has no effect "
                  f"(Uintah's IdealGas does not read it either; R = (gamma - 1) cv)", file=sys.stderr)
        models = self._read_viscosity_models(node, props)
        cv_model = read_specific_heat_model(node)
        if cv_model is not None and self.n_before:
            raise cv_model.node.error("<SpecificHeatModel> is available for ICE alone, not in MPMICE")
        objects = []
        gos = node.children("geom_object")
        for go in gos:
            objects.append((geo.read_object(go, outside_ok=True), go.read(GEOM)))
            self._check_initial_state(go, objects[-1][1], eos, props, cv_model)
        if not objects:
            raise node.error("material has no <geom_object> (initial condition)")
        outside = self._check_absent(node, geo, objects, gos)
        mat = Material(name, eos, props, objects)
        mat.viscosity_models = models
        mat.object_nodes = gos
        mat.first_object_outside = bool(outside and outside[0])
        mat.cv_model = cv_model
        return mat

    def _check_absent(self, node, geo, objects, gos):
        """Uintah's idiom for a material that starts with no mass (a reaction's product): its
        geometry objects all lie outside the domain. With other materials present it is
        accepted, and the material starts as Uintah's initializeCells leaves it in cells no
        object covers: volume fraction 0 plus the trace tiny_rho, temperature and velocity
        from its first object. An object outside beside one inside contributes nothing but
        those first-object values (Uintah's MPMICE decks DDT, BurnRate, ... use it): accepted
        with a note. Refused: the problem's only material with all its objects outside.
        Returns which objects lie outside (None without a level)."""
        if geo.level is None:
            return None
        out = [geo.outside(piece) for piece, _ in objects]
        if not any(out):
            return out
        k = out.index(True)
        if all(out):
            if getattr(self, "n_all", 1) > 1:
                return out
            geo.check_overlap(objects[k][0], gos[k], " (a material whose objects all lie outside starts absent, "
                              "Uintah's idiom for a reaction's product, only where other materials fill the domain)")
        go = gos[k]
        print(f"pysus: note: {go.filename}:{go.line}: this geometry object lies wholly outside the domain and "
              f"puts no material anywhere (as in Uintah){' (its values fill the cells no object covers)' if k == 0 else ''}",
              file=sys.stderr)
        return out

    def _read_viscosity_models(self, node, props):
        """<dynamicViscosityModels>: Uintah's Sutherland (a, b) and SpongeLayer (maxDynamicViscosity
        in a box's cells), applied in that order (Uintah's call order) to the interior cells of
        the viscosity field; [("Sutherland", a, b) | ("SpongeLayer", mu, lo_index, hi_index)]."""
        vm = node.child("dynamicViscosityModels")
        if vm is None:
            return []
        lv = self.level
        out = []
        for mn in vm.children("Model"):
            kind = mn.attr("name", choices=("Sutherland", "SpongeLayer"))
            if kind == "Sutherland":
                out.append((0, ("Sutherland", mn.get("a", "float", 0.0), mn.get("b", "float", 0.0))))
                continue
            mu = mn.get("maxDynamicViscosity", "float", at_least=0.0)
            box = mn.child("box", required=True)
            box.attr("label", default="")
            lo = np.maximum(np.array(box.get("min", "vector"), dtype=np.float64), lv.anchor)
            hi = np.minimum(np.array(box.get("max", "vector"), dtype=np.float64), lv.upper)
            ilo = np.floor((lo - lv.anchor) / lv.dx + 0.5).astype(np.int64)
            ihi = np.floor((hi - lv.anchor) / lv.dx + 0.5).astype(np.int64)
            if np.any(ihi - ilo < 1):
                raise box.error("the sponge layer's box holds no cell in some direction; accepted: at least "
                                "one cell between min and max")
            out.append((1, ("SpongeLayer", mu, ilo, ihi)))
        if out and self.n_before:
            raise vm.error("<dynamicViscosityModels> are available for ICE alone, not in MPMICE")
        if out and props["dynamic_viscosity"] > 0.0:
            raise vm.error("<dynamicViscosityModels> with a non-zero <dynamic_viscosity> is not available "
                           "(its per-cell diffusion step limit); accepted: the models with dynamic_viscosity 0")
        return [m for _, m in sorted(out, key=lambda e: e[0])]

    def _check_initial_state(self, go, values, eos, props, cv_model=None):
        """Say when <pressure> is not the EOS pressure at <density> and <temperature>: like
        Uintah, the run starts from those two."""
        if not (values["volumeFraction"] == -1.0 or 0.0 <= values["volumeFraction"] <= 1.0):
            raise go.child("volumeFraction").error("<volumeFraction> must be between 0 and 1 (or -1: the geometry's)")
        if self.n_before:           # MPMICE starts its fluids from <pressure> and <temperature>
            return
        params = np.zeros(MAX_PARAMS)
        params[:len(eos.params())] = eos.params()
        cv = props["specific_heat"] if cv_model is None else cv_model.cv(values["temperature"])
        p_eos = float(eos_press_eos(eos.code, params, values["density"], values["temperature"], cv, props["gamma"])[0])
        p_deck = values["pressure"]
        if abs(p_eos - p_deck) > 1e-6 * max(abs(p_deck), abs(p_eos)) and world_rank() == 0:
            node = go.child("pressure")
            print(f"pysus: note: {node.filename}:{node.line}: <pressure> {p_deck:g} Pa is not the EOS pressure "
                  f"{p_eos:g} Pa at <density> {values['density']:g} and <temperature> {values['temperature']:g}; "
                  "as in Uintah, the state starts from the density and temperature", file=sys.stderr)

    @staticmethod
    def _read_coefficient_model(node, n):
        """<exchange_properties><CoefficientModel>: which of <momentum> and <heat> take Uintah's
        linearVariation coefficients (from each cell's mass ratio, kernels.mass_ratio_coefficients)
        in the cell-centred exchange; (False, False) without it."""
        cm = node.child("CoefficientModel") if node is not None else None
        if cm is None or n == 1:
            return False, False
        return tuple(cm.get(tag, "str", "ConstantCoeff", choices=("ConstantCoeff", "linearVariation"))
                     == "linearVariation" for tag in ("momentum", "heat"))

    @staticmethod
    def _read_exchange(node, n, skip=()):
        """The constant coefficient matrices K and H of <exchange_coefficients>; a tag in `skip`
        (heat under a linearVariation <CoefficientModel>, which Uintah does not count) is left zero."""
        K, H = np.zeros((n, n)), np.zeros((n, n))
        if node is None:
            return K, H
        if n == 1:      # as Uintah (ExchangeCoefficients::problemSetup): one material has no pair to exchange
            node.mark_used()
            return K, H
        ec = node.child("exchange_coefficients")
        if ec is None:
            return K, H
        pairs = [(a, b) for a in range(n) for b in range(a + 1, n)]
        for tag, mat in (("momentum", K), ("heat", H)):
            c = ec.child(tag)
            if c is None:
                continue
            if tag in skip:
                c.mark_used()
                continue
            txt = c.text().strip()
            try:
                vals = [float(v) for v in txt.strip("[]").replace(",", " ").split()]
            except ValueError:
                raise c.error(f"'{txt}' is not a list of numbers [K01, K02, ..., K12, ...]") from None
            if len(vals) != len(pairs):
                raise c.error(f"{len(vals)} coefficients for {n} materials; expected {len(pairs)} "
                              "(pairs 0-1, 0-2, ..., 1-2, ...)")
            if any(v < 0 for v in vals):
                raise c.error("exchange coefficients must be >= 0")
            for (a, b), v in zip(pairs, vals):
                mat[a, b] = mat[b, a] = v
        return K, H

    # -- scheduling -----------------------------------------------------------------------
    def schedule_initialize(self, level, sched):
        t = Task("ICE::actuallyInitialize", self.initialize, self.matls) \
            .computes(I.rho_CC).computes(I.vel_CC).computes(I.temp_CC).computes(I.sp_vol_CC) \
            .computes(I.speedSound_CC).computes(I.press_CC, matls=[0])
        t.computes(I.specific_heat).computes(I.gamma)
        sched.add_task(t)
        for model in self.scalars + self.tracers:
            model.schedule_initialize(sched)
        for model in self.caloric.values():      # its species and the mixture's cv, gamma
            model.schedule_initialize(sched)

    def schedule_transported(self, sched, matls):
        """Uintah's computeLagrangian_Transported_Vars: the models' scalars as m f (after mass_L_CC)."""
        if not self.scalars:
            return
        t = Task("ICE::computeLagrangian_Transported_Vars", self.lagrangian_transported, matls) \
            .requires(NEW, I.mass_L_CC)
        for model in self.scalars:
            t.requires(OLD, model.f, matls=[model.matl]).requires(NEW, model.src, matls=[model.matl]) \
                .computes(model.f_L, matls=[model.matl])
        sched.add_task(t)

    def advect_scalars(self, t, gadv):
        """The advection task t carries the models' m f too and computes their f."""
        for model in self.scalars:
            t.requires(NEW, model.f_L, G, gadv, matls=[model.matl]).computes(model.f, matls=[model.matl])

    def schedule_compute_stable_timestep(self, level, sched):
        g = (G, 1) if self.conservative_dt else ()     # the swept volume reads neighbours
        step = sched.graph_name == "timestep"
        t = Task("ICE::computeStableTimestep", self.stable_timestep_step if step else self.stable_timestep,
                 self.matls) \
            .requires(NEW, I.vel_CC, *g).requires(NEW, I.temp_CC, *g).requires(NEW, I.sp_vol_CC, *g) \
            .requires(NEW, I.speedSound_CC, *g).computes(L.delT)
        if self.delt_trace_vol_frac > 0.0:
            t.requires(NEW, I.rho_CC, *g)
        if self.cv_matls:
            t.requires(NEW, I.specific_heat, matls=self.cv_matls)
        transport = self._transport_matls()
        if transport:
            t.requires(NEW, I.gamma, matls=transport)
            if step:
                t.requires(NEW, I.viscosity, matls=transport).requires(NEW, I.thermalCond, matls=transport)
        sched.add_task(t)

    def _transport_matls(self):
        """The materials whose viscosity and thermal conductivity a model gives per cell (those
        with a model owning their caloric EOS, and a non-zero <dynamic_viscosity> or
        <thermal_conductivity>, which turn ICE's diffusion terms on as in Uintah)."""
        return sorted(m for m in self.caloric
                      if self.materials[m].viscosity > 0 or self.materials[m].conductivity > 0)

    def schedule_time_advance(self, level, sched):
        m0 = [0]
        many = len(self.matls) > 1
        gadv = 2 if self.second_order else 1
        dirs = [d for d in range(3) if self.dims[d]]
        lodi = self.lodi is not None
        if lodi:
            sched.add_task(Task("ICE::maxMach_on_Lodi_BC_Faces", self.max_mach_faces, self.matls)
                           .requires(OLD, I.vel_CC).requires(OLD, I.speedSound_CC).computes(I.maxMach_faces))
        cvm = self.cv_matls
        # Uintah's computeThermoTransportProperties: cv(T) of the step's start (runs only with a
        # <SpecificHeatModel> or when specific_heat or gamma is saved)
        t = Task("ICE::computeSpecificHeat", self.specific_heat_field, self.matls) \
            .requires(OLD, I.temp_CC).computes(I.specific_heat).computes(I.gamma)
        for model in self.caloric.values():
            for s in model.species:
                t.requires(OLD, s.f, matls=[model.matl])
        sched.add_task(t)
        t = Task("ICE::computeEquilibrationPressure", self.equilibration_pressure, self.matls) \
            .requires(OLD, I.rho_CC).requires(OLD, I.temp_CC).requires(OLD, I.sp_vol_CC) \
            .computes(I.press_equil_CC, matls=m0).computes(I.vol_frac_CC).computes(I.sp_vol_CC) \
            .computes(I.speedSound_CC)
        if cvm:
            t.requires(NEW, I.specific_heat, matls=cvm)
        if self.caloric:
            t.requires(NEW, I.gamma, matls=sorted(self.caloric))
        if many:
            t.requires(OLD, I.press_CC, matls=m0)
        if lodi:
            t.requires(OLD, I.vel_CC).requires(NEW, I.maxMach_faces)
        sched.add_task(t)
        for model in self.scalars + self.source_models + self.tracers:    # Uintah's computeModelSources
            model.schedule_sources(sched)
        for model in self.tracers:          # the tracer particles to their new patches, at the end of the step
            model.schedule_relocation(sched)
            model.schedule_diagnostics(sched)

        t = Task("ICE::computeVel_FC", self.vel_fc, self.matls) \
            .requires(OLD, L.delT).requires(OLD, I.rho_CC, G, 1).requires(OLD, I.vel_CC, G, 1) \
            .requires(NEW, I.sp_vol_CC, G, 1).requires(NEW, I.press_equil_CC, G, 1, matls=m0)
        for d in dirs:
            t.computes(I.FC_VEL[d])
            if not self.exchange and not self.implicit:
                t.computes(I.FC_VEL_ME[d])
        sched.add_task(t)

        if self.implicit:
            # eqs. 28-30 with the pressure increment implicit: outer iteration around a PCG solve
            self.schedule_implicit_pressure(sched, dirs)
        elif self.exchange:
            t = Task("ICE::addExchangeContributionToFCVel", self.exchange_fc, self.matls) \
                .requires(OLD, L.delT).requires(NEW, I.vol_frac_CC, G, 1).requires(NEW, I.sp_vol_CC, G, 1)
            for d in dirs:
                t.requires(NEW, I.FC_VEL[d], G, 1).computes(I.FC_VEL_ME[d])
            sched.add_task(t)

        if not self.implicit:
            t = Task("ICE::computeDelPressAndUpdatePressCC", self.delp_press, self.matls) \
                .requires(OLD, L.delT).requires(NEW, I.sp_vol_CC).requires(NEW, I.speedSound_CC) \
                .requires(NEW, I.press_equil_CC, matls=m0) \
                .computes(I.delP_Dilatate, matls=m0).computes(I.press_CC, matls=m0)
            if many:
                t.requires(NEW, I.vol_frac_CC, G, self.delp_vol_frac_ghost)
            else:
                t.requires(NEW, I.vol_frac_CC)
            for d in dirs:
                t.requires(NEW, I.FC_VEL_ME[d], G, 1)
            if lodi:
                t.requires(OLD, I.rho_CC).requires(OLD, I.vel_CC).requires(NEW, I.maxMach_faces)
            sched.add_task(t)

        t = Task("ICE::computePressFC", self.press_fc, self.matls) \
            .requires(NEW, I.press_CC, G, 1, matls=m0).requires(OLD, I.rho_CC, G, 1)
        for d in dirs:
            t.computes(I.PRESS_FC[d], matls=m0)
        sched.add_task(t)
        sched.add_task(Task("ICE::computeDelP_MassX", self.delp_mass_exchange, m0)   # only when saved
                       .requires(NEW, I.press_CC, matls=m0).requires(NEW, I.press_equil_CC, matls=m0)
                       .requires(NEW, I.delP_Dilatate, matls=m0).computes(I.delP_MassX, matls=m0))
        sched.add_task(Task("ICE::computeTerm2", self.mass_exchange_term, self.matls)   # only when saved
                       .requires(NEW, I.delP_MassX, matls=m0).requires(NEW, I.vol_frac_CC)
                       .requires(NEW, I.sp_vol_CC).requires(NEW, I.speedSound_CC).computes(I.term2, matls=m0))

        transport = self._transport_matls()
        own_mu = [m for m in self.matls if m not in self.caloric]     # (the models compute the others')
        if self.viscous and own_mu:
            sched.add_task(Task("ICE::computeThermoTransportProperties", self.viscosity_field, own_mu)
                           .requires(OLD, I.temp_CC).computes(I.viscosity))                 # only when saved
        if self.viscous:
            turb = self.turbulence
            if turb is not None:
                # Uintah's Turbulence::callTurb: the subgrid-scale viscosity from the face velocities
                t = Task("ICE::computeTurbViscosity", self.turbulent_viscosity, self.matls) \
                    .requires(OLD, I.rho_CC, G, 1).requires(NEW, I.vol_frac_CC, G, 1) \
                    .requires(OLD, I.vel_CC, G, 2 if turb.dynamic else 1) \
                    .computes(I.turb_viscosity_CC).computes(I.total_viscosity_CC)
                for d in dirs:
                    t.requires(NEW, I.FC_VEL_ME[d], G, turb.ghost)
                sched.add_task(t)
            t = Task("ICE::viscousShearStress", self.viscous_source, self.matls) \
                .requires(OLD, I.vel_CC, G, 1).requires(NEW, I.vol_frac_CC, G, 1) \
                .requires(OLD, I.temp_CC, G, 1).computes(I.viscous_src_CC)
            if turb is not None:
                t.requires(NEW, I.total_viscosity_CC, G, 1)
            if transport:
                t.requires(NEW, I.viscosity, G, 1, matls=transport)
            sched.add_task(t)
            t = Task("ICE::computeTauFC", self.tau_fc, self.matls) \
                .requires(OLD, I.vel_CC, G, 1).requires(NEW, I.vol_frac_CC, G, 1) \
                .requires(OLD, I.temp_CC, G, 1)    # only when saved
            if turb is not None:
                t.requires(NEW, I.total_viscosity_CC, G, 1)
            if transport:
                t.requires(NEW, I.viscosity, G, 1, matls=transport)
            for d in dirs:
                t.computes(I.TAU_FC[d])
            sched.add_task(t)
        if self.conduction:
            t = Task("ICE::computeHeatFlux", self.conduction_source, self.matls) \
                .requires(OLD, L.delT).requires(OLD, I.temp_CC, G, 1).requires(NEW, I.vol_frac_CC, G, 1) \
                .computes(I.heatCond_src_CC)
            if transport:
                t.requires(NEW, I.thermalCond, G, 1, matls=transport)
            sched.add_task(t)

        t = Task("ICE::computeLagrangianValues", self.lagrangian_values, self.matls) \
            .requires(OLD, L.delT).requires(OLD, I.rho_CC).requires(OLD, I.vel_CC).requires(OLD, I.temp_CC) \
            .requires(NEW, I.vol_frac_CC).requires(NEW, I.sp_vol_CC).requires(NEW, I.speedSound_CC) \
            .requires(NEW, I.press_CC, matls=m0).requires(NEW, I.delP_Dilatate, matls=m0) \
            .computes(I.mass_L_CC).computes(I.mom_L_CC).computes(I.int_eng_L_CC)
        for d in dirs:
            t.requires(NEW, I.PRESS_FC[d], G, 1, matls=m0)
        lodi_caloric = lodi and bool(self.caloric)      # its exchange needs the species' m Y_L: a task of its own
        if not self.exchange and not lodi_caloric:
            t.computes(I.mom_L_ME_CC).computes(I.int_eng_L_ME_CC)
        if lodi and not lodi_caloric:
            t.requires(NEW, I.maxMach_faces)
        if self.conserve_energy:
            t.computes(I.tot_eng_L_CC)
            if not self.exchange:
                t.computes(I.tot_eng_L_ME_CC)
            for d in dirs:
                t.requires(NEW, I.FC_VEL_ME[d], G, 1)
        if self.viscous:
            t.requires(NEW, I.viscous_src_CC)
        if self.conduction:
            t.requires(NEW, I.heatCond_src_CC)
        if cvm:
            t.requires(NEW, I.specific_heat, matls=cvm)
        for model in self.source_models:
            model.lagrangian_requires(t)
        sched.add_task(t)
        sched.add_task(Task("ICE::computeMomentumSource", self.momentum_source, self.matls)   # only when saved
                       .requires(NEW, I.mom_L_CC).requires(OLD, I.rho_CC).requires(OLD, I.vel_CC)
                       .computes(I.mom_source_CC))

        if self.exchange:
            t = Task("ICE::addExchangeToMomentumAndEnergy", self.exchange_cc, self.matls) \
                .requires(OLD, L.delT).requires(NEW, I.mass_L_CC).requires(NEW, I.mom_L_CC) \
                .requires(NEW, I.int_eng_L_CC).requires(NEW, I.vol_frac_CC).requires(NEW, I.sp_vol_CC) \
                .computes(I.mom_L_ME_CC).computes(I.int_eng_L_ME_CC)
            if self.conserve_energy:
                t.requires(NEW, I.tot_eng_L_CC).computes(I.tot_eng_L_ME_CC)
            sched.add_task(t)

        t = Task("ICE::computeLagrangianSpecificVolume", self.lagrangian_sp_vol, self.matls) \
            .requires(OLD, L.delT).requires(NEW, I.mass_L_CC).requires(NEW, I.sp_vol_CC) \
            .requires(NEW, I.vol_frac_CC).requires(NEW, I.speedSound_CC) \
            .requires(NEW, I.delP_Dilatate, matls=m0).requires(NEW, I.press_CC, matls=m0).computes(I.sp_vol_L_CC)
        if many:
            t.requires(NEW, I.int_eng_L_ME_CC).requires(OLD, I.temp_CC)
        self.schedule_sp_vol_src(t, sched)
        sched.add_task(t)

        self.schedule_transported(sched, self.matls)
        if lodi_caloric:
            # Uintah's exchange task with a model-owned caloric EOS: after computeLagrangian_Transported_Vars
            t = Task("ICE::addExchangeToMomentumAndEnergy", self.lodi_exchange_caloric, self.matls) \
                .requires(NEW, I.mass_L_CC).requires(NEW, I.mom_L_CC).requires(NEW, I.int_eng_L_CC) \
                .requires(OLD, I.rho_CC).requires(NEW, I.press_CC, matls=m0).requires(NEW, I.speedSound_CC) \
                .requires(NEW, I.maxMach_faces).requires(NEW, I.gamma) \
                .computes(I.mom_L_ME_CC).computes(I.int_eng_L_ME_CC)
            for model in self.caloric.values():
                for sp in model.species:
                    t.requires(NEW, sp.f_L, matls=[model.matl])
            sched.add_task(t)

        t = Task("ICE::advectAndAdvanceInTime", self.advect_and_advance, self.matls) \
            .requires(OLD, L.delT).requires(NEW, I.mass_L_CC, G, gadv).requires(NEW, I.mom_L_ME_CC, G, gadv) \
            .requires(NEW, I.int_eng_L_ME_CC, G, gadv).requires(NEW, I.sp_vol_L_CC, G, gadv) \
            .requires(NEW, I.vol_frac_CC) \
            .computes(I.rho_CC).computes(I.vel_CC).computes(I.temp_CC).modifies(I.sp_vol_CC)
        for d in dirs:
            t.requires(NEW, I.FC_VEL_ME[d], G, 1)
        if self.conserve_energy:
            t.requires(NEW, I.tot_eng_L_ME_CC, G, gadv)
        self.advect_scalars(t, gadv)
        if lodi:
            t.requires(NEW, I.press_CC, matls=m0).requires(NEW, I.speedSound_CC).requires(NEW, I.maxMach_faces)
            if self.caloric:
                t.requires(NEW, I.gamma, matls=sorted(self.caloric))
        if cvm:
            t.requires(NEW, I.specific_heat, matls=cvm)
        sched.add_task(t)
        if lodi:
            t = Task("ICE::LODI_Li", self.lodi_li, self.matls) \
                .requires(NEW, I.rho_CC).requires(NEW, I.vel_CC).requires(NEW, I.press_CC, matls=m0) \
                .requires(NEW, I.speedSound_CC).requires(NEW, I.maxMach_faces)    # only when saved
            for lab in I.LODI_Li:
                t.computes(lab)
            sched.add_task(t)
        for model in self.scalars:
            model.schedule_conservation(sched, dirs)

        t = Task("ICE::sumConservedQuantities", self.conserved_sums, self.matls) \
            .requires(OLD, L.delT).requires(NEW, I.rho_CC).requires(NEW, I.vel_CC).requires(NEW, I.temp_CC) \
            .computes(I.TotalMass).computes(I.KineticEnergy).computes(I.TotalIntEng).computes(I.TotalMomentum)
        for d in dirs:
            t.requires(NEW, I.FC_VEL_ME[d])
        if cvm:
            t.requires(NEW, I.specific_heat, matls=cvm)
        for model in self.caloric.values():
            for sp in model.species:
                t.requires(NEW, sp.f, matls=[model.matl])
        sched.add_task(t)
        sched.add_task(Task("ICE::computeMach", self.compute_mach, self.matls)
                       .requires(NEW, I.vel_CC).requires(NEW, I.speedSound_CC).computes(I.mach))
