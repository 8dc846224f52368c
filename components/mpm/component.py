"""Explicit MPM (Uintah's SerialMPM, paper 000 sec. 3.2, paper 004 eqs. 5-17).

`<SimulationComponent type="mpm">`. The deck blocks read here:
  <MPM>                 FLAGS below (interpolator linear|gimp|cpdi|fast_cpdi, explicit only,
                        DoExplicitHeatConduction: p.temperature and conduction, thermal.py)
  <PhysicalConstants>   <gravity>
  <MaterialProperties><MPM>  <material> (materials.py; models incl. ideal_gas_fluid, the
                        fluid points of paper 004, and membrane, its membrane/string points
                        laid along a <membrane_polygon>), <contact> null | single_velocity |
                        friction (friction_bard, approach) | friction_LR(Var) | rigid
                        (specified) (contact.py), <thermal_contact> (thermal.py)
  <Grid><BoundaryConditions> velocity Dirichlet / Neumann / symmetry faces, Dirichlet
                        temperature (bc.py)
  <PhysicalBC><MPM>     <pressure>, <torque>, <heat_flux> load curves on surface
                        particles (pressure.py)
  <DataAnalysis>        <Module name="particleExtract"> (analysis.py)

The particle<->grid transfers are fused numba kernels (transfer.py): p2g scatters into
the warehouse's node arrays, g2p updates x, v (and with USL L, F, V) in one pass, MUSL
remaps the new momentum in that pass and finds L, F, V in one more.

One timestep (tasks.py), all MPM materials in each task:
  interpolateParticlesToGrid      m_i, v_i, V_i, fext_i, fint_i from the particles
                                  and their stress (update stress last)
  computeLogisticRegression       friction_LR's alpha material, normal, prominences
  exMomInterpolated               contact on v_i          (only with contact)
  computeAndIntegrateAcceleration a_i, v*_i
  computeContactArea, computeBoundaryTractions  the <boundary_traction_faces> reductions
                                  (only when saved, boundary_tractions.py)
  exMomIntegrated                 contact on v*_i, a_i    (only with contact)
  setGridBoundaryConditions       v*_i, a_i on boundary nodes (only with BCs)
  setPrescribedMotion             v*_i = Fdot F^-1 x_i, a_i = 0 (only with <UsePrescribedDeformation>,
                                  prescribed.py)
  computeSPlusSSPlusVp            XPIC(2)'s twice-smoothed grid velocity (only with <XPIC2>)
  computeGridVelocityForFTM       a force-transmitting material's one acceleration (only with one)
  interpolateToParticlesAndUpdate v_p, x_p (USL: L_p, F_p, V_p; MUSL: v^L_i); totals
  computeStressTensor             (MUSL: L_p, F_p, V_p from v^L) sigma_p, strain energy,
                                  wave speed
  computeAccStrainEnergy          AccStrainEnergy (only when saved)
  relocateParticles, computeStableTimestep
"""
from __future__ import annotations

import numpy as np

from framework import labels as FL
from framework.component import Component, register
from framework.problemspec import Param
from framework.task import NEW, OLD, Task
from framework.variables import Ghost

from . import labels as L
from .analysis import ParticleExtract
from .bc import GridBCs
from .boundary_tractions import (BoundaryTractionTasks, read_traction_faces, saves_face_labels,
                                 schedule_acc_strain_energy)
from .contact import Contact
from .materials import Material
from .shape import AXI
from .transfer import kernels, merged_p2g, xpic_kernel
from .tasks import MPMTasks
from .thermal import ThermalTasks

FLAGS = {
    "time_integrator": Param("str", "explicit", ("explicit",), "only explicit MPM is implemented"),
    "interpolator": Param("str", "linear", ("linear", "gimp", "cpdi", "fast_cpdi", "cpti"),
                          "cpti is read to be refused with its reason (its domains come from a preprocessing step)"),
    "cpdi_lcrit": Param("float", 1.0e10, doc="CPDI: corners farther than this (cells) are pulled back"),
    "withColor": Param("bool", False, doc="carry p.color from <geom_object><color>"),
    "artificial_damping_coeff": Param("float", 0.0, doc="a_i -= coeff * v_i (1/s)"),
    "minimum_particle_mass": Param("float", 0.0, doc="lighter particles are deleted"),
    "maximum_particle_velocity": Param("float", np.inf, doc="faster particles are deleted"),
    "minimum_mass_for_acc": Param("float", 0.0, doc="nodes this light get no force acceleration"),
    "do_grid_reset": Param("bool", True, (True,), doc="the grid is always reset"),
    "DoExplicitHeatConduction": Param("bool", False, doc="particle temperature and explicit heat conduction (thermal.py)"),
    "conduction_gradient": Param("str", "previous", ("previous", "current"),
                                 "grad T_p of the heat conduction (thermal.py): previous = the particles' "
                                 "p.temperatureGradient of the last step (Uintah's; stable step rho cv / "
                                 "(4 k sum 1/dx^2)); current = pysus: from this step's g.temperature (twice "
                                 "that step)"),
    "artificial_viscosity": Param("bool", False, doc="bulk viscosity q of compressed solid particles in the "
                                  "internal force (artificial_viscosity.py)"),
    "artificial_viscosity_heating": Param("bool", False, doc="elastic_plastic's viscous work to heat (on with "
                                          "<artificial_viscosity> unless false is given)"),
    "artificial_viscosity_coeff1": Param("float", 0.2, doc="A1, the linear term of q", at_least=0.0),
    "artificial_viscosity_coeff2": Param("float", 2.0, doc="A2, the quadratic term of q", at_least=0.0),
    "do_contact_friction_heating": Param("bool", False, (False,), "friction work to heat: not implemented"),
    "computeColinearNormals": Param("bool", True, doc="contact normals (friction, approach) made collinear "
                                    "with the other materials' (Uintah's default); false: each material's own"),
    "axisymmetric": Param("bool", False, doc="Uintah's axisymmetric MPM: x is r, y the axial z, one cell in z; "
                          "particle volumes and masses per radian"),
    "delT_activeDirectionsOnly": Param("bool", True, doc="pysus: the wave-speed step over the active "
                                       "directions; false: over all three, a one-cell one too (Uintah's)"),
    "stress_update": Param("str", "musl", ("musl", "usl"),
                           "pysus: musl = paper 004 eqs. 11-14 (stress from the remapped updated "
                           "velocity, robust at nearly empty nodes); usl = Uintah's (stress from v*)"),
    "DoPressureStabilization": Param("bool", False, doc="each cell's particles take the cell's mean J "
                                     "(volume-weighted) in F and L, as Uintah's SerialMPM"),
    "UseGradientEnhancedVelocityProjection": Param(
        "bool", False, doc="the particle-to-grid momentum takes m (v_p + L_p (x_i - x_p)) with L_p of the "
        "particle's last step, as Uintah's SerialMPM"),
    "XPIC2": Param("bool", False, doc="particle velocity and position from XPIC(2) (Hammerquist & Nairn 2017) "
                   "instead of FLIP, as Uintah's SerialMPM; not for rigid materials"),
    "use_load_curves": Param("bool", False, doc="pressure and torque BCs follow <PhysicalBC> load curves"),
    "use_CBDI_boundary_condition": Param("bool", False, doc="pressure loads act on the loaded face of each "
                                         "particle's deformed domain, spread from its corners (cbdi.py)"),
    "boundary_traction_faces": Param("str", "[]", doc="[xminus, ..., zplus]: the BndyForce_, BndyTraction_ and "
                                     "BndyContactArea_<face> reductions there, computed when saved "
                                     "(boundary_tractions.py)"),
    "particles_leaving_domain": Param("str", "warn", ("warn", "error"),
                                      "pysus: particles leaving through a face without a wall are deleted "
                                      "(as in Uintah) with a warning line, or stop the run"),
    "RunMMSProblem": Param("str", "", doc="a manufactured solution's body force (mms.py): StretchedBar, "
                           "TwistedAnnulus"),
    "mms_amplitude": Param("float", 1.0, doc="pysus, mms.py: the stretch (bar) or twist (annulus) at the end"),
    "mms_ramp_time": Param("float", 1.0, above=0.0, doc="pysus, mms.py: the time the motion takes"),
    "UsePrescribedDeformation": Param("bool", False, doc="the grid velocity of a prescribed deformation "
                                      "(prescribed.py); implies <stress_update>usl"),
    "PrescribedDeformationFile": Param("str", "", doc="its table (prescribed.py)"),
    "minimum_subcycles_for_F": Param("int", 1, doc="F^{n+1} = exp(L dt) F^n: < 0 the Taylor series to that many "
                                     "terms, > 1 that many substeps (Uintah's); 1: I + L dt (USL only otherwise)"),
    "UseMomentumForm": Param("bool", False, (False,), "read (false only); sus's validation refuses the tag"),
    "InsertParticles": Param("bool", False, doc="move particles of a colour into place at the times of "
                             "<InsertParticlesFile> (insert_particles.py; needs <withColor>)"),
    "InsertParticlesFile": Param("str", "", doc="its table: t colour dx dy dz vx vy vz a line"),
}


@register("mpm")
class MPM(ThermalTasks, MPMTasks, BoundaryTractionTasks, Component):
    """Explicit single-grid MPM with Uintah's deck tags and variable names."""

    holes_ok = True

    analysis_modules = ("particleExtract",)    # <DataAnalysis> modules this component reads itself
    # MPMICE hooks: the <MPM> flag table, grid-BC reader, contact and material readers it may extend
    flags_spec = FLAGS
    grid_bcs_class = GridBCs
    contact_class = Contact
    material_class = Material
    # another component reads g.volume (MPMICE: the cell volume fractions)
    coupled_reads_grid_volume = False
    # why <axisymmetric>true is refused in this component (None: it is supported)
    axisymmetric_refused = None
    # why <XPIC2>true is refused in this component (None: it is supported)
    xpic_refused = None
    # why <UseGradientEnhancedVelocityProjection>true is refused here (None: it is supported)
    projection_refused = None
    # why <artificial_viscosity>true is refused in this component (None: it is supported)
    artificial_viscosity_refused = None
    # why <is_force_transmitting_material>true is refused in this component (None: it is supported)
    ftm_refused = None
    # (final, pre-relocation) particle labels a coupled model computes and relocation carries
    carry_models = ()
    # the particles' conservation sums; MPMICE puts them under its own names and adds the gas's
    totals = (L.TotalMass, L.KineticEnergy, L.TotalMomentum)
    # a <save label="p.temperature"> without <DoExplicitHeatConduction> turns conduction on
    # (Uintah's default; without it the save names nothing computed)
    saved_temperature_conducts = True

    @property
    def save_aliases(self):
        """ArenaSoil's p.plasticStrain is a tensor, held as p.plasticStrainTensor (labels.py)."""
        models = {m.model_name for m in self.materials}
        if "ArenaSoil" in models and not models & {"elastic_plastic", "elastic_plastic_hp", "comp_neo_hook_plastic",
                                                   "UCNH", "UCNHVar"}:
            return {"p.plasticStrain": "p.plasticStrainTensor"}
        return {}

    def problem_setup(self, root, level):
        self.level = level
        self.dims = tuple(not c for c in level.collapsed)
        self.dim = level.dim
        mpm = root.child("MPM")
        self.flags = mpm.read(self.flags_spec) if mpm is not None else {k: p.default for k, p in self.flags_spec.items()}
        pc = root.child("PhysicalConstants")
        self.gravity = np.array(pc.get("gravity", "vector", (0.0, 0.0, 0.0)) if pc is not None else (0.0, 0.0, 0.0))
        if pc is not None:
            pc.get("reference_pressure", "float", 101325.0)
        self.kind = self.flags["interpolator"]
        if self.kind == "cpti":
            raise mpm.child("interpolator").error(
                "cpti needs the particles' tetrahedral domains from Uintah's preprocessing step (.pts files "
                "with the r vectors), which pysus does not read; accepted: linear, gimp, cpdi, fast_cpdi")
        self.musl = self.flags["stress_update"] == "musl"
        self.prescribed = None
        if self.flags["UsePrescribedDeformation"]:
            from . import prescribed
            if mpm.has("stress_update") and self.musl:
                raise mpm.child("stress_update").error("a prescribed deformation sets v* (Uintah's USL): accepted "
                                                       "with it: usl")
            if not mpm.has("PrescribedDeformationFile"):
                raise mpm.error("<UsePrescribedDeformation>true needs <PrescribedDeformationFile>")
            self.musl = False
            self.prescribed = prescribed.read(mpm.child("PrescribedDeformationFile"), mpm.filename)
        self.insertion = None
        if self.flags["InsertParticles"]:
            from . import insert_particles
            if not self.flags["withColor"]:
                raise mpm.child("InsertParticles").error("particles are inserted by colour: accepted with "
                                                         "<withColor>true</withColor>")
            if not mpm.has("InsertParticlesFile"):
                raise mpm.error("<InsertParticles>true needs <InsertParticlesFile>")
            self.insertion = insert_particles.read(mpm.child("InsertParticlesFile"), mpm.filename)
        self.f_terms = self.flags["minimum_subcycles_for_F"]
        if self.f_terms == 0:
            raise mpm.child("minimum_subcycles_for_F").error("0 is not accepted: < 0 Taylor terms, > 0 substeps")
        if self.f_terms != 1 and self.musl:
            raise mpm.child("minimum_subcycles_for_F").error("a value other than 1 needs <stress_update>usl "
                                                             "(or a prescribed deformation)")
        if self.dim == 0:
            raise root.child("Grid").error("MPM needs at least one direction with more than one cell")
        if self.kind != "linear":
            bad = [d for d in range(3) if self.dims[d] and not level.periodic[d] and level.extra[d] < 1]
            if bad:
                raise root.child("Grid").error(
                    f"{self.kind.upper()} particles reach one node beyond the domain: <extraCells> must be at least 1 in "
                    f"{'xyz'[bad[0]]} (Uintah needs the same)")
        self.axes = sum(1 << d for d in range(3) if self.dims[d])     # active-axis mask (transfer.py)
        self.axisymmetric = self.flags["axisymmetric"]
        if self.axisymmetric:
            self._check_axisymmetric_grid(root, mpm, level)
        self.act = self.axes | (AXI if self.axisymmetric else 0)      # the kernels' mask (shape.AXI)
        self.projection = self.flags["UseGradientEnhancedVelocityProjection"]
        if self.projection:
            why = self.projection_refused or (
                "with <DoExplicitHeatConduction>true (Uintah then also projects the temperature with "
                "p.temperatureGradient, which pysus does not compute)" if self.flags["DoExplicitHeatConduction"]
                else None)
            if why:
                raise mpm.child("UseGradientEnhancedVelocityProjection").error(
                    f"the gradient-enhanced velocity projection is not implemented {why}; accepted: false")
        self.p2g_runs, self.g2p, self.grad = kernels(self.kind, self.act, self.projection)
        self.p2g = merged_p2g(self.p2g_runs)      # one array per variable (MPMICE)
        self.xpic = self.flags["XPIC2"]
        if self.xpic:
            if self.xpic_refused or self.axisymmetric:
                why = self.xpic_refused or "with <axisymmetric>true"
                raise mpm.child("XPIC2").error(f"XPIC2 is not implemented {why}; accepted: false")
            self.xpic_spssp = xpic_kernel(self.kind, self.act)
        self.ng = 1 if self.kind == "linear" else 2
        self.grid_volume = True           # until schedule_time_advance knows who reads g.volume
        mp = root.child("MaterialProperties", required=True).child("MPM", required=True)
        geom = getattr(root, "_geometry_reader", None)
        if geom is None:
            from framework.geometry import GeometryReader
            geom = GeometryReader(level)
        self.materials = [self.material_class(m, i, geom, self.flags["withColor"])
                          for i, m in enumerate(mp.children("material"))]
        if not self.materials:
            raise mp.error("no <material>")
        self.matls = list(range(len(self.materials)))
        if any(mt.draws for mt in self.materials):      # lay Uintah's particles for Uintah's draws
            for mt in self.materials:
                mt.collapsed_layers = True
        if self.projection:             # every material's L_p is kept for the next step's projection
            for mt in self.materials:
                mt.uses_L = True
        smooth = [o for m in self.materials for o in m.objects if o.get("smooth")]
        affine = [o for m in self.materials for o in m.objects if o.get("affine") is not None]
        if affine and self.kind == "gimp":
            raise affine[0]["node"].error(
                "an affine transformation's particles with <interpolator>gimp are not implemented (their "
                "domains are not boxes); accepted: linear, cpdi, fast_cpdi")
        if smooth and self.kind == "gimp":
            raise smooth[0]["node"].child("smoothcyl").error(
                "a <smoothcyl>'s particles with <interpolator>gimp are not implemented (Uintah's GIMP reads the "
                "diagonal of their turned size matrix); accepted: linear, cpdi, fast_cpdi")
        # CPDI takes each particle's domain from its size matrix (p.sizeMatrix), turned with a
        # <smoothcyl>'s ring sector; lattice particles keep the diagonal p.size
        self.size_matrix = bool(smooth or affine) and self.kind in ("cpdi", "fast_cpdi")
        self.has_membrane = any(m.is_membrane for m in self.materials)
        # fluid points with artificial viscosity: its scales are reduced over the level
        self.av_matls = [i for i, m in enumerate(self.materials)
                         if m.model_name == "ideal_gas_fluid" and m.params.artificial_viscosity]
        if len(self.materials) > 16 and self.av_matls:
            raise mp.error("artificial viscosity supports at most 16 MPM materials")
        self.contact = self.contact_class(mp, len(self.materials))
        self._rigid_contact_setup()
        self._ftm_setup(mp)
        if self.contact.needs_color and not self.flags["withColor"]:
            raise mp.child("contact").child("type").error(
                "friction_LRVar takes mu from the colour: it needs <MPM><withColor>true</withColor>")
        self.bcs = self.grid_bcs_class(root, level, len(self.materials))
        self.bcs.mirror_extra = self.kind != "linear"
        self.analysis = ParticleExtract(root, self)
        self.pressure_bcs = None
        self.thermal_contact_node = mp.child("thermal_contact")
        self.heat_flag_given = mpm is not None and mpm.has("DoExplicitHeatConduction")
        da = root.child("DataArchiver")
        self.saves_temperature = self.saved_temperature_conducts and da is not None and any(
            sv.attr("label", default="") == "p.temperature" for sv in da.children("save"))
        self.thermal_setup()
        self._read_physical_bc(root)      # <PhysicalBC><MPM><pressure>, <torque>, <heat_flux> (pressure.py)
        self.cbdi = self.flags["use_CBDI_boundary_condition"]
        if self.cbdi:
            tag = mpm.child("use_CBDI_boundary_condition")
            if not self.pressure_bcs or not any(b.kind == "pressure" for b in self.pressure_bcs.bcs):
                raise tag.error("CBDI acts on <PhysicalBC><MPM><pressure> loads: it needs one, with "
                                "<use_load_curves>true (Uintah reads p.loadCurveID then); accepted: false")
            if self.axisymmetric:
                raise tag.error("CBDI is not implemented with <axisymmetric>true; accepted: false")
        self.mms = None
        if self.flags["RunMMSProblem"]:
            from .mms import ManufacturedSolution
            if self.pressure_bcs:
                raise mpm.child("RunMMSProblem").error("a manufactured solution's body force and <PhysicalBC> "
                                                       "loads cannot be combined")
            self.mms = ManufacturedSolution(mpm, self.flags, self.materials, level)
        if self.axisymmetric:
            self._check_axisymmetric_physics(mpm, mp)
        self.av = None
        if self.flags["artificial_viscosity"]:
            if self.artificial_viscosity_refused:
                raise mpm.child("artificial_viscosity").error(
                    f"artificial viscosity is not implemented {self.artificial_viscosity_refused}; accepted: false")
            from .artificial_viscosity import ArtificialViscosity
            self.av = ArtificialViscosity(mpm, self.flags, self.materials, level.dx)
            for mt, bulk in zip(self.materials, self.av.bulk):
                if bulk is not None:    # q reads tr D: L_p also of the models whose stress needs only F
                    mt.uses_L = True
        elif self.flags["artificial_viscosity_heating"]:
            raise mpm.child("artificial_viscosity_heating").error(
                "artificial_viscosity_heating needs <artificial_viscosity>true (as in Uintah)")
        self.saves_disp = self.saves_scale = False      # until schedule_time_advance sees the <save>s
        self.saves_localized = False
        self.saves_acc_energy = self.saves_tractions = False
        self.traction_faces = read_traction_faces(mpm, self.flags["boundary_traction_faces"], level)
        self._carried()

    def _rigid_contact_setup(self):
        """Uintah's SpecifiedBodyContact makes its master material rigid (FLIP's particle update
        under <XPIC2>) and, with <XPIC2>, acts after interpolation too (its OneOrTwoStep 2)."""
        c = self.contact
        if c.type not in ("rigid", "specified_friction"):
            return
        self.materials[c.master].is_rigid = True
        if self.xpic and c.active:
            c.interpolated = True

    def _ftm_setup(self, mp):
        """Force-transmitting rigid materials (Uintah's is_force_transmitting_material): each
        moves as one rigid body, a = (sum of its nodal external forces + the force the rigid
        contact exerts on the others' nodes, taken with the opposite sign) / its nodal mass."""
        self.ftm = [m for m, mat in enumerate(self.materials) if mat.is_ftm]
        self.ftm_contact = False
        if not self.ftm:
            return
        tag = self.materials[self.ftm[0]].node.child("is_force_transmitting_material")
        if self.ftm_refused or self.axisymmetric:
            why = self.ftm_refused or "with <axisymmetric>true"
            raise tag.error(f"a force-transmitting material is not implemented {why}; accepted: false")
        if len(self.materials) > 16:
            raise tag.error("a force-transmitting material needs at most 16 MPM materials")
        # the rigid contact's reaction joins its master's force (Uintah's SpecifiedBodyContact)
        self.ftm_contact = self.contact.active and self.contact.type == "rigid"

    def _check_axisymmetric_grid(self, root, mpm, level):
        """Axisymmetric MPM (Uintah's): x is r >= 0, y the axial direction, z (one cell) the angle."""
        tag = mpm.child("axisymmetric")
        if self.axisymmetric_refused:
            raise tag.error(f"axisymmetric MPM is not implemented {self.axisymmetric_refused}; accepted: false")
        if self.dims[2]:
            raise tag.error("axisymmetric MPM needs one cell in z (the angle; x is r, y the axis), "
                            f"the grid has {level.ncells[2]}; accepted: false, or a grid one cell thick in z")
        if not self.dims[0]:
            raise tag.error("axisymmetric MPM needs more than one cell in x (the radius)")
        if self.kind not in ("linear", "gimp", "cpdi", "fast_cpdi"):
            raise mpm.child("interpolator").error(
                f"{self.kind} is not implemented with <axisymmetric>true; accepted there: linear, gimp, cpdi, fast_cpdi")
        if level.anchor[0] < 0.0:
            raise root.child("Grid").error(f"with <axisymmetric>true x is the radius: the domain's lower x "
                                           f"({level.anchor[0]:g}) must be >= 0 (the axis is x = 0)")
        if self.gravity[2] != 0.0:
            raise root.child("PhysicalConstants").child("gravity").error(
                "with <axisymmetric>true z is the angle: gravity has no z component; accepted: [gx, gy, 0]")

    def _check_axisymmetric_physics(self, mpm, mp):
        """The parts of MPM whose axisymmetric form is not implemented are refused."""
        tag = mpm.child("axisymmetric")
        if self.conducting or self.thermal_contact:
            raise tag.error("heat conduction is not implemented with <axisymmetric>true (Uintah has no "
                            "axisymmetric temperature gradient either); accepted: <DoExplicitHeatConduction>false "
                            "(the particles' own heating, as elastic_plastic_hp's, is kept)")
        if self.contact.needs_lr:
            raise mp.child("contact").child("type").error(
                f"contact type {self.contact.type} is not implemented with <axisymmetric>true (its normals are "
                "planar); accepted there: null, single_velocity, rigid, friction")
        for m in self.materials:
            if m.is_membrane:
                self._check_axisymmetric_membrane(m)

    @staticmethod
    def _check_axisymmetric_membrane(m):
        """A membrane of revolution: biaxial ('plane') only, and every point off the axis (its
        ring would have no mass); the model then carries the hoop stress (membrane.py)."""
        if m.params.formulation != "plane":
            raise m.node.child("constitutive_model").child("formulation").error(
                f"membrane formulation {m.params.formulation} is not implemented with <axisymmetric>true; "
                "accepted: plane (a membrane of revolution carries meridional and hoop stress)")
        for obj in m.objects:
            if obj["chain"][:, 0].min() <= 0.0:
                raise obj["node"].error(
                    f"with <axisymmetric>true a membrane point at r = {obj['chain'][:, 0].min():g} has no ring "
                    "(r is x); start and end the <membrane_polygon> off the axis, e.g. half a <spacing> from it")
        m.hoop = True

    def _carried(self):
        """(final, pre-relocation) particle labels this deck carries, besides p.x."""
        c = [(L.pVelocity, L.pVelocityPre), (L.pMass, L.pMassPre), (L.pVolume, L.pVolumePre),
             (L.pStress, L.pStressPre), (L.pF, L.pFPre), (L.pID, L.pIDPre)]
        # GIMP, CPDI; friction_LR: the particle faces; p.scalefactor
        if self.kind != "linear" or self.contact.needs_lr or self.saves_scale or self.cbdi:
            c.append((L.pSize, L.pSizePre))
        if self.size_matrix:
            c.append((L.pSizeMatrix, L.pSizeMatrixPre))
        if self.contact.needs_lr:
            c.append((L.pSurface, L.pSurfacePre))
        if self.flags["withColor"]:
            c.append((L.pColor, L.pColorPre))
        if any(m.increment_energy for m in self.materials):
            c.append((L.pStrainEnergy, L.pStrainEnergyPre))
        states = dict.fromkeys(k for m in self.materials for k in m.state_names)
        if self.saves_localized:              # Uintah carries it for every material: 0 unless localized
            states["p.localizedMPM"] = None
        for name in states:
            c.append(L.STATE[name])
        if self.has_membrane:                 # 004 sec. 3.2: tangent and thickness per point
            c += [(L.pTangent, L.pTangentPre), (L.pThickness, L.pThicknessPre)]
        if self.pressure_bcs:
            c += [(L.pExtForce, L.pExtForcePre), (L.pLoadCurveID, L.pLoadCurveIDPre)]
            if self.pressure_bcs.heat_flux:
                c.append((L.pExternalHeatRate, L.pExternalHeatRatePre))
        if self.mms or self.saves_disp:       # X = p.x - p.displacement for the body force; saved
            c.append((L.pDisp, L.pDispPre))
        if self.av:                           # the bulk viscosity of the next step's internal force
            c.append((L.pQ, L.pQPre))
        if self.saves_scale:
            c.append((L.pScaleFactor, L.pScaleFactorPre))
        if self.projection:                   # L_p of the last step for the projection
            c.append((L.pVelGradLast, L.pVelGradLastPre))
        self.carry = c
        self.carry_thermal = [(L.pTemperature, L.pTemperaturePre)] if self.thermal else []
        if self.gradient_carried:             # grad T* of the last step: this step's conduction (thermal.py)
            self.carry_thermal.append((L.pTemperatureGradient, L.pTemperatureGradientPre))

    # -- scheduling ---------------------------------------------------------------------
    def schedule_initialize(self, level, sched):
        t = Task("MPM::actuallyInitialize", self.initialize, self.matls).computes(L.pX)
        for final, _ in self.carry:
            t.computes(final)
        for r in (L.WaveSpeed, L.StrainEnergy, L.CenterOfMassPosition) + self.totals:
            t.computes(r)
        if self.pressure_bcs:
            t.computes(L.PressureBCParticles)
        sched.add_task(t)
        schedule_acc_strain_energy(self, sched, initialize=True)
        self.schedule_thermal_initialize(sched)
        sched.register_particle_labels(L.pX, L.pID)

    def _schedule_logistic_regression(self, sched):
        """friction_LR's normals and prominences (contact.py), once per step after the
        particles reach the grid, before the first contact task."""
        g, ng = Ghost.AROUND_NODES, self.ng
        t = Task("MPM::computeLogisticRegression", self.logistic_regression, self.matls).requires(NEW, L.gMass)
        for lab in (L.pX, L.pSize, L.pSurface):
            t.requires(OLD, lab, g, ng)
        t.computes(L.gAlphaMaterial, [0]).computes(L.gNormAlphaToBeta, [0]).computes(L.gMatlProminence)
        if self.contact.needs_color:
            m = self.contact.master
            t.requires(OLD, L.pMass, g, ng, [m]).requires(OLD, L.pColor, g, ng, [m]).computes(L.gColor, [m])
        sched.add_task(t)

    def _requires_lr(self, t):
        c = self.contact
        if c.needs_lr:
            t.requires(NEW, L.gAlphaMaterial, matls=[0]).requires(NEW, L.gNormAlphaToBeta, matls=[0])
            t.requires(NEW, L.gMatlProminence)
            if c.needs_color:
                t.requires(NEW, L.gColor, matls=[c.master])

    def schedule_compute_stable_timestep(self, level, sched):
        sched.add_task(Task("MPM::computeStableTimestep", self.compute_stable_timestep, self.matls)
                       .requires(NEW, L.WaveSpeed).computes(FL.delT))

    def _saved_particle_labels(self, sched):
        """p.displacement and p.scalefactor are carried only when a deck saves them (as Uintah
        computes p.scalefactor): decks without them pay nothing. So is p.localizedMPM where no
        damage model sets it (zero, as Uintah's for such a material)."""
        out = getattr(sched, "output_labels", ())
        self.saves_acc_energy = L.AccStrainEnergy.name in out
        self.saves_tractions = saves_face_labels(self.traction_faces, out)
        disp, scale, loc = "p.displacement" in out, "p.scalefactor" in out, "p.localizedMPM" in out
        if (disp, scale, loc) != (self.saves_disp, self.saves_scale, self.saves_localized):
            self.saves_disp, self.saves_scale, self.saves_localized = disp, scale, loc
            self._carried()

    def schedule_time_advance(self, level, sched):
        ms, g, ng = self.matls, Ghost.AROUND_NODES, self.ng
        self._saved_particle_labels(sched)
        t = Task("MPM::interpolateParticlesToGrid", self.interpolate_particles_to_grid, ms)
        for lab in self._p2g_labels():
            t.requires(OLD, lab, g, ng)
        self.grid_volume = self._grid_volume_needed(sched)
        for lab in (L.gMass, L.gVelocity, L.gExtForce, L.gIntForce) + ((L.gVolume,) if self.grid_volume else ()):
            t.computes(lab)
        if self.pressure_bcs:
            t.requires(OLD, FL.simTime).requires(OLD, L.PressureBCParticles)
        if self.mms:
            t.requires(OLD, FL.simTime)
        sched.add_task(t)
        t = Task("MPM::interpolateStressToGrid", self.interpolate_stress_to_grid, ms)
        for lab in [L.pX, L.pMass, L.pStress] + self.size_labels():
            t.requires(OLD, lab, g, ng)
        sched.add_task(t.computes(L.gStressFS))       # pruned unless g.stressFS is saved
        self.schedule_heat_conduction(sched)
        if self.contact.needs_lr:
            self._schedule_logistic_regression(sched)
        if self.contact.interpolated:
            t = Task("MPM::exMomInterpolated", self.ex_mom_interpolated, ms) \
                .requires(NEW, L.gMass).modifies(L.gVelocity).requires(OLD, FL.delT)
            if self.contact.needs_time:
                t.requires(OLD, FL.simTime)
            if self.contact.needs_normals:
                for lab in [L.pX, L.pMass] + ([L.pVolume] if self.axisymmetric else []) + self.size_labels():
                    t.requires(OLD, lab, g, ng)
                t.computes(L.gSurfNorm)
                if self.contact.needs_traction:
                    t.requires(OLD, L.pStress, g, ng).computes(L.gNormTraction)
            self._requires_lr(t)
            sched.add_task(t)
        t = (Task("MPM::computeAndIntegrateAcceleration", self.integrate_acceleration, ms)
             .requires(OLD, FL.delT).requires(NEW, L.gMass).requires(NEW, L.gVelocity)
             .requires(NEW, L.gIntForce).requires(NEW, L.gExtForce)
             .computes(L.gVelocityStar).computes(L.gAcceleration))
        sched.add_task(t.computes(L.FTMForce) if self.ftm else t)
        self.schedule_boundary_tractions(sched)
        if self.contact.active:
            t = (Task("MPM::exMomIntegrated", self.ex_mom_integrated, ms)
                 .requires(OLD, FL.delT).requires(NEW, L.gMass).requires(NEW, L.gVelocity)
                 .modifies(L.gVelocityStar).modifies(L.gAcceleration))
            if self.contact.needs_normals:
                t.requires(NEW, L.gSurfNorm)
            if self.contact.needs_traction:
                t.requires(NEW, L.gNormTraction)
            if self.contact.needs_time:
                t.requires(OLD, FL.simTime)
            if self.contact.type == "rigid":
                t.requires(NEW, L.gIntForce).computes(L.RigidReactionForce).computes(L.RigidReactionTorque)
            if self.ftm and self.ftm_contact:
                t.computes(L.FTMContactForce)
            self._requires_lr(t)
            sched.add_task(t)
        if self.bcs.items:
            sched.add_task(Task("MPM::setGridBoundaryConditions", self.set_grid_bcs, ms)
                           .requires(OLD, FL.delT).requires(NEW, L.gVelocity)
                           .modifies(L.gVelocityStar).modifies(L.gAcceleration))
        if self.prescribed is not None:
            sched.add_task(Task("MPM::setPrescribedMotion", self.set_prescribed_motion, ms)
                           .requires(OLD, FL.simTime).modifies(L.gVelocityStar).modifies(L.gAcceleration))
        gg = 2 * ng if self.musl else ng
        if self.xpic:       # ghost particles' nodes: 2 ng around the patch
            t = Task("MPM::computeSPlusSSPlusVp", self.xpic_grid_velocity, ms)
            for lab in [L.pX, L.pMass] + self.size_labels():
                t.requires(OLD, lab, g, ng)
            sched.add_task(t.requires(NEW, L.gVelocity, Ghost.AROUND_CELLS, 2 * ng).requires(NEW, L.gMass)
                           .computes(L.gVelSPSSP))
        if self.ftm:        # after the grid BCs, which a force-transmitting material does not see
            t = (Task("MPM::computeGridVelocityForFTM", self.ftm_grid_velocity, self.ftm)
                 .requires(OLD, FL.delT).requires(NEW, L.FTMForce).requires(NEW, L.gVelocity)
                 .modifies(L.gVelocityStar).modifies(L.gAcceleration).computes(L.SumTransmittedForce))
            sched.add_task(t.requires(NEW, L.FTMContactForce) if self.ftm_contact else t)
        t = Task("MPM::interpolateToParticlesAndUpdate", self.interpolate_to_particles, ms).requires(OLD, FL.delT)
        pg = (g, ng) if self.musl else (Ghost.NONE, 0)
        for lab in [L.pX, L.pVelocity, L.pMass] + self.size_labels():
            t.requires(OLD, lab, *pg)
        t.requires(NEW, L.gVelocityStar, Ghost.AROUND_CELLS, gg).requires(NEW, L.gAcceleration, Ghost.AROUND_CELLS, gg)
        if self.xpic:
            t.requires(NEW, L.gVelocity, Ghost.AROUND_CELLS, gg).requires(NEW, L.gVelSPSSP, Ghost.AROUND_CELLS, gg)
        t.computes(L.pXpre).computes(L.pVelocityPre)
        if self.musl:
            t.requires(NEW, L.gMass).requires(OLD, FL.delT).computes(L.gVelocityL)
            if self.contact.needs_normals:
                t.requires(NEW, L.gSurfNorm)
            if self.contact.needs_traction:
                t.requires(NEW, L.gNormTraction)
            if self.contact.needs_time:
                t.requires(OLD, FL.simTime)
            if self.contact.active:
                self._requires_lr(t)
        else:       # USL: F and V in the same pass (transfer.py)
            t.computes(L.pVelGrad).requires(OLD, L.pF).computes(L.pFPre).computes(L.pVolumePre)
            if self.flags["DoPressureStabilization"]:
                t.requires(OLD, L.pVolume)
        for r in (L.CenterOfMassPosition,) + self.totals:
            t.computes(r)
        sched.add_task(t)
        self.schedule_temperature_update(sched)
        if self.has_membrane:   # 004 sec. 3.2: tangents from the neighbours along the chain
            sched.add_task(Task("MPM::membraneTangents", self.membrane_tangents, ms)
                           .requires(OLD, L.pX, Ghost.AROUND_NODES, 1).requires(OLD, L.pID, Ghost.AROUND_NODES, 1)
                           .computes(L.pTangentNbr))
        if self.av_matls:     # 004 eq. 24's c_max and max|div v| over the level, not a patch
            t = (Task("MPM::artificialViscosityScale", self.artificial_viscosity_scale, ms)
                 .requires(OLD, FL.delT).requires(OLD, L.pIntEnergy).computes(L.AVScale))
            if self.musl:
                for lab in [L.pX, L.pMass, L.pF] + self.size_labels():
                    t.requires(OLD, lab)
                t.requires(NEW, L.gVelocityL, Ghost.AROUND_CELLS, ng)
            else:
                t.requires(NEW, L.pVelGrad)
            sched.add_task(t)
            self._av_level_wide = True
        t = (Task("MPM::computeStressTensor", self.compute_stress_tensor, ms)
             .requires(OLD, FL.delT).requires(OLD, L.pVelocity))
        if self.av_matls:
            t.requires(NEW, L.AVScale)
        if any(mt.needs_time for mt in self.materials):     # the erosion's time of localization
            t.requires(OLD, FL.simTime)
            if not self.musl and any(mt.erodes_F for mt in self.materials):
                t.modifies(L.pFPre)                 # F of localized particles (damage.py)
        if self.has_membrane:
            t.requires(NEW, L.pTangentNbr)
        if any(getattr(mt.params, "density_from_grid", False) for mt in self.materials):
            if not self.musl or self.kind != "linear":     # ideal_gas_fluid.grid_volumes
                raise ValueError("<density_from_grid> needs <stress_update>musl and <interpolator>linear")
            t.requires(NEW, L.gMass, Ghost.AROUND_CELLS, ng).requires(NEW, L.gVolume, Ghost.AROUND_CELLS, ng)
        if self.musl:
            t.requires(NEW, L.gVelocityL, Ghost.AROUND_CELLS, ng).requires(OLD, L.pX)
        else:
            t.requires(NEW, L.pVelGrad).requires(NEW, L.pFPre).requires(NEW, L.pVolumePre).requires(OLD, L.pF)
            if self.has_membrane:
                t.requires(OLD, L.pVolume)
        moved = {L.pVelocity.name, L.pScaleFactor.name} | (set() if self.musl else {L.pF.name, L.pVolume.name})
        for final, pre in self.carry:
            if final.name not in moved:
                t.requires(OLD, final).computes(pre)
        if self.saves_scale:
            t.computes(L.pScaleFactorPre)
        t.computes(L.WaveSpeed).computes(L.StrainEnergy)
        if self.saves_acc_energy:
            t.computes(L.StepStrainEnergy)
        hot = [m for m, mt in enumerate(self.materials) if mt.needs_temperature]
        warm = [m for m, mt in enumerate(self.materials) if mt.uses_temperature and not mt.needs_temperature]
        if hot:                         # elastic_plastic_hp: p.temperature+ += p.dTdt dt
            t.requires(OLD, L.pTemperature, matls=hot + (warm if self.thermal else [])) \
                .modifies(L.pTemperaturePre, matls=hot)
            t.computes(L.pdTdt, matls=hot)
        elif warm and self.thermal:     # visco_scram reads the particles' temperature
            t.requires(OLD, L.pTemperature, matls=warm)
        if self.pressure_bcs:
            t.requires(OLD, FL.simTime).requires(OLD, L.PressureBCParticles).computes(L.PressureBCParticles)
            if not self.musl:
                t.requires(OLD, L.pX)
        if self.mms or self.saves_disp:     # p.displacement+ = p.displacement + p.x+ - p.x
            t.requires(NEW, L.pXpre)
            if not self.musl and not self.pressure_bcs:
                t.requires(OLD, L.pX)
        sched.add_task(t)
        schedule_acc_strain_energy(self, sched)
        if self.analysis.active:
            self.analysis.schedule(sched)
        if self.insertion is not None:
            from . import insert_particles
            insert_particles.schedule(self, sched)
        carry = self.carry + self.carry_thermal + list(self.carry_models)
        sched.schedule_particle_relocation(L.pXpre, [pre for _, pre in carry], L.pX,
                                           [final for final, _ in carry], ms, id_label=L.pID,
                                           mass_pre=L.pMassPre, on_leaving=self.flags["particles_leaving_domain"])

    def _grid_volume_needed(self, sched):
        """g.volume costs a sixth of the particle-to-grid scatter: it is computed when a task
        reads it (<density_from_grid>; a coupled component, coupled_reads_grid_volume) or
        the deck saves it or the boundary reductions (boundary_tractions.py)."""
        return (self.coupled_reads_grid_volume or "g.volume" in getattr(sched, "output_labels", ())
                or self.saves_tractions
                or any(getattr(m.params, "density_from_grid", False) for m in self.materials)
                or bool(self.pressure_bcs) or bool(self.mms))    # the scatter variant with fext adds V_i too

    def _p2g_labels(self):
        labs = [L.pX, L.pMass, L.pVelocity, L.pVolume, L.pStress]
        labs += self.size_labels()
        if self.pressure_bcs:
            labs.append(L.pLoadCurveID)
        if self.cbdi:                       # the loaded faces (cbdi.py)
            labs += [lab for lab in (L.pF, self._size_label) if lab not in labs]
        if self.mms:
            labs.append(L.pDisp)
        if self.av:
            labs.append(L.pQ)
        if self.projection:
            labs.append(L.pVelGradLast)
        return labs

    def _read_physical_bc(self, root):
        from .pressure import PressureBCs
        self.pressure_bcs = PressureBCs.read(root, self)
