"""Task graph compile checks, pruning, access checks and ghost filling."""
import numpy as np
import pytest

from framework import labels as L
from framework.datawarehouse import DataWarehouse, WarehouseError
from framework.grid import Level
from framework.loadbalancer import LoadBalancer
from framework.scheduler.compile import GraphError
from framework.scheduler.scheduler import Scheduler
from framework.task import NEW, OLD, Task, TaskError
from framework.variables import GRID_TYPES, Ghost, VarType

A = L.create("test.A", VarType.CC)
B = L.create("test.B", VarType.CC)
C = L.create("test.C", VarType.CC)
R = L.create("test.R", VarType.REDUCTION, reduction="sum")
ran = []


def make(patches=(2, 2, 1), periodic=(False, False, False), n=(8, 8, 1)):
    lv = Level((0, 0, 0), (1, 1, 1), n, patches=patches, extra=(1, 1, 1), periodic=periodic)
    return lv, Scheduler(lv, LoadBalancer(lv, 1, 0))


def fill(label, value=1.0):
    def fn(patch, matls, old_dw, new_dw):
        ran.append(label.name)
        new_dw.allocate(label, 0, patch, value)
    return fn


def test_requirement_nobody_computes_is_refused_before_running():
    ran.clear()
    lv, s = make()
    s.begin_graph("g")
    s.add_task(Task("useB", fill(C), [0]).requires(NEW, B).computes(C))
    with pytest.raises(GraphError, match="task useB requires test.B .* no task computes it"):
        s.compile({C.name}, None)
    assert ran == []


def test_label_computed_twice_is_refused():
    lv, s = make()
    s.begin_graph("g")
    s.add_task(Task("one", fill(A), [0]).computes(A))
    s.add_task(Task("two", fill(A), [0]).computes(A))
    with pytest.raises(GraphError, match="test.A is computed by task one and again by task two"):
        s.compile({A.name}, None)


def test_cycle_is_refused_naming_tasks_and_labels():
    lv, s = make()
    s.begin_graph("g")
    s.add_task(Task("first", fill(A), [0]).requires(NEW, B).computes(A))
    s.add_task(Task("second", fill(B), [0]).requires(NEW, A).computes(B))
    with pytest.raises(GraphError, match="cycle.*first.*second"):
        s.compile({A.name, B.name}, None)


def test_old_requirement_must_be_available():
    lv, s = make()
    s.begin_graph("g")
    s.add_task(Task("t", fill(B), [0]).requires(OLD, A).computes(B))
    with pytest.raises(GraphError, match="requires test.A from the old warehouse"):
        s.compile({B.name}, {"other"})


def test_pruning_drops_tasks_nobody_needs():
    lv, s = make()
    s.begin_graph("g")
    s.add_task(Task("makeA", fill(A), [0]).computes(A))
    s.add_task(Task("makeB", fill(B), [0]).requires(NEW, A).computes(B))
    s.add_task(Task("makeC", fill(C), [0]).computes(C))
    cg = s.compile({B.name}, None)
    assert [t.name for t in cg.tasks] == ["makeA", "makeB"] and [t.name for t in cg.pruned] == ["makeC"]


def test_undeclared_read_and_missing_compute_fail_with_names():
    lv, s = make()

    def sneaky(patch, matls, old_dw, new_dw):
        new_dw.get(A, 0, patch)

    s.begin_graph("g")
    s.add_task(Task("makeA", fill(A), [0]).computes(A))
    s.add_task(Task("sneaky", sneaky, [0]).computes(B))
    cg = s.compile({A.name, B.name}, None)
    with pytest.raises(TaskError, match="task sneaky reads test.A"):
        s.execute(cg, None, DataWarehouse())

    s.begin_graph("h")
    s.add_task(Task("lazy", lambda *a: None, [0]).computes(C))
    cg = s.compile({C.name}, None)
    with pytest.raises(TaskError, match="task lazy declared it computes test.C .* did not put it"):
        s.execute(cg, None, DataWarehouse())


def test_single_assignment():
    lv, _ = make()
    dw = DataWarehouse()
    p = lv.patches[0]
    dw.allocate(A, 0, p)
    with pytest.raises(WarehouseError, match="put twice"):
        dw.allocate(A, 0, p)


def test_scrubbing_frees_variables_after_their_last_reader():
    lv, s = make()
    s.begin_graph("g")
    s.add_task(Task("makeA", fill(A), [0]).computes(A))
    s.add_task(Task("makeB", fill(B), [0]).requires(NEW, A).computes(B))
    cg = s.compile({B.name}, None)
    dw = DataWarehouse()
    s.execute(cg, None, dw)
    assert not any(k[0] == A.name for k in dw.grid) and any(k[0] == B.name for k in dw.grid)


def index_value(vt, idx, lv):
    """A value that identifies a global index (wrapped periodically)."""
    n = lv.ncells
    w = [idx[d] % n[d] if lv.periodic[d] else idx[d] for d in range(3)]
    return w[0] + 100.0 * w[1] + 10000.0 * w[2]


@pytest.mark.parametrize("vt", GRID_TYPES)
@pytest.mark.parametrize("periodic", [(False, False, False), (True, True, False)])
def test_ghost_fill_matches_neighbour_data(vt, periodic):
    label = L.create(f"test.ghost.{vt.value}", vt)
    out = L.create(f"test.ghostcheck.{vt.value}", VarType.REDUCTION, reduction="sum")
    lv, s = make(patches=(3, 2, 1), periodic=periodic, n=(9, 8, 1))

    def init(patch, matls, old_dw, new_dw):
        a = new_dw.allocate(label, 0, patch, np.nan)
        lo, hi = patch.owned(vt)
        base = patch.low_index(vt)
        for i in range(lo[0], hi[0]):
            for j in range(lo[1], hi[1]):
                a[i - base[0], j - base[1], 0] = index_value(vt, (i, j, 0), lv)

    def check(patch, matls, old_dw, new_dw):
        a = new_dw.get(label, 0, patch)
        lo, hi = patch.window(vt, 1)
        base = patch.low_index(vt)
        bad = 0
        for i in range(lo[0], hi[0]):
            for j in range(lo[1], hi[1]):
                bad += a[i - base[0], j - base[1], 0] != index_value(vt, (i, j, 0), lv)
        new_dw.put_reduction(out, bad)

    s.begin_graph("g")
    s.add_task(Task("init", init, [0]).computes(label))
    s.add_task(Task("check", check, [0]).requires(NEW, label, Ghost.AROUND_CELLS, 1).computes(out))
    cg = s.compile({out.name}, None)
    s.set_halo([cg])
    dw = DataWarehouse()
    s.execute(cg, None, dw)
    assert dw.get_reduction(out) == 0


def test_requested_halo_widens_storage_without_exchange():
    lv, s = make()
    s.begin_graph("g")
    s.add_task(Task("makeA", fill(A), [0]).computes(A))
    cg = s.compile({A.name}, None)
    s.request_halo(VarType.CC, 2)
    s.set_halo([cg])
    dw = DataWarehouse()
    s.execute(cg, None, dw)
    p = lv.patches[0]
    assert dw.get(A, 0, p).shape[:2] == (4 + 1 + 2, 4 + 1 + 2)   # 4 cells, 1 extra cell, 2 ghosts
