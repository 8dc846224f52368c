"""Framework overhead: per task-patch execution cost, graph compile time, scrubbing.

Measures (medians of several repetitions):
  * time per task-patch of an empty task (goal: at most 30 microseconds),
  * compile time of graphs with about 1,000 and 10,000 task-patch nodes (goal: 10,000
    under 3 s), including the networkx task-patch graph and its ghost edges,
  * warehouse memory at the end of a step with and without scrubbing.
Prints a table and writes JSON.  About 30 s:
    .venv/bin/python scripts/bench/framework_overhead.py [--json out.json]
"""
from __future__ import annotations

import argparse
import json
import statistics
import time

import numpy as np

from framework import labels as L
from framework.datawarehouse import DataWarehouse
from framework.grid import Level
from framework.loadbalancer import LoadBalancer
from framework.scheduler.scheduler import Scheduler
from framework.task import NEW, Task
from framework.variables import Ghost, VarType


def scheduler(patches, n=(256, 256, 1)):
    lv = Level((0, 0, 0), (1, 1, 1), n, patches=patches, extra=(1, 1, 1))
    return lv, Scheduler(lv, LoadBalancer(lv, 1, 0))


def empty_task_cost(ntasks=20, patches=(16, 16, 1), reps=7):
    lv, s = scheduler(patches)
    s.begin_graph("empty")
    for i in range(ntasks):
        t = Task(f"empty{i}", lambda patch, matls, old_dw, new_dw: None, [0])
        t.always = True
        s.add_task(t)
    cg = s.compile(set(), None, build_patch_graph=False)
    s.set_halo([cg])
    times = []
    for _ in range(reps):
        dw = DataWarehouse()
        t0 = time.perf_counter()
        s.execute(cg, None, dw)
        times.append(time.perf_counter() - t0)
    n = ntasks * len(lv.patches)
    return statistics.median(times) / n * 1e6, n


def small_task_cost(ntasks=20, patches=(16, 16, 1), reps=7):
    """Per task-patch cost of tasks that get one variable and allocate and put another (16x16 cells)."""
    lv, s = scheduler(patches)
    labels = [L.create(f"bench.small{i}", VarType.CC) for i in range(ntasks + 1)]

    def fn_for(src, dst):
        def fn(patch, matls, old_dw, new_dw):
            new_dw.get(src, 0, patch)
            new_dw.allocate(dst, 0, patch, None)
        return fn

    s.begin_graph("small")
    s.add_task(Task("first", lambda p, m, o, n: n.allocate(labels[0], 0, p), [0]).computes(labels[0]))
    for i in range(ntasks):
        s.add_task(Task(f"small{i}", fn_for(labels[i], labels[i + 1]), [0])
                   .requires(NEW, labels[i]).computes(labels[i + 1]))
    cg = s.compile({labels[-1].name}, None, build_patch_graph=False)
    s.set_halo([cg])
    times = []
    for _ in range(reps):
        dw = DataWarehouse()
        t0 = time.perf_counter()
        s.execute(cg, None, dw)
        times.append(time.perf_counter() - t0)
    n = (ntasks + 1) * len(lv.patches)
    return statistics.median(times) / n * 1e6, n


def compile_time(ntasks, patches, reps=3):
    lv, s = scheduler(patches, n=(patches[0] * 8, patches[1] * 8, 1))
    labels = [L.create(f"bench.v{i}", VarType.CC) for i in range(ntasks)]
    times = []
    for _ in range(reps):
        s.begin_graph("chain")
        s.add_task(Task("t0", None, [0]).computes(labels[0]))
        for i in range(1, ntasks):
            s.add_task(Task(f"t{i}", None, [0]).requires(NEW, labels[i - 1], Ghost.AROUND_CELLS, 1)
                       .computes(labels[i]))
        t0 = time.perf_counter()
        cg = s.compile({labels[-1].name}, None)
        cg.graph                                    # the task-patch graph is built when asked for
        times.append(time.perf_counter() - t0)
    return statistics.median(times), cg.graph.number_of_nodes(), cg.graph.number_of_edges()


def scrub_memory(n=512, nvars=8, patches=(4, 4, 1)):
    lv, s = scheduler(patches, n=(n, n, 1))
    labels = [L.create(f"bench.s{i}", VarType.CC) for i in range(nvars)]

    def producer(lab, src):
        def fn(patch, matls, old_dw, new_dw):
            a = new_dw.allocate(lab, 0, patch)
            if src is not None:
                a += new_dw.get(src, 0, patch)
        return fn

    s.begin_graph("chain")
    for i, lab in enumerate(labels):
        t = Task(f"s{i}", producer(lab, labels[i - 1] if i else None), [0]).computes(lab)
        if i:
            t.requires(NEW, labels[i - 1])
        s.add_task(t)
    cg = s.compile({labels[-1].name}, None)
    s.set_halo([cg])
    out = {}
    for name, keep in (("with scrubbing", frozenset()), ("without scrubbing", frozenset(l.name for l in labels))):
        dw = DataWarehouse()
        s.execute(cg, None, dw, keep=keep)
        out[name] = dw.nbytes()
    return out, n * n


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--json", default="framework_overhead.json")
    args = ap.parse_args()
    res = {}
    us, n = empty_task_cost()
    res["empty_task_us_per_task_patch"] = us
    print(f"{'empty task, per task-patch':44s} {us:10.2f} us   ({n} task-patches per run; goal <= 30 us)")
    us, n = small_task_cost()
    res["get_allocate_task_us_per_task_patch"] = us
    print(f"{'get+allocate+put task, per task-patch':44s} {us:10.2f} us   ({n} task-patches per run)")
    for ntasks, patches in ((10, (10, 10, 1)), (10, (40, 25, 1))):
        t, nodes, edges = compile_time(ntasks, patches)
        res[f"compile_{nodes}_nodes_s"] = t
        print(f"{'compile ' + str(nodes) + ' task-patch nodes':44s} {t:10.3f} s    ({edges} edges; goal for 10,000: < 3 s)")
    mem, cells = scrub_memory()
    for k, v in mem.items():
        res[f"warehouse_bytes_{k.replace(' ', '_')}"] = v
        print(f"{'warehouse ' + k:44s} {v / 2**20:10.1f} MiB ({v / cells:.0f} B/cell)")
    with open(args.json, "w") as f:
        json.dump(res, f, indent=1)
    print(f"wrote {args.json}")


if __name__ == "__main__":
    main()
