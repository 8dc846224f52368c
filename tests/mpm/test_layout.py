"""1 patch and 4 patches give bitwise equal particles (sums ordered by particle ID)."""
import numpy as np
import pytest

from tests.conftest import UINTAH_INPUTS

from .helpers import deck_text, run


@pytest.mark.parametrize("interp", ["linear", "gimp"])
def test_patches_bitwise(tmp_path, interp):
    out = []
    for layout in ("[1,1,1]", "[2,2,1]"):
        text = deck_text(UINTAH_INPUTS / "MPM" / "disks_sulsky.ups", maxTime=1.3, patches=layout,
                         interpolator=interp, extraCells="[1,1,0]")
        ctl, da = run(text, tmp_path, name=f"{interp}{layout[1]}")
        p = da.particles(0, -1)
        x = p["p.x"]
        out.append((p, np.lexsort((x[:, 2], x[:, 1], x[:, 0]))))   # same order if bitwise equal
    (a, oa), (b, ob) = out
    for key in ("p.x", "p.velocity", "p.stress"):
        xa, xb = a[key][oa], b[key][ob]
        assert xa.shape == xb.shape and xa.shape[0] > 400
        assert np.array_equal(xa, xb), key
