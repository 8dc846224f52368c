"""ICE decks on 2 and 3 ranks give bitwise the one-rank answer.

Ghost cells are exact copies and every sum in a cell update has a fixed order, so the
patch layout and rank count do not change the arithmetic.
"""
import numpy as np
import pytest

from framework.archiver import DataArchive
from tests.conftest import ROOT, UINTAH_INPUTS, pysus_ranks

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


def prepared(tmp_path, case):
    src, repl, labels = CASES[case]
    text = src.read_text()
    for a, b in repl:
        assert a in text, (case, a)
        text = text.replace(a, b)
    path = tmp_path / f"{case}.ups"
    path.write_text(text)
    return path, labels


@pytest.mark.parametrize("case", sorted(CASES))
def test_ice_ranks_equal_one_rank(tmp_path, case):
    path, labels = prepared(tmp_path, case)
    runs = {}
    for n in (1, 2, 3):
        uda = tmp_path / f"{case}_{n}.uda"
        r = pysus_ranks(path, "--filebase", uda, np_=n)
        assert r.returncode == 0, r.stderr[-2000:]
        runs[n] = DataArchive(uda)
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
