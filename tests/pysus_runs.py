"""`mpiexec -n N python -m tests.pysus_runs RUNS.json`: several pysus runs in one MPI launch.

RUNS.json holds a list of [argv, n]: each run is the pysus command line argv (framework.cli.main,
what the pysus command runs) on the first n ranks, in a communicator split off MPI's world; the
runs go one after another. One launch instead of one per run spares every run after the first
the start of n Python processes and the loading of the kernels (about 1 CPU s a rank). Exits
with the first non-zero exit code of a run (rank 0 names the run on stderr); a run that raises
ends the whole launch, as pysus on several ranks does (framework/cli.py _exit).
"""
import json
import sys
import time

from mpi4py import MPI

from framework.cli import main
from framework.scheduler.comm import Comm


def wait_for_all(comm):
    """A barrier that waits in sleeps, so that a rank idle while the others run takes next to no
    CPU (in MPI's Barrier it keeps polling: 0.3-0.9 CPU s more a launch of test_mpi_ice's or
    test_heat's runs, measured with MPIR_CVAR_ENABLE_HEAVY_YIELD=1)."""
    req = comm.Ibarrier()
    while not req.Test():
        time.sleep(0.002)


def run_all(runs) -> int:
    world = MPI.COMM_WORLD
    failed = 0
    for argv, n in runs:
        wait_for_all(world)
        sub = world.Split(0 if world.Get_rank() < n else MPI.UNDEFINED, world.Get_rank())
        if sub == MPI.COMM_NULL:
            continue
        rc = main([*map(str, argv), "-q"], comm=Comm(sub))
        sub.Free()
        if rc and not failed:
            failed = rc
            if world.Get_rank() == 0:
                print(f"pysus_runs: {' '.join(map(str, argv))} on {n} ranks exited with {rc}", file=sys.stderr)
    wait_for_all(world)
    return world.allreduce(failed, op=MPI.MAX)


if __name__ == "__main__":
    with open(sys.argv[1]) as f:
        sys.exit(run_all(json.load(f)))
