"""Shared helpers: run a deck in-process or through the `pysus` command."""
from __future__ import annotations

import contextlib
import importlib.util
import io
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
BIN = Path(sys.executable).parent
UINTAH_INPUTS = ROOT.parent / "shared" / "uintah-inputs"

# The MPI tests run 2 and 3 ranks beside the other test workers, more processes than cores: an
# MPICH rank that waits for a message spins (sched_yield) through the time slices the rank it
# waits for needs. With heavy yield the waiting rank sleeps instead (nanosleep): the same
# messages and answers, a third of the CPU time of a 3-rank ICE run on 2 cores. Every mpiexec
# started by a test inherits it; a value set outside is kept.
os.environ.setdefault("MPIR_CVAR_ENABLE_HEAVY_YIELD", "1")


def load_script(name):
    """scripts/NAME.py as a module (the scripts are not a package)."""
    spec = importlib.util.spec_from_file_location(name, ROOT / "scripts" / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def run_deck(text, tmp_path, name="run", **kw):
    """Run deck text in this process; returns the Controller (ctl.archiver.dir is the .uda)."""
    from framework.controller import Controller
    ctl = Controller(str(tmp_path / f"{name}.ups"), deck_text=text, quiet=True,
                     filebase=str(tmp_path / f"{name}.uda"), **kw)
    ctl.final_dw = ctl.run()
    return ctl


def pysus(*args, np_=1, env=None, timeout=300, cwd=None):
    """Run the pysus command (under mpiexec when np_ > 1) in the test's directory; returns
    CompletedProcess."""
    cmd = [str(BIN / "pysus"), *map(str, args), "-q"]
    if np_ > 1:
        cmd = [str(BIN / "mpiexec"), "-n", str(np_)] + cmd
    e = dict(os.environ)
    e.update(env or {})
    return subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, cwd=cwd or os.getcwd(), env=e)


def pysus_ranks(*args, np_=1, timeout=300):
    """pysus(*args, np_=n) with the one-rank run in this process through framework.cli.main (what
    the pysus command runs on one rank: the same serial code and kernels, its exit code, output
    and error lines), without a second Python start-up and loading of the kernels (0.7-1.0 CPU s
    a run); more ranks under mpiexec. Returns a CompletedProcess (returncode, stdout, stderr)."""
    if np_ > 1:
        return pysus(*args, np_=np_, timeout=timeout)
    from framework.cli import main
    argv = [*map(str, args), "-q"]
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        rc = main(argv)
    return subprocess.CompletedProcess(argv, rc, out.getvalue(), err.getvalue())


def pysus_launch(runs, workdir, timeout=600):
    """The pysus runs [(args, n), ...], each on n ranks, one after another in ONE mpiexec launch
    of the largest n processes (tests/pysus_runs.py: each run through framework.cli.main on the
    first n ranks): the 2- and 3-rank runs of a file's decks start Python and load their kernels
    once per rank, not once per run and rank (about 1 CPU s each). Returns the CompletedProcess
    (returncode: the first failed run's, which rank 0 names on stderr)."""
    import json
    spec = Path(workdir) / "pysus_runs.json"
    spec.write_text(json.dumps([[list(map(str, args)), n] for args, n in runs]))
    # as a module (tests.pysus_runs, found through PYTHONPATH): run as a script, Python would put
    # tests/ first on sys.path, where the test packages tests/framework and tests/components hide
    # pysus's own (and numba's cache index of every kernel would be rewritten)
    cmd = [str(BIN / "mpiexec"), "-n", str(max(n for _, n in runs)), sys.executable, "-m", "tests.pysus_runs", str(spec)]
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(filter(None, (str(ROOT), os.environ.get("PYTHONPATH")))))
    return subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, cwd=workdir, env=env)


def pysus_runs(runs, workdir, timeout=1200):
    """The pysus runs [(args, n), ...] in workdir: those on one rank in this process, first (the
    kernels they compile, numba's cache then hands to the ranks), then all the others in one
    pysus_launch. Returns each run's (return code, stderr) in the order of runs (the ranks' runs
    share their launch's)."""
    out = [None] * len(runs)
    with pytest.MonkeyPatch.context() as mp:
        mp.chdir(workdir)
        for i, (args, n) in enumerate(runs):
            if n == 1:
                r = pysus_ranks(*args)
                out[i] = (r.returncode, r.stderr)
    ranks = [(args, n) for args, n in runs if n > 1]
    if ranks:
        r = pysus_launch(ranks, workdir, timeout=timeout)
        out = [o or (r.returncode, r.stderr) for o in out]
    return out


def edited_deck(src, edits, dest):
    """The deck src with each (old, new) of edits replaced (old must be in it), written to dest
    byte for byte otherwise (Latin-1 in and out)."""
    text = Path(src).read_text(encoding="iso-8859-1")
    for old, new in edits:
        assert old in text, (str(src), old)
        text = text.replace(old, new)
    Path(dest).write_text(text, encoding="iso-8859-1")


def run_cases(workdir, cases, ranks):
    """Each case's deck workdir/CASE.ups on every rank count of ranks (pysus_runs; its uda
    workdir/CASE_N.uda): {(case, n): (return code, stderr)}."""
    d = Path(workdir)
    runs = [(case, n) for case in cases for n in ranks]
    out = pysus_runs([((d / f"{case}.ups", "--filebase", d / f"{case}_{n}.uda"), n) for case, n in runs], d)
    return dict(zip(runs, out))


# The test files that take the most CPU seconds, heaviest first (PYSUS_TEST_CPU below, in a
# fresh-clone run of the whole suite after the shipped decks' warm-up: a file's figure includes
# the numba compilation of the specialisations it was first to need). pytest-xdist (scripts/test:
# --dist loadfile --no-loadscope-reorder) hands whole files to its workers in collection order:
# these start first and the many short files fill in behind them, so the workers finish together
# instead of one running a long file alone at the end.
HEAVY_FILES = (                       # CPU s, self + children, in a fresh-clone run of the suite
    "tests/mpi/test_mpi_mpm.py",                         # 37
    "tests/mpm/test_arena_soil.py",                      # 31
    "tests/mpm/test_axisymmetric.py",                    # 31
    "tests/mpmice/test_container_rupture.py",            # 30
    "tests/models/test_ddt1.py",                         # 25
    "tests/models/test_gas_combustion.py",               # 24
    "tests/mpm/test_artificial_viscosity.py",            # 22
    "tests/mpm/test_disks.py",                           # 17
    "tests/mpm/test_cbdi.py",                            # 17
    "tests/ice/test_uintah_decks.py",                    # 17
    "tests/mpi/test_mpi_models.py",                      # 17
    "tests/mpm/test_damage_draws.py",                    # 17
    "tests/mpmice/test_mpi_mpmice.py",                   # 15
    "tests/mpm/test_boundary_tractions.py",              # 15
    "tests/mpmice/test_piston_validation.py",            # 15
    "tests/mpmice/test_cylinder.py",                     # 15
    "tests/mpm/test_xpic.py",                            # 14
    "tests/mpm/test_half_space.py",                      # 14
    "tests/mpm/test_thermal.py",                         # 13
    "tests/mpm/test_gurson.py",                          # 12
    "tests/mpmice/test_open_faces.py",                   # 12
    "tests/mpmice/test_guni2drt.py",                     # 11
    "tests/mpm/test_damage.py",                          # 11
    "tests/mpm/test_hard_cases.py",                      # 9
    "tests/mpm/test_membrane.py",                        # 9
    "tests/efem/test_archimedes.py",                     # 9
    "tests/mpm/test_disks_complex.py",                   # 9
    "tests/framework/test_numba_compile_lock.py",        # 8
    "tests/mpm/test_shape.py",                           # 8
    "tests/mpm/test_extrude_rt.py",                      # 7
    "tests/framework/test_geometry_tri.py",              # 7
    "tests/ice/test_order.py",                           # 7
    "tests/mpi/test_mpi.py",                             # 7
    "tests/ice/test_implicit.py",                        # 7
    "tests/mpm/test_mpi_decks.py",                       # 6
    "tests/mpi/test_mpi_ice.py",                         # 6
)


def pytest_collection_modifyitems(items):
    """Collect the files of HEAVY_FILES first, in that order; the others keep theirs."""
    rank = {f: i for i, f in enumerate(HEAVY_FILES)}
    items.sort(key=lambda item: rank.get(item.nodeid.split("::")[0], len(rank)))


@pytest.fixture(autouse=True)
def _run_in_tmp(tmp_path, monkeypatch):
    """Every test runs in its own directory: a deck's relative filebase never writes into the
    repository, and tests running side by side never share an output directory."""
    monkeypatch.chdir(tmp_path)


@pytest.fixture
def deckfile(tmp_path):
    def make(text, name="deck.ups"):
        p = tmp_path / name
        p.write_text(text)
        return p
    return make



_TEST_CPU_CSV = os.environ.get("PYSUS_TEST_CPU")
if _TEST_CPU_CSV:
    # PYSUS_TEST_CPU=file.csv appends a row per test: its CPU seconds (set-up, call, tear-down;
    # this process and the processes it waited for, e.g. mpiexec's ranks), the numba kernels it
    # compiled (cache misses) with their CPU seconds, and its wall seconds: where the suite's time
    # goes, and which tests compile a kernel that scripts/warm_kernels did not.
    import csv
    import resource
    import time

    from numba.core import event as numba_event

    class _CompileTimer(numba_event.Listener):
        """The kernels this process compiles and their CPU seconds, outermost compilations only
        (a kernel loaded from numba's cache is no event)."""

        def __init__(self):
            self.depth, self.count, self.cpu, self.t0 = 0, 0, 0.0, 0.0
            self.names = []

        def on_start(self, event):
            if self.depth == 0:
                self.t0 = time.process_time()
            self.depth += 1

        def on_end(self, event):
            self.depth -= 1
            if self.depth == 0:
                self.count += 1
                seconds = time.process_time() - self.t0
                self.cpu += seconds
                py = event.data["dispatcher"].py_func
                self.names.append(f"{py.__module__}.{py.__qualname__}={seconds:.2f}")

    _compiles = _CompileTimer()
    numba_event.register("numba:compile", _compiles)

    @pytest.hookimpl(hookwrapper=True)
    def pytest_runtest_protocol(item, nextitem):
        kids0 = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu0, wall0 = time.process_time(), time.perf_counter()
        n0, c0 = _compiles.count, _compiles.cpu
        del _compiles.names[:]
        yield
        kids1 = resource.getrusage(resource.RUSAGE_CHILDREN)
        kids = (kids1.ru_utime + kids1.ru_stime) - (kids0.ru_utime + kids0.ru_stime)
        row = [item.nodeid, f"{time.process_time() - cpu0:.3f}", f"{kids:.3f}",
               _compiles.count - n0, f"{_compiles.cpu - c0:.3f}", f"{time.perf_counter() - wall0:.3f}",
               " ".join(_compiles.names)]
        new = not os.path.exists(_TEST_CPU_CSV)
        with open(_TEST_CPU_CSV, "a", newline="") as f:
            if new:
                csv.writer(f).writerow(["test", "cpu_self_s", "cpu_children_s", "kernels_compiled",
                                        "compile_cpu_s", "wall_s", "kernels"])
            csv.writer(f).writerow(row)
