"""ICE decks on 2 and 3 ranks give bitwise the one-rank answer.

Ghost cells are exact copies and every sum in a cell update has a fixed order, so the
patch layout and rank count do not change the arithmetic.
"""
import numpy as np
import pytest

from framework.archiver import DataArchive
from tests.conftest import ROOT, UINTAH_INPUTS, edited_deck, run_cases

CASES = {
    # deck, replacements making it small and giving it enough patches for 3 ranks, labels.
    # riemann_sm: cells as deep as they are long (its 1 mm depth set delT), 146 steps instead of
    # 816; its rarefaction and shock still cross the patch boundaries at x = 1/3 and 2/3
    "riemann_sm": (UINTAH_INPUTS / "ICE" / "riemann_sm.ups",
                   [("[1,1,1]    </patches>", "[3,1,1]    </patches>"), ("[250,1,1]", "[102,1,1]"),
                    ("[1,0.001,0.001]", "[1,0.01,0.01]")],
                   ["rho_CC", "press_CC", "vel_CC"]),
    "hotBlob2mat": (UINTAH_INPUTS / "ICE" / "hotBlob2mat.ups",
                    [("[1,1,1]         </patches>", "[2,2,1]         </patches>"),
                     ("0.001         </maxTime>", "0.0002         </maxTime>")], ["rho_CC", "temp_CC", "vel_CC"]),
    "explosion2D": (ROOT / "inputs" / "ICE" / "explosion2D.ups",
                    [("[128,128,1]", "[36,36,1]"), ("0.25 </maxTime>", "0.05 </maxTime>")],
                    ["rho_CC", "press_CC", "vel_CC"]),
}


@pytest.fixture(scope="module")
def launched(tmp_path_factory):
    """Every case's deck on 1 rank in this process, then on 2 and 3 ranks in one mpiexec launch:
    the directory of the udas and each run's (return code, stderr)."""
    d = tmp_path_factory.mktemp("ice_ranks")
    for case, (src, repl, _) in CASES.items():
        edited_deck(src, repl, d / f"{case}.ups")
    return d, run_cases(d, sorted(CASES), (1, 2, 3))


@pytest.mark.parametrize("case", sorted(CASES))
def test_ice_ranks_equal_one_rank(launched, case):
    d, out = launched
    labels = CASES[case][2]
    for n in (1, 2, 3):
        rc, err = out[case, n]
        assert rc == 0, err[-2000:]
    runs = {n: DataArchive(d / f"{case}_{n}.uda") for n in (1, 2, 3)}
    nm = len(runs[1].materials)
    compared = 0
    for n in (2, 3):
        assert np.array_equal(runs[1].times, runs[n].times)
        for lab in labels:
            for m in range(nm):
                try:
                    a = runs[1].read(lab, m, -1)[0]
                except KeyError:
                    continue
                assert np.array_equal(a, runs[n].read(lab, m, -1)[0]), (case, n, lab, m)
                compared += 1
    assert compared >= 2 * len(labels)
