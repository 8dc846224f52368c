"""Ghost particles read in two parts (TaskView.get_split) and run by run (particle_kernels.runs)
give exactly the merged ID-ordered array that get() returns."""
import numpy as np

from framework import labels as L
from framework.datawarehouse import DataWarehouse
from framework.grid import Level
from framework.loadbalancer import LoadBalancer
from framework.scheduler.particle_kernels import runs
from framework.scheduler.scheduler import Scheduler
from framework.task import OLD, Task
from framework.variables import Ghost, VarType

X = L.create("p.x", VarType.PARTICLE, (3,))
ID = L.create("p.particleID", VarType.PARTICLE, dtype=np.int64)
OUT = L.create("test.splitcount", VarType.REDUCTION, reduction="sum")


def test_runs_rebuild_order():
    rng = np.random.default_rng(0)
    ids = np.r_[np.arange(0, 200, 2), rng.choice(np.arange(1, 200, 2), 30, replace=False)]
    order = np.argsort(ids, kind="stable")
    r = runs(order, 100)
    rebuilt = np.concatenate([np.arange(a, b) + (100 if src else 0) for src, a, b in r])
    assert np.array_equal(rebuilt, order)
    assert len(r) < len(order)                       # consecutive owned rows form one run
    assert len(runs(np.arange(50), 50)) == 1


def test_split_equals_merged():
    lv = Level((0, 0, 0), (1, 1, 1), (8, 8, 1), patches=(2, 2, 1))
    s = Scheduler(lv, LoadBalancer(lv, 1, 0))
    rng = np.random.default_rng(3)
    pts = np.c_[rng.random((500, 2)), np.full(500, 0.5)]
    ids = rng.permutation(500).astype(np.int64)
    old = DataWarehouse()
    owner = lv.patch_ids_of_cells(lv.cells_of(pts))
    for p in lv.patches:
        sel = np.nonzero(owner == p.id)[0]
        sel = sel[np.argsort(ids[sel])]
        old.create_particles(0, p, len(sel))
        old.put(X, 0, p, pts[sel])
        old.put(ID, 0, p, ids[sel])
    checked = []

    def look(patch, matls, old_dw, new_dw):
        own, ghost, order = old_dw.get_split(X, 0, patch)
        whole = np.concatenate([own, ghost])
        assert len(ghost) > 0 and order is not None
        assert np.array_equal(whole[order], old_dw.get(X, 0, patch))
        pieces = [(own if src == 0 else ghost)[a:b] for src, a, b in runs(order, len(own))]
        assert np.array_equal(np.concatenate(pieces), old_dw.get(X, 0, patch))
        checked.append(patch.id)
        new_dw.put_reduction(OUT, len(own))

    s.register_particle_labels(X, ID)
    s.begin_graph("g")
    s.add_task(Task("look", look, [0]).requires(OLD, X, Ghost.AROUND_NODES, 1).computes(OUT))
    cg = s.compile({OUT.name}, {X.name, ID.name})
    s.set_halo([cg])
    s.execute(cg, old, DataWarehouse())
    assert sorted(checked) == [p.id for p in lv.patches]
