"""Kinds of simulation variables and their index spaces.

CC lives on cells, NC on nodes, SFCX/SFCY/SFCZ on the x/y/z faces, PARTICLE on the
particles of a patch, REDUCTION is one value over the whole level (combined with an
operation such as min or sum) and PERPATCH is one value per patch.
"""
from __future__ import annotations

from enum import Enum


class VarType(Enum):
    CC = "CC"
    NC = "NC"
    SFCX = "SFCX"
    SFCY = "SFCY"
    SFCZ = "SFCZ"
    PARTICLE = "Particle"
    REDUCTION = "Reduction"
    PERPATCH = "PerPatch"

    # identity hashing in C (members are singletons, equality is identity): the warehouse and
    # the patches' caches hash a type hundreds of times a step, Enum's own hash is Python code
    __hash__ = object.__hash__

    def node_like(self, d: int) -> bool:
        """True where this type has one more entry than cells along direction d."""
        return self is VarType.NC or (self is VarType.SFCX and d == 0) or \
            (self is VarType.SFCY and d == 1) or (self is VarType.SFCZ and d == 2)


GRID_TYPES = (VarType.CC, VarType.NC, VarType.SFCX, VarType.SFCY, VarType.SFCZ)
for _vt in VarType:
    _vt.is_grid = _vt in GRID_TYPES         # a plain attribute: read for every get and put


class Ghost(Enum):
    """Where ghost data is wanted around a patch (Uintah's Ghost::GhostType)."""

    NONE = "None"
    AROUND_CELLS = "AroundCells"
    AROUND_NODES = "AroundNodes"
    AROUND_FACES = "AroundFaces"
    AROUND_FACES_X = "AroundFacesX"
    AROUND_FACES_Y = "AroundFacesY"
    AROUND_FACES_Z = "AroundFacesZ"

    __hash__ = object.__hash__


REDUCTION_OPS = ("min", "max", "sum")
