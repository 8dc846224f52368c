"""Heat in the MPM solids: particle temperature and explicit heat conduction on the grid.

Uintah's MPM HeatConduction (explicit), written as three tasks per timestep:

  MPM::interpolateTemperatureToGrid   g.temperature = sum S m T_p / m_i (mass-weighted)
  MPM::computeInternalHeatRate        g.temperatureRate: m_i cv dT_i/dt = -sum_p V_p k
                                      grad S_ip . grad T_p (the Galerkin weak form of
                                      rho cv dT/dt = div(k grad T) with particle quadrature;
                                      no flux leaves a free surface)
  MPM::updateParticleTemperature      T_p += dt sum S_ip (dT/dt)_i, plus MPMICE's exchange
                                      rate (dTdt_NC) when the solid is coupled to fluids, and
                                      p.temperatureGradient = sum_i T*_i grad S_ip of
                                      g.temperatureStar T* = g.temperature + dt dT/dt

grad T_p is a particle variable carried from step to step, as Uintah's p.temperatureGradient:
the conduction of step n+1 uses the gradient of step n's T* at the particles' positions of
step n (zero at the start, so the first step conducts nothing). The lag is first order in dt.
`<MPM><conduction_gradient>current` (pysus) takes grad T_p = sum_j T_j grad S_jp of this
step's g.temperature instead, in computeInternalHeatRate: nothing is carried, and a ghost
particle's grad T reads g.temperature at its own nodes, up to 2 ng beyond the patch, which
the task requires from the neighbours (AroundCells 2 ng). The owned nodes' rates take only
ghost particles within reach of them, whose nodes lie within ng; the wider halo keeps every
ghost gradient defined.

Since sum_i grad S_ip = 0, the conduction rates conserve sum_i m_i cv T_i exactly and the
particle update hands every node's heat to its particles in proportion to S m: an
insulated body keeps its heat to round-off. A particle near a nearly empty node takes
S_ip dT_i/dt from it, whose 1/m_i the small S_ip cancels, so such nodes do not limit the
step. Ghost particles bring their own grad T_p (AroundNodes) or the nodes to take it from, and
every patch computes its own nodes in particle-ID order, so 1, 2, 3 ranks agree bitwise.

The tasks run only when `<MPM><DoExplicitHeatConduction>` is true, MPMICE needs the
solid temperature (heat exchange with a fluid) or a constitutive model reads it
(elastic_plastic with sub-models, which adds its own p.dTdt dt afterwards); the conduction task only for materials
with thermal_conductivity > 0. Forward Euler on the lumped-mass linear element is stable for
dt <= rho cv / (2 k sum_d 1/dx_d^2) (the finite-difference limit); with the gradient a step
late a mode with dt lambda = -a grows as z^2 - z + a = 0, stable for a <= 1, half of that
(measured: the bar of tests/mpm/test_thermal.py blows up at 0.6 of the Euler limit, runs at
0.55). The stable timestep takes rho cv / (4 k sum_d 1/dx_d^2) into account (Uintah's has no
thermal limit), with this step's gradient the Euler limit rho cv / (2 k sum_d 1/dx_d^2).
"""
from __future__ import annotations

import numpy as np
from numba import njit

from framework import labels as FL
from framework.task import NEW, OLD, Task
from framework.variables import Ghost, VarType

from . import labels as L
from .shape import _counts as _sizes
from .shape import AXI, CPDI, GIMP, LINEAR, _corners, _over_nodes, _stencil

FM = {'contract'}
NC = VarType.NC


@njit(cache=True, inline="always")
def _inv(dx, act):
    """The inverse spacings of the active axes, then the spacings (as shape._inv_dx)."""
    return ((1.0 / dx[0] if act & 1 else 0.0), (1.0 / dx[1] if act & 2 else 0.0), (1.0 / dx[2] if act & 4 else 0.0),
            float(dx[0]), float(dx[1]), float(dx[2]))


@njit(cache=True, fastmath=FM, inline="always")
def _share(acc, args, act, x, y, z, n, wa, wb, wc, ga, gb, gc, ha):
    """p2g_heat at one node: += m T S."""
    f, mT = args
    f[n] += mT * wa * wb * wc
    return acc


@njit(cache=True, fastmath=FM)
def p2g_heat(kind, act, px, particle_mass, particle_temperature, lp, anchor, dx, node_low, grid_mass_temperature):
    """gmT_i += sum_p S_ip m_p T_p (shares beyond the node array dropped)."""
    ih = _inv(dx, act)
    f = grid_mass_temperature.reshape(-1)
    for p in range(px.shape[0]):
        mT = particle_mass[p] * particle_temperature[p]
        for q in range(_corners(kind, act)):
            st = _stencil(kind, act, px, lp, p, anchor, ih, node_low, q)
            _over_nodes(_share, kind, act, (st[0], st[1], st[2]), grid_mass_temperature.shape, st[3:], True, 0.0,
                        (f, mT))


@njit(cache=True, fastmath=FM, inline="always")
def _conduct(acc, args, act, x, y, z, n, wa, wb, wc, ga, gb, gc, ha):
    """heat_rate at one node: -= (k/cv) V grad S . grad T_p."""
    fa, s, t0, t1, t2 = args
    fa[n] -= s * (ga * wb * wc * t0 + wa * gb * wc * t1 + wa * wb * gc * t2)
    return acc


@njit(cache=True, fastmath=FM)
def heat_rate(kind, act, px, particle_volume, particle_temperature_gradient, lp, anchor, dx, node_low,
              conductivity_over_cv, grid_heat_rate):
    """heat_rate_i -= (k/cv) V_p grad S_ip . grad T_p with the particles' grad T_p of the last
    step (Uintah's computeInternalHeatRate, which reads p.temperatureGradient from the old DW);
    shares beyond the node array dropped."""
    ih = _inv(dx, act)
    fa = grid_heat_rate.reshape(-1)
    for p in range(px.shape[0]):
        args = (fa, conductivity_over_cv * particle_volume[p], particle_temperature_gradient[p, 0],
                particle_temperature_gradient[p, 1], particle_temperature_gradient[p, 2])
        for q in range(_corners(kind, act)):
            st = _stencil(kind, act, px, lp, p, anchor, ih, node_low, q)
            _over_nodes(_conduct, kind, act, (st[0], st[1], st[2]), grid_heat_rate.shape, st[3:], True, 0.0, args)


@njit(cache=True, fastmath=FM, inline="always")
def _gradient(acc, args, act, x, y, z, n, wa, wb, wc, ga, gb, gc, ha):
    """grid_temperature_gradient at one node: += T_i grad S_ip."""
    t0, t1, t2 = acc
    T = args[n]
    return t0 + T * ga * wb * wc, t1 + T * wa * gb * wc, t2 + T * wa * wb * gc


@njit(cache=True, fastmath=FM)
def grid_temperature_gradient(kind, act, px, lp, anchor, dx, node_low, grid_temperature, gradient_out):
    """grad T_p = sum_i T_i grad S_ip of this step's g.temperature (<conduction_gradient>current);
    every particle's nodes must lie in the node array."""
    sh0, sh1, sh2 = grid_temperature.shape
    na, nb, nc = _sizes(kind, act)
    ih = _inv(dx, act)
    ft = grid_temperature.reshape(-1)
    for p in range(px.shape[0]):
        acc = (0.0, 0.0, 0.0)
        for q in range(_corners(kind, act)):
            st = _stencil(kind, act, px, lp, p, anchor, ih, node_low, q)
            i, j, k = st[0], st[1], st[2]
            if not (i >= 0 and i + na <= sh0 and j >= 0 and j + nb <= sh1 and k >= 0 and k + nc <= sh2):
                raise IndexError("particle's nodes lie outside the patch node arrays")
            acc = _over_nodes(_gradient, kind, act, (i, j, k), (sh0, sh1, sh2), st[3:], False, acc, ft)
        gradient_out[p, 0], gradient_out[p, 1], gradient_out[p, 2] = acc


@njit(cache=True, fastmath=FM, inline="always")
def _gather_heat(acc, args, act, x, y, z, n, wa, wb, wc, ga, gb, gc, ha):
    """g2p_heat at one node: += S rate_i and, with the gradient, T*_i grad S."""
    r, t0, t1, t2 = acc
    fr, fs, with_gradient = args
    r += wa * wb * wc * fr[n]
    if with_gradient:
        T = fs[n]
        t0 += T * ga * wb * wc
        t1 += T * wa * gb * wc
        t2 += T * wa * wb * gc
    return r, t0, t1, t2


@njit(cache=True, fastmath=FM)
def g2p_heat(kind, act, px, particle_temperature, particle_mass, lp, anchor, dx, node_low, grid_temperature_rate, dt,
             T_out, specific_heat, grid_temperature_star, gradient_out):
    """T_p += dt sum S_ip rate_i; returns sum m_p cv T_p of the updated particles. Unless
    gradient_out is empty, also grad T_p = sum_i T*_i grad S_ip of g.temperatureStar
    (Uintah's p.temperatureGradient of interpolateToParticlesAndUpdate, at the same x_p)."""
    sh0, sh1, sh2 = grid_temperature_rate.shape
    na, nb, nc = _sizes(kind, act)
    ih = _inv(dx, act)
    args = (grid_temperature_rate.reshape(-1), grid_temperature_star.reshape(-1), gradient_out.shape[0] > 0)
    e = 0.0
    for p in range(px.shape[0]):
        acc = (0.0, 0.0, 0.0, 0.0)
        for q in range(_corners(kind, act)):
            st = _stencil(kind, act, px, lp, p, anchor, ih, node_low, q)
            i, j, k = st[0], st[1], st[2]
            if not (i >= 0 and i + na <= sh0 and j >= 0 and j + nb <= sh1 and k >= 0 and k + nc <= sh2):
                raise IndexError("particle's nodes lie outside the patch node arrays")
            acc = _over_nodes(_gather_heat, kind, act, (i, j, k), (sh0, sh1, sh2), st[3:], False, acc, args)
        r, t0, t1, t2 = acc
        T = particle_temperature[p] + dt * r
        T_out[p] = T
        e += particle_mass[p] * specific_heat * T
        if args[2]:
            gradient_out[p, 0] = t0
            gradient_out[p, 1] = t1
            gradient_out[p, 2] = t2
    return e


@njit(cache=True)
def contact_temperature_rate(gmass, gT, cv, dt, out):
    """Uintah's STThermalContact: every material's nodal temperature relaxes in one step to
    the heat-capacity-weighted mean, out_m = (sum m cv T / sum m cv - T_m)/dt (0 where no
    material has mass). gmass, gT, out: (materials, nodes)."""
    nm, nn = gmass.shape
    for i in range(nn):
        num = 0.0
        den = 0.0
        for m in range(nm):
            num += gT[m, i] * gmass[m, i] * cv[m]
            den += gmass[m, i] * cv[m]
        for m in range(nm):
            out[m, i] = (num / den - gT[m, i]) / dt if den > 0.0 else 0.0


@njit(cache=True)
def divide_by_mass(gm, q, out):
    """out_i = q_i / m_i where m_i > 0, else 0 (g.temperature, g.temperatureRate)."""
    f, fm, fo = q.reshape(-1), gm.reshape(-1), out.reshape(-1)
    for n in range(f.shape[0]):
        fo[n] = f[n] / fm[n] if fm[n] > 0.0 else 0.0


def _total(rates, shape):
    """The sum of the nodal rate arrays (the one array itself; zeros for none)."""
    if len(rates) == 1:
        return rates[0]
    return sum(rates) if rates else np.zeros(shape)


class _Keep:
    """A new warehouse whose put_reduction is kept (to combine two stable timesteps)."""

    def __init__(self, dw):
        self.dw, self.value = dw, None

    def __getattr__(self, name):
        return getattr(self.dw, name)

    def put_reduction(self, label, value, m=-1):
        self.value = value


class ThermalTasks:
    """Mixed into the MPM component (before MPMTasks): the heat tasks and their scheduling.

    `thermal_rates` lists extra NC rate labels (MPMICE: dTdt_NC) that the particle update
    adds to the conduction rate; `thermal_needed` turns the model on without the flag.

    `<MaterialProperties><MPM><thermal_contact/>` (Uintah's STThermalContact, no tags): at
    every node the materials' temperatures relax to their heat-capacity-weighted mean
    in one step (g.thermalContactTemperatureRate, one more of the rates). Dirichlet
    "Temperature" grid BCs (bc.py) set g.temperature on their nodes (the interpolated
    one kept as g.temperatureNoBC), and the particle update takes the total nodal rate
    as (T* - g.temperatureNoBC)/dt with T* = g.temperature + rate dt and the BC applied
    to T* (Uintah's integrateTemperatureRate). Both need heat conduction on."""

    thermal_needed = False
    thermal_rates = ()
    thermal_contact_node = None

    def thermal_setup(self):
        """After the materials are read: which tasks this deck needs."""
        node = self.thermal_contact_node
        self.temperature_bcs = bool(self.bcs.temperature_items)
        # Uintah's default is conduction on: a deck that leaves the flag out and asks for thermal
        # contact, Temperature BCs or saves p.temperature gets it (pysus's default, off, only spares decks without them)
        implied = not self.heat_flag_given and (node is not None or self.temperature_bcs
                                                 or getattr(self, "saves_temperature", False))
        # elastic_plastic_hp carries p.temperature (its p.dTdt heats the particles) but conducts
        # only where Uintah would: not with <DoExplicitHeatConduction>false
        carries_T = any(m.needs_temperature for m in self.materials)
        conduct = (bool(self.flags["DoExplicitHeatConduction"]) or self.thermal_needed or implied
                   or (carries_T and not self.heat_flag_given))
        self.thermal = conduct or carries_T
        self.conducting = [m for m, mat in enumerate(self.materials) if conduct and mat.conductivity > 0]
        # grad T_p of the conduction: carried from the last step (Uintah's) or this step's (pysus)
        self.gradient_carried = bool(self.conducting) and self.flags["conduction_gradient"] == "previous"
        for m in self.conducting:
            if self.materials[m].specific_heat <= 0:
                raise self.materials[m].node.error(
                    "heat conduction needs <specific_heat> > 0 (thermal_conductivity is positive)")
        # active-axis mask of the kernels; axisymmetric: the r-weighted weights (shape.AXI), as
        # Uintah's g.temperature (the heat of a non-conducting run: conduction is refused there)
        self.th_act = sum(1 << d for d in range(3) if self.dims[d]) | (AXI if self.axisymmetric else 0)
        self.thermal_contact = node is not None and len(self.materials) > 1
        for what, given, where in (("<thermal_contact>", node is not None, node),
                                   ("a Temperature grid BC", self.temperature_bcs, None)):
            if given and not self.thermal:
                where = where or self.bcs.temperature_node
                raise where.error(f"{what} needs heat conduction, which <DoExplicitHeatConduction>false turns "
                                  "off (Uintah then ignores it); accepted: true or no such tag")
        if node is not None:
            for child in node.children():
                raise child.error("<thermal_contact> takes no tags (Uintah's STThermalContact)")
        self.dt_thermal = np.inf
        ih2 = sum(1.0 / self.level.dx[d] ** 2 for d in range(3) if self.dims[d])
        lag = 2.0 if self.gradient_carried else 1.0     # the last step's gradient halves the Euler limit
        for m in self.conducting:
            mat = self.materials[m]
            self.dt_thermal = min(self.dt_thermal,
                                  mat.density * mat.specific_heat / (2.0 * lag * mat.conductivity * ih2))

    # -- scheduling ---------------------------------------------------------------------------
    def schedule_thermal_initialize(self, sched):
        if self.thermal:
            t = (Task("MPM::initializeTemperature", self.initialize_temperature, self.matls)
                 .requires(NEW, L.pID).requires(NEW, L.pMass).computes(L.pTemperature).computes(L.ThermalEnergy))
            sched.add_task(t.computes(L.pTemperatureGradient) if self.gradient_carried else t)

    def schedule_heat_conduction(self, sched):
        """g.temperature and (with conduction) g.temperatureRate, after particles -> grid."""
        if not self.thermal:
            return
        ms, g, ng = self.matls, Ghost.AROUND_NODES, self.ng
        lp = self.size_labels()
        t = Task("MPM::interpolateTemperatureToGrid", self.interpolate_temperature, ms).requires(NEW, L.gMass)
        for lab in [L.pX, L.pMass, L.pTemperature] + lp:
            t.requires(OLD, lab, g, ng)
        if self.temperature_bcs:
            t.computes(L.gTemperatureNoBC)
        sched.add_task(t.computes(L.gTemperature))
        if self.conducting:
            t = Task("MPM::computeInternalHeatRate", self.internal_heat_rate, self.conducting).requires(NEW, L.gMass)
            if self.gradient_carried:
                t.requires(OLD, L.pTemperatureGradient, g, ng)
            else:                                    # a ghost particle's grad T: its nodes, up to 2 ng out
                t.requires(NEW, L.gTemperature, Ghost.AROUND_CELLS, 2 * ng)
            for lab in [L.pX, L.pVolume] + lp:
                t.requires(OLD, lab, g, ng)
            if self.pressure_bcs and self.pressure_bcs.heat_flux:
                t.requires(OLD, L.pLoadCurveID, g, ng).requires(OLD, FL.simTime).requires(OLD, L.PressureBCParticles)
            sched.add_task(t.computes(L.gTemperatureRate))
        if self.thermal_contact:
            sched.add_task(Task("MPM::computeHeatExchange", self.heat_exchange, ms).requires(OLD, FL.delT)
                           .requires(NEW, L.gMass).requires(NEW, L.gTemperature)
                           .computes(L.gThermalContactRate))

    def schedule_temperature_update(self, sched):
        """p.temperature+ from the nodal rates, after the exchange has added its own."""
        if not self.thermal:
            return
        t = Task("MPM::updateParticleTemperature", self.update_particle_temperature, self.matls)
        t.requires(OLD, FL.delT)
        for lab in [L.pX, L.pMass, L.pTemperature] + self.size_labels():
            t.requires(OLD, lab)
        if self.conducting:
            t.requires(NEW, L.gTemperatureRate, Ghost.AROUND_CELLS, self.ng, matls=self.conducting)
        for lab in self.thermal_rates + ((L.gThermalContactRate,) if self.thermal_contact else ()):
            t.requires(NEW, lab, Ghost.AROUND_CELLS, self.ng)
        if self.temperature_bcs or self.gradient_carried:
            t.requires(NEW, L.gTemperature, Ghost.AROUND_CELLS, self.ng)
        if self.temperature_bcs:
            t.requires(NEW, L.gTemperatureNoBC, Ghost.AROUND_CELLS, self.ng)
        if self.gradient_carried:
            t.computes(L.pTemperatureGradientPre)
        sched.add_task(t.computes(L.pTemperaturePre).computes(L.ThermalEnergy))

    # -- task bodies ----------------------------------------------------------------------------
    def initialize_temperature(self, patch, matls, old_dw, new_dw):
        """p.temperature = the <temperature> of the geometry object that made the particle
        (object number = p.particleID >> 40, see Material.create); p.temperatureGradient = 0 where
        it is carried."""
        e = 0.0
        for m in matls:
            mat = self.materials[m]
            temps = np.array([o["temperature"] for o in mat.objects], float)
            ids = new_dw.get(L.pID, m, patch)
            T = temps[(ids >> 40) - self._obj_base(m)] if len(ids) else np.zeros(0)
            new_dw.put(L.pTemperature, m, patch, np.ascontiguousarray(T))
            if self.gradient_carried:    # Uintah's ParticleCreator: zero, so the first step conducts nothing
                new_dw.put(L.pTemperatureGradient, m, patch, np.zeros((len(ids), 3)))
            e += mat.specific_heat * float(np.dot(new_dw.get(L.pMass, m, patch), T)) if len(ids) else 0.0
        new_dw.put_reduction(L.ThermalEnergy, e)

    def _heat_stencil(self):
        """The heat kernels' weights: the run's interpolator (shape.LINEAR, GIMP or CPDI, whose
        particles visit their domain's corners) and what its weights read of each particle, read-only
        (MPMTasks._lp_read_only: one compilation of each heat kernel for every interpolator)."""
        return {"linear": LINEAR, "gimp": GIMP}.get(self.kind, CPDI), self._lp_read_only

    def interpolate_temperature(self, patch, matls, old_dw, new_dw):
        """g.temperature = sum S m T / m_i from the owned and ghost particles."""
        lv = self.level
        low = np.array(patch.low_index(NC), np.int64)
        kind, lps = self._heat_stencil()
        for m in matls:
            px = old_dw.get(L.pX, m, patch)
            gmT = np.zeros(patch.alloc_shape(NC))
            p2g_heat(kind, self.th_act, px, old_dw.get(L.pMass, m, patch), old_dw.get(L.pTemperature, m, patch),
                     lps(old_dw, m, patch, len(px)), lv.anchor, lv.dx, low, gmT)
            T = new_dw.allocate(L.gTemperature, m, patch, None)
            divide_by_mass(new_dw.get(L.gMass, m, patch), gmT, T)
            if self.temperature_bcs:
                new_dw.put(L.gTemperatureNoBC, m, patch, T.copy())
                self.bcs.apply_temperature(patch, m, T)

    def heat_exchange(self, patch, matls, old_dw, new_dw):
        """g.thermalContactTemperatureRate of every material (Uintah's STThermalContact)."""
        dt = old_dw.get_reduction(FL.delT)
        gmass = np.stack([new_dw.get(L.gMass, m, patch).reshape(-1) for m in matls])
        gT = np.stack([new_dw.get(L.gTemperature, m, patch).reshape(-1) for m in matls])
        cv = np.array([self.materials[m].specific_heat for m in matls])
        out = np.empty_like(gT)
        contact_temperature_rate(gmass, gT, cv, dt, out)
        for k, m in enumerate(matls):
            new_dw.put(L.gThermalContactRate, m, patch, out[k].reshape(patch.alloc_shape(NC)))

    def internal_heat_rate(self, patch, matls, old_dw, new_dw):
        """g.temperatureRate = (-sum_p k V_p grad S_ip . grad T_p + sum_p S_ip q_p) / (m_i cv)
        (Uintah's computeInternalHeatRate and solveHeatEquations); q_p the heat rates of
        the <heat_flux> BCs at the step's start (pressure.py), when the deck has any. grad T_p: the
        carried p.temperatureGradient, or with <conduction_gradient>current this step's g.temperature's."""
        flux = self.pressure_bcs is not None and self.pressure_bcs.heat_flux
        lv = self.level
        low = np.array(patch.low_index(NC), np.int64)
        kind, lps = self._heat_stencil()
        for m in matls:
            mat = self.materials[m]
            px = old_dw.get(L.pX, m, patch)
            acc = np.zeros(patch.alloc_shape(NC))
            if self.gradient_carried:
                gradient = old_dw.get(L.pTemperatureGradient, m, patch)
            else:
                gradient = np.empty((len(px), 3))
                grid_temperature_gradient(kind, self.th_act, px, lps(old_dw, m, patch, len(px)), lv.anchor, lv.dx,
                                          low, new_dw.get(L.gTemperature, m, patch), gradient)
            heat_rate(kind, self.th_act, px, old_dw.get(L.pVolume, m, patch), gradient,
                      lps(old_dw, m, patch, len(px)), lv.anchor, lv.dx, low, mat.conductivity / mat.specific_heat, acc)
            if flux:
                q = self.pressure_bcs.heat_rates(px, old_dw.get(L.pLoadCurveID, m, patch),
                                                 old_dw.get_reduction(FL.simTime),
                                                 old_dw.get_reduction(L.PressureBCParticles))
                p2g_heat(kind, self.th_act, px, q / mat.specific_heat, np.ones(len(px)),
                         lps(old_dw, m, patch, len(px)), lv.anchor, lv.dx, low, acc)
            divide_by_mass(new_dw.get(L.gMass, m, patch), acc, new_dw.allocate(L.gTemperatureRate, m, patch, None))

    def update_particle_temperature(self, patch, matls, old_dw, new_dw):
        """T_p^{n+1} = T_p^n + dt sum S_ip (conduction + exchange rates)_i; ThermalEnergy; with
        the gradient carried the next step's p.temperatureGradient from g.temperatureStar = g.temperature
        + dt (conduction + contact rates), the Temperature BCs applied (Uintah's
        integrateTemperatureRate; the MPMICE exchange rate is added after it, as in Uintah)."""
        lv = self.level
        dt = old_dw.get_reduction(FL.delT)
        low = np.array(patch.low_index(NC), np.int64)
        kind, lps = self._heat_stencil()
        shape = patch.alloc_shape(NC)
        e = 0.0
        for m in matls:
            mat = self.materials[m]
            rates = [new_dw.get(L.gThermalContactRate, m, patch)] if self.thermal_contact else []
            if m in self.conducting:
                rates.append(new_dw.get(L.gTemperatureRate, m, patch))
            t_star = None
            if self.temperature_bcs or self.gradient_carried:
                rate = _total(rates, shape)
                t_star = new_dw.get(L.gTemperature, m, patch) + rate * dt
                if self.temperature_bcs:
                    self.bcs.apply_temperature(patch, m, t_star)
                    rate = (t_star - new_dw.get(L.gTemperatureNoBC, m, patch)) / dt
                rates = [rate]
            rate = np.ascontiguousarray(_total(rates + [new_dw.get(lab, m, patch) for lab in self.thermal_rates],
                                               shape))
            px = old_dw.get(L.pX, m, patch)
            T_new = np.empty(len(px))
            gradient = np.empty((len(px) if self.gradient_carried else 0, 3))
            e += g2p_heat(kind, self.th_act, px, old_dw.get(L.pTemperature, m, patch), old_dw.get(L.pMass, m, patch),
                          lps(old_dw, m, patch, len(px)), lv.anchor, lv.dx, low, rate, dt, T_new, mat.specific_heat,
                          rate if t_star is None else np.ascontiguousarray(t_star), gradient)
            new_dw.put(L.pTemperaturePre, m, patch, T_new)
            if self.gradient_carried:
                new_dw.put(L.pTemperatureGradientPre, m, patch, gradient)
        new_dw.put_reduction(L.ThermalEnergy, e)

    def compute_stable_timestep(self, patch, matls, old_dw, new_dw):
        """The mechanical step (MPMTasks) and, with conduction, the explicit diffusion limit."""
        if not self.conducting:
            return super().compute_stable_timestep(patch, matls, old_dw, new_dw)
        keep = _Keep(new_dw)
        super().compute_stable_timestep(patch, matls, old_dw, keep)
        new_dw.put_reduction(FL.delT, min(float(keep.value), self.dt_thermal))
