"""How MPMICE reads a deck through the MPM and ICE components (one global material space).

MPM materials come first (indices 0..nm-1), then ICE's (nm..N-1), as in Uintah.
  MPMinMPMICE  MPM with the extra <MPM> flag testForNegTemps_mpm, velocity BCs read
               from a deck whose <BoundaryConditions> are ICE's (only Dirichlet velocity
               and symmetry act on the grid nodes; ICE's other BCTypes are left to ICE),
               and <contact><materials> that may name ICE materials (they are dropped).
  ICEinMPMICE  ICE whose per-material arrays (EOS code and parameters, cv, gamma,
               exchange coefficients, boundary conditions, material list) cover all N
               materials, so ICE's multi-material task bodies and kernels run over the
               global indices unchanged. A solid enters the ICE kernels with the
               condensed-phase EOS of paper 000 sec. 3.1: its bulk response
               p = p_ref + K (rho/rho0 - 1) above the threshold p_th = p_ref and
               p = p_ref (rho/rho0)^(K/p_ref) below it (C1 at p_ref, -> 0 as v -> inf);
               ICE's Murnaghan code with n = 1, P0 = p_ref is exactly that curve. The
               models Uintah builds as UCNH (comp_neo_hook, comp_neo_hook_plastic, UCNH)
               take Uintah's UCNH computePressEOSCM instead, eos.py's SOLID_UCNH:
               p_ref + K/2 (x - 1/x) above rho0 (x = rho/rho0) and c^2 = K/rho, the same
               curve below; a visco_scram solid with <useJWLEOS> its JWL (SOLID_JWL).
"""
from __future__ import annotations

import numpy as np

from components.ice.component import ICE
from components.ice.eos import MAX_PARAMS, MURNAGHAN, SOLID_JWL, SOLID_UCNH
from components.mpm.bc import GridBCs
from components.mpm.component import FLAGS, MPM
from components.mpm.contact import Contact
from framework.grid import FACES
from framework.gridspec import boundary_faces, sub_faces
from framework.problemspec import Param

from . import labels as MI


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
    """MPM grid BCs from an MPMICE deck: Dirichlet velocity and symmetry act on the nodes.

    Neumann velocity (free) and the ICE-only labels (Pressure, Temperature, Density,
    SpecificVol) have no nodal meaning for the solid; ICE reads and applies them.
    """

    n_all = 1

    def __init__(self, root, level, nmat):
        self.items = []
        grid = root.child("Grid")
        bcs = grid.child("BoundaryConditions") if grid is not None else None
        if bcs is None:
            return
        faces = [(side, None, face) for side, face in boundary_faces(bcs, FACES)] + sub_faces(bcs, FACES, level)
        for side, geom, face in faces:
            d, s = FACES.index(side) // 2, FACES.index(side) % 2
            for bc in face.children("BCType"):
                ident, var, label = bc.attr("id"), bc.attr("var"), bc.attr("label")
                if var == "symmetry":
                    comps, value = np.eye(3, dtype=np.bool_)[d], np.zeros(3)
                elif var == "Dirichlet" and label == "Velocity":
                    comps, value = np.ones(3, np.bool_), np.array(bc.get("value", "vector"), float)
                else:
                    continue
                mats = tuple(range(nmat)) if ident == "all" else tuple(m for m in (int(ident),) if m < nmat)
                if mats and not level.collapsed[d] and not level.periodic[d]:
                    self.items.append((d, s, comps, value, mats, geom))
        self._place_sub_faces(faces, nmat)


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


class _SolidStub:
    """What ICE's task bodies look up in self.materials[m] for an MPM material m."""

    def __init__(self, mat):
        self.name = mat.name
        self.viscosity = 0.0
        self.conductivity = 0.0
        self.objects = []


# the models Uintah builds as its class UCNH, whose solid EOS in MPMICE is eos.py's SOLID_UCNH
UCNH_MODELS = ("comp_neo_hook", "comp_neo_hook_plastic", "UCNH")


class ICEinMPMICE(ICE):
    """ICE over the global material index space (see the module docstring)."""

    press_floor = 1.0e-12       # Uintah's clamp of press_CC: solids in tension (tests/mpmice/test_hard_cases.py)

    def __init__(self, mpm_materials, solid_cv, p_ref_bulk):
        super().__init__()
        self.n_before = len(mpm_materials)
        self._mpm_materials = mpm_materials
        self._solid_cv = solid_cv
        self._solid_bulk = p_ref_bulk

    def problem_setup(self, root, level):
        super().problem_setup(root, level)
        nm, ice_mats = self.n_before, self.materials
        self.ice_matls = list(range(nm, nm + len(ice_mats)))
        p_ref = self.reference_pressure
        rows, codes, cvs, gammas = [], [], [], []
        for mat, K in zip(self._mpm_materials, self._solid_bulk):
            row = np.zeros(MAX_PARAMS)
            if getattr(mat.params, "useJWLEOS", False):        # visco_scram's JWL (Uintah's ViscoScram)
                q = mat.params
                row[:8] = (q.A, q.B, q.R1, q.R2, q.om, q.Cv, mat.density, p_ref if q.useModifiedEOS else 0.0)
                codes.append(SOLID_JWL)
            elif mat.model_name in UCNH_MODELS:                # Uintah's UCNH computePressEOSCM
                row[:3] = (K, mat.density, p_ref)
                codes.append(SOLID_UCNH)
            else:
                row[:4] = (1.0 / K, 1.0, mat.density, p_ref)   # Murnaghan: compressibility, n, rho0, P0
                codes.append(MURNAGHAN)
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
        """A fluid's advection next to the solids: Uintah's, or where the deck asks for it
        (`<advection openFaceTransfers="true">`) MPMICE's open_faces (tasks.py)."""
        if not self.open_faces:
            return super().advection_faces(patch, m, new_dw, dt)
        return self.coupling.open_faces(patch, m, new_dw, dt)
