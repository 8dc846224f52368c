"""The single-assignment data warehouse.

One warehouse holds the variables of one timestep for the patches of this rank. Grid
variables are stored over the patch's allocation box (owned entries plus the level's
halo for that type), so a ghost fill writes the halo in place and a task reads the
whole window without copies. A second `put` of the same (label, material, patch) is
an error; `modify` is the declared way to change a value. The new warehouse of step n
becomes the old one of step n+1.
"""
from __future__ import annotations

import math

import numpy as np

from .labels import VarLabel
from .variables import VarType

_IDENTITY = {"min": np.inf, "max": -np.inf, "sum": 0.0}
_COMBINE = {"min": min, "max": max, "sum": lambda a, b: a + b}


class WarehouseError(Exception):
    pass


def _filled(shape, dtype, fill):
    """A new array of this shape filled with fill (None: left unset); a fill of +0 comes zeroed
    from the allocator (np.zeros), in half the time of np.empty and fill on a small array."""
    if fill is None:
        return np.empty(shape, dtype=dtype)
    if fill == 0 and math.copysign(1.0, fill) > 0.0:
        return np.zeros(shape, dtype=dtype)
    a = np.empty(shape, dtype=dtype)
    a.fill(fill)
    return a


class DataWarehouse:
    """Variables keyed by (label name, material, patch id); reductions by (name, material)."""

    def __init__(self, generation: int = 0):
        self.generation = generation
        self.grid: dict = {}
        self.particles: dict = {}
        self.nparticles: dict = {}
        self.pre_counts: dict = {}
        self.reductions: dict = {}
        # while a task runs on a patch, its sum reductions are kept per patch, so that the
        # scheduler can add them in patch order: the same total on any number of ranks
        self.reduction_patch = None
        self.patch_sums: dict = {}
        self.perpatch: dict = {}
        self.ghost_particles: dict = {}
        self.ghost_order: dict = {}     # (matl, patch, g) -> (ID order, owned mask) of owned+ghost
        self.ghost_select: dict = {}    # (matl, g) -> where each ghost comes from and goes (comm._Layout)
        self.ghost_seen: set = set()
        self.ghost_candidates: dict = {}  # (matl, source patch, g) -> its ghosts per neighbour box
        self.halo_valid: dict = {}

    # -- grid and particle variables ---------------------------------------------
    def _store(self, label: VarLabel):
        vt = label.vartype
        if vt.is_grid:
            return self.grid
        if vt is VarType.PARTICLE:
            return self.particles
        if vt is VarType.PERPATCH:
            return self.perpatch
        raise WarehouseError(f"{label.name} is a reduction variable: use put_reduction/get_reduction")

    def exists(self, label: VarLabel, matl: int = -1, patch=None) -> bool:
        if label.vartype is VarType.REDUCTION:
            return (label.name, matl) in self.reductions
        return (label.name, matl, patch.id) in self._store(label)

    def allocate(self, label: VarLabel, matl: int, patch, fill=0.0) -> np.ndarray:
        """Allocate and put a grid or particle variable; returns the array to fill."""
        if label.vartype.is_grid:       # put's checks without its shape check: the shape is right
            a = _filled(patch.alloc_shape(label.vartype) + label.shape, label.dtype, fill)
            key = (label.name, matl, patch.id)
            if key in self.grid:
                self._put_twice(label, matl, patch)
            self.grid[key] = a
            self.halo_valid.pop((label.name, matl), None)
            return a
        if label.vartype is VarType.PARTICLE:
            shape = (self.num_particles(matl, patch),) + label.shape
        else:
            raise WarehouseError(f"cannot allocate {label.name} ({label.vartype.value})")
        a = _filled(shape, label.dtype, fill)
        self.put(label, matl, patch, a)
        return a

    def put(self, label: VarLabel, matl: int, patch, value):
        store = self._store(label)
        key = (label.name, matl, patch.id)
        if key in store:
            self._put_twice(label, matl, patch)
        if label.vartype.is_grid:
            want = patch.alloc_shape(label.vartype) + label.shape
            if value.shape != want:
                raise WarehouseError(f"{label.name} on patch {patch.id}: array shape {value.shape}, expected {want}")
        elif label.vartype is VarType.PARTICLE:
            n = self.num_particles(matl, patch)
            if len(value) != n:
                raise WarehouseError(f"{label.name} on patch {patch.id}: {len(value)} particles, expected {n}")
        store[key] = value
        self.halo_valid.pop((label.name, matl), None)

    @staticmethod
    def _put_twice(label, matl, patch):
        raise WarehouseError(f"{label.name} (material {matl}, patch {patch.id}) put twice: "
                             "the warehouse is single-assignment; declare modifies instead")

    def replace(self, label: VarLabel, matl: int, patch, value):
        """Swap in a new array for a variable the caller declared to modify."""
        self._store(label)[(label.name, matl, patch.id)] = value
        self.halo_valid.pop((label.name, matl), None)

    def get(self, label: VarLabel, matl: int, patch) -> np.ndarray:
        try:
            return (self.grid if label.vartype.is_grid else self._store(label))[(label.name, matl, patch.id)]
        except KeyError:
            raise WarehouseError(f"{label.name} (material {matl}, patch {patch.id}) is not in the "
                                 f"warehouse of generation {self.generation}") from None

    def remove(self, label: VarLabel, matl: int, patch):
        self._store(label).pop((label.name, matl, patch.id), None)

    def scrub_all(self, names):
        """Free every instance of each of these labels, in one pass over the stores."""
        names = frozenset(names)
        if not names:
            return
        for store in (self.grid, self.particles, self.perpatch, self.ghost_particles):
            for key in [k for k in store if k[0] in names]:
                del store[key]

    # -- particle sets ---------------------------------------------------------------
    def create_particles(self, matl: int, patch, n: int):
        """Declare that material matl has n particles on this patch."""
        key = (matl, patch.id)
        if key in self.nparticles:
            raise WarehouseError(f"particle set of material {matl} on patch {patch.id} created twice")
        self.nparticles[key] = int(n)

    def add_particles(self, matl: int, patch, k: int):
        """Grow the set of matl on patch carried from the old warehouse by k particles made in
        this step (Uintah's ParticleSubset::addParticles): the pre-relocation variables put after
        this hold them, after the old ones; relocation then hands them on like any others."""
        key = (matl, patch.id)
        if key in self.nparticles:
            raise WarehouseError(f"particles added to material {matl} on patch {patch.id} after its set was made")
        self.pre_counts[key] = self.num_particles(matl, patch) + int(k)

    def num_particles(self, matl: int, patch) -> int:
        """Particles of matl on patch; before relocation, the count carried from the old warehouse."""
        key = (matl, patch.id)
        try:
            return self.nparticles[key] if key in self.nparticles else self.pre_counts[key]
        except KeyError:
            raise WarehouseError(f"no particle set for material {matl} on patch {patch.id}") from None

    def has_particles(self, matl: int, patch) -> bool:
        return (matl, patch.id) in self.nparticles or (matl, patch.id) in self.pre_counts

    # -- reductions -----------------------------------------------------------------
    def put_reduction(self, label: VarLabel, value, matl: int = -1):
        """Combine a patch's contribution into the rank's partial reduction."""
        key = (label.name, matl)
        v = float(value) if label.shape == () else np.asarray(value, dtype=np.float64)
        if label.reduction == "sum" and label.patch_order and self.reduction_patch is not None:
            parts = self.patch_sums.setdefault(key, {})
            pid = self.reduction_patch
            parts[pid] = parts[pid] + v if pid in parts else v
            return
        if key in self.reductions:
            self.reductions[key] = _COMBINE[label.reduction](self.reductions[key], v) if label.shape == () \
                else self._combine_array(label.reduction, self.reductions[key], v)
        else:
            self.reductions[key] = v

    @staticmethod
    def _combine_array(op, a, b):
        return {"min": np.minimum, "max": np.maximum, "sum": np.add}[op](a, b)

    def set_reduction(self, label: VarLabel, value, matl: int = -1):
        self.reductions[(label.name, matl)] = value

    def get_reduction(self, label: VarLabel, matl: int = -1):
        try:
            return self.reductions[(label.name, matl)]
        except KeyError:
            raise WarehouseError(f"reduction {label.name} (material {matl}) is not in the warehouse") from None

    @staticmethod
    def identity(label: VarLabel):
        v = _IDENTITY[label.reduction]
        return v if label.shape == () else np.full(label.shape, v)

    # -- memory ----------------------------------------------------------------------
    def nbytes(self) -> int:
        total = 0
        for store in (self.grid, self.particles):
            total += sum(a.nbytes for a in store.values())
        total += sum(a.nbytes for a in self.ghost_particles.values())
        return total
