"""Ghost particles: owned + neighbours' particles within the stencil, in ID order, with an owned mask."""
import numpy as np

from framework import labels as L
from framework.datawarehouse import DataWarehouse
from framework.grid import Level
from framework.loadbalancer import LoadBalancer
from framework.scheduler.scheduler import Scheduler
from framework.task import NEW, OLD, Task
from framework.variables import Ghost, VarType

X = L.create("p.x", VarType.PARTICLE, (3,))
ID = L.create("p.particleID", VarType.PARTICLE, dtype=np.int64)
OUT = L.create("test.ghostcount", VarType.REDUCTION, reduction="sum")


def test_ghost_particles_sorted_by_id_with_owned_mask():
    lv = Level((0, 0, 0), (1, 1, 1), (8, 8, 1), patches=(2, 2, 1))
    s = Scheduler(lv, LoadBalancer(lv, 1, 0))
    rng = np.random.default_rng(1)
    pts = np.c_[rng.random((400, 2)), np.full(400, 0.5)]
    ids = rng.permutation(400).astype(np.int64)
    old = DataWarehouse()
    owner = lv.patch_ids_of_cells(lv.cells_of(pts))
    for p in lv.patches:
        sel = np.nonzero(owner == p.id)[0]
        sel = sel[np.argsort(ids[sel])]
        old.create_particles(0, p, len(sel))
        old.put(X, 0, p, pts[sel])
        old.put(ID, 0, p, ids[sel])
    seen = {}

    def look(patch, matls, old_dw, new_dw):
        x = old_dw.get(X, 0, patch)
        i = old_dw.get(ID, 0, patch)
        mask = old_dw.ghost_owned_mask(X, 0, patch)
        seen[patch.id] = (x, i, mask)
        new_dw.put_reduction(OUT, len(x))

    s.register_particle_labels(X, ID)
    s.begin_graph("g")
    s.add_task(Task("look", look, [0]).requires(OLD, X, Ghost.AROUND_NODES, 1).computes(OUT))
    cg = s.compile({OUT.name}, {X.name, ID.name})
    s.set_halo([cg])
    s.execute(cg, old, DataWarehouse())
    for p in lv.patches:
        x, i, mask = seen[p.id]
        assert np.all(np.diff(i) > 0)
        assert mask.sum() == old.num_particles(0, p)
        c = lv.cells_of(x)
        inside = np.all((c[:, :2] >= p.lo[:2]) & (c[:, :2] < p.hi[:2]), axis=1)
        assert np.array_equal(inside, mask)
        near = np.all((c[:, :2] >= np.array(p.lo[:2]) - 1) & (c[:, :2] < np.array(p.hi[:2]) + 1), axis=1)
        assert near.all()
        expect = np.all((lv.cells_of(pts)[:, :2] >= np.array(p.lo[:2]) - 1) &
                        (lv.cells_of(pts)[:, :2] < np.array(p.hi[:2]) + 1), axis=1).sum()
        assert len(x) == expect
