"""Tasks: one algorithm step written for ONE patch, with declared inputs and outputs.

A task requires (label, old or new warehouse, materials, ghost type and count),
computes or modifies labels. The callback `fn(patch, matls, old_dw, new_dw)` sees the
warehouses through a `TaskView` that refuses any read it did not declare and any
write it did not declare; after the call the executor checks every compute was put.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .labels import VarLabel
from .variables import Ghost, VarType

OLD = "old"
NEW = "new"
PARENT_OLD = "parent_old"   # inside a Loop body: the timestep's old warehouse
PARENT_NEW = "parent_new"   # inside a Loop body: the timestep's new warehouse
WAREHOUSES = (OLD, NEW, PARENT_OLD, PARENT_NEW)


class TaskError(Exception):
    """A task broke its declaration (read undeclared data, missed a compute ...)."""


@dataclass(frozen=True)
class Dependency:
    label: VarLabel
    dw: str
    matls: tuple | None
    ghost: Ghost = Ghost.NONE
    n: int = 0


class Task:
    """A named step with its callback and declarations.

    `matls` is the material subset it runs for (None: no materials, e.g. a reduction
    over everything). Dependencies default to the task's materials.
    """

    def __init__(self, name: str, fn, matls=None):
        self.name = name
        self.fn = fn
        self.matls = tuple(matls) if matls is not None else ()
        self.requires_: list[Dependency] = []
        self.computes_: list[Dependency] = []
        self.modifies_: list[Dependency] = []
        self.order = -1

    def __repr__(self):
        return f"Task({self.name})"

    def _matls(self, label, matls):
        if matls is not None:
            return tuple(matls)
        if label.vartype is VarType.REDUCTION:
            return (-1,)
        return self.matls

    def requires(self, dw, label: VarLabel, ghost: Ghost = Ghost.NONE, n: int = 0, matls=None):
        if dw not in WAREHOUSES:
            raise ValueError(f"task {self.name}: dw must be one of {WAREHOUSES}, not {dw!r}")
        if (ghost is Ghost.NONE) != (n == 0):
            raise ValueError(f"task {self.name}: {label.name} ghost type {ghost.value} with {n} layers")
        self.requires_.append(Dependency(label, dw, self._matls(label, matls), ghost, int(n)))
        return self

    def computes(self, label: VarLabel, matls=None):
        self.computes_.append(Dependency(label, NEW, self._matls(label, matls)))
        return self

    def modifies(self, label: VarLabel, matls=None):
        self.modifies_.append(Dependency(label, NEW, self._matls(label, matls)))
        return self

    def writes(self):
        return self.computes_ + self.modifies_


def _union(have, matls):
    """The materials of two declarations of one label; () stands for any material."""
    if have is None:
        return matls
    if not have or not matls:
        return ()
    return tuple(dict.fromkeys(have + matls))


def _declared(task: Task, which: str):
    """(reads, ghosted, writes) of a task in warehouse `which`: label name -> materials, the
    widest ghost, materials written. Kept on the task (a view is made for every run of it)
    until a declaration is added."""
    key = (which, len(task.requires_), len(task.modifies_), len(task.computes_))
    cache = task.__dict__.setdefault("_declared", {})
    if key in cache:
        return cache[key]
    reads, ghosted, writes = {}, {}, {}
    for dep in task.requires_:
        if dep.dw == which:       # a label required twice (a model's extra materials): the union
            reads[dep.label.name] = _union(reads.get(dep.label.name), dep.matls)
            if dep.n:
                ghosted[dep.label.name] = max(dep.n, ghosted.get(dep.label.name, 0))
    if which == NEW:
        for dep in task.modifies_:
            reads[dep.label.name] = dep.matls
            writes[dep.label.name] = dep.matls
        for dep in task.computes_:
            writes[dep.label.name] = dep.matls
    cache[key] = (reads, ghosted, writes)
    return cache[key]


class TaskView:
    """A warehouse as one task may see it: only what it declared."""

    __slots__ = ("dw", "task", "which", "reads", "writes", "puts", "ghosted")

    def __init__(self, dw, task: Task, which: str, declared=None):
        self.dw = dw
        self.task = task
        self.which = which
        self.reads, self.ghosted, self.writes = declared if declared is not None else _declared(task, which)

    def _fail(self, what, label, matl):
        return TaskError(f"task {self.task.name} {what} {label.name} (material {matl}) in the "
                         f"{self.which} warehouse without declaring it")

    def _check_read(self, label, matl):
        m = self.reads.get(label.name)
        if m is None or (matl not in m and matl != -1 and m):
            raise self._fail("reads", label, matl)

    def _check_write(self, label, matl):
        m = self.writes.get(label.name)
        if m is None or (matl not in m and matl != -1 and m):
            raise self._fail("writes", label, matl)

    # -- reads ---------------------------------------------------------------------
    def get(self, label: VarLabel, matl: int, patch):
        """The variable; grid arrays include the halo, particles include declared ghosts."""
        m = self.reads.get(label.name)          # _check_read, inline: the most frequent call of a task
        if m is None or (matl not in m and matl != -1 and m):
            raise self._fail("reads", label, matl)
        if label.vartype is VarType.PARTICLE and label.name in self.ghosted:
            a = self.dw.ghost_particles[(label.name, matl, patch.id, self.ghosted[label.name])]
            return a if isinstance(a, np.ndarray) else a.merged()
        return self.dw.get(label, matl, patch)

    def get_split(self, label: VarLabel, matl: int, patch):
        """A particle variable as (owned, ghost, order) with get() equal to (owned + ghost)[order],
        or to owned + ghost where order is None, without forming it (no ghosts declared: ghost
        is empty)."""
        self._check_read(label, matl)
        if label.name not in self.ghosted:
            own = self.dw.get(label, matl, patch)
            return own, own[:0], None
        a = self.dw.ghost_particles[(label.name, matl, patch.id, self.ghosted[label.name])]
        if isinstance(a, np.ndarray):
            own = self.dw.get(label, matl, patch)
            return own, a[len(own):], None
        return a.owned, a.ghost, a.order

    def get_reduction(self, label: VarLabel, matl: int = -1):
        self._check_read(label, matl)
        return self.dw.get_reduction(label, matl)

    def ghost_owned_mask(self, label: VarLabel, matl: int, patch):
        """Which entries of get(label) (a ghosted particle variable) belong to this patch.

        None when there are no ghost particles (every entry is owned).
        """
        self._check_read(label, matl)
        g = self.ghosted.get(label.name)
        if g is None:
            return None
        return self.dw.ghost_order.get((matl, patch.id, g), (None, None))[1]

    def num_particles(self, matl: int, patch) -> int:
        return self.dw.num_particles(matl, patch)

    def num_ghost_particles(self, label: VarLabel, matl: int, patch) -> int:
        """Owned plus ghost particles returned by get() for a ghosted particle label."""
        return len(self.get(label, matl, patch))

    def exists(self, label: VarLabel, matl: int = -1, patch=None) -> bool:
        return self.dw.exists(label, matl, patch)

    # -- writes --------------------------------------------------------------------
    def allocate(self, label: VarLabel, matl: int, patch, fill=0.0):
        m = self.writes.get(label.name)         # _check_write, inline
        if m is None or (matl not in m and matl != -1 and m):
            raise self._fail("writes", label, matl)
        return self.dw.allocate(label, matl, patch, fill)

    def put(self, label: VarLabel, matl: int, patch, value):
        self._check_write(label, matl)
        self.dw.put(label, matl, patch, value)

    def get_modifiable(self, label: VarLabel, matl: int, patch):
        m = self.writes.get(label.name)
        if m is None or label.name not in self.reads:
            raise self._fail("modifies", label, matl)
        self.dw.halo_valid.pop((label.name, matl), None)
        return self.dw.get(label, matl, patch)

    def replace(self, label: VarLabel, matl: int, patch, value):
        """Put a new array for a variable the task declared to modify."""
        if label.name not in self.writes or label.name not in self.reads:
            raise self._fail("modifies", label, matl)
        self.dw.replace(label, matl, patch, value)

    def put_reduction(self, label: VarLabel, value, matl: int = -1):
        self._check_write(label, matl)
        self.dw.put_reduction(label, value, matl)

    def create_particles(self, matl: int, patch, n: int):
        if self.which != NEW:
            raise TaskError(f"task {self.task.name} creates particles in the old warehouse")
        self.dw.create_particles(matl, patch, n)

    def add_particles(self, matl: int, patch, k: int):
        if self.which != NEW:
            raise TaskError(f"task {self.task.name} adds particles in the old warehouse")
        self.dw.add_particles(matl, patch, k)
