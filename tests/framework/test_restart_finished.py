"""Restarting a finished run: one clean line saying so, and --maxTime to continue it; the
continued run matches the uninterrupted one (up to the step cut short at the old maxTime)."""
import os
from pathlib import Path

import numpy as np

from framework.archiver import DataArchive
from tests.conftest import pysus_ranks

ROOT = Path(__file__).resolve().parents[2]


def _pysus(cwd, *args):
    """`pysus -q ARGS` run from the directory cwd, in this process (tests/conftest.py pysus_ranks:
    the command's own main, without a Python start-up and loading of the kernels a run)."""
    here = os.getcwd()
    os.chdir(cwd)
    try:
        return pysus_ranks(*args)
    finally:
        os.chdir(here)


def test_restart_of_finished_run_says_so_and_maxtime_continues_it(tmp_path):
    deck = (ROOT / "inputs/examples/quickstart.ups").read_text(encoding="latin-1")
    deck = deck.replace('<checkpoint interval="0.25" cycle="2"/>', '<checkpoint interval="0.05" cycle="2"/>')
    (tmp_path / "short.ups").write_text(deck.replace("0.5      </maxTime>", "0.05 </maxTime>")
                                        .replace("quickstart.uda", "short.uda"), encoding="latin-1")
    (tmp_path / "long.ups").write_text(deck.replace("0.5      </maxTime>", "0.1 </maxTime>")
                                       .replace("quickstart.uda", "long.uda"), encoding="latin-1")
    assert _pysus(tmp_path, "short.ups").returncode == 0
    r = _pysus(tmp_path, "-restart", "short.uda")
    assert r.returncode == 2
    assert r.stderr.count("\n") == 1 and "already reached maxTime 0.05 s" in r.stderr, r.stderr
    assert not (tmp_path / "short.uda.000").exists()          # no empty uda written
    r = _pysus(tmp_path, "-restart", "short.uda", "--maxTime", "0.1")
    assert r.returncode == 0, r.stderr
    assert _pysus(tmp_path, "long.ups").returncode == 0
    cont, _ = DataArchive(tmp_path / "short.uda.000").read("temp_CC", 0, -1)
    whole, _ = DataArchive(tmp_path / "long.uda").read("temp_CC", 0, -1)
    assert DataArchive(tmp_path / "short.uda.000").times[-1] == DataArchive(tmp_path / "long.uda").times[-1]
    # not bitwise: the short run's last step was cut to end at 0.05 exactly, the long run's was not
    assert np.abs(cont - whole).max() < 1e-3 * np.abs(whole).max()
    r = _pysus(tmp_path, "-restart", "short.uda", "--maxTime", "nan")
    assert r.returncode == 2 and "--maxTime" in r.stderr and "Traceback" not in r.stderr


def test_restart_writes_beside_the_uda_it_continues(tmp_path):
    """A run made with --filebase and restarted from another directory continues in
    runs/mine.uda.000 (then .001), not in the deck's filebase under the current directory."""
    deck = (ROOT / "inputs/examples/quickstart.ups").read_text(encoding="latin-1")
    deck = (deck.replace("[64, 64, 1]", "[16, 16, 1]").replace("0.5      </maxTime>", "0.1 </maxTime>")
            .replace('<checkpoint interval="0.25" cycle="2"/>', '<checkpoint interval="0.05" cycle="2"/>'))
    (tmp_path / "runs").mkdir()
    (tmp_path / "elsewhere").mkdir()
    (tmp_path / "d.ups").write_text(deck, encoding="latin-1")
    assert _pysus(tmp_path, "d.ups", "--filebase", "runs/mine.uda").returncode == 0
    r = _pysus(tmp_path / "elsewhere", "-restart", "../runs/mine.uda", "-t", "0", "-copy")
    assert r.returncode == 0, r.stderr
    r = _pysus(tmp_path / "elsewhere", "-restart", "../runs/mine.uda.000", "--maxTime", "0.15")
    assert r.returncode == 0, r.stderr
    assert sorted(p.name for p in (tmp_path / "runs").iterdir()) == ["mine.uda", "mine.uda.000", "mine.uda.001"]
    assert list((tmp_path / "elsewhere").iterdir()) == [] and not (tmp_path / "quickstart.uda").exists()
    assert DataArchive(tmp_path / "runs/mine.uda.001").times[-1] == 0.15
    r = _pysus(tmp_path, "-restart", "runs/none.uda")
    assert r.returncode == 2 and r.stderr == "pysus: error: runs/none.uda: no such .uda directory\n"
