"""scripts/batch/slurm_example.sh as sbatch runs it, with Slurm stood in for: a copy of the
script started from another directory with SLURM_SUBMIT_DIR set, and an `srun` that runs its
command once. A deck runs into the submit directory; a finished uda given alone (no deck)
continues with the options after it, beside the old uda; a missing input is one line."""
import os
import shutil
import stat
import subprocess
import sys
from pathlib import Path

from framework.archiver import DataArchive
from tests.framework import decks

ROOT = Path(__file__).resolve().parents[2]


def _tool(path, text):
    path.write_text(text)
    path.chmod(path.stat().st_mode | stat.S_IXUSR)


def test_slurm_example_runs_a_deck_then_restarts_without_it(tmp_path):
    bin_, sub, spool = tmp_path / "bin", tmp_path / "sub", tmp_path / "spool"
    for d in (bin_, sub, spool):
        d.mkdir()
    _tool(bin_ / "pysus", f'#!/bin/bash\nPYTHONPATH={ROOT} exec {sys.executable} -m framework "$@"\n')
    _tool(bin_ / "srun", '#!/bin/bash\necho "srun $*" >> "$SLURM_SUBMIT_DIR/srun.log"\nexec "$@"\n')
    shutil.copy(ROOT / "scripts/batch/slurm_example.sh", spool / "job.sh")   # sbatch runs a copy
    (sub / "heat.ups").write_text(decks.heat(n=8, maxTime=0.02, checkpoint='<checkpoint interval="0.01" cycle="2"/>'))
    env = dict(os.environ, PATH=f"{bin_}:{os.environ['PATH']}", SLURM_SUBMIT_DIR=str(sub),
               XDG_CACHE_HOME=str(tmp_path / "cache"))   # the per-user cache the job compiles into
    env.pop("PYSUS", None)
    env.pop("NUMBA_CACHE_DIR", None)

    def job(*args):
        return subprocess.run(["bash", str(spool / "job.sh"), *args], cwd=spool, env=env,
                              capture_output=True, text=True, timeout=600)

    r = job("heat.ups")
    assert r.returncode == 0, r.stderr
    first = DataArchive(sub / "heat.uda")
    assert first.times[-1] == 0.02 and first.index["checkpoints"]
    assert list((tmp_path / "cache/pysus/numba").glob("*/*.nbc"))      # the kernels were cached there
    r = job("heat.uda", "--maxTime", "0.04", "-copy")
    assert r.returncode == 0, r.stderr
    whole = DataArchive(sub / "heat.uda.000")
    assert whole.times[0] == 0.0 and whole.times[-1] == 0.04      # one history, old outputs copied
    assert sorted(os.listdir(spool)) == ["job.sh"]                 # nothing written where sbatch ran it
    assert (sub / "srun.log").read_text().splitlines() == [
        "srun pysus -q heat.ups", "srun pysus -q -restart heat.uda --maxTime 0.04 -copy"]
    r = job("none.uda")
    assert r.returncode == 2 and r.stderr.strip() == f"slurm_example.sh: no none.uda in {sub}"
