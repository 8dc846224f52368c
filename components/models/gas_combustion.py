"""Uintah's gasCombustion model for ICE: a reacting ideal-gas mixture whose species mass
fractions are passive scalars of one ICE material, with finite-rate chemistry from a mechanism file.

    <Models><Model type="gasCombustion"><gasCombustion>
      <material> name </material>
      <mechanismFile> path </mechanismFile>        (gas_mechanism.py; the working directory, the
                                                   deck's folder and the deck's parent folders)
      <closureSpecies> N2 </closureSpecies>       its Y = 1 - sum of the others, not transported
      <Y_init> [...] </Y_init>                    the tracked species (mechanism order, closure left out)
      <geom_object> pieces <Y> [...] </Y> </geom_object> ...   regions with other fractions
      <initProfile> <filename/> <axis> x|y|z </axis> </initProfile>   a 1D profile file (below)
      <doChemistry/> <doDiffusion/> (true)  <rtol/> <atol_Y/> <atol_T/> (1e-12)
      <safety/> (0.9) <max_grow/> (2) <max_shrink/> (0.1)
    </gasCombustion></Model></Models>

Each tracked species k is the scalar scalar-Y<k> (ICE advects m Y like a PassiveScalar's f).
The model owns the material's caloric equation of state, as Uintah's: ICE carries the sensible
energy e_s(T, Y) (NASA-7, reference 298.15 K) instead of cv T, and takes T back from e_s and the
advected Y by Newton's method; cv and gamma are the mixture's per cell at the step's start (so
p = rho R_mix T). Each step every cell's reactor is integrated at constant volume over delT by
an adaptive Heun-Euler pair (gas_kinetics.chemistry_cells): the species' increments are
scalar_Y<k>_src and the change of e_s is modelEng_src, so the chemistry's heat appears as the
energy of formation moves into sensible energy. With doDiffusion, the species diffuse with
mixture-averaged coefficients (Fick's law on mole fractions with the mass-conserving correction)
and carry their sensible enthalpy.

<initProfile> (Uintah's): every cell, extra cells included, takes T, the axis' velocity, rho and
the tracked species from the file's rows (x T u rho p Y_1 .. Y_nt, '#' lines skipped) linearly
interpolated at its centre (the end rows beyond them); cv, gamma and the speed of sound are the
mixture's there (p = rho R_mix T, the file's p unused).

The mixture's viscosity (Wilke's rule) and thermal conductivity, of the step's start, are
ICE's viscosity and thermalCond where the material's <dynamic_viscosity> or
<thermal_conductivity> is non-zero (they turn ICE's viscous and conduction terms on, as in
Uintah): the stress, the heat flux and the delT's diffusion limit then use them per cell
(0 with doDiffusion false). Saved only when a deck asks: HeatReleaseRate (W/m^3), dt_chemistry
(the smallest sub-step a cell took), viscosity and thermalCond, diffCoef-Y<k>.

pysus runs it in explicit ICE with one material (LODI faces allowed), without
<dynamicViscosityModels>, <turbulence> or the conservative delT; <units> other than SI are
refused.
"""
from __future__ import annotations

import numpy as np

from components.ice import labels as I
from framework import labels as L
from framework.task import NEW, OLD, Task
from framework.variables import Ghost, VarType

from . import gas_kinetics as GK
from . import labels as ML
from .gas_mechanism import find_mechanism_file, read_mechanism
from .simple_burn import _material

CC = VarType.CC
HeatReleaseRate = L.create("HeatReleaseRate", CC)
dt_chemistry = L.create("dt_chemistry", CC)
dt_chemistry_limiter = L.create("dt_chemistry_limiter", CC)
SI_UNITS = {"length": "m", "mass": "kg", "time": "s", "temperature": "K"}


class SpeciesScalar:
    """One tracked species as ICE's transported scalar (the model computes its initial value and
    source; ICE advects m Y and applies the boundary conditions of scalar-Y<k>)."""

    def __init__(self, name, matl):
        self.name = f"scalar-Y{name}"
        self.matl = matl
        self.f = L.create(self.name, CC)
        self.src = L.create(f"scalar_Y{name}_src", CC)
        self.f_L = L.create(self.name + "_L", CC)

    def schedule_initialize(self, sched):
        pass                            # GasCombustion.initialize computes every species

    def schedule_sources(self, sched):
        pass                            # GasCombustion.sources_task computes every source

    def schedule_conservation(self, sched, dirs):
        pass


class GasCombustion:
    """One <Model type="gasCombustion">: the mechanism, the species' scalars and the integrator's knobs."""

    owns_caloric_eos = True

    def __init__(self, node, ice, geo):
        self.ice = ice
        gc = node.child("gasCombustion", required=True)
        self.node = gc
        self.matl = _material(gc, "material", ice.material_names())
        closure = gc.child("closureSpecies")
        if closure is None:
            raise gc.error("<closureSpecies> is missing: name the species set by 1 - the sum of the others "
                           "(normally the inert bath gas, e.g. N2)")
        mech_node = gc.child("mechanismFile", required=True)
        name = mech_node.text().strip()
        path = find_mechanism_file(name, gc.filename)
        if path is None:
            raise mech_node.error(f"mechanism file {name} not found (looked in the working directory, next to the "
                                  "deck and in the deck's parent folders)")
        self.mech = read_mechanism(path, closure.text().strip())
        self.kin = GK.kinetics(self.mech)
        m = self.mech
        self.tracked = [m.names[k] for k in m.tracked]
        nt = len(self.tracked)
        self.do_chemistry = gc.get("doChemistry", "bool", True)
        self.do_diffusion = gc.get("doDiffusion", "bool", True)
        gc.get("debug", "bool", False)
        gc.get("debugCell", "str", "")
        self.rtol = gc.get("rtol", "float", 1e-12, above=0.0)
        self.atol_y = gc.get("atol_Y", "float", 1e-12, above=0.0)
        self.atol_t = gc.get("atol_T", "float", 1e-12, above=0.0)
        self.safety = gc.get("safety", "float", 0.9, above=0.0)
        self.max_grow = gc.get("max_grow", "float", 2.0, above=0.0)
        self.max_shrink = gc.get("max_shrink", "float", 0.1, above=0.0)
        units = gc.child("units")
        if units is not None:
            for tag, si in SI_UNITS.items():
                u = units.get(tag, "str", si).strip()
                if u != si:
                    raise units.child(tag).error(f"<{tag}> {u}: pysus's gasCombustion takes SI units; accepted: {si}")
        self.y_init = self._fractions(gc, "Y_init", nt)
        self.profile = self._read_profile(gc.child("initProfile"), nt) if gc.has("initProfile") else None
        self.regions = []
        for go in gc.children("geom_object"):
            self.regions.append((geo.read_object(go), self._fractions(go, "Y", nt)))
        self.species = [SpeciesScalar(s, self.matl) for s in self.tracked]
        self.diff_coef = [L.create(f"diffCoef-Y{s}", CC) for s in m.names]
        self.t_warn = np.array([m.t_low, m.t_high])
        self.t_hard = np.array([0.6 * m.t_low, 1.4 * m.t_high])
        self._warned = False

    def _fractions(self, node, tag, nt):
        """A tracked-species list of mass fractions (<Y_init>, a region's <Y>), checked."""
        y = np.array(self._list(node, tag))
        if y.size != nt:
            raise node.child(tag).error(f"{y.size} mass fractions; accepted: {nt}, the tracked species "
                                        f"{' '.join(self.tracked)} (the closure species left out)")
        if y.sum() > 1.0 + 1e-6:
            raise node.child(tag).error(f"the mass fractions sum to {y.sum():.6g} > 1 (the closure species "
                                        "would be negative)")
        if np.any(y < 0.0):
            raise node.child(tag).error("a negative mass fraction; accepted: values in [0, 1]")
        return y

    @staticmethod
    def _read_profile(node, nt):
        """<initProfile>: the file's rows x T u rho p Y_1 .. Y_nt (the tracked species in mechanism
        order; '#' lines and blank lines skipped, further columns ignored) as (axis, x, table) with
        table's rows T, u, rho, Y_1 .. Y_nt (Uintah's gasCombustion reads the same columns; it
        takes p from rho R_mix T instead of the file's)."""
        axis_name = node.get("axis", "str").strip().upper()
        if axis_name not in ("X", "Y", "Z"):
            raise node.child("axis").error(f"<axis> {axis_name.lower()}; accepted: x, y, z")
        name = node.get("filename", "str").strip()
        path = find_mechanism_file(name, node.filename)
        if path is None:
            raise node.child("filename").error(f"profile file {name} not found (looked in the working directory, next "
                                               "to the deck and in the deck's parent folders)")
        rows = []
        with open(path) as f:
            for number, line in enumerate(f, 1):
                if not line.strip() or line.startswith("#"):
                    continue
                words = line.split()
                try:
                    values = [float(w) for w in words[:5 + nt]]
                except ValueError:
                    raise node.child("filename").error(f"{path}:{number}: cannot read numbers from this row") from None
                if len(values) < 5 + nt:
                    raise node.child("filename").error(f"{path}:{number}: {len(values)} columns; accepted: x T u rho p "
                                                       f"and the {nt} tracked species' mass fractions")
                rows.append(values)
        if len(rows) < 2:
            raise node.child("filename").error(f"{path}: {len(rows)} data rows; accepted: at least 2")
        data = np.array(rows)
        if np.any(np.diff(data[:, 0]) <= 0.0):
            raise node.child("filename").error(f"{path}: the positions x (first column) must increase row by row")
        table = np.ascontiguousarray(np.delete(data[:, 1:], 3, axis=1).T)     # T u rho Y..., p left out
        return "XYZ".index(axis_name), np.ascontiguousarray(data[:, 0]), table

    @staticmethod
    def _list(node, tag):
        text = node.get(tag, "str").replace("[", " ").replace("]", " ").replace(",", " ")
        try:
            return [float(x) for x in text.split()]
        except ValueError:
            raise node.child(tag).error(f"cannot read numbers from '{text.strip()}'") from None

    def check(self, ice):
        """The ICE set-ups pysus's gasCombustion runs in (module docstring), refused otherwise."""
        mat = ice.materials[self.matl]
        where = self.node.child("material")
        if len(ice.materials) > 1 or ice.n_before:
            raise where.error("gasCombustion is available with one ICE material (ICE alone)")
        if ice.implicit:
            raise where.error("gasCombustion is available with explicit ICE only (no <ImplicitSolver>)")
        if ice.conserve_energy:
            raise where.error("gasCombustion is not available with <conserveTotalEnergy>")
        if getattr(mat, "viscosity_models", None):
            raise where.error("gasCombustion gives the material's viscosity itself; accepted: no "
                              "<dynamicViscosityModels>")
        if ice.turbulence is not None:
            raise where.error("gasCombustion is not available with a <turbulence> model")
        if ice.conservative_dt and (mat.viscosity > 0.0 or mat.conductivity > 0.0):
            raise where.error("gasCombustion with a non-zero <dynamic_viscosity> or <thermal_conductivity> takes the "
                              "aggressive delT; accepted: <Scheme_for_delT_calc> aggressive")
        if getattr(mat, "cv_model", None) is not None:
            raise where.error("gasCombustion gives the material's cv itself; accepted: no <SpecificHeatModel>")

    # -- ICE's caloric equation of state -----------------------------------------------------
    def _y_stack(self, dw, patch, view=None):
        """The tracked species' fractions of a data warehouse as one (nt, ...) array."""
        arrs = [dw.get(s.f, self.matl, patch) for s in self.species]
        if view is not None:
            arrs = [view(a) for a in arrs]
        return np.ascontiguousarray(np.stack(arrs))

    def thermo(self, patch, temp, cv, gamma, dw, lo, hi):
        """cv and gamma of the mixture at (temp, Y of dw, or Y itself: an (nt, ...) array) over [lo, hi)."""
        y = dw if isinstance(dw, np.ndarray) else self._y_stack(dw, patch)
        bad = GK.thermo_cells(self.kin, y, lo, hi, (temp, cv, gamma))
        if bad[0] >= 0:
            raise RuntimeError(f"gasCombustion: the mixture's cv is negative in cell {self._cell(patch, bad)}")

    def carrier_cv(self, patch, temp, dw, lo, hi, view=None):
        """e_s(T, Y) / T over [lo, hi): the 'cv' with which ICE's m cv T is the carried energy m e_s."""
        y = self._y_stack(dw, patch, view)
        es = np.zeros(temp.shape)
        GK.energy_cells(self.kin, y, lo, hi, (temp, es))
        sl = tuple(slice(a, b) for a, b in zip(lo, hi))
        out = np.ones(temp.shape)
        out[sl] = es[sl] / temp[sl]
        return out

    def temperature(self, patch, es, y, temp, lo, hi):
        """temp = T(e_s, Y) over [lo, hi) (es and temp may be one array)."""
        bad = GK.temperature_cells(self.kin, y, lo, hi, (es, temp, self.mech.t_low, self.mech.t_high))
        if bad[0] >= 0:
            raise RuntimeError(f"gasCombustion: no temperature for the sensible energy in cell {self._cell(patch, bad)} "
                               "(Newton's method did not converge)")

    def sensible_energy(self, temp, y, es, lo, hi):
        """es = e_s(T, Y) over [lo, hi) (y: the tracked species, an (nt, ...) array)."""
        GK.energy_cells(self.kin, y, lo, hi, (temp, es))

    @staticmethod
    def _cell(patch, ijk):
        return tuple(int(a) + int(b) for a, b in zip(ijk, patch.low_index(VarType.CC)))

    # -- scheduling (the ICE component calls these) ----------------------------------------------
    def schedule_initialize(self, sched):
        t = Task("gasCombustion::initialize", self.initialize, [self.matl]) \
            .modifies(I.specific_heat).modifies(I.gamma)
        if self.profile is None:
            t.requires(NEW, I.temp_CC)
        else:
            for lab in (I.temp_CC, I.vel_CC, I.rho_CC, I.sp_vol_CC, I.speedSound_CC):
                t.modifies(lab)
        for s in self.species:
            t.computes(s.f)
        sched.add_task(t)

    def schedule_sources(self, sched):
        g = (Ghost.AROUND_CELLS, 1) if self.do_diffusion else ()
        t = Task("gasCombustion::computeModelSources", self.sources_task, [self.matl]) \
            .requires(OLD, L.delT).requires(OLD, I.temp_CC, *g).requires(OLD, I.rho_CC, *g) \
            .computes(ML.modelEng_src).computes(HeatReleaseRate).computes(dt_chemistry)
        for s in self.species:
            t.requires(OLD, s.f, *g).computes(s.src)
        sched.add_task(t)
        sched.add_task(Task("gasCombustion::zeroSources", self.zero_sources, [self.matl])    # only when saved
                       .computes(ML.modelMass_src).computes(ML.modelMom_src))
        t = Task("gasCombustion::transportProperties", self.transport_task, [self.matl]) \
            .requires(OLD, I.temp_CC).requires(OLD, I.rho_CC).computes(I.viscosity).computes(I.thermalCond)
        for s in self.species:
            t.requires(OLD, s.f)
        for lab in self.diff_coef:
            t.computes(lab)
        sched.add_task(t)                       # for ICE's viscous, conduction and delT terms, or when saved

    def lagrangian_requires(self, t):
        t.requires(NEW, ML.modelEng_src, matls=[self.matl])
        for s in self.species:
            t.requires(OLD, s.f, matls=[self.matl])

    # -- tasks -----------------------------------------------------------------------------------
    def initialize(self, patch, matls, old_dw, new_dw):
        """Y_init everywhere (extra cells included), each <geom_object>'s Y in the interior cells whose
        centre it holds (later regions win), then cv and gamma of the mixture at the initial
        temperature, extra cells included (Uintah's gasCombustion::initialize)."""
        b = self.ice.boxes(patch)
        arrs = [new_dw.allocate(s.f, self.matl, patch) for s in self.species]
        for a, y0 in zip(arrs, self.y_init):
            a[...] = y0
        if self.regions:
            inner = tuple(slice(l, h) for l, h in zip(b.lo, b.hi))
            x = _centres(patch, b)
            for piece, y in self.regions:
                hit = piece.inside(x).reshape(arrs[0][inner].shape)
                for a, yk in zip(arrs, y):
                    a[inner][hit] = yk
        if self.profile is not None:
            self._initialize_profile(patch, b, arrs, new_dw)
            return
        temp = new_dw.get(I.temp_CC, self.matl, patch)
        self.thermo(patch, temp, new_dw.get_modifiable(I.specific_heat, self.matl, patch),
                    new_dw.get_modifiable(I.gamma, self.matl, patch), np.stack(arrs), b.olo, b.ohi)

    def _initialize_profile(self, patch, b, arrs, new_dw):
        """<initProfile> (Uintah's gasCombustion::initialize): every cell, extra cells included,
        takes T, the axis' velocity (the others 0), rho (sp_vol = 1 / rho) and the species from
        the profile at its centre; cv, gamma and the speed of sound are the mixture's there."""
        axis, px, table = self.profile
        m = self.matl
        lv = patch.level
        dx = lv.dx[axis]
        idx = np.arange(b.olo[axis], b.ohi[axis]) + patch.low_index(VarType.CC)[axis]
        xq = lv.anchor[axis] + dx * idx + dx * 0.5        # Uintah's Level::getCellPosition
        vals = np.empty((table.shape[0], xq.size))
        GK.interpolate_profile(px, table, xq, vals)
        shape = [1, 1, 1]
        shape[axis] = xq.size
        own = tuple(slice(l, h) for l, h in zip(b.olo, b.ohi))
        temp, vel, rho, spv, cs = (new_dw.get_modifiable(lab, m, patch) for lab in
                                   (I.temp_CC, I.vel_CC, I.rho_CC, I.sp_vol_CC, I.speedSound_CC))
        temp[own] = vals[0].reshape(shape)
        vel[own] = 0.0
        vel[own + (axis,)] = vals[1].reshape(shape)
        rho[own] = vals[2].reshape(shape)
        spv[own] = 1.0 / rho[own]
        for a, v in zip(arrs, vals[3:]):
            a[own] = v.reshape(shape)
        bad = GK.sound_cells(self.kin, np.stack(arrs), b.olo, b.ohi,
                             (temp, rho, new_dw.get_modifiable(I.specific_heat, m, patch),
                              new_dw.get_modifiable(I.gamma, m, patch), cs))
        if bad[0] >= 0:
            raise RuntimeError(f"gasCombustion: the mixture's cv is negative in cell {self._cell(patch, bad)}")

    def sources_task(self, patch, matls, old_dw, new_dw):
        """The chemistry of every interior cell over delT (gas_kinetics.chemistry_cells), then the
        species' diffusion: scalar_Y<k>_src, modelEng_src, HeatReleaseRate and dt_chemistry."""
        b = self.ice.boxes(patch)
        m = self.matl
        dt = float(old_dw.get_reduction(L.delT))
        temp, rho = old_dw.get(I.temp_CC, m, patch), old_dw.get(I.rho_CC, m, patch)
        y = self._y_stack(old_dw, patch)
        src = np.zeros(y.shape)
        eng = new_dw.allocate(ML.modelEng_src, m, patch)
        hrr = new_dw.allocate(HeatReleaseRate, m, patch)
        dtc = new_dw.allocate(dt_chemistry, m, patch)
        dtc[...] = dt
        limiter = np.full(temp.shape, -1.0)
        status = GK.chemistry_cells(self.kin, y, temp, rho, src, eng, dtc, limiter, hrr, b.lo, b.hi, dt, b.vol,
                                    self.rtol, self.atol_y, self.atol_t, self.safety, self.max_grow, self.max_shrink,
                                    self.t_warn, self.t_hard, self.do_chemistry)
        if status[0] != GK.OK:
            raise RuntimeError(f"gasCombustion: {_STATUS[status[0]]} {status[4]:.6g} in cell "
                               f"{self._cell(patch, status[1:4])}")
        if status[5] and not self._warned:
            self._warned = True
            print(f"gasCombustion: temperatures outside the NASA-7 range [{self.mech.t_low:g}, "
                  f"{self.mech.t_high:g}] K (the polynomials are extrapolated there)", flush=True)
        if self.do_diffusion:
            GK.diffusion_sources(self.kin, y, temp, rho, src, eng, self.ice.dims, b.lo, b.hi, patch.level.dx, dt)
        for k, s in enumerate(self.species):
            new_dw.put(s.src, m, patch, np.ascontiguousarray(src[k]))

    def zero_sources(self, patch, matls, old_dw, new_dw):
        """modelMass_src and modelMom_src: the model moves no mass and no momentum."""
        new_dw.allocate(ML.modelMass_src, self.matl, patch)
        new_dw.allocate(ML.modelMom_src, self.matl, patch)

    def transport_task(self, patch, matls, old_dw, new_dw):
        """The mixture's viscosity, thermalCond and diffCoef-Y<k> of the step's start, extra cells included."""
        b = self.ice.boxes(patch)
        m = self.matl
        temp, rho = old_dw.get(I.temp_CC, m, patch), old_dw.get(I.rho_CC, m, patch)
        mu = new_dw.allocate(I.viscosity, m, patch)
        lam = new_dw.allocate(I.thermalCond, m, patch)
        diff = np.zeros((len(self.mech.names),) + temp.shape)
        GK.transport_cells(self.kin, self._y_stack(old_dw, patch), b.olo, b.ohi, (temp, rho, mu, lam, diff))
        if not self.do_diffusion:
            mu[...] = 0.0
            lam[...] = 0.0
            diff[...] = 0.0
        for k, lab in enumerate(self.diff_coef):
            new_dw.put(lab, m, patch, np.ascontiguousarray(diff[k]))

    def add_lagrangian(self, patch, m, mass_L, mom_L, eng_L, old_dw, new_dw):
        """(m e)_L += modelEng_src in the interior cells."""
        if m != self.matl:
            return
        b = self.ice.boxes(patch)
        sl = tuple(slice(l, h) for l, h in zip(b.lo, b.hi))
        eng = eng_L[sl]
        eng += new_dw.get(ML.modelEng_src, m, patch)[sl]


_STATUS = {GK.NEG_DENSITY: "non-positive density", GK.HARD_T: "temperature outside the hard limits",
           GK.NEG_Y: "negative mass fraction", GK.BAD_SUM: "mass fractions summing to",
           GK.NO_CONVERGENCE: "the chemistry integration did not converge at temperature"}


def _centres(patch, b):
    """Centres (n, 3) of a patch's interior cells, in C order."""
    lv = patch.level
    low = np.array(patch.low_index(VarType.CC))
    axes = [lv.anchor[d] + (np.arange(b.lo[d], b.hi[d]) + low[d] + 0.5) * lv.dx[d] for d in range(3)]
    g = np.meshgrid(*axes, indexing="ij")
    return np.stack([a.ravel() for a in g], axis=1)
