"""MPMICE: MPM solids and ICE fluids coupled through the multi-field equations (paper 000).

`<SimulationComponent type="mpmice">` (and "rmpmice": the same coupling with solids whose
motion is prescribed, Uintah's RigidMPM: zero stress, no pressure force, no delT limit,
moved by their own velocity or <contact type="rigid">; rigid.py). Reads
<MPM>, <CFD><ICE>, <MaterialProperties><MPM> and <ICE>, <exchange_properties> through
the MPM and ICE components (setup.py): MPM materials first, then ICE, one global
material index space. One timestep, paper 000 sec. 3.3 (Uintah's MPMICE.cc order):

  1  MPM::interpolateParticlesToGrid, MPMICE::interpolateNCToCC_0
  2  MPMICE::computeEquilibrationPressure     (ICE's body, all materials, solids with
                                               the sec. 3.1 threshold EOS)
  3  ICE::computeVel_FC, addExchangeContributionToFCVel   (all materials)
  5  ICE::computeDelPressAndUpdatePressCC, 6 ICE::computePressFC   (all materials)
  7  MPMICE::interpolatePAndGradP (mean pressure in the solid's internal force),
     MPM::computeAndIntegrateAcceleration; ICE viscous stress (fluids)
  8-9  MPMICE::computeLagrangianValuesMPM, ICE::computeLagrangianValues (fluids)
  10 ICE::addExchangeToMomentumAndEnergy (all), 11 computeLagrangianSpecificVolume (all)
  -> MPMICE::computeCCVelAndTempRates, interpolateCCToNC (the solid's change to the nodes);
     a solid with a nonzero <heat> coefficient to a fluid carries p.temperature (MPM's
     thermal.py) and takes part in the energy exchange like a fluid: computeCCTempRates,
     interpolateCCToNC_T carry its dT/dt back to the nodes and particles (tasks.py).
     Fluids with thermal_conductivity > 0 conduct (ICE::computeHeatFlux).
  13 MPM grid BCs, interpolateToParticlesAndUpdate, computeStressTensor, relocation
  12 ICE::advectAndAdvanceInTime (fluids; with prescribed solids unless <advection
     openFaceTransfers="false">, else with "true", where a
     solid's particles advance through a cell toward a more open neighbour, the fluid they
     displace crosses the face as open as that neighbour: tasks.open_faces, docs/MPMICE.md)
The ICE and MPM tasks are those components' own task bodies; this module only
declares them over the right material sets and interleaves the coupling tasks.
With <CFD><ICE><ImplicitSolver> steps 3-5 are ICE's semi-implicit pressure solve
(components/ice/implicit.py) over all materials, as Uintah's MPMICE implicit branch:
eq. P's compressibility sums theta v / c^2 of solids and fluids, its face terms use the
exchange-corrected face specific volumes (the K = 1e15 coupling), the outer iteration
recomputes every material's exchanged face velocities; delT then comes from the flow
speed (and MPM's wave speed, except for prescribed solids).

<CFD><ICE><ADD_HEAT> (add_heat_matls, add_heat_coeff, add_heat_t_start, add_heat_t_final)
adds dt coeff rho_CC V to int_eng_L_CC of the named fluids where their volume fraction
exceeds 0.001 (Uintah's accumulateEnergySourceSinks). Uintah's diagnostic labels
mom_source_CC, intE_source_CC and Tdot are computed by tasks that only run when a <save>
names them. Validation: inputs/MPMICE/ slab_rest, piston, pressurized_cylinder (paper
sec. 4.1, scripts/accuracy_cost.py cylinder), piston_validation (sec. 4.2, implicit,
scripts/piston_validation.py), wedge_mach3 (sec. 4.3, scripts/wedge_shock_angle.py);
Uintah's symAnnulus.ups and pistonValidation.ups run unchanged.

<exchange_properties><Model type="slip">: Uintah's slip exchange (slip.py schedules its surface
normals, mean free path and face coefficients before step 3; ICE's exchange tasks read them).
ICE's TracerParticles model rides on a fluid; its particles relocate with the MPM particles in
the step's one relocation task.
"""
from __future__ import annotations

import sys

import numpy as np

from components.ice import labels as I
from components.mpm import labels as M
from framework import labels as FL
from framework.component import Component, register
from components.models import read_models
from framework.geometry import GeometryReader
from framework.task import NEW, OLD, Task
from framework.variables import Ghost

from . import labels as MI
from .rigid import RigidSolid, activate_master_contact, describe
from .setup import ICEinMPMICE, MPMinMPMICE
from .slip import SlipTasks
from .tasks import MPMICETasks, _Capture

# the conservation sums each fluid gets (Uintah's conservationTest); the first three also summed
# with the particles' under their own names
SUMS = (I.TotalMass, I.KineticEnergy, I.TotalMomentum, I.TotalIntEng)

G = Ghost.AROUND_CELLS
STATE = (I.rho_CC, I.vel_CC, I.temp_CC)
MPM_AFTER = "MPM::computeAndIntegrateAcceleration"


class _Recorder:
    """Collects the tasks a component schedules; passes the particle set-up through."""

    def __init__(self, sched):
        self.sched, self.tasks = sched, []

    def add_task(self, task):
        self.tasks.append(task)
        return task

    def __getattr__(self, name):
        return getattr(self.sched, name)


@register("mpmice", "rmpmice")
class MPMICE(MPMICETasks, Component):
    """Fluid-structure interaction: explicit MPM solids in explicit multi-material ICE."""

    analysis_modules = ("particleExtract",)    # <DataAnalysis> modules this component reads itself
    tiny = 1e-12        # solid density added in every cell, kg/m^3 (Uintah's d_TINY_RHO)

    def problem_setup(self, root, level):
        self.level = level
        self.names_used = root.child("SimulationComponent").attr("type")
        if not hasattr(root, "_geometry_reader"):
            root._geometry_reader = GeometryReader(level)     # one label namespace for MPM and ICE objects
        mp = root.child("MaterialProperties", required=True)
        ice_node = mp.child("ICE", required=True)
        n_ice = len(ice_node.children("material"))
        mpm_node = mp.child("MPM", required=True)
        n_all = len(mpm_node.children("material")) + n_ice
        for cm in root.child("MaterialProperties").child("MPM").children("material"):
            c = cm.child("constitutive_model")
            if c is not None and c.has("useModifiedEOS"):
                c.get("useModifiedEOS", "bool")        # the solid's EOS below rho0 (setup.solid_eos)
        self.mpm = MPMinMPMICE(n_all)
        if self.rigid:
            self.mpm.material_class = RigidSolid
        self.mpm.problem_setup(root, level)
        if self.mpm.kind not in ("linear", "gimp"):
            raise root.child("MPM").child("interpolator").error(
                f"{self.mpm.kind} is not implemented with MPMICE; accepted there: linear, gimp")
        activate_master_contact(self.mpm.contact)
        if not self.rigid and self.mpm.axes not in (1, 3, 7):
            raise root.child("Grid").error(
                "MPMICE with deformable solids needs the active directions first (x, xy or xyz; the "
                "pressure force on the particles assumes it); rmpmice (prescribed solids) accepts any")
        nm = len(self.mpm.materials)
        for mat in self.mpm.materials:          # the solid's temperature enters the exchange and the gas's EOS
            for obj in mat.objects:
                if "node" in obj and obj["temperature"] <= 0.0:
                    raise obj["node"].child("temperature").error(
                        "a solid at 0 K is accepted by MPM alone, not with MPMICE (its temperature enters "
                        "the heat exchange and the gas's EOS in mixed cells); accepted: a number > 0")
        for mat in self.mpm.materials:          # visco_scram's own solid EOS options
            flag = mat.params.eos_flag() if hasattr(mat.params, "eos_flag") else None
            cm = mat.node.child("constitutive_model")
            if flag == "useJWLEOS":             # Uintah's ViscoScram JWL (ice/eos.py SOLID_JWL)
                missing = [t for t in ("A", "B", "R1", "R2", "om", "Cv") if not cm.has(t)]
                if missing:
                    raise cm.error(f"<useJWLEOS> true needs <{'>, <'.join(missing)}> (the solid's JWL EOS)")
            elif flag:
                raise cm.child(flag).error(
                    f"<{flag}> true is not implemented in MPMICE (the solid's EOS is ViscoScram's standard "
                    "one, or <useJWLEOS>'s JWL); accepted: false")
        self.mpm_matls = list(range(nm))
        for m in self.mpm.materials:
            if m.model_name == "ArenaSoil":
                raise m.node.child("constitutive_model").error(
                    "ArenaSoil in MPMICE (its Murnaghan EOS of <K0_Murnaghan_EOS>, <n_Murnaghan_EOS>) is not "
                    "implemented; accepted there: the other MPM models")
        cv = [_specific_heat(m) for m in self.mpm.materials]
        node = root.child("MPMICE")
        self.gas_start = "particles" if self.rigid else "geometry"
        if node is not None and node.has("gas_start"):      # pysus's own start (docs/MPMICE.md)
            self.gas_start = node.get("gas_start", "str", choices=("geometry", "particles"))
        # prescribed solids with pysus's particle start (unscaled: setup.solid_eos) take a Murnaghan stand-in
        self.ice = ICEinMPMICE(self.mpm.materials, cv, self.rigid and self.gas_start == "particles", self.rigid)
        self.ice.problem_setup(root, level)
        self.ice.coupling = self          # the fluids' advection next to the solids (tasks.open_faces)
        if self.ice.implicit:
            self.may_recompute = self.ice.may_recompute      # iters_before_timestep_restart
        if self.ice.conserve_energy:
            raise self.ice._conserve_node.error("<conserveTotalEnergy> is not available with MPMICE")
        # false: the Temperature face conditions leave the solids' nodes free (Uintah sets them: tasks.py)
        self.solid_temperature_bcs = node.get("solid_temperature_bcs", "bool", True) if node is not None else True
        self.setup_solid_heat()           # p.temperature and the solid's heat exchange (tasks.py)
        self.all_matls = list(range(n_all))
        self.materials = self.ice.materials
        self.dims_i = np.array(self.ice.dims, dtype=np.int64)
        self.models = read_models(root, self)        # <Models> (components/models), else None
        if self.models is not None and self.ice.implicit:
            self.ice.mass_exchange = self.models     # the burned mass in eq. P (ice/implicit.py)
        self.solid_temp = {m: mat.objects[0]["temperature"] for m, mat in enumerate(self.mpm.materials)}
        self.add_heat = _read_add_heat(root.child("CFD").child("ICE").child("ADD_HEAT"), self.ice.ice_matls)
        self.slip = SlipTasks(self) if self.ice.slip is not None else None   # <Model type="slip">
        # true: pysus's rule for fluid slivers in solid-filled cells (tasks.exchange); Uintah has none
        self.trace_temperatures = node.get("trace_temperatures", "bool", False) if node is not None else False
        # true: a compressed ideal gas's flow work at most the adiabat's (adiabatic.py); Uintah has none
        self.adiabatic_compression = node.get("adiabatic_compression", "bool", False) if node is not None else False

    def material_names(self):
        return self.ice.material_names()

    # -- scheduling -----------------------------------------------------------------------------
    def schedule_initialize(self, level, sched):
        self.mpm.schedule_initialize(level, sched)
        ng = self.mpm.ng
        t = Task("MPMICE::actuallyInitialize", self.initialize_fluids, self.ice.ice_matls) \
            .computes(I.rho_CC).computes(I.vel_CC).computes(I.temp_CC).computes(I.sp_vol_CC) \
            .computes(I.speedSound_CC).computes(I.press_CC, matls=[0])
        for lab in [M.pX, M.pMass, M.pVolume] + ([M.pSize] if self.mpm.kind == "gimp" else []):
            t.requires(NEW, lab, Ghost.AROUND_NODES, ng, matls=self.mpm_matls)
        sched.add_task(t)
        if self.mpm.thermal or self.models is not None:     # read by step 1 and the burn models
            sched.add_task(Task("MPMICE::initializeSolidTemperature", self.initialize_solid_temperature,
                                self.mpm_matls).computes(I.temp_CC))
        for model in self.ice.scalars + self.ice.tracers:      # ICE's PassiveScalar, TracerParticles models
            model.schedule_initialize(sched)
        if self.models is not None:             # the reaction models' own state (Unsteady_Burn)
            self.models.schedule_initialize(sched)

    def schedule_compute_stable_timestep(self, level, sched):
        fn = self.stable_timestep_flow if self.ice.implicit or self.rigid else self.stable_timestep
        g = (Ghost.AROUND_CELLS, 1) if self.ice.conservative_dt else ()
        t = Task("MPMICE::computeStableTimestep", fn, self.ice.ice_matls) \
            .requires(NEW, I.vel_CC, *g).requires(NEW, I.temp_CC, *g).requires(NEW, I.sp_vol_CC, *g) \
            .requires(NEW, I.speedSound_CC, *g).requires(NEW, M.WaveSpeed).computes(FL.delT)
        if self.ice.delt_trace_vol_frac > 0.0:          # <delT_traceVolFrac>: the fluids' volume fractions
            t.requires(NEW, I.rho_CC, *g)
        sched.add_task(t)

    def schedule_time_advance(self, level, sched):
        if self.rigid and not self._described and sched.comm.rank == 0:
            print(describe(self.mpm, self.mpm_matls), file=sys.stderr)
        self._described = True
        if self.models is not None:                 # reaction tasks, after the tasks they follow
            sched = self.models.hook(sched)
        rec = _Recorder(sched)
        self.mpm.schedule_time_advance(level, rec)
        names = [t.name for t in rec.tasks]
        cut = names.index(MPM_AFTER)
        before, acc, after = rec.tasks[:cut], rec.tasks[cut], rec.tasks[cut + 1:]
        for t in before:
            sched.add_task(t)
        self._schedule_fluid_lagrangian_start(sched)
        sched.add_task(acc)
        self._schedule_exchange(sched)
        for t in after:
            sched.add_task(t)
        self._schedule_advection(sched)
        if not self.rigid:      # after every task that reads the solids' step-1 vel_CC
            sched.add_task(Task("MPMICE::solidVelocityAfterExchange", self.solid_velocity_after_exchange,
                                self.mpm_matls)
                           .requires(NEW, I.mass_L_CC).requires(NEW, I.mom_L_ME_CC).modifies(I.vel_CC))
        if self.mpm.thermal:    # after every task that reads the solids' step-1 temp_CC
            sched.add_task(Task("MPMICE::solidTemperatureAfterExchange", self.solid_temperature_after_exchange,
                                self.mpm_matls)
                           .requires(NEW, I.mass_L_CC).requires(NEW, I.int_eng_L_ME_CC).modifies(I.temp_CC))

    def _schedule_fluid_lagrangian_start(self, sched):
        """Steps 1-7: solid state at cell centres, pressure, face velocities, solid forces."""
        ice, ms, alls, fl, m0 = self.ice, self.mpm_matls, self.all_matls, self.ice.ice_matls, [0]
        dirs = [d for d in range(3) if ice.dims[d]]
        t = Task("MPMICE::interpolateNCToCC_0", self.interpolate_nc_to_cc, ms) \
            .computes(MI.cMass).computes(MI.sp_vol_mpm_CC).computes(I.rho_CC).computes(I.vel_CC) \
            .computes(I.temp_CC)
        for lab in (M.gMass, M.gVolume, M.gVelocity):
            t.requires(NEW, lab, G, 1)
        if self.mpm.thermal:        # the temperature the last exchange left (Uintah's blend)
            t.requires(OLD, I.temp_CC)
        sched.add_task(self.thermal_requires(t, "nc_to_cc"))

        t = Task("MPMICE::computeEquilibrationPressure", self.equilibration_pressure, alls) \
            .requires(OLD, I.press_CC, matls=m0).requires(NEW, MI.sp_vol_mpm_CC, matls=ms) \
            .computes(I.press_equil_CC, matls=m0).computes(I.vol_frac_CC).computes(I.sp_vol_CC) \
            .computes(I.speedSound_CC).computes(I.TMV_CC, matls=m0)
        self._start_state(t, (I.rho_CC, I.temp_CC, I.sp_vol_CC), 0)
        sched.add_task(t)
        if self.slip is not None:
            self.slip.schedule_pre_exchange(sched)

        t = Task("ICE::computeVel_FC", self.vel_fc, alls) \
            .requires(OLD, FL.delT).requires(NEW, I.sp_vol_CC, G, 1).requires(NEW, I.press_equil_CC, G, 1, matls=m0)
        self._start_state(t, (I.rho_CC, I.vel_CC), 1)
        for d in dirs:
            t.computes(I.FC_VEL[d])
        sched.add_task(t)
        if ice.implicit:
            # steps 3 and 5 with the increment implicit (ICE's eq. P over solids and fluids)
            ice.schedule_implicit_pressure(sched, dirs, alls)
        else:
            t = Task("ICE::addExchangeContributionToFCVel", ice.exchange_fc, alls) \
                .requires(OLD, FL.delT).requires(NEW, I.vol_frac_CC, G, 1).requires(NEW, I.sp_vol_CC, G, 1)
            for d in dirs:
                t.requires(NEW, I.FC_VEL[d], G, 1).computes(I.FC_VEL_ME[d])
            if self.slip is not None:
                self.slip.face_requires(t)
            sched.add_task(t)

            t = Task("ICE::computeDelPressAndUpdatePressCC", ice.delp_press, alls) \
                .requires(OLD, FL.delT).requires(NEW, I.sp_vol_CC).requires(NEW, I.speedSound_CC) \
                .requires(NEW, I.press_equil_CC, matls=m0).requires(NEW, I.vol_frac_CC, G, ice.delp_vol_frac_ghost) \
                .computes(I.delP_Dilatate, matls=m0).computes(I.press_CC, matls=m0)
            for d in dirs:
                t.requires(NEW, I.FC_VEL_ME[d], G, 1)
            sched.add_task(t)

        t = Task("ICE::computePressFC", self.press_fc, alls).requires(NEW, I.press_CC, G, 1, matls=m0)
        self._start_state(t, (I.rho_CC,), 1)
        for d in dirs:
            t.computes(I.PRESS_FC[d], matls=m0)
        sched.add_task(t)
        if not ice.implicit or self.models is not None:
            sched.add_task(Task("ICE::computeDelP_MassX", ice.delp_mass_exchange, m0)     # only when saved
                           .requires(NEW, I.press_CC, matls=m0).requires(NEW, I.press_equil_CC, matls=m0)
                           .requires(NEW, I.delP_Dilatate, matls=m0).computes(I.delP_MassX, matls=m0))

        if not self.rigid:
            ng = self.mpm.ng
            t = Task("MPMICE::interpolatePAndGradP", self.pressure_internal_force, ms) \
                .requires(NEW, I.press_CC, G, ng + 1, matls=m0).modifies(M.gIntForce).computes(MI.pPressure)
            for lab in [M.pX, M.pVolume] + ([M.pSize] if self.mpm.kind == "gimp" else []):
                t.requires(OLD, lab, Ghost.AROUND_NODES, ng)
            sched.add_task(t)

        if ice.viscous:
            sched.add_task(Task("ICE::viscousShearStress", ice.viscous_source, fl)
                           .requires(OLD, FL.delT).requires(OLD, I.vel_CC, G, 1).requires(NEW, I.vol_frac_CC, G, 1)
                           .computes(I.viscous_src_CC))
        if ice.conduction:          # the fluids' own conduction; solid-fluid heat goes through the exchange
            sched.add_task(Task("ICE::computeHeatFlux", ice.conduction_source, fl)
                           .requires(OLD, FL.delT).requires(OLD, I.temp_CC, G, 1).requires(NEW, I.vol_frac_CC, G, 1)
                           .computes(I.heatCond_src_CC))

    def _start_state(self, t, labels, ghost):
        """Requires of the start-of-step state: fluids from OLD, solids from step 1 (NEW)."""
        g = (G, ghost) if ghost else (Ghost.NONE, 0)
        for lab in labels:
            t.requires(OLD, lab, *g, matls=self.ice.ice_matls)
            if lab is not I.sp_vol_CC:
                t.requires(NEW, lab, *g, matls=self.mpm_matls)

    def _schedule_exchange(self, sched):
        """Steps 8-11 and the exchange's change of the solid carried back to the nodes."""
        ice, ms, alls, fl, m0 = self.ice, self.mpm_matls, self.all_matls, self.ice.ice_matls, [0]
        dirs = [d for d in range(3) if ice.dims[d]]
        t = Task("MPMICE::computeLagrangianValuesMPM", self.lagrangian_values_mpm, ms) \
            .requires(OLD, FL.delT).requires(NEW, MI.cMass).requires(NEW, I.temp_CC).requires(NEW, I.vel_CC) \
            .requires(NEW, M.gMass, G, 1).requires(NEW, M.gVolume, G, 1).requires(NEW, M.gVelocityStar, G, 1) \
            .requires(NEW, I.vol_frac_CC).requires(NEW, I.sp_vol_CC).requires(NEW, I.speedSound_CC) \
            .requires(NEW, I.press_CC, matls=m0).requires(NEW, I.delP_Dilatate, matls=m0) \
            .computes(MI.mom_mpm_CC).computes(I.mass_L_CC).computes(I.mom_L_CC).computes(I.int_eng_L_CC)
        for d in dirs:
            t.requires(NEW, I.PRESS_FC[d], G, 1, matls=m0)
        sched.add_task(self.thermal_requires(t, "lagrangian"))

        t = Task("ICE::computeLagrangianValues", self.lagrangian_values_fluid, fl) \
            .requires(OLD, FL.delT).requires(OLD, I.rho_CC).requires(OLD, I.vel_CC).requires(OLD, I.temp_CC) \
            .requires(NEW, I.vol_frac_CC).requires(NEW, I.sp_vol_CC).requires(NEW, I.speedSound_CC) \
            .requires(NEW, I.press_CC, matls=m0).requires(NEW, I.delP_Dilatate, matls=m0) \
            .requires(NEW, I.TMV_CC, matls=m0) \
            .computes(I.mass_L_CC).computes(I.mom_L_CC).computes(I.int_eng_L_CC)
        for d in dirs:
            t.requires(NEW, I.PRESS_FC[d], G, 1, matls=m0)
        if ice.viscous:
            t.requires(NEW, I.viscous_src_CC)
        if ice.conduction:
            t.requires(NEW, I.heatCond_src_CC)
        if self.add_heat is not None:
            t.requires(OLD, FL.simTime)
        sched.add_task(t)
        for model in ice.scalars + ice.tracers:     # the passive scalars: source, then m f; tracers move
            model.schedule_sources(sched)
        for model in ice.tracers:       # their relocation joins the MPM particles' (one relocation task)
            model.schedule_relocation(sched)
            model.schedule_diagnostics(sched)
        ice.schedule_transported(sched, fl)

        t = Task("ICE::addExchangeToMomentumAndEnergy", self.exchange, alls) \
            .requires(OLD, FL.delT).requires(NEW, I.mass_L_CC).requires(NEW, I.mom_L_CC) \
            .requires(NEW, I.int_eng_L_CC).requires(NEW, I.vol_frac_CC).requires(NEW, I.sp_vol_CC) \
            .computes(I.mom_L_ME_CC).computes(I.int_eng_L_ME_CC)
        if self.models is not None:         # where the models feed a fluid (MPMICE.exchange)
            from components.models import labels as ML
            t.requires(NEW, ML.modelMass_src, matls=self.models.products())
        if self.slip is not None:
            self.slip.cell_requires(t)
            self.slip.schedule_diagnostics(sched)
        sched.add_task(t)

        t = Task("ICE::computeLagrangianSpecificVolume", self.lagrangian_sp_vol, alls) \
            .requires(OLD, FL.delT).requires(NEW, I.mass_L_CC).requires(NEW, I.sp_vol_CC) \
            .requires(NEW, I.vol_frac_CC).requires(NEW, I.speedSound_CC) \
            .requires(NEW, I.delP_Dilatate, matls=m0).requires(NEW, I.press_CC, matls=m0) \
            .computes(I.sp_vol_L_CC).requires(NEW, I.int_eng_L_ME_CC)
        self._start_state(t, (I.temp_CC,), 0)
        ice.schedule_sp_vol_src(t, sched)
        if self.models is not None:         # the burn models' created volume, before ICE's clamp
            self.models.lagrangian_volume_requires(t)
            ice.model_volume_sources = self.models.volume_sources_into
        sched.add_task(t)

        self._schedule_diagnostics(sched)

        if not self.rigid:
            sched.add_task(Task("MPMICE::computeCCVelAndTempRates", self.velocity_rates, ms)
                           .requires(OLD, FL.delT).requires(NEW, I.mom_L_ME_CC).requires(NEW, MI.mom_mpm_CC)
                           .requires(NEW, I.mass_L_CC).requires(NEW, M.gMass).requires(NEW, M.gVolume)
                           .requires(NEW, M.gVelocityStar).computes(MI.dVdt_CC))
            sched.add_task(Task("MPMICE::interpolateCCToNC", self.interpolate_cc_to_nc, ms)
                           .requires(OLD, FL.delT).requires(NEW, MI.dVdt_CC, G, 1)
                           .modifies(M.gVelocityStar).modifies(M.gAcceleration))
        self.schedule_solid_heat(sched)

    def _schedule_diagnostics(self, sched):
        """Uintah's source and rate labels (mom_source_CC, intE_source_CC, Tdot) for output only:
        nothing downstream reads them, so the scheduler drops these tasks unless a <save> names them."""
        alls = self.all_matls
        t = Task("ICE::accumulateSourceSinks", self.source_sinks, alls) \
            .requires(NEW, I.mass_L_CC).requires(NEW, I.mom_L_CC).requires(NEW, I.int_eng_L_CC) \
            .computes(MI.mom_source_CC).computes(MI.intE_source_CC)
        self._start_state(t, (I.vel_CC, I.temp_CC), 0)
        sched.add_task(t)
        t = Task("MPMICE::computeTdot", self.temperature_rate, alls) \
            .requires(OLD, FL.delT).requires(NEW, I.mass_L_CC).requires(NEW, I.int_eng_L_ME_CC) \
            .computes(MI.Tdot)
        self._start_state(t, (I.temp_CC,), 0)
        sched.add_task(t)

    def _schedule_advection(self, sched):
        """Step 12 for the fluids, and the fluids' Mach number."""
        ice, fl = self.ice, self.ice.ice_matls
        dirs = [d for d in range(3) if ice.dims[d]]
        gadv = 2 if ice.second_order else 1
        t = Task("ICE::advectAndAdvanceInTime", ice.advect_and_advance, fl) \
            .requires(OLD, FL.delT).requires(NEW, I.mass_L_CC, G, gadv).requires(NEW, I.mom_L_ME_CC, G, gadv) \
            .requires(NEW, I.int_eng_L_ME_CC, G, gadv).requires(NEW, I.sp_vol_L_CC, G, gadv) \
            .requires(NEW, I.vol_frac_CC, G, gadv, matls=self.all_matls) \
            .computes(I.rho_CC).computes(I.vel_CC).computes(I.temp_CC).modifies(I.sp_vol_CC)
        for d in dirs:
            t.requires(NEW, I.FC_VEL_ME[d], G, 1, matls=self.all_matls)
        if ice.open_faces:          # the solids' own velocity across a face, the flow work's p (tasks.open_faces)
            t.requires(NEW, I.vel_CC, G, 1, matls=self.mpm_matls).requires(NEW, I.press_CC, G, 1, matls=[0]) \
                .requires(NEW, I.TMV_CC, G, 1, matls=[0])
        ice.advect_scalars(t, gadv)
        sched.add_task(t)
        for model in ice.scalars:
            model.schedule_conservation(sched, dirs)
        t = Task("ICE::TestConservation", ice.fluid_sums, fl) \
            .requires(OLD, FL.delT).requires(NEW, I.rho_CC).requires(NEW, I.vel_CC).requires(NEW, I.temp_CC) \
            .computes(I.TotalIntEng)
        for lab in SUMS:
            t.computes(lab, matls=fl)
        for d in dirs:
            t.requires(NEW, I.FC_VEL_ME[d])
        sched.add_task(t)
        t = Task("MPMICE::sumConservedQuantities", self.sum_conserved, fl)
        for total, particles in zip(SUMS[:3], self.mpm.totals):
            t.requires(NEW, particles).requires(NEW, total, matls=fl).computes(total)
        sched.add_task(t)
        sched.add_task(Task("ICE::computeMach", ice.compute_mach, fl)
                       .requires(NEW, I.vel_CC).requires(NEW, I.speedSound_CC).computes(I.mach))

    def stable_timestep_flow(self, patch, matls, old_dw, new_dw):
        """delT with implicit ICE or prescribed solids: ICE's step over the fluids, and MPM's
        wave-speed step over the solids unless they are prescribed (rmpmice: Uintah's RigidMPM
        sets no limit)."""
        a = _Capture(new_dw)
        self.ice.stable_timestep(patch, self.ice.ice_matls, old_dw, a)
        dt = float(a.value)
        if not self.rigid:
            b = _Capture(new_dw)
            self.mpm.compute_stable_timestep(patch, self.mpm_matls, old_dw, b)
            dt = min(dt, float(b.value))
        new_dw.put_reduction(FL.delT, dt)

    def sum_conserved(self, patch, matls, old_dw, new_dw):
        """TotalMass, KineticEnergy and TotalMomentum: the particles' plus every fluid's, as
        Uintah's MPM and ICE put into one reduction. The parts are global sums already, so only
        the level's first patch puts them (the reduction adds the patches)."""
        if patch.id != patch.level.patches[0].id:
            return
        for total, particles in zip(SUMS[:3], self.mpm.totals):
            new_dw.put_reduction(total, new_dw.get_reduction(particles)
                                 + sum(new_dw.get_reduction(total, m) for m in matls))

    @property
    def rigid(self):
        """rmpmice: the solid's motion is prescribed (no pressure force, no exchange change)."""
        return self.names_used == "rmpmice"

    names_used = "mpmice"
    _described = False


def _read_add_heat(node, ice_matls):
    """<ADD_HEAT> (Uintah's ICE): add_heat_coeff[i] W/kg heats material add_heat_matls[i]
    (a global index: MPM materials first) in every cell where its volume fraction exceeds
    0.001, for add_heat_t_start <= t <= add_heat_t_final. None when the deck has no <ADD_HEAT>."""
    if node is None:
        return None
    node.mark_used(recursive=False)

    def _list(tag, conv):
        c = node.child(tag, required=True)
        c.mark_used(recursive=False)
        txt = c.text().strip()
        try:
            if not (txt.startswith("[") and txt.endswith("]")):
                raise ValueError(txt)
            vals = [conv(v) for v in txt[1:-1].replace(",", " ").split()]
        except ValueError:
            raise c.error(f"'{txt}' is not a list [a, b, ...] of {conv.__name__} values") from None
        if not vals:
            raise c.error("empty list")
        return c, vals

    mnode, matls = _list("add_heat_matls", int)
    cnode, coeffs = _list("add_heat_coeff", float)
    if len(matls) != len(coeffs):
        raise cnode.error(f"{len(coeffs)} coefficients for {len(matls)} materials in <add_heat_matls>")
    for m in matls:
        if m not in ice_matls:
            raise mnode.error(f"material {m} is not an ICE material; accepted: {ice_matls} "
                              "(global indices, MPM materials first)")
    t0, t1 = node.get("add_heat_t_start", "float"), node.get("add_heat_t_final", "float")
    return dict(zip(matls, coeffs)), t0, t1


def _specific_heat(mat):
    return getattr(mat, "specific_heat", 0.0) or 1.0
