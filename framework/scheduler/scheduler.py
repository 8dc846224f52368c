"""The scheduler: collects a component's tasks, compiles them, and executes the graph.

Serial and MPI execution are the same code: with one rank every ghost source is
local and no MPI call is made. Component code never calls MPI; every copy and
message comes from the task declarations.
"""
from __future__ import annotations

import time
from collections import defaultdict


from ..datawarehouse import DataWarehouse
from ..labels import delT as delT_label
from ..task import NEW, OLD, PARENT_NEW, PARENT_OLD, Task, TaskError, TaskView, _declared
from ..variables import VarType
from .comm import Comm, Exchange, GridPlan
from .compile import CompiledGraph, GraphError, compile_graph, halo_widths
from .loop import Loop, run_loop
from .relocate import RelocationSpec, relocate, relocation_task


def _ghosted(task: Task, which: str):
    """The (label, layers, materials) of a task's ghosted grid and particle requirements in
    warehouse `which`, kept on the task until a requirement is added."""
    key = ("ghosted", which, len(task.requires_))
    cache = task.__dict__.setdefault("_ghosted", {})
    if key not in cache:
        deps = [d for d in task.requires_ if d.dw == which and d.n]
        cache[key] = ([(d.label, d.n, d.matls) for d in deps if d.label.vartype.is_grid],
                      [(d.label, d.n, d.matls) for d in deps if d.label.vartype is VarType.PARTICLE])
    return cache[key]


_TASK, _LOOP, _RELOCATION = 0, 1, 2


def _graph_plan(cg: CompiledGraph, keep):
    """(task, kind, labels to scrub from the new and the old warehouse after it) for each task of
    a compiled graph, kept on the graph per set of kept labels: execute runs it every step."""
    keep = frozenset(keep)
    key = (keep, len(cg.tasks))
    cache = cg.__dict__.setdefault("_plans", {})
    plan = cache.get(key)
    if plan is None:
        plan = cache[key] = [
            (task, _RELOCATION if hasattr(task, "relocation") else _LOOP if isinstance(task, Loop) else _TASK,
             frozenset(name for name in cg.scrub_after.get(task, ()) if name not in keep),
             frozenset(cg.scrub_old_after.get(task, ()))) for task in cg.tasks]
    return plan


def _task_plan(task: Task, loop_body: bool):
    """What running a task needs at every step, from its declarations: its views' declarations
    (old, new and, in a loop body, the parents' warehouses), its ghosted requirements per
    warehouse (index into those four, grid, particles), the grid, particle and per-patch
    computes that each patch must have put (store index, name, materials) and its reduction
    computes. Kept on the task until a declaration is added."""
    key = (loop_body, len(task.requires_), len(task.computes_), len(task.modifies_))
    cache = task.__dict__.setdefault("_run_plan", {})
    plan = cache.get(key)
    if plan is None:
        which = (OLD, NEW, PARENT_OLD, PARENT_NEW) if loop_body else (OLD, NEW)
        decl = tuple(_declared(task, w) for w in which)
        ghosted = [(i, *_ghosted(task, w)) for i, w in enumerate(which)]
        ghosted = [g for g in ghosted if g[1] or g[2]]
        checks, reductions = [], []
        for dep in task.computes_:
            vt = dep.label.vartype
            if vt is VarType.REDUCTION:
                reductions.append(dep)
            else:
                checks.append((0 if vt.is_grid else 1 if vt is VarType.PARTICLE else 2, dep.label.name, dep.matls))
        plan = cache[key] = (decl, ghosted, checks, reductions)
    return plan


class Scheduler:
    """What a component schedules into, and what runs the compiled graphs."""

    def __init__(self, level, lb, comm: Comm | None = None):
        self.level = level
        self.lb = lb
        self.comm = comm or Comm(None)
        self.tasks: list[Task] = []
        self.relocation: list[RelocationSpec] = []     # one per particle set (disjoint materials)
        self.position_label = None
        self.particle_id_label = None
        self.timing: dict = defaultdict(float)
        # time in execute outside the task bodies: ghost exchange, relocation
        self.overhead: dict = defaultdict(float, {"ghost exchange": 0.0})
        self._ghost_wall = 0.0
        self.calls: dict = defaultdict(int)
        self.particles_removed = 0
        self.scrub_old = True
        self._plans: dict = {}
        self.min_halo: dict = {}
        self.recompute_reason = None
        self.graph_name = ""

    # -- what components call ----------------------------------------------------------
    def add_task(self, task: Task):
        self.tasks.append(task)
        return task

    def schedule_particle_relocation(self, pos_pre, labels_pre, pos, labels, matls, id_label=None,
                                     mass_pre=None, on_leaving="warn"):
        """Move particles to their new patch at the end of the step (Uintah's relocation);
        particles leaving the domain are deleted and reported (their mass, with mass_pre).
        Each call adds a particle set over its own materials (MPM's particles and a model's
        tracers); they relocate together in the step's one relocation task, and share the
        position and ID labels (p.x, p.particleID), as in Uintah."""
        if len(labels_pre) != len(labels):
            raise ValueError("relocation needs one final label per pre-relocation label")
        for other in self.relocation:
            if set(other.matls) & set(matls) or other.pos.name != pos.name or \
                    (other.id_label is None) != (id_label is None) or \
                    (id_label is not None and other.id_label.name != id_label.name):
                raise ValueError(f"a second particle relocation over materials {tuple(matls)} needs materials of "
                                 f"its own (have {other.matls}) and the same position and ID labels")
        self.relocation.append(RelocationSpec(pos_pre, list(labels_pre), pos, list(labels), tuple(matls), id_label,
                                              mass_pre, on_leaving))
        self.register_particle_labels(pos, id_label)

    def request_recompute(self, reason: str):
        """Ask the controller to redo this timestep with a smaller delT (Uintah's
        recomputeTimestep), e.g. when an iterative solve did not converge. Any rank may ask."""
        self.recompute_reason = reason

    def register_particle_labels(self, pos, id_label=None):
        """Position label (for ghost particles) and, optionally, the ID label that fixes their order."""
        self.position_label = pos
        self.particle_id_label = id_label

    @property
    def local_patches(self):
        return self.lb.local_patches()

    # -- compile ---------------------------------------------------------------------------
    def begin_graph(self, name: str):
        self.graph_name = name
        self.tasks = []
        self.relocation = []

    def compile(self, needed, old_available, protect=None, build_patch_graph=True) -> CompiledGraph:
        tasks = list(self.tasks)
        for t in tasks:
            self._add_implicit_particle_requires(t)
        if self.relocation:
            tasks.append(relocation_task(self.relocation))
        for t in tasks:
            if isinstance(t, Loop):
                self._compile_loop(t)
        return compile_graph(self.graph_name, tasks, self.level.patches, self.level, set(needed),
                             old_available, protect, build_patch_graph)

    def _compile_loop(self, loop: Loop):
        for t in loop.body:
            self._add_implicit_particle_requires(t)
            if isinstance(t, Loop):
                self._compile_loop(t)           # a loop nested in a loop's body
        first = set(loop.init)
        for t in loop.body:
            for d in t.requires_:
                if d.dw == OLD and d.label.name not in first:
                    raise GraphError(f"task {t.name} in loop {loop.name} requires {d.label.name} from the "
                                     f"previous iteration, but the loop's init does not provide it")
        loop.body_graph = compile_graph(f"{self.graph_name}:{loop.name}", loop.body, self.level.patches,
                                        self.level, loop.needed(), first, build_patch_graph=False)

    def _add_implicit_particle_requires(self, task):
        """Ghost particles are chosen by position (and ordered by ID): the task reads those too."""
        extra = [l for l in (self.position_label, self.particle_id_label) if l is not None]
        for dep in list(task.requires_):
            if dep.label.vartype is not VarType.PARTICLE or not dep.n:
                continue
            for lab in extra:
                if not any(d.label.name == lab.name and d.dw == dep.dw and d.n >= dep.n for d in task.requires_):
                    task.requires(dep.dw, lab, dep.ghost, dep.n, dep.matls)

    def request_halo(self, vt: VarType, width: int):
        """Store arrays of type vt with at least `width` ghost layers even if no task requires
        them (e.g. scatter targets of ghost particles); no exchange is implied."""
        self.min_halo[vt] = max(self.min_halo.get(vt, 0), int(width))

    def set_halo(self, graphs):
        """Fix the stored halo of each grid type to the widest ghost any task requires."""
        halo = halo_widths(graphs)
        for vt in self.level.halo:
            self.level.halo[vt] = max(halo.get(vt, 0), self.min_halo.get(vt, 0))
        self.level.clear_cache()
        self._plans.clear()

    def grid_plan(self, vt: VarType, g: int) -> GridPlan:
        key = (vt, g, self.lb.version)
        if key not in self._plans:
            self._plans[key] = GridPlan(self.level, self.lb.rank_of, vt, g, self.comm.rank)
        return self._plans[key]

    # -- execute ---------------------------------------------------------------------------
    def execute(self, cg: CompiledGraph, old_dw, new_dw, keep=frozenset(), parents=None):
        """Run every task of the graph on this rank's patches (parents: a loop body's timestep DWs)."""
        if old_dw is not None:
            new_dw.pre_counts = dict(old_dw.nparticles)
        for task, kind, scrub_new, scrub_old in _graph_plan(cg, keep):
            t0 = time.perf_counter()
            if kind == _RELOCATION:
                for spec in task.relocation:
                    relocate(self, spec, new_dw)
                self.overhead["relocation"] += time.perf_counter() - t0
            elif kind == _LOOP:
                run_loop(self, task, old_dw, new_dw)     # its body's tasks have their own rows
            else:
                ghost0 = self._ghost_wall
                self._run(task, old_dw, new_dw, parents)
                self.timing[task.name] += time.perf_counter() - t0 - (self._ghost_wall - ghost0)
            self.calls[task.name] += 1
            if scrub_new:
                new_dw.scrub_all(scrub_new)
            if scrub_old and old_dw is not None and self.scrub_old:
                old_dw.scrub_all(scrub_old)

    def _run(self, task: Task, old_dw, new_dw, parents=None):
        decl, ghosted, checks, reductions = _task_plan(task, parents is not None)
        ov = TaskView(old_dw, task, OLD, decl[0]) if old_dw is not None else None
        nv = TaskView(new_dw, task, NEW, decl[1])
        views = (ov, nv)
        dws = (old_dw, new_dw)
        if parents is not None:
            views = (ov, nv, TaskView(parents[0], task, PARENT_OLD, decl[2]),
                     TaskView(parents[1], task, PARENT_NEW, decl[3]))
            dws = (old_dw, new_dw, parents[0], parents[1])
        patches = self.local_patches
        if not ghosted:
            for p in patches:
                self._call(task, p, views, new_dw, checks)
        else:
            exchanges = []
            g0 = time.perf_counter()
            for i, grid, parts in ghosted:
                ex = Exchange(self, dws[i], grid, parts)
                ex.begin()
                exchanges.append(ex)
            g1 = time.perf_counter()
            remote = set().union(*(ex.remote_patches for ex in exchanges))
            for p in patches:
                if p.id not in remote:
                    self._call(task, p, views, new_dw, checks)
            g2 = time.perf_counter()
            for ex in exchanges:
                ex.finish()
            ghost = (g1 - g0) + (time.perf_counter() - g2)
            self._ghost_wall += ghost
            self.overhead["ghost exchange"] += ghost
            for p in patches:
                if p.id in remote:
                    self._call(task, p, views, new_dw, checks)
        in_patch_order = {}
        for dep in reductions:
            for m in dep.matls:
                key = (dep.label.name, m)
                if dep.label.reduction == "sum" and dep.label.patch_order:
                    in_patch_order[key] = (dep.label, new_dw.patch_sums.pop(key, {}))
                    continue
                v = new_dw.reductions.get(key, new_dw.identity(dep.label))
                new_dw.reductions[key] = self.comm.allreduce(v, dep.label.reduction)
        if in_patch_order:
            new_dw.reductions.update(self._sums_in_patch_order(in_patch_order))

    def _sums_in_patch_order(self, sums):
        """{key: sum} of every patch's contribution to each of a task's sums ({key: (label,
        {patch id: part})}), added in patch-id order whatever rank holds each patch, so saved
        sums are bitwise the same on any number of ranks; one allgather for all of them."""
        parts = {key: {} for key in sums}
        for d in self.comm.allgather({key: p for key, (_, p) in sums.items()}):   # [own] on one rank
            for key, p in d.items():
                parts[key].update(p)
        out = {}
        for key, (label, _) in sums.items():
            total = DataWarehouse.identity(label)
            for pid in sorted(parts[key]):
                total = total + parts[key][pid]
            out[key] = total
        return out

    def _call(self, task, patch, views, new_dw, checks=None):
        new_dw.reduction_patch = patch.id
        try:
            task.fn(patch, task.matls, *views)
        except Exception as e:
            if not hasattr(e, "pysus_where"):
                e.pysus_where = f"task {task.name} on patch {patch.id}"
            raise
        finally:
            new_dw.reduction_patch = None
        if checks is None:
            checks = _task_plan(task, False)[2]
        stores = (new_dw.grid, new_dw.particles, new_dw.perpatch)
        pid = patch.id
        for which, name, matls in checks:
            store = stores[which]
            for m in matls:
                if (name, m, pid) not in store:
                    raise TaskError(f"task {task.name} declared it computes {name} "
                                    f"(material {m}) but did not put it on patch {pid}")

    # -- helpers for the controller ----------------------------------------------------
    def reduce_delT(self, dw) -> float:
        return float(dw.get_reduction(delT_label))

    def patch_costs(self, dw) -> list[float]:
        """Measured cost per patch (cells + weighted particles), gathered on every rank."""
        from ..loadbalancer import PARTICLE_WEIGHT
        local = {}
        for p in self.local_patches:
            n = sum(v for (m, pid), v in dw.nparticles.items() if pid == p.id)
            local[p.id] = p.ncells + PARTICLE_WEIGHT * n
        merged = {}
        for d in self.comm.allgather(local):
            merged.update(d)
        return [merged[p.id] for p in self.level.patches]

    def timing_table(self):
        """(name, seconds, calls, % of the rows' sum) per task, then ghost exchange and relocation."""
        rows = sorted(self.timing.items(), key=lambda kv: -kv[1]) + sorted(self.overhead.items())
        total = sum(t for _, t in rows) or 1.0
        return [(name, t, self.calls.get(name, 0), 100.0 * t / total) for name, t in rows]

