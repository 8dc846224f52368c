"""Reaction models (Uintah's <Models>): tasks MPMICE schedules only when the deck has <Models>.

    <Models>
      <Model type="Simple_Burn">
        <Simple_Burn>
          <fromMaterial> reactant </fromMaterial>   <toMaterial> product </toMaterial>
          <ThresholdTemp> K </ThresholdTemp>        <ThresholdPressure> Pa </ThresholdPressure>
          <Enthalpy> J/kg </Enthalpy>  <BurnCoeff> kg/(m^2 s) </BurnCoeff>  <refPressure> Pa </refPressure>
        </Simple_Burn>
      </Model>
    </Models>

Steady_Burn (steady_burn.py) shares Simple_Burn's tasks with the WSB burn rate, Unsteady_Burn
(unsteady_burn.py) Steady_Burn's with the burn rate relaxed in time; JWLpp (jwlpp.py) turns an
ICE explosive into ICE products; DDT1 (ddt1.py) burns a solid into a product by
Steady_Burn's deflagration, in cracks, and JWL++'s detonation. A PassiveScalar and a TracerParticles model (passive_scalar.py,
tracer_particles.py) are ICE's: the ICE component reads them and MPMICE schedules them.
`read_models(root, mpmice)` reads the block (None without it); `Models.hook(sched)` wraps
the scheduler so that each model's tasks are added right after the MPMICE tasks they
follow (see simple_burn.py), leaving MPMICE's own schedule untouched.
"""
from __future__ import annotations

import numpy as np

from components.ice import labels as I
from . import labels as ML
from framework.task import NEW, OLD, Task

from .simple_burn import SimpleBurn
from .jwlpp import JWLpp
from .steady_burn import SteadyBurn
from .unsteady_burn import UnsteadyBurn
from .ddt1 import DDT1

SOURCES_AFTER = "MPMICE::computeEquilibrationPressure"      # where every reaction model computes its sources
MODELS = {"Simple_Burn": SimpleBurn, "Steady_Burn": SteadyBurn, "Unsteady_Burn": UnsteadyBurn, "JWLpp": JWLpp,
          "DDT1": DDT1}


def read_models(root, component):
    node = root.child("Models")
    if node is None:
        return None
    models, scalars = [], 0
    for m in node.children("Model"):
        kind = m.attr("type", choices=tuple(MODELS) + ("PassiveScalar", "TracerParticles"))
        if kind in ("PassiveScalar", "TracerParticles"):    # ICE's models (ice_models.py, read by ICE)
            scalars += 1
            continue
        models.append(MODELS[kind](m, component, root))
    if not models:
        if scalars:
            return None
        raise node.error("<Models> without a <Model type=...>; accepted: " + ", ".join(MODELS) + ", PassiveScalar, TracerParticles")
    return Models(models, component)


class Models:
    def __init__(self, models, comp):
        self.models = models
        self.comp = comp

    def schedule_initialize(self, sched):
        for m in self.models:
            if hasattr(m, "schedule_initialize"):
                m.schedule_initialize(sched)

    def products(self):
        """The fluids the models feed (their modelMass_src)."""
        return sorted({m.prod for m in self.models})

    # semi-implicit ICE's eq. P (components/ice/implicit.py: ImplicitICE.mass_exchange)
    def requires(self, task, dw):
        for m in self.models:
            m.mass_exchange_requires(task, dw)

    def term(self, patch, dw):
        return sum(m.mass_exchange_term(patch, dw) for m in self.models)

    def lagrangian_volume_requires(self, t):
        """What volume_sources_into reads (added to ICE::computeLagrangianSpecificVolume)."""
        for m in self.models:
            if hasattr(m, "volume_source_into"):
                t.requires(NEW, ML.modelMass_src, matls=[m.prod]).requires(NEW, ML.modelVol_src, matls=[m.prod])

    def volume_sources_into(self, patch, matls, new_dw, sp_vol_L):
        """The burn models' created volume in the products' Lagrangian volume (ICE's hook
        model_volume_sources: before ICE's clamp, Uintah's order)."""
        for m in self.models:
            if hasattr(m, "volume_source_into"):
                m.volume_source_into(patch, matls, new_dw, sp_vol_L)

    def hook(self, sched):
        after = {}
        for m in self.models:
            for name, make in m.tasks_after():
                after.setdefault(name, []).append(make)
        after[SOURCES_AFTER].append(self._volume_fraction_task)      # after every model's sources
        return _Hooked(sched, after)

    def _volume_fraction_task(self):
        c = self.comp
        t = Task("ICE::updateVolumeFraction", self.update_volume_fraction, c.all_matls) \
            .requires(NEW, I.rho_CC, matls=c.mpm_matls).requires(OLD, I.rho_CC, matls=c.ice.ice_matls) \
            .requires(NEW, I.sp_vol_CC).modifies(I.vol_frac_CC)
        for m in self.models:
            m.volume_sources_requires(t)
        return t

    def update_volume_fraction(self, patch, matls, old_dw, new_dw):
        """Uintah's ICE::updateVolumeFraction: the volume the models move between materials shifts
        their volume fractions before the face velocities and the pressure see them,
        theta_m = max((theta_m V_tot + V_src,m) / V_tot, 1e-100), V_tot = sum_m m_m v_m."""
        c = self.comp
        b = c.ice.boxes(patch)
        own = tuple(slice(lo, hi) for lo, hi in zip(b.olo, b.ohi))
        src = {}
        for mod in self.models:
            for m, a in mod.volume_sources(patch, new_dw).items():
                src[m] = src.get(m, 0.0) + a[own]
        total = sum((new_dw if m in c.mpm_matls else old_dw).get(I.rho_CC, m, patch)[own] * b.vol
                    * new_dw.get(I.sp_vol_CC, m, patch)[own] for m in matls)
        for m in matls:
            if m in src:
                vf = new_dw.get_modifiable(I.vol_frac_CC, m, patch)
                vf[own] = np.maximum((vf[own] * total + src[m]) / total, 1e-100)


class _Hooked:
    """A scheduler that adds the models' tasks after the named tasks (each once)."""

    def __init__(self, sched, after):
        self.sched, self.after = sched, dict(after)

    def add_task(self, task):
        out = self.sched.add_task(task)
        for make in self.after.pop(task.name, []):
            self.sched.add_task(make())
        return out

    def __getattr__(self, name):
        return getattr(self.sched, name)
