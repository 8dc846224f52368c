"""Uintah's MPMICE regression deck TRWnoz (air through a copper nozzle read from a tri file),
three steps against sus.

Deck: uintah_reference/TRWnoz.ups (the R_Tester deck with 3 steps, every step saved, the air's
density made consistent with its pressure; its header says why). data/sus_TRWnoz.npz is sus's
output on that deck, one rank, made with
    sus TRWnoz.ups   (in a folder holding the deck and trwnozzlentop3_01mesh.pts/.tri)
and read with framework.uintah_uda.UintahArchive: the time after each step (timestep.xml), and
press_equil_CC, vol_frac_CC of the copper (material 0), temp_CC and sp_vol_src_CC of the air
(material 1) over the interior cells after steps 1 and 3.

The gas starts from its geometry as sus's (docs/MPMICE.md, "Gas start"): after step 1
vol_frac_CC equals sus's everywhere to 7e-16, press_equil_CC to 3.9e-10 of its maximum; after 3
steps the nozzle's mixed cells are 2 % off in pressure (peak 6.97e5 Pa, sus 7.11e5; the
particles' smeared start gave 4.8e5) and 4e-3 in volume fraction. Away from the copper (cells whose
neighbours hold none) the fields equal sus's to round-off: measured press_equil_CC, temp_CC 1e-16
of their maxima, sp_vol_src_CC 1e-18; the steps 3.4e-6.
"""
import pathlib

import numpy as np
import pytest

from tests.conftest import run_deck

HERE = pathlib.Path(__file__).parent
DECK = HERE / "uintah_reference" / "TRWnoz.ups"
MESH = HERE / "uintah_reference" / "trwnozzlentop3_01mesh"


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    from framework.archiver import DataArchive
    text = DECK.read_text(encoding="latin-1").replace("<name>trwnozzlentop3_01mesh<", f"<name>{MESH}<")
    ctl = run_deck(text, tmp_path_factory.mktemp("trwnoz"), "trwnoz")
    return DataArchive(ctl.archiver.dir), np.load(HERE / "data" / "sus_TRWnoz.npz")


def _away_from_solid(vol_frac_solid):
    """Cells with no copper in themselves or their four in-plane neighbours."""
    solid = vol_frac_solid > 1e-10
    near = solid.copy()
    near[1:] |= solid[:-1]
    near[:-1] |= solid[1:]
    near[:, 1:] |= solid[:, :-1]
    near[:, :-1] |= solid[:, 1:]
    return ~near


def test_trwnoz_steps_as_uintah(runs):
    """delT of the three steps as sus's (the first is delt_init; measured 3.4e-6 on the third)."""
    da, sus = runs
    assert np.allclose(da.times[1:], sus["times"], rtol=1e-5, atol=0)
    assert np.diff(da.times)[1] == pytest.approx(np.diff(sus["times"])[0], rel=1e-6)


@pytest.mark.parametrize("step", [1, 3])
def test_trwnoz_fields_away_from_nozzle_as_uintah(runs, step):
    """press_equil_CC, temp_CC and sp_vol_src_CC (Uintah's specific volume source of eq. 40)
    equal sus's to round-off in the cells next to no copper; the nozzle's cells differ (module
    docstring) but stay in sus's ranges' order."""
    da, sus = runs
    away = _away_from_solid(sus[f"vol_frac_CC_step{step}"])
    assert away.sum() > 800
    for label, m in (("press_equil_CC", 0), ("temp_CC", 1), ("sp_vol_src_CC", 1)):
        got, want = da.read(label, m, step)[0][:, :, 0], sus[f"{label}_step{step}"]
        scale = np.abs(want).max()
        assert np.allclose(got[away], want[away], rtol=0, atol=1e-12 * scale), label
    press, temp = da.read("press_equil_CC", 0, step)[0], da.read("temp_CC", 1, step)[0]
    assert temp.min() == pytest.approx(300.0) and temp.max() > 300.0
    if step == 3:
        assert 4e5 < press.max() < sus["press_equil_CC_step3"].max()
        assert sus["temp_CC_step3"].max() == pytest.approx(temp.max(), rel=1e-3)
