"""The component contract and the registry of components by deck name.

A component reads its part of the deck in `problem_setup` and schedules tasks written
for one patch. It schedules a task only when the deck asks for that physics.
"""
from __future__ import annotations

import importlib

from .problemspec import InputError

# deck name -> module that registers it (imported on demand)
KNOWN = {
    "examples": "components.examples",
    "heat": "components.examples",
    "advect_particles": "components.examples",
    "ice": "components.ice.component",
    "mpm": "components.mpm.component",
    "mpmice": "components.mpmice.component",
    "rmpmice": "components.mpmice.component",
    "efem": "components.efem.component",
}

_registry: dict = {}


def register(*names):
    def deco(cls):
        for n in names:
            _registry[n] = cls
        cls.names = names
        return cls
    return deco


def lookup(name, ps_node):
    """The component class for `<SimulationComponent type=name>`."""
    if name not in _registry and name in KNOWN:
        try:
            importlib.import_module(KNOWN[name])
        except ModuleNotFoundError as e:
            if not e.name or not e.name.startswith("components"):
                raise
    if name not in _registry:
        avail = sorted(n for n in KNOWN if _importable(n))
        raise ps_node.error(f"component type=\"{name}\" is not available in this build; available: "
                            f"{', '.join(avail)}")
    return _registry[name]


def _importable(name):
    try:
        importlib.import_module(KNOWN[name])
    except ModuleNotFoundError:
        return False
    return name in _registry


class Component:
    """Base class: the null component. Subclasses override what they need."""

    names: tuple = ()
    holes_ok = False       # runs on a level whose <Box>es do not fill one box (boundary faces on holes)

    def __init__(self):
        self.materials: list = []

    def problem_setup(self, root, level):
        """Read this component's tags from the deck root (a ProblemSpec)."""

    def material_names(self) -> list:
        return [getattr(m, "name", str(i)) for i, m in enumerate(self.materials)]

    def schedule_initialize(self, level, sched):
        raise InputError(f"component {type(self).__name__} schedules no initialization")

    def schedule_compute_stable_timestep(self, level, sched):
        pass

    def schedule_time_advance(self, level, sched):
        pass

    def output_hint(self) -> str:
        return ""
