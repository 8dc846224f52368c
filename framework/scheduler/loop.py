"""A sub-graph repeated until a convergence test says stop (Uintah's sub-scheduler).

Iterative solvers need ghost exchange and reductions inside every iteration, so the
iteration is itself a task graph: its tasks read the previous iteration's warehouse
as OLD and write the current one as NEW, and read the timestep's warehouses as
PARENT_OLD / PARENT_NEW. `init` seeds the first iteration from the timestep's new
warehouse, `results` hands the last iteration's values back to it. All ranks see the
same reduced values, so they stop at the same iteration.
"""
from __future__ import annotations

from ..datawarehouse import DataWarehouse
from ..task import NEW, OLD, PARENT_NEW, PARENT_OLD, Task
from ..variables import VarType


class LoopError(Exception):
    """The iteration did not converge in max_iterations."""


class Loop(Task):
    """A task whose body is a graph run repeatedly.

    init: {iteration label: timestep-new label} copied in before the first iteration.
    results: {iteration label: timestep-new label} put after the last iteration; a value
    may be (label, matls) when a result exists for fewer materials than the loop's.
    A Loop may sit in another Loop's body: its PARENT warehouses are then the
    enclosing iteration's (an outer Newton-type iteration around an inner solve).
    converged(dw, iteration, parent_new_dw) -> bool reads the iteration's (already reduced) values.
    done_before(parent_new_dw) -> bool, if given, is asked once before the first iteration: True
    runs none (the results are the init values).
    """

    def __init__(self, name, matls, body, init: dict, results: dict, converged, max_iterations=100,
                 fail="error", done_before=None):
        super().__init__(name, None, matls)
        self.body = list(body)
        self.init = dict(init)
        self.results = {k: (v if isinstance(v, tuple) else (v, None)) for k, v in results.items()}
        self.converged = converged
        self.max_iterations = int(max_iterations)
        self.fail = fail
        self.done_before = done_before
        self.iterations = 0
        self.body_graph = None
        for it_label, parent_label in self.init.items():
            self.requires(NEW, parent_label)
        for it_label, (parent_label, rmatls) in self.results.items():
            self.computes(parent_label, matls=rmatls)
        for t in self.body:
            for d in t.requires_:
                if d.dw in (PARENT_OLD, PARENT_NEW):
                    self.requires(OLD if d.dw == PARENT_OLD else NEW, d.label, d.ghost, d.n, d.matls)

    def needed(self):
        names = set(self.init) | set(self.results)
        for t in self.body:
            names |= {d.label.name for d in t.computes_ if d.label.vartype is VarType.REDUCTION}
        return names


def run_loop(sched, loop: Loop, old_dw, new_dw):
    """Seed, iterate until converged, hand back the results."""
    from .. import labels as L
    it_old = DataWarehouse(-1)
    for it_name, parent_label in loop.init.items():
        lab = L.find(it_name)
        if lab.vartype is VarType.REDUCTION:
            for m in (loop.matls or (-1,)):
                key = (parent_label.name, m) if (parent_label.name, m) in new_dw.reductions else (parent_label.name, -1)
                it_old.reductions[(it_name, key[1])] = new_dw.reductions[key]
            continue
        for (name, m, pid), arr in list(new_dw.grid.items()) + list(new_dw.particles.items()):
            if name == parent_label.name:
                (it_old.grid if lab.vartype.is_grid else it_old.particles)[(it_name, m, pid)] = arr
    it_old.nparticles = dict(new_dw.nparticles)
    converged = loop.done_before is not None and bool(loop.done_before(new_dw))
    k = 0
    while not converged and k < loop.max_iterations:
        it_new = DataWarehouse(-1)
        it_new.pre_counts = dict(it_old.nparticles)
        sched.execute(loop.body_graph, it_old, it_new, parents=(old_dw, new_dw))
        k += 1
        converged = loop.converged(it_new, k, new_dw)
        it_old = it_new
        if converged:
            break
    loop.iterations = k
    if not converged and loop.fail == "error":
        raise LoopError(f"{loop.name} did not converge in {loop.max_iterations} iterations")
    loop.converged_last = converged
    for it_name, (parent_label, rmatls) in loop.results.items():
        lab = L.find(it_name)
        if lab.vartype is VarType.REDUCTION:
            for (name, m), v in it_old.reductions.items():
                if name == it_name:
                    new_dw.reductions[(parent_label.name, m)] = v
            continue
        for p in sched.local_patches:
            for m in (loop.matls if rmatls is None else rmatls):
                new_dw.put(parent_label, m, p, it_old.get(lab, m, p))
