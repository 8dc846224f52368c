"""The VarLabel registry: one label per name, as in Uintah (press_CC, p.x, g.mass ...)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .variables import REDUCTION_OPS, VarType


@dataclass(frozen=True, eq=False)
class VarLabel:
    """A named variable: its kind, the shape of one entry and (for reductions) the op.

    `shape` is () for scalars, (3,) for vectors, (3, 3) for tensors. `dtype` is float64
    unless stated (particle IDs are int64).
    """

    name: str
    vartype: VarType
    shape: tuple = ()
    dtype: type = np.float64
    reduction: str | None = None
    # a sum reduction whose per-patch parts are added in patch order (the same on any number of
    # ranks); False for a rank-local array where every entry has one contributor
    patch_order: bool = True

    def __repr__(self):
        return f"VarLabel({self.name}, {self.vartype.value})"

    def __hash__(self):
        return hash(self.name)


_registry: dict[str, VarLabel] = {}


def create(name, vartype: VarType, shape=(), dtype=np.float64, reduction=None, patch_order=True) -> VarLabel:
    """Create (or fetch the identical existing) label; a conflicting redefinition is an error."""
    if vartype is VarType.REDUCTION and reduction not in REDUCTION_OPS:
        raise ValueError(f"reduction label {name} needs reduction= one of {REDUCTION_OPS}")
    label = VarLabel(name, vartype, tuple(shape), np.dtype(dtype).type, reduction, patch_order)
    old = _registry.get(name)
    if old is not None:
        if (old.vartype, old.shape, old.dtype, old.reduction) != \
                (label.vartype, label.shape, label.dtype, label.reduction):
            raise ValueError(f"label {name} already defined as {old}, not {label}")
        return old
    _registry[name] = label
    return label


def find(name) -> VarLabel | None:
    return _registry.get(name)


# Labels the framework itself provides to every component.
delT = create("delT", VarType.REDUCTION, reduction="min")
simTime = create("simulationTime", VarType.REDUCTION, reduction="max")
# mass of the particles that left the domain through a face without a wall in this step
# (relocation deletes them, as Uintah does); <save label="LostParticleMass"/> writes it
LostParticleMass = create("LostParticleMass", VarType.REDUCTION, reduction="sum")
