"""Uintah's UCNH: the model of comp_neo_hook_plastic.py, elastic unless <usePlasticity>true.

Uintah builds ``type="UCNH"`` and ``type="comp_neo_hook_plastic"`` as the same class; they
differ only in the default of ``usePlasticity`` (false here).  Elastic, it is comp_neo_hook.
"""
from dataclasses import dataclass

from .comp_neo_hook_plastic import (ENERGY_IS_INCREMENT, STABILIZED_WAVE_SPEED, Params as _PlasticParams,  # noqa: F401
                                    initial_state, state_of, update)


@dataclass(frozen=True)
class Params(_PlasticParams):
    usePlasticity: bool = False
