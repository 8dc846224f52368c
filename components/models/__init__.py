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

Steady_Burn (steady_burn.py) shares Simple_Burn's tasks with the WSB burn rate. A
PassiveScalar and a TracerParticles model (passive_scalar.py, tracer_particles.py) are ICE's: the ICE
component reads them and MPMICE schedules them.
`read_models(root, mpmice)` reads the block (None without it); `Models.hook(sched)` wraps
the scheduler so that each model's tasks are added right after the MPMICE tasks they
follow (see simple_burn.py), leaving MPMICE's own schedule untouched.
"""
from __future__ import annotations

from .simple_burn import SimpleBurn
from .steady_burn import SteadyBurn

MODELS = {"Simple_Burn": SimpleBurn, "Steady_Burn": SteadyBurn}


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
    return Models(models)


class Models:
    def __init__(self, models):
        self.models = models

    def hook(self, sched):
        after = {}
        for m in self.models:
            for name, make in m.tasks_after():
                after.setdefault(name, []).append(make)
        return _Hooked(sched, after)


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
