"""Uintah's MPMICE advect3mat.ups (R_Tester MPMICE.py, test advect3Mat) for 2 steps, against sus.

Deck: uintah_reference/advect3mat.ups, Uintah's file as it is (12^3 cells, one patch): two
comp_neo_hook_plastic blocks (PISTON, bulk modulus 1.02e9, and HMX BLOCK, 1.02e7; materials 0
and 1) and an ideal gas (material 2) all moving at 0.01 in x, y and z, exchange coefficients
1e10. The run sets <max_Timesteps> 2 and output every step, as sus's reference run did.

data/sus_advect3mat_2steps.npz is sus's output on that deck (one rank, read with
framework.uintah_uda.UintahArchive): the output times and, after steps 1 and 2, press_CC and
every material's rho_CC and temp_CC over the whole level. The expected values are sus's.

Measured: the times (delT 1e-5 then 0.0154449) exactly. After step 1 press_CC to 2.7e-10 of
its largest value, rho_CC to 1e-22 of it, temp_CC to 4e-16. After step 2 rho_CC to 2.1e-16 and
the gas's temp_CC to 8e-16; press_CC to 1.07e-7, in the PISTON's cells (cell (7, 6, 7)): its
bulk modulus is 1e9 times the pressure, so a round-off difference of 2e-16 in its density
shows as 1e-7 in its pressure (in the HMX block's cells, bulk modulus 1e7, 2.2e-9; in the
gas's, 4e-16). The solids' temp_CC to 4e-13 where they are (volume fraction > 1e-3) and to
1.04e-10 of 300 K (3.1e-8 K) in the cells they do not occupy.
"""
import pathlib

import numpy as np
import pytest

from tests.conftest import run_deck

HERE = pathlib.Path(__file__).parent
DECK = HERE / "uintah_reference" / "advect3mat.ups"


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    from framework.archiver import DataArchive
    text = DECK.read_text(encoding="iso-8859-1")
    text = text.replace("<max_Timesteps>     100         </max_Timesteps>",
                        "<max_Timesteps>2</max_Timesteps>")
    text = text.replace("<outputTimestepInterval>10</outputTimestepInterval>",
                        "<outputTimestepInterval>1</outputTimestepInterval>")
    ctl = run_deck(text, tmp_path_factory.mktemp("advect3mat"), "advect3mat")
    return DataArchive(ctl.archiver.dir), np.load(HERE / "data" / "sus_advect3mat_2steps.npz")


def relative_difference(got, want):
    """Largest |got - want| over the level, as a fraction of sus's largest |value|."""
    return np.abs(got - want).max() / np.abs(want).max()


def test_advect3mat_times_as_uintah(runs):
    da, sus = runs
    assert np.array_equal(da.times[1:], sus["times"])


# (label, material, step): tolerance, a few times the measured difference (module doc)
TOLERANCES = {("press_CC", 0, 1): 1e-9, ("press_CC", 0, 2): 3e-7}
for _m in (0, 1, 2):
    TOLERANCES[("rho_CC", _m, 1)] = TOLERANCES[("rho_CC", _m, 2)] = 1e-15
    TOLERANCES[("temp_CC", _m, 1)] = 1e-15
    TOLERANCES[("temp_CC", _m, 2)] = 3e-10 if _m < 2 else 3e-15


@pytest.mark.parametrize("label,material,step", sorted(TOLERANCES))
def test_advect3mat_fields_as_uintah(runs, label, material, step):
    da, sus = runs
    key = f"press_CC@{step}" if label == "press_CC" else f"{label}_{material}@{step}"
    got = da.read(label, material, step)[0]
    assert got.shape == sus[key].shape == (12, 12, 12)
    assert relative_difference(got, sus[key]) < TOLERANCES[(label, material, step)]


def test_advect3mat_solid_temperature_where_occupied(runs):
    """Where the blocks are (volume fraction > 1e-3 after step 2, 144 cells each) their
    temperature is sus's to round-off; the 1e-10 of the field test is in cells they do not occupy."""
    da, sus = runs
    for m in (0, 1):
        where = da.read("vol_frac_CC", m, 2)[0] > 1e-3
        assert where.sum() == 144
        assert np.abs(da.read("temp_CC", m, 2)[0] - sus[f"temp_CC_{m}@2"])[where].max() < 2e-12
