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

    @property
    def is_grid(self) -> bool:
        return self in GRID_TYPES

    def node_like(self, d: int) -> bool:
        """True where this type has one more entry than cells along direction d."""
        return self is VarType.NC or (self is VarType.SFCX and d == 0) or \
            (self is VarType.SFCY and d == 1) or (self is VarType.SFCZ and d == 2)


GRID_TYPES = (VarType.CC, VarType.NC, VarType.SFCX, VarType.SFCY, VarType.SFCZ)


class Ghost(Enum):
    """Where ghost data is wanted around a patch (Uintah's Ghost::GhostType)."""

    NONE = "None"
    AROUND_CELLS = "AroundCells"
    AROUND_NODES = "AroundNodes"
    AROUND_FACES = "AroundFaces"
    AROUND_FACES_X = "AroundFacesX"
    AROUND_FACES_Y = "AroundFacesY"
    AROUND_FACES_Z = "AroundFacesZ"


REDUCTION_OPS = ("min", "max", "sum")
