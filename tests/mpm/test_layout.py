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


@pytest.mark.parametrize("deck,layouts,tags", [
    ("thick_cylinder.ups", ("[1,1,1]", "[2,2,1]"), {"resolution": "[22,22,1]", "maxTime": "2e-4"}),
    ("friction_block.ups", ("[1,1,1]", "[2,1,1]"), {"maxTime": "0.05"}),
    ("rigid_piston.ups", ("[1,1,1]", "[3,1,1]"), {"maxTime": "0.2"}),
    ("sod_fluid_points.ups", ("[1,1,1]", "[2,1,1]"), {"maxTime": "0.03"}),
])
def test_features_patches_bitwise(tmp_path, deck, layouts, tags):
    """Pressure BCs, friction and rigid contact, fluid points: the patch layout changes
    no bit of the particles. (The fluid's artificial viscosity scales with max |div v| of
    a material on one patch; in the Sod deck each gas stays on one patch, so it holds.)"""
    from .helpers import MPM_INPUTS
    out = []
    for layout in layouts:
        text = deck_text(MPM_INPUTS / deck, patches=layout, **tags)
        ctl, da = run(text, tmp_path, name=f"{deck}{layout[1]}")
        out.append([da.particles(m, -1) for m in range(len(ctl.component.materials))])
    for a, b in zip(*out):
        oa, ob = (np.lexsort((p["p.x"][:, 2], p["p.x"][:, 1], p["p.x"][:, 0])) for p in (a, b))
        for key in ("p.x", "p.velocity", "p.stress"):
            if key not in a:
                continue
            xa, xb = a[key][oa], b[key][ob]
            assert xa.shape == xb.shape and len(xa) > 10
            assert np.array_equal(xa, xb), (key, np.abs(xa - xb).max())
