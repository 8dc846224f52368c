"""<conserveTotalEnergy> with two ideal gases and stiff exchange (the closed 2D blast of
test_conservation.py, 4 patches, 20 steps) on 2 and 3 ranks: bitwise the one-rank answer,
the saved total energy equal to round-off (a sum over ranks)."""
import numpy as np

from framework.archiver import DataArchive
from tests.conftest import pysus_runs

from .test_conservation import deck, totals

LABELS = ("rho_CC", "temp_CC", "vel_CC", "sp_vol_CC")


def test_two_gases_conserving_energy_ranks_equal_one_rank(tmp_path):
    path = tmp_path / "blast2.ups"
    path.write_text(deck(2, 1e10, steps=20, every=20, saves=LABELS))
    out = pysus_runs([((path, "--filebase", tmp_path / f"r{n}.uda"), n) for n in (1, 2, 3)], tmp_path)
    runs = {}
    for n, (rc, err) in zip((1, 2, 3), out):
        assert rc == 0, err[-2000:]
        runs[n] = DataArchive(tmp_path / f"r{n}.uda")
    for n in (2, 3):
        for lab in LABELS:
            for m in (0, 1):
                assert np.array_equal(runs[1].read(lab, m, -1)[0], runs[n].read(lab, m, -1)[0]), (n, lab, m)
        # the reductions are sums of per-rank partial sums: equal to round-off, not bitwise
        np.testing.assert_allclose(totals(runs[n])[1], totals(runs[1])[1], rtol=1e-14)
