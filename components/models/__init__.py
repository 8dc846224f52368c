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
ICE explosive into ICE products. A
PassiveScalar model (passive_scalar.py) is ICE's: the ICE component reads and schedules it.
`read_models(root, mpmice)` reads the block (None without it); `Models.hook(sched)` wraps
the scheduler so that each model's tasks are added right after the MPMICE tasks they
follow (see simple_burn.py), leaving MPMICE's own schedule untouched.
"""
from __future__ import annotations

from .simple_burn import SimpleBurn
from .jwlpp import JWLpp
from .steady_burn import SteadyBurn
from .unsteady_burn import UnsteadyBurn

MODELS = {"Simple_Burn": SimpleBurn, "Steady_Burn": SteadyBurn, "Unsteady_Burn": UnsteadyBurn, "JWLpp": JWLpp}


def read_models(root, component):
    node = root.child("Models")
    if node is None:
        return None
    models, scalars = [], 0
    for m in node.children("Model"):
        kind = m.attr("type", choices=tuple(MODELS) + ("PassiveScalar",))
        if kind == "PassiveScalar":         # ICE's transported scalar (passive_scalar.py, read by ICE)
            scalars += 1
            continue
        models.append(MODELS[kind](m, component, root))
    if not models:
        if scalars:
            return None
        raise node.error("<Models> without a <Model type=...>; accepted: " + ", ".join(MODELS) + ", PassiveScalar")
    return Models(models)


class Models:
    def __init__(self, models):
        self.models = models

    def schedule_initialize(self, sched):
        for m in self.models:
            if hasattr(m, "schedule_initialize"):
                m.schedule_initialize(sched)

    # semi-implicit ICE's eq. P (components/ice/implicit.py: ImplicitICE.mass_exchange)
    def requires(self, task, dw):
        for m in self.models:
            m.mass_exchange_requires(task, dw)

    def term(self, patch, dw):
        return sum(m.mass_exchange_term(patch, dw) for m in self.models)

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
