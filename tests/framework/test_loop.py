"""Iterated sub-graphs (framework.scheduler.loop) through the example's implicit heat solve."""
import numpy as np
import pytest

from framework.archiver import DataArchive
from framework.scheduler.compile import GraphError
from framework.scheduler.loop import Loop, LoopError
from tests.components.examples.test_examples import heat_error
from tests.conftest import pysus_runs, run_deck
from tests.framework import decks


def test_implicit_heat_takes_large_steps_and_matches_exact(tmp_path):
    # backward Euler at 8x the explicit limit: first order in time, still close to the
    # exact Gaussian, and heat is conserved by the zero-flux boundaries
    explicit = run_deck(decks.heat(n=32, maxTime=0.1, extra_save='<save label="TotalHeat"/>'), tmp_path, name="e")
    implicit = run_deck(decks.heat(n=32, maxTime=0.1, implicit=True, cfl=3.2,
                                   extra_save='<save label="TotalHeat"/>'), tmp_path, name="i")
    assert implicit.timestep <= explicit.timestep / 5
    half = run_deck(decks.heat(n=32, maxTime=0.1, implicit=True, cfl=1.6), tmp_path, name="h")
    e1, e2 = heat_error(implicit.archiver.dir), heat_error(half.archiver.dir)
    assert e1 < 2e-3 and 1.5 < e1 / e2 < 2.5, (e1, e2)   # backward Euler: first order in time
    _, h = DataArchive(implicit.archiver.dir).reduction("TotalHeat")
    assert np.ptp(h) < 1e-14 * h.max()
    assert implicit.component.solve.iterations > 2


def test_patches_agree_to_solver_tolerance(tmp_path):
    kw = dict(n=32, maxTime=0.05, implicit=True, cfl=3.2, tolerance=1e-12)
    a = run_deck(decks.heat(patches="[1,1,1]", **kw), tmp_path, name="a")
    b = run_deck(decks.heat(patches="[4,2,1]", **kw), tmp_path, name="b")
    ta = DataArchive(a.archiver.dir).read("temp_CC", 0, -1)[0]
    tb = DataArchive(b.archiver.dir).read("temp_CC", 0, -1)[0]
    assert np.abs(ta - tb).max() < 1e-10 * np.abs(ta).max()


def test_nonconvergence_is_an_error(tmp_path):
    text = decks.heat(n=16, maxTime=0.05, implicit=True, cfl=3.2).replace(
        "</tolerance>", "</tolerance><max_iterations>2</max_iterations>")
    with pytest.raises(LoopError, match="did not converge in 2 iterations"):
        run_deck(text, tmp_path)


def test_body_reading_an_unseeded_variable_is_refused():
    from framework import labels as L
    from framework.grid import Level
    from framework.loadbalancer import LoadBalancer
    from framework.scheduler.scheduler import Scheduler
    from framework.task import OLD, Task
    from framework.variables import VarType
    A = L.create("test.loop.A", VarType.CC)
    lv = Level((0, 0, 0), (1, 1, 1), (8, 8, 1))
    s = Scheduler(lv, LoadBalancer(lv, 1, 0))
    s.begin_graph("g")
    body = [Task("body", None, [0]).requires(OLD, A).computes(A)]
    s.add_task(Loop("loop", [0], body, init={}, results={}, converged=lambda *a: True))
    with pytest.raises(GraphError, match="loop's init does not provide it"):
        s.compile(set(), None)


@pytest.fixture(scope="module")
def on_ranks(tmp_path_factory):
    """The implicit heat deck on 1 rank in this process, then on 2 and 3 ranks in one mpiexec
    launch: the directory of n1.uda, n2.uda, n3.uda and each run's (return code, stderr)."""
    d = tmp_path_factory.mktemp("loop_ranks")
    (d / "d.ups").write_text(decks.heat(n=32, patches="[3,2,1]", maxTime=0.05, implicit=True, cfl=3.2, tolerance=1e-12))
    return d, pysus_runs([((d / "d.ups", "--filebase", d / f"n{n}.uda"), n) for n in (1, 2, 3)], d)


@pytest.mark.parametrize("nranks", [2, 3])
def test_implicit_solve_on_ranks_matches_one_rank(on_ranks, nranks):
    d, out = on_ranks
    for rc, err in (out[0], out[nranks - 1]):
        assert rc == 0, err
    t1 = DataArchive(d / "n1.uda").read("temp_CC", 0, -1)[0]
    tn = DataArchive(d / f"n{nranks}.uda").read("temp_CC", 0, -1)[0]
    assert np.abs(t1 - tn).max() < 1e-10 * np.abs(t1).max()
