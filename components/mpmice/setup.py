"""How MPMICE reads a deck through the MPM and ICE components (one global material space).

MPM materials come first (indices 0..nm-1), then ICE's (nm..N-1), as in Uintah.
  MPMinMPMICE  MPM with the extra <MPM> flag testForNegTemps_mpm, velocity BCs read
               from a deck whose <BoundaryConditions> are ICE's (only Dirichlet velocity
               and symmetry act on the grid nodes; ICE's other BCTypes are left to ICE),
               and <contact><materials> that may name ICE materials (they are dropped).
  ICEinMPMICE  ICE whose per-material arrays (EOS code and parameters, cv, gamma,
               exchange coefficients, boundary conditions, material list) cover all N
               materials, so ICE's multi-material task bodies and kernels run over the
               global indices unchanged. A solid enters the ICE kernels with its
               constitutive model's EOS, as Uintah's MPMICE calls the model's
               computePressEOSCM and computeRhoMicroCM (solid_eos: an EOS code and
               parameter row per solid, ice/eos.py SOLID_UCNH .. SOLID_JWLPP, SOLID_JWL);
               with <useModifiedEOS> below rho0 the condensed-phase threshold curve of
               paper 000 sec. 3.1, p = p_ref (rho/rho0)^(K/p_ref) (C1 at p_ref, -> 0 as
               v -> inf). rmpmice's prescribed solids too with <gas_start>geometry (Uintah's
               start and scaling): Uintah's RigidMPM keeps the deck's model, whose EOS MPMICE
               calls; with pysus's particle start (their default, unscaled) a stand-in, ICE's
               Murnaghan with n = 1, P0 = p_ref (p_ref + K (rho/rho0 - 1) above rho0, the
               threshold curve below). comp_mooney_rivlin is refused: Uintah's
               CompMooneyRivlin has none (its density 0: sus stops at step 1 with NaN).
"""
from __future__ import annotations

import numpy as np

import dataclasses
import importlib

from components.ice.component import ICE
from components.ice.eos import (MAX_PARAMS, MURNAGHAN, SOLID_HYPER, SOLID_HYPO, SOLID_IDEAL_GAS, SOLID_JWL, SOLID_JWLPP,
                                SOLID_RIGID, SOLID_UCNH)
from components.mpm.bc import GridBCs
from components.mpm.component import FLAGS, MPM
from components.mpm.contact import Contact
from components.mpm.materials import MODELS, model_kind, read_model_params
from framework.grid import FACES
from framework.gridspec import boundary_faces, sub_faces
from framework.problemspec import Param

from . import labels as MI
from .rigid import _RigidModel, _RigidView


class ContactWithICE(Contact):
    """<contact> whose <materials> list may hold ICE indices (Uintah decks do); those are dropped."""

    n_all = 1

    def __init__(self, mpm_node, nmat):
        super().__init__(mpm_node, max(nmat, self.n_all))
        self.materials = tuple(m for m in self.materials if m < nmat)
        many = len(self.materials) > 1
        self.active = self.active and many
        for flag in ("interpolated", "needs_normals", "needs_lr", "needs_color", "needs_time"):
            if hasattr(self, flag):         # one solid left (TBurner_2dRT's approach on [0]): no contact
                setattr(self, flag, getattr(self, flag) and many)


class GridBCsWithICE(GridBCs):
    """MPM grid BCs from an MPMICE deck: Dirichlet velocity and symmetry act on the nodes, and a
    Temperature condition naming a solid (id="all" or its index) on its nodal temperature (bc.py),
    as Uintah's MPM applies it to gTemperature and gTemperatureStar in MPMICE too.

    Neumann velocity (free) and the ICE-only labels (Pressure, Density, SpecificVol) have no
    nodal meaning for the solid; ICE reads and applies them.
    """

    n_all = 1

    def __init__(self, root, level, nmat):
        self.items = []
        self.temperature_items = []
        # held until MPMICE knows whether the solid carries a temperature (use_temperature_bcs)
        self.solid_temperature_items = []
        grid = root.child("Grid")
        bcs = grid.child("BoundaryConditions") if grid is not None else None
        if bcs is None:
            return
        faces = [(side, None, face) for side, face in boundary_faces(bcs, FACES)] + sub_faces(bcs, FACES, level)
        for side, geom, face in faces:
            d, s = FACES.index(side) // 2, FACES.index(side) % 2
            for bc in face.children("BCType"):
                ident, var, label = bc.attr("id"), bc.attr("var"), bc.attr("label")
                mats = tuple(range(nmat)) if ident == "all" else tuple(m for m in (int(ident),) if m < nmat)
                if label == "Temperature" and var in ("Dirichlet", "Neumann"):
                    if mats and not level.collapsed[d] and not level.periodic[d]:
                        self.temperature_node = bc
                        self.temperature_items.append((d, s, var == "Neumann", bc.get("value", "float"), mats,
                                                       geom))
                    continue
                if var == "symmetry":
                    comps, value = np.eye(3, dtype=np.bool_)[d], np.zeros(3)
                elif var == "Dirichlet" and label == "Velocity":
                    comps, value = np.ones(3, np.bool_), np.array(bc.get("value", "vector"), float)
                else:
                    continue
                if mats and not level.collapsed[d] and not level.periodic[d]:
                    self.items.append((d, s, comps, value, mats, geom))
        self._place_sub_faces(faces, nmat)
        self.solid_temperature_items, self.temperature_items = self.temperature_items, []

    def use_temperature_bcs(self):
        """Apply the Temperature conditions to the solid's nodes (it carries p.temperature)."""
        self.temperature_items = self.solid_temperature_items
        return bool(self.temperature_items)


class MPMinMPMICE(MPM):
    flags_spec = {**FLAGS, "testForNegTemps_mpm": Param("bool", True, doc="MPMICE: read; no MPM temperature")}
    coupled_reads_grid_volume = True
    saved_temperature_conducts = False     # MPMICE decides on the solids' temperature itself
    axisymmetric_refused = "with MPMICE (ICE's fluxes and the MPM-ICE pressure force are planar)"
    xpic_refused = "in MPMICE (Uintah's MPMICE does not schedule its passes either)"
    artificial_viscosity_refused = None
    ftm_refused = "in MPMICE (Uintah's MPMICE does not schedule its task either)"
    projection_refused = "in MPMICE (its particle-to-grid transfer of mass, momentum and temperature is its own)"
    totals = (MI.mpm_TotalMass, MI.mpm_KineticEnergy, MI.mpm_TotalMomentum)

    def __init__(self, n_all):
        super().__init__()
        self.contact_class = type("ContactN", (ContactWithICE,), {"n_all": n_all})
        self.grid_bcs_class = GridBCsWithICE


# constitutive model -> the EOS code of Uintah's model (ice/eos.py); its bulk modulus (Pa) from params
SOLID_EOS = {"comp_neo_hook": SOLID_UCNH, "comp_neo_hook_plastic": SOLID_UCNH, "UCNH": SOLID_UCNH,
             "UCNHVar": SOLID_UCNH,
             "elastic_plastic": SOLID_HYPER, "elastic_plastic_hp": SOLID_HYPER, "visco_scram": SOLID_HYPER,
             "hypo_elastic": SOLID_HYPO, "rigid": SOLID_RIGID,
             "membrane": SOLID_HYPER,             # Uintah's Membrane.cc (not in its build): ElasticPlasticHP's curve
             "ideal_gas_fluid": SOLID_IDEAL_GAS,  # Uintah's IdealGasMP (deck type ideal_gas)
             "jwlpp_mpm": SOLID_JWLPP}
RIGID_BULK = 1.0e200      # Uintah's RigidMaterial without <bulk_modulus>
NO_EOS = {"comp_mooney_rivlin": "Uintah's CompMooneyRivlin has no EOS for MPMICE's equilibration (its "
                                "computeRhoMicroCM returns 0: sus stops at step 1 with NaN)"}


def _bulk(mat):
    """The solid's bulk modulus for the Murnaghan stand-in (none or 0 given: effectively
    incompressible); a negative one is an input error (the rigid model itself reads any)."""
    K = getattr(mat.params, "bulk_modulus", 0.0) or 0.0
    if K < 0:
        raise mat.node.child("constitutive_model").child("bulk_modulus").error(
            f"value '{K:g}' is out of range; accepted: a finite number >= 0 (the solid's bulk modulus in "
            "the Murnaghan stand-in of its EOS)")
    return K if K > 0 else 1e12


def _asked_model(mat):
    """(deck type, Params) of an rmpmice solid's own <constitutive_model> (RigidSolid reads it as
    rigid; its EOS is the asked model's), read and range-checked as MPM reads a material's
    (materials.py: read_params, or read_model_params)."""
    node = mat.node._node if isinstance(mat.node, _RigidView) else mat.node
    cm = node.child("constitutive_model")
    kind = model_kind(cm)
    model = importlib.import_module(f"components.mpm.constitutive.{MODELS[kind]}")
    if hasattr(model, "read_params"):
        return kind, model.read_params(cm, node, mat.props)
    params = read_model_params(cm, model, kind)
    if hasattr(model, "MATERIAL_PROPERTIES"):
        params = dataclasses.replace(params, **{k: mat.props[k] for k in model.MATERIAL_PROPERTIES})
    return kind, params


def solid_eos(mat, p_ref, stand_in=False):
    """(code, parameter row) of MPM material mat's EOS in the equilibration: its Uintah model's
    computePressEOSCM (SOLID_EOS; visco_scram's <useJWLEOS> SOLID_JWL); a prescribed (rmpmice)
    solid's deck model's, as Uintah's RigidMPM keeps it. stand_in (prescribed solids left
    unscaled, pysus's particle start): Murnaghan n = 1 with the threshold at p_ref, K the
    <bulk_modulus>; an incompressible rigid solid there leaves the fluids no room where the
    particles' mapped mass fills a cell (the Mach 3 wedge stops at step 4)."""
    row = np.zeros(MAX_PARAMS)
    if stand_in:
        row[:4] = (1.0 / _bulk(mat), 1.0, mat.density, p_ref)   # Murnaghan: compressibility, n, rho0, P0
        return MURNAGHAN, row
    kind, q = mat.model_name, mat.params
    if getattr(mat, "model_asked", kind) != kind:
        kind, q = _asked_model(mat)
    cm = mat.node.child("constitutive_model")
    if isinstance(cm, _RigidModel):          # rigid.py's view of the deck's node
        cm = cm._cm
    if kind in NO_EOS:
        raise cm.error(f"type=\"{kind}\" is not accepted with MPMICE: {NO_EOS[kind]}; accepted: "
                       + ", ".join(sorted(SOLID_EOS)))
    code = SOLID_EOS[kind]
    if getattr(q, "useJWLEOS", False):                  # visco_scram's JWL (Uintah's ViscoScram)
        row[:8] = (q.A, q.B, q.R1, q.R2, q.om, q.Cv, mat.density, p_ref if q.useModifiedEOS else 0.0)
        return SOLID_JWL, row
    if code == SOLID_IDEAL_GAS:
        row[:2] = (q.gamma, q.specific_heat or mat.specific_heat)
        return code, row
    if code == SOLID_JWLPP:
        row[:7] = (q.A, q.B, q.R1, q.R2, q.omega, mat.specific_heat, mat.density)
        return code, row
    modified = (cm.get("useModifiedEOS", "bool", False) and kind not in ("UCNHVar", "membrane"))  # neither reads it
    if code == SOLID_HYPO:
        K = q.K
    elif code == SOLID_RIGID:
        K = q.bulk_modulus if q.bulk_modulus > 0.0 else RIGID_BULK
    elif kind == "UCNHVar":             # Uintah's UCNHVar: the largest entry's
        K = float(max(q.bulk_modulus))
    else:
        K = q.bulk_modulus
    row[:5] = (K, mat.density, p_ref, float(modified), float(kind == "visco_scram"))
    return code, row


class _SolidStub:
    """What ICE's task bodies look up in self.materials[m] for an MPM material m."""

    def __init__(self, mat):
        self.name = mat.name
        self.viscosity = 0.0
        self.conductivity = 0.0
        self.objects = []


class ICEinMPMICE(ICE):
    """ICE over the global material index space (see the module docstring)."""

    press_floor = 1.0e-12       # Uintah's clamp of press_CC: solids in tension (tests/mpmice/test_hard_cases.py)

    def __init__(self, mpm_materials, solid_cv, stand_in, prescribed=False):
        super().__init__()
        # the open-face transfers by default where the solids are prescribed (rmpmice): their
        # particles' velocity and volume are the solid's exact motion and extent, where a
        # deformable solid's mapped ones set off transfers that blew up a solid in tension next
        # to compressed gas (tests/mpmice/test_hard_cases.py; docs/MPMICE.md, step 12)
        self.open_faces_default = prescribed
        self.n_before = len(mpm_materials)
        self._mpm_materials = mpm_materials
        self._solid_cv = solid_cv
        self._stand_in = stand_in

    def problem_setup(self, root, level):
        super().problem_setup(root, level)
        nm, ice_mats = self.n_before, self.materials
        self.ice_matls = list(range(nm, nm + len(ice_mats)))
        p_ref = self.reference_pressure
        rows, codes = [], []
        for mat in self._mpm_materials:
            code, row = solid_eos(mat, p_ref, self._stand_in)
            codes.append(code)
            rows.append(row)
        cvs = list(self._solid_cv)
        gammas = [1.0] * nm
        self.params = np.vstack(rows + [self.params])
        self.codes = np.array(codes + list(self.codes), dtype=np.int64)
        self.cvs = np.array(cvs + list(self.cvs))
        self.gammas = np.array(gammas + list(self.gammas))
        self.materials = [_SolidStub(m) for m in self._mpm_materials] + list(ice_mats)
        self.matls = self.ice_matls
        self.exchange = True          # the solid-fluid coupling always runs through the exchange

    def material_names(self):
        return [m.name for m in self.materials]

    def advection_faces(self, patch, m, new_dw, dt):
        """A fluid's advection next to the solids: MPMICE's open_faces (tasks.py) where
        `<advection openFaceTransfers>` (by default: the solids prescribed) holds, else Uintah's."""
        if not self.open_faces:
            return super().advection_faces(patch, m, new_dw, dt)
        return self.coupling.open_faces(patch, m, new_dw, dt)
