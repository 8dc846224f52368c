"""Compile a list of tasks into an ordered, checked, pruned task graph.

The graph's nodes are (task, patch) pairs; an edge runs from the task-patch that
writes a variable to every task-patch that reads it, across patches where ghosts are
required. Bad graphs are refused before anything runs, with the task and label
named: a requirement nobody computes, a label computed twice, a cycle. Tasks whose
outputs nobody needs are pruned.
"""
from __future__ import annotations

import heapq
from dataclasses import dataclass, field

from ..task import NEW, OLD, Task
from ..variables import VarType


class GraphError(Exception):
    """The task graph is not valid; the message names the task and label."""


@dataclass
class CompiledGraph:
    """Tasks in execution order plus what the executor needs to run them."""

    name: str
    tasks: list
    pruned: list
    carried: set
    computed: set
    scrub_after: dict = field(default_factory=dict)
    scrub_old_after: dict = field(default_factory=dict)
    halo: dict = field(default_factory=dict)
    patch_graph_of: tuple | None = field(default=None, repr=False)   # task_patch_graph's arguments

    @property
    def graph(self):
        """The (task, patch) graph (networkx), built when first asked for (the time loop needs only
        the task order, and a run then starts without importing networkx); None when compiled
        without it."""
        if self.patch_graph_of is not None and not hasattr(self, "_graph"):
            self._graph = task_patch_graph(*self.patch_graph_of)
        return getattr(self, "_graph", None)


def _writers(tasks):
    """label name -> [(task, 'computes'|'modifies')] in add order; refuses double computes."""
    out: dict = {}
    for t in tasks:
        for dep in t.computes_:
            lst = out.setdefault(dep.label.name, [])
            for other, kind in lst:
                if kind == "computes" and set(other_matls(other, dep.label)) & set(dep.matls):
                    raise GraphError(f"label {dep.label.name} is computed by task {other.name} and again by "
                                     f"task {t.name}; use modifies in the second")
            lst.append((t, "computes"))
        for dep in t.modifies_:
            out.setdefault(dep.label.name, []).append((t, "modifies"))
    return out


def other_matls(task, label):
    for dep in task.computes_:
        if dep.label.name == label.name:
            return dep.matls
    return ()


def _bind(task, name, writers):
    """The writer whose version of `name` the task reads: the latest one added before it."""
    lst = writers.get(name, [])
    before = [w for w, _ in lst if w.order < task.order]
    if before:
        return before[-1]
    after = [w for w, kind in lst if kind == "computes" and w is not task]
    return after[0] if after else None


def compile_graph(name, tasks: list[Task], patches, level, needed: set, old_available: set | None,
                  protect: set | None = None, build_patch_graph=True) -> CompiledGraph:
    """Check, prune, order and annotate `tasks`.

    needed: label names that must be produced (carried to the next step, output, delT).
    old_available: label names the old warehouse will hold (None: no old warehouse).
    protect: label names never scrubbed (default: needed); output labels are left out of
    it so they are freed on steps that write no output.
    """
    for i, t in enumerate(tasks):
        t.order = i
    names = [t.name for t in tasks]
    dup = {n for n in names if names.count(n) > 1}
    if dup:
        raise GraphError(f"task name {sorted(dup)[0]} scheduled twice in graph {name}")
    writers = _writers(tasks)

    for t in tasks:
        for dep in t.requires_:
            if dep.dw == NEW and _bind(t, dep.label.name, writers) is None:
                raise GraphError(f"task {t.name} requires {dep.label.name} from the new warehouse, "
                                 "but no task computes it")
            if dep.dw == OLD and old_available is not None and dep.label.name not in old_available:
                raise GraphError(f"task {t.name} requires {dep.label.name} from the old warehouse, "
                                 "but neither initialization nor the previous timestep computes it")
            if dep.dw == OLD and old_available is None:
                raise GraphError(f"task {t.name} requires {dep.label.name} from the old warehouse, "
                                 f"which does not exist in graph {name}")
        for dep in t.modifies_:
            prev = [w for w, _ in writers.get(dep.label.name, []) if w.order < t.order]
            if not prev:
                raise GraphError(f"task {t.name} modifies {dep.label.name}, which no earlier task computes")

    # Task-level dependency graph (cycle check, order, pruning): edges (writer, reader, label).
    edges = []
    for t in tasks:
        for dep in t.requires_:
            if dep.dw == NEW:
                w = _bind(t, dep.label.name, writers)
                if w is not t:
                    edges.append((w, t, dep.label.name))
        for dep in t.modifies_:
            prev = [w for w, _ in writers[dep.label.name] if w.order < t.order]
            edges.append((prev[-1], t, dep.label.name))
            # readers of the earlier version must run before this modification
            for r in tasks:
                if r is not t and r.order < t.order and any(
                        d.dw == NEW and d.label.name == dep.label.name for d in r.requires_):
                    edges.append((r, t, dep.label.name))
    order = _task_order(tasks, edges)
    if order is None:
        raise GraphError(_cycle_message(name, tasks, edges))

    # Pruning: keep tasks that (transitively) produce a needed label.
    want = set(needed)
    keep = set()
    changed = True
    while changed:
        changed = False
        for t in reversed(order):
            if t in keep:
                continue
            if any(d.label.name in want for d in t.writes()) or getattr(t, "always", False):
                keep.add(t)
                changed = True
                for d in t.requires_:
                    if d.dw == NEW:
                        want.add(d.label.name)
                for d in t.modifies_:
                    want.add(d.label.name)
    kept = [t for t in order if t in keep]
    pruned = [t for t in order if t not in keep]

    carried = {d.label.name for t in kept for d in t.requires_ if d.dw == OLD}
    computed = {d.label.name for t in kept for d in t.computes_}

    cg = CompiledGraph(name, kept, pruned, carried, computed)
    _scrub_points(cg, needed if protect is None else protect)
    if build_patch_graph:
        cg.patch_graph_of = (kept, writers, patches, level)
    return cg


def _task_order(tasks, edges):
    """The tasks in an order that runs every edge's writer before its reader, of the tasks ready
    the one added first (networkx's lexicographical_topological_sort keyed by add order, Kahn's
    algorithm with a heap); None when the edges make a cycle."""
    after = {t: {} for t in tasks}          # a dict: each successor once, as a graph's edge
    for w, r, _ in edges:
        after[w][r] = None
    waiting = dict.fromkeys(tasks, 0)
    for t in tasks:
        for r in after[t]:
            waiting[r] += 1
    ready = [(t.order, t) for t in tasks if not waiting[t]]
    heapq.heapify(ready)
    order = []
    while ready:
        _, t = heapq.heappop(ready)
        order.append(t)
        for r in after[t]:
            waiting[r] -= 1
            if not waiting[r]:
                heapq.heappush(ready, (r.order, r))
    return order if len(order) == len(tasks) else None


def _cycle_message(name, tasks, edges):
    """The error for a graph with a cycle: the cycle networkx finds, each edge with its label."""
    import networkx as nx
    tg = nx.DiGraph()
    tg.add_nodes_from(tasks)
    for w, r, label in edges:
        tg.add_edge(w, r, label=label)
    cyc = nx.find_cycle(tg)
    path = " -> ".join(f"{a.name} ({tg.edges[a, b]['label']})" for a, b in cyc)
    return f"cycle in graph {name}: {path} -> {cyc[0][0].name}"


def _scrub_points(cg: CompiledGraph, needed: set):
    """After which task each new/old-warehouse label can be freed."""
    last_new, last_old = {}, {}
    for t in cg.tasks:
        for d in t.requires_:
            (last_new if d.dw == NEW else last_old)[d.label.name] = t
        for d in t.writes():
            last_new[d.label.name] = t
    for lbl, t in last_new.items():
        if lbl not in needed:
            cg.scrub_after.setdefault(t, []).append(lbl)
    for lbl, t in last_old.items():
        cg.scrub_old_after.setdefault(t, []).append(lbl)


def task_patch_graph(tasks, writers, patches, level):
    """The (task, patch) graph (a networkx DiGraph) with edges across patches where ghosts are
    required."""
    import networkx as nx
    g = nx.DiGraph()
    g.add_nodes_from((t.name, p.id) for t in tasks for p in patches)
    edges = []
    for t in tasks:
        for dep in t.requires_ + t.modifies_:
            if dep.dw != NEW:
                continue
            w = _bind(t, dep.label.name, writers)
            if w is None or w is t:
                continue
            for p in patches:
                edges.append(((w.name, p.id), (t.name, p.id)))
                if dep.n:
                    if dep.label.vartype is VarType.PARTICLE:
                        srcs = {q.id for q, _, _ in level.particle_ghost_sources(p, dep.n)}
                    else:
                        srcs = {q.id for q, _, _ in level.ghost_sources(p, dep.label.vartype, dep.n)}
                    edges.extend(((w.name, q), (t.name, p.id)) for q in srcs if q != p.id)
    g.add_edges_from(edges)
    return g


def halo_widths(graphs) -> dict:
    """The widest ghost requirement of each grid type over all graphs."""
    halo = {}
    graphs = list(graphs)
    for cg in graphs:
        for t in cg.tasks:
            if getattr(t, "body_graph", None) is not None:
                graphs.append(t.body_graph)
            for d in t.requires_:
                vt = d.label.vartype
                if vt.is_grid:
                    halo[vt] = max(halo.get(vt, 0), d.n)
    return halo
