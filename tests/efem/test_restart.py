"""Restarting from a checkpoint continues the run as if it had never stopped: a block falling
into the pool, checkpointed at step 10, restarted to step 20 on 2 ranks, equals the straight
20-step run bit for bit."""
import numpy as np

from framework.archiver import DataArchive
from tests.conftest import pysus, pysus_ranks

from .decks import deck
from .test_conservation import BLOCK
from .test_mpi import FIELDS


def test_restart_equals_straight_run(tmp_path):
    path = tmp_path / "fall.ups"
    path.write_text(deck(res=(20, 20), patches=(2, 2), steps=20, block=BLOCK, every=10, checkpoint=(10, 2)))
    r = pysus_ranks(path, "--filebase", tmp_path / "a.uda")
    assert r.returncode == 0, r.stderr[-2000:]
    r = pysus("-restart", tmp_path / "a.uda", "-t", "0", "--filebase", tmp_path / "b.uda", np_=2)
    assert r.returncode == 0, r.stderr[-2000:]
    a, b = DataArchive(tmp_path / "a.uda"), DataArchive(tmp_path / "b.uda")
    assert a.times[-1] == b.times[-1]
    for lab, m in FIELDS:
        assert np.array_equal(a.read(lab, m, -1)[0], b.read(lab, m, -1)[0]), (lab, m)
