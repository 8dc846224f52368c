"""A block falling into the pool (4 patches, 30 steps) on 1, 2 and 3 ranks: every saved field
bit for bit the one-rank answer (the pressure solver's sums are taken in patch order)."""
import numpy as np

from framework.archiver import DataArchive
from tests.conftest import pysus_runs

from .decks import deck
from .test_conservation import BLOCK

FIELDS = (("vol_frac_CC", 0), ("vol_frac_CC", 1), ("g.velocity", 0), ("press_CC", 0), ("stress_CC", 0))


def test_falling_block_ranks_equal_one_rank(tmp_path):
    path = tmp_path / "fall.ups"
    path.write_text(deck(res=(20, 20), patches=(2, 2), steps=30, block=BLOCK))
    out = pysus_runs([((path, "--filebase", tmp_path / f"r{n}.uda"), n) for n in (1, 2, 3)], tmp_path)
    runs = {}
    for n, (rc, err) in zip((1, 2, 3), out):
        assert rc == 0, err[-2000:]
        runs[n] = DataArchive(tmp_path / f"r{n}.uda")
    for n in (2, 3):
        assert runs[n].times[-1] == runs[1].times[-1]
        for lab, m in FIELDS:
            assert np.array_equal(runs[1].read(lab, m, -1)[0], runs[n].read(lab, m, -1)[0]), (n, lab, m)
