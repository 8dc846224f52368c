"""A burning run restarted from a checkpoint gives the answer of the run that never stopped."""
import numpy as np

from framework.archiver import DataArchive
from tests.conftest import pysus, pysus_ranks

from .test_simple_burn import DECK


def test_restart_mid_burn_equals_straight_run(tmp_path):
    text = open(DECK).read().replace("<outputTimestepInterval> 20 </outputTimestepInterval>",
                                     '<outputTimestepInterval> 20 </outputTimestepInterval>'
                                     '<checkpoint timestepInterval="80" cycle="2"/>')
    deck = tmp_path / "burn.ups"
    deck.write_text(text)
    straight = tmp_path / "straight.uda"
    r = pysus_ranks(deck, "--filebase", straight)
    assert r.returncode == 0, r.stderr[-2000:]
    r = pysus("-restart", straight, "-t", 0, "--filebase", tmp_path / "again.uda")
    assert r.returncode == 0, r.stderr[-2000:]
    a, b = DataArchive(straight), DataArchive(tmp_path / "again.uda")
    assert a.times[-1] == b.times[-1]
    for lab, m in (("press_CC", 0), ("rho_CC", 1), ("temp_CC", 1)):
        assert np.array_equal(a.read(lab, m, -1)[0], b.read(lab, m, -1)[0]), lab
    pa, pb = a.particles(0, -1), b.particles(0, -1)
    assert len(pa["p.mass"]) == 8 and np.array_equal(pa["p.mass"], pb["p.mass"])
