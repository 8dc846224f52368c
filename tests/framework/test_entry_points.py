"""The command line is reachable as `python -m framework` as well as the `pysus` script."""
import os
import subprocess
import sys

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def _run(*args):
    env = dict(os.environ, PYTHONPATH=ROOT)
    return subprocess.run([sys.executable, "-m", "framework", *args], capture_output=True, text=True, env=env,
                          timeout=120)


def test_module_entry_prints_help():
    r = _run("--help")
    assert r.returncode == 0
    assert "usage:" in r.stdout and "-restart" in r.stdout


def test_module_entry_refuses_a_missing_deck_cleanly(tmp_path):
    r = _run(str(tmp_path / "nothing.ups"))
    assert r.returncode == 2
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("pysus: error:") and "nothing.ups" in lines[0]


def test_warm_writes_the_bytecode_of_pysus_modules():
    """`pysus --warm` (compile_bytecode) leaves beside each module of framework/ and components/ a
    .pyc stamped with the source's mtime and size, which later processes load instead of
    compiling the source (Python writes none itself where PYTHONDONTWRITEBYTECODE is set)."""
    import importlib.util
    import struct

    from framework.cli import compile_bytecode
    modules = [os.path.join(ROOT, rel) for rel in ("framework/cli.py", "framework/scheduler/compile.py",
                                                   "components/mpm/materials.py")]
    for src in modules:
        if os.path.exists(importlib.util.cache_from_source(src)):
            os.unlink(importlib.util.cache_from_source(src))
    compile_bytecode()
    for src in modules:
        with open(importlib.util.cache_from_source(src), "rb") as f:
            _, flags, mtime, size = struct.unpack("<4sIII", f.read(16))
        st = os.stat(src)
        assert flags == 0 and mtime == int(st.st_mtime) & 0xFFFFFFFF and size == st.st_size & 0xFFFFFFFF


END_OF_RUN = """
import atexit, sys
from framework.cli import main


class Teardown:
    def __del__(self):
        print("torn down", flush=True)


kept = Teardown()                     # freed only by the interpreter's teardown
atexit.register(lambda: print("atexit ran"))
sys.argv = ["pysus", "inputs/examples/quickstart.ups", "--max-timesteps", "2", "--filebase", sys.argv[1]]
sys.exit(main())
"""


def test_command_ends_after_its_run_without_the_teardown(tmp_path):
    """The pysus command's process, once its run is written, runs the atexit handlers, flushes its
    output and ends without the interpreter's teardown (cli._end_process); the uda is complete."""
    from framework.archiver import DataArchive
    env = dict(os.environ, PYTHONPATH=ROOT)
    uda = str(tmp_path / "run.uda")
    r = subprocess.run([sys.executable, "-c", END_OF_RUN, uda], capture_output=True, text=True, env=env,
                       cwd=ROOT, timeout=300)
    assert r.returncode == 0, r.stderr
    lines = r.stdout.strip().splitlines()
    assert lines[-2].startswith("pysus: 2 timesteps") and lines[-1] == "atexit ran"
    assert "torn down" not in r.stdout
    da = DataArchive(uda)
    temp, _ = da.read("temp_CC", 0, -1)
    assert da.timesteps == [0] and temp.size == 64 * 64 and np.isfinite(temp).all()


RANKS_ENDING_APART = """
import sys, time
from mpi4py import MPI
from framework.cli import _end_process
if MPI.COMM_WORLD.Get_rank() == 1:
    time.sleep(1.0)
    print("rank 1 finished its run", flush=True)
_end_process(0)
"""


def test_ranks_ending_apart_each_finish(tmp_path):
    """Under mpiexec a rank that ends its process first must not end the others: _end_process
    finalizes MPI before skipping the teardown (where mpi4py would finalize); without it mpiexec
    ended rank 1 in its last second, its final output unwritten."""
    from tests.conftest import BIN
    env = dict(os.environ, PYTHONPATH=ROOT)
    r = subprocess.run([str(BIN / "mpiexec"), "-n", "2", sys.executable, "-c", RANKS_ENDING_APART],
                       capture_output=True, text=True, env=env, cwd=tmp_path, timeout=120)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "rank 1 finished its run" in r.stdout


RANKS_ENDING_TOGETHER = """
import ctypes, os
from mpi4py import MPI
from framework.cli import _end_process
MPI.COMM_WORLD.allgather(MPI.COMM_WORLD.rank)
# a handler of the C library's exit (on_exit): it runs at exit, never at _exit
said = ctypes.CFUNCTYPE(None, ctypes.c_int, ctypes.c_void_p)(lambda status, arg: os.write(1, b"left through exit\\n"))
ctypes.CDLL(None).on_exit(said, None)
_end_process(0)
"""


def test_ranks_leave_through_exit_after_finalize(tmp_path):
    """Under mpiexec _end_process leaves through the C library's exit (each rank's on_exit
    handler runs and its line reaches mpiexec), and three ranks ending together after a
    collective end the job with 0. Through _exit after MPI_Finalize (no handler runs: the line
    check fails every time), MPICH's process manager counted a rank as failed now and then and
    killed the job (exit code 9: 1 in 15 and 1 in 12 such launches of three ranks, and once in
    a fresh-clone CI's 3-rank container run after its last output)."""
    from tests.conftest import BIN
    env = dict(os.environ, PYTHONPATH=ROOT)
    for _ in range(2):
        r = subprocess.run([str(BIN / "mpiexec"), "-n", "3", sys.executable, "-c", RANKS_ENDING_TOGETHER],
                           capture_output=True, text=True, env=env, cwd=tmp_path, timeout=120)
        assert r.returncode == 0, r.stdout + r.stderr
        assert r.stdout.count("left through exit") == 3, r.stdout
