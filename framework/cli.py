"""`pysus`: run a deck, restart from a checkpoint, or show the task graph.

    pysus deck.ups                    run on one rank
    pysus --np 4 deck.ups             run on 4 ranks (re-launches itself under mpiexec)
    mpiexec -n 4 pysus deck.ups       the same, launched by the user or a batch script
    pysus -restart run.uda [-t -1]    continue from a checkpoint (any number of ranks) into a new uda;
                                      -copy / -move: the new uda starts with the old one's outputs
                                      (moved: the old uda is deleted); -nocopy (default): it does not
    pysus --graph deck.ups [--dot f]  print the tasks the deck will run, in order
    pysus -validate deck.ups          check the deck (set-up, grid, task graphs) and exit
    pysus info|extract|plot RUN.uda   inspect a run's output (framework/uda_tools.py)
    pysus --warm deck.ups             compile the deck's numba kernels (set-up + one step, no output)
                                      and the .pyc files of pysus's modules

numba caches compiled kernels next to the source unless NUMBA_CACHE_DIR is set; --cache-dir DIR
sets it for this run (a per-user directory such as ~/.cache/pysus/numba lets one `--warm` in a
batch job serve every rank that follows).
"""
from __future__ import annotations

import argparse
import errno
import os
import shutil
import sys
import traceback
from pathlib import Path

from .archiver import CHECKPOINT_NAME, RESTART_MODES
from .errors import RunStopped

MPI_ENV = ("PMI_RANK", "PMI_SIZE", "PMIX_RANK", "OMPI_COMM_WORLD_SIZE", "MPI_LOCALNRANKS", "HYDI_CONTROL_FD")


def under_mpi() -> bool:
    return any(v in os.environ for v in MPI_ENV)


def make_comm():
    """The MPI communicator when launched by mpiexec, else the serial stand-in (no MPI import)."""
    from .scheduler.comm import Comm
    if under_mpi():
        from mpi4py import MPI
        return Comm(MPI.COMM_WORLD)
    return Comm(None)


def parser():
    p = argparse.ArgumentParser(prog="pysus", description="Uintah-style simulations: MPM, ICE, MPMICE.")
    p.add_argument("deck", nargs="?", help="the .ups input deck")
    p.add_argument("--np", type=int, default=1, help="number of MPI ranks (launches mpiexec)")
    p.add_argument("-restart", "--restart", dest="restart", metavar="UDA", help="continue from a checkpoint")
    for mode in RESTART_MODES:
        p.add_argument(f"-{mode}", dest="restart_mode", action="store_const", const=mode,
                       help={"nocopy": "with -restart: the new uda holds only what the restart writes (default)",
                             "copy": "with -restart: copy the old uda's outputs up to the checkpoint into the new one",
                             "move": "with -restart: move them, and delete the old uda"}[mode])
    p.set_defaults(restart_mode="nocopy")
    p.add_argument("-t", dest="t", type=int, default=-1, help="which checkpoint of -restart (index, default newest)")
    p.add_argument("--graph", action="store_true", help="print the scheduled tasks in order and exit")
    p.add_argument("-validate", "--validate", dest="validate", action="store_true",
                   help="read the deck, set up the grid and compile the task graphs, then exit (as Uintah's sus)")
    p.add_argument("--dot", metavar="FILE", help="with --graph: also write the task graph as DOT")
    p.add_argument("--quiet", "-q", action="store_true", help="no progress display")
    p.add_argument("--filebase", help="override <DataArchiver><filebase>")
    p.add_argument("--max-timesteps", type=int, help="override <Time><max_Timesteps>")
    p.add_argument("--maxTime", "--max-time", dest="max_time", type=float,
                   help="override <Time><maxTime> (e.g. to continue a finished run with -restart)")
    p.add_argument("--timing", action="store_true", help="print time per task at the end")
    p.add_argument("--warm", action="store_true",
                   help="compile the kernels the deck uses (set-up and one step, output thrown away), then exit")
    p.add_argument("--cache-dir", metavar="DIR",
                   help="numba's cache directory for this run (sets NUMBA_CACHE_DIR; default: that variable, "
                        "else next to the source)")
    return p


def relaunch(args, argv):
    """Re-run this command under the mpiexec next to this Python, with --np removed."""
    mpiexec = os.path.join(os.path.dirname(sys.executable), "mpiexec")
    if not os.path.exists(mpiexec):
        mpiexec = shutil.which("mpiexec") or "mpiexec"
    rest, skip = [], False
    for a in argv:
        if skip:
            skip = False
            continue
        if a == "--np":
            skip = True
            continue
        if a.startswith("--np="):
            continue
        rest.append(a)
    cmd = [mpiexec, "-n", str(args.np), sys.executable, "-m", "framework.cli"] + rest
    if sys.stdout.isatty():     # the ranks write into mpiexec's pipe: keep the progress line on
        os.environ.setdefault("PYSUS_PROGRESS", "1")
    os.execv(cmd[0], cmd)


def main(argv=None, comm=None):
    """Run the pysus command line argv (sys.argv's when None: the pysus command itself, whose process
    ends in _end_process once a run has finished); comm: the communicator of the ranks to run on
    (a framework.scheduler.comm.Comm; default MPI's world under mpiexec, else serial)."""
    command_line = argv is None
    argv = sys.argv[1:] if argv is None else argv
    from .uda_tools import COMMANDS
    if argv and argv[0] in COMMANDS:        # pysus info|extract|plot RUN.uda (framework/uda_tools.py)
        from .uda_tools import main as tool_main
        return tool_main(argv)
    args = parser().parse_args(argv)
    args.deck = shipped_deck(args.deck)
    if args.np > 1 and not under_mpi():
        relaunch(args, argv)
    if not args.deck and not args.restart:
        parser().print_usage(sys.stderr)
        print("pysus: error: give a deck (or -restart UDA)", file=sys.stderr)
        return 2
    if args.cache_dir:
        os.environ["NUMBA_CACHE_DIR"] = os.path.abspath(os.path.expanduser(args.cache_dir))
        if "numba" in sys.modules:          # importing framework loaded numba's config: read it again
            sys.modules["numba"].config.reload_config()
    if args.warm:
        return warm(args)
    comm = comm or make_comm()
    from .problemspec import InputError
    from .scheduler.compile import GraphError
    try:
        from .controller import Controller
        ctl = Controller(args.deck, comm, restart=args.restart, restart_index=args.t, quiet=args.quiet,
                         filebase=args.filebase, max_timesteps=args.max_timesteps,
                         max_time=args.max_time, restart_mode=args.restart_mode)
        if args.graph:
            if comm.rank == 0:
                from .graphview import describe, write_dot
                print(describe(ctl))
                if args.dot:
                    write_dot(ctl, args.dot)
            return 0
        if args.validate:
            if comm.rank == 0 and not args.quiet:
                print(f"pysus: {args.deck or args.restart}: valid ({ctl.component_name}, "
                      f"{' x '.join(map(str, ctl.level.ncells))} cells, {len(ctl.step_graph.tasks)} tasks a step)")
            return 0
        ctl.run()
        if comm.rank == 0 and not args.quiet:
            n = len(ctl.step_times)
            print(f"pysus: {n} timesteps to t = {ctl.t:.6g} in {ctl.wall:.2f} s"
                  + (f" on {comm.size} ranks" if comm.size > 1 else "")
                  + (f"; output in {ctl.archiver.dir}" if ctl.archiver else ""))
        if args.timing and comm.rank == 0:
            for name, t, calls in ctl.timing_table():
                counted = f"{calls:7d} calls" if calls else " " * 13      # rows that are not tasks have no count
                print(f"  {name:40s} {t:9.3f} s {counted} {100.0 * t / (ctl.wall or 1.0):5.1f}%")
            total = "total (wall)" if comm.size == 1 else f"total (wall, rank 0 of {comm.size})"
            print(f"  {total:40s} {ctl.wall:9.3f} s")
        if command_line:
            _end_process(0)
        return 0
    except (InputError, FileNotFoundError) as e:
        # every rank reads the same deck and finds the same error: report once, exit together
        if comm.rank == 0:
            print(f"pysus: error: {e}", file=sys.stderr)
        return 2
    except GraphError as e:
        if comm.rank == 0:
            print(f"pysus: task graph error: {e}", file=sys.stderr)
        return 3
    except Exception as e:
        prefix = f"[rank {comm.rank}] " if comm.size > 1 else ""
        if not (_out_of_space(e) or isinstance(e, RunStopped)):     # not bugs: their one line says it all
            msg = traceback.format_exc()
            sys.stderr.write("".join(prefix + line + "\n" for line in msg.rstrip().split("\n")))
        sys.stderr.write(prefix + failure_summary(e, ctl if "ctl" in locals() else None) + "\n")
        return _exit(comm, 1)


def shipped_deck(path):
    """The deck as given, or else the same relative path under pysus's own tree (the wheel
    installs inputs/ beside framework/), so `pysus inputs/examples/quickstart.ups` runs anywhere."""
    if path and not os.path.exists(path) and not os.path.isabs(path):
        shipped = Path(__file__).resolve().parents[1] / path
        if shipped.is_file():
            return str(shipped)
    return path


def warm(args) -> int:
    """Run set-up and one timestep of the deck into a throwaway directory, so that numba compiles
    (and caches) every kernel the deck uses; a batch job runs this once before starting its ranks."""
    import tempfile
    compile_bytecode()
    # a restart compiles what its deck does: warm with the copy of the deck the uda keeps
    deck = args.deck or os.path.join(args.restart, "input.ups")
    with tempfile.TemporaryDirectory(prefix="pysus-warm-") as tmp:
        rc = main(["-q", "--max-timesteps", "1", "--filebase", os.path.join(tmp, "warm.uda"), deck])
    if rc == 0 and not args.quiet:
        print(f"pysus: kernels for {args.deck or args.restart} compiled"
              f" (cache: {os.environ.get('NUMBA_CACHE_DIR') or 'next to the source'})")
    return rc


def compile_bytecode():
    """Write the .pyc files of pysus's own modules (framework/, components/), as `python -m
    compileall` would: every later process (an MPI rank, a test's run) loads them instead of
    compiling each module from its source (0.25-0.4 CPU s a process), also where
    PYTHONDONTWRITEBYTECODE keeps Python from writing them on import. Up-to-date files are kept;
    a tree that cannot be written to is left as it is."""
    import compileall
    root = Path(__file__).resolve().parents[1]
    for package in ("framework", "components"):
        compileall.compile_dir(str(root / package), quiet=2)


def _out_of_space(exc) -> bool:
    """Whether an exception (or one it was raised from) is a full disk or an exhausted quota."""
    while exc is not None:
        if isinstance(exc, OSError) and exc.errno in (errno.ENOSPC, errno.EDQUOT):
            return True
        exc = exc.__cause__ or exc.__context__
    return False


def failure_summary(exc, ctl) -> str:
    """One line saying where the run failed and what is left to restart from."""
    where = ", ".join(w for w in (getattr(exc, "pysus_when", None), getattr(exc, "pysus_where", None)) if w)
    line = f"pysus: the run failed{' at ' + where if where else ''}: {type(exc).__name__}: {exc}"
    arch = getattr(ctl, "archiver", None)
    if arch is not None and getattr(arch, "dir", None):
        cps = sorted(p.name for p in Path(arch.dir).glob("checkpoints/t*") if CHECKPOINT_NAME.match(p.name)) \
            if Path(arch.dir).is_dir() else []
        line += (f"; last checkpoint {arch.dir}/checkpoints/{cps[-1]} (pysus -restart {arch.dir})" if cps
                 else f"; output so far in {arch.dir} (no checkpoint)")
    return line


def _end_process(code):
    """End the pysus command's process after its run: the atexit handlers run, MPI is finalized
    and the standard streams are flushed, but the interpreter's teardown, which
    frees every module and numba's and LLVM's objects one at a time, is skipped (0.15 CPU s, a
    tenth of a small deck's whole run: the 12-cell pressurized cylinder). Every file a run
    writes is closed when the run returns (the archiver writes each in a `with`). MPI is
    finalized here: mpi4py does it in the interpreter's teardown, and a rank that leaves without
    it lets mpiexec end the ranks still running (tests/framework/test_entry_points.py); a rank
    then leaves through the C library's exit, whose handlers MPICH's process manager needs."""
    import atexit
    atexit._run_exitfuncs()
    mpi = sys.modules.get("mpi4py.MPI")
    under_mpi = mpi is not None and mpi.Is_initialized()
    if under_mpi and not mpi.Is_finalized():
        mpi.Finalize()
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):           # a closed pipe: nothing more can reach it
            pass
    if under_mpi:
        # the C library's exit: MPICH's process manager counts a rank that leaves through
        # _exit after MPI_Finalize as failed now and then (mpiexec then kills the job: exit
        # code 9), one that leaves through exit never (tests/framework/test_entry_points.py)
        import ctypes
        ctypes.CDLL(None).exit(code)
    os._exit(code)


def _exit(comm, code):
    """End every rank promptly: one rank's error aborts the whole job, never a hang. The pause
    lets mpiexec forward the last lines (the failure summary) before the abort ends its
    forwarding: without it a loaded machine lost the summary now and then."""
    sys.stderr.flush()
    if comm.size > 1:
        import time
        time.sleep(0.3)
        comm.mpi.Abort(code)
    return code


if __name__ == "__main__":
    sys.exit(main())
