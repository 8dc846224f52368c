"""Uintah's slip exchange model (<exchange_properties><Model type="slip">) against sus, one step.

Deck: uintah_reference/slipExch_small.ups (Uintah's advectSlipExch.ups with useSlipCoeffs true,
made small, a copper cube at rest at 400 K in air at 10 m/s; its header says why).
data/sus_slipExch_small.npz is sus's output on that deck, one rank (sus slipExch_small.ups),
read with framework.uintah_uda.UintahArchive after the step: press_CC, and of the air
(material 1) vel_CC, temp_CC, vol_frac_CC, meanFreePath, vel_CCTransposed, and of the copper
surfaceNorm; noslip_*: sus on the same deck with useSlipCoeffs false; imp_*: sus on the deck
with the original's <ImplicitSolver> and <Solver type="CGSolver"/> (test_slip_exchange_implicit).

The model's own quantities equal sus's: surfaceNorm exactly, meanFreePath to round-off,
vel_CCTransposed (Q u before the exchange) to 4.5e-13 of its largest value. In the cells that
are mostly air, where the slip acts, the air's velocity after the step is sus's to 2.5e-9 of its
largest value, pressure 3e-16; there sus's slip changes the velocity by up to 13 m/s from the
no-slip run. The gas starts from its geometry as sus's (docs/MPMICE.md, "Gas start"), so the
copper's volume fraction in a surface cell, which K_slip divides by, is sus's (0.12; the
particles' smeared start gave 0.14 and velocities 1.45e-3 off). The air's temperature is sus's
to 1.9e-4 (0.077 K of a 1 K rise in the surface cells): what is left is in the slip's heat
exchange, not yet looked into (with the smeared start it was 7e-5, errors partly cancelling).
"""
import pathlib

import numpy as np
import pytest

from tests.conftest import run_deck

HERE = pathlib.Path(__file__).parent
DECK = HERE / "uintah_reference" / "slipExch_small.ups"


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    from framework.archiver import DataArchive
    ctl = run_deck(DECK.read_text(encoding="latin-1"), tmp_path_factory.mktemp("slip"), "slip")
    return DataArchive(ctl.archiver.dir), np.load(HERE / "data" / "sus_slipExch_small.npz")


def test_slip_model_fields_as_uintah(runs):
    """Surface normals, mean free path and the rotated velocity are sus's."""
    da, sus = runs
    assert np.array_equal(da.read("surfaceNorm", 0, 1)[0], sus["surfaceNorm_0"])
    assert np.allclose(da.read("meanFreePath", 1, 1)[0], sus["meanFreePath_1"], rtol=1e-13, atol=0)
    got, want = da.read("vel_CCTransposed", 1, 1)[0], sus["vel_CCTransposed_1"]
    assert np.abs(want).max() > 10.0
    assert np.abs(got - want).max() < 1e-11 * np.abs(want).max()


def test_slip_exchange_as_uintah(runs):
    """The air after the step in the cells that are mostly air matches sus's, and what the slip
    changes there (up to 13 m/s against sus's no-slip run) is reproduced."""
    da, sus = runs
    assert np.diff(da.times)[0] == pytest.approx(sus["times"][0], rel=1e-12)
    air = sus["vol_frac_CC_1"] > 0.5
    vel, want = da.read("vel_CC", 1, 1)[0], sus["vel_CC_1"]
    scale = np.abs(want).max()
    assert np.abs(vel - want)[air].max() < 1e-8 * scale
    slip_change = np.abs(want - sus["noslip_vel_CC_1"])[air].max()
    assert slip_change > 10.0
    temp = da.read("temp_CC", 1, 1)[0]
    assert np.abs(temp - sus["temp_CC_1"])[air].max() < 2.5e-4 * sus["temp_CC_1"].max()   # module doc
    assert np.abs(temp - sus["noslip_temp_CC_1"])[air].max() > 50.0     # the slip's temperature jump
    press = da.read("press_CC", 0, 1)[0]
    assert np.abs(press - sus["press_CC_0"])[air].max() < 1e-12 * sus["press_CC_0"].max()


IMPLICIT = """        <ClampSpecificVolume>false</ClampSpecificVolume>
        <ImplicitSolver>
           <max_outer_iterations> 20 </max_outer_iterations>
           <outer_iteration_tolerance> 1e-8 </outer_iteration_tolerance>
           <iters_before_timestep_restart> 15 </iters_before_timestep_restart>
           <Parameters variable="implicitPressure">
             <tolerance> 1.e-10 </tolerance> <solver> cg </solver> <preconditioner> pfmg </preconditioner>
             <maxiterations> 500 </maxiterations>
           </Parameters>
        </ImplicitSolver>"""


def test_slip_exchange_implicit_as_uintah(tmp_path):
    """The same step with the semi-implicit pressure (the original deck's), the slip's K of
    each cell in eq. P's face terms and in the outer iteration's face exchange; sus with
    <Solver type="CGSolver"/> (imp_* in the data). Measured in the air cells: vel_CC 2.7e-9,
    temp_CC 1.8e-4 (the slip's heat exchange, module doc), press_CC 8e-11 of their maxima."""
    from framework.archiver import DataArchive
    sus = np.load(HERE / "data" / "sus_slipExch_small.npz")
    text = DECK.read_text(encoding="latin-1").replace("<ClampSpecificVolume>false</ClampSpecificVolume>",
                                                      IMPLICIT, 1)
    da = DataArchive(run_deck(text, tmp_path, "implicit").archiver.dir)
    assert np.diff(da.times)[0] == pytest.approx(sus["imp_times"][0], rel=1e-12)
    air = sus["imp_vol_frac_CC_1"] > 0.5
    for label, m, tol in (("vel_CC", 1, 1e-8), ("temp_CC", 1, 2.5e-4), ("press_CC", 0, 1e-9)):
        got, want = da.read(label, m, 1)[0], sus[f"imp_{label}_{m}"]
        assert np.abs(got - want)[air].max() < tol * np.abs(want).max(), label
    assert np.abs(da.read("vel_CC", 1, 1)[0] - sus["noslip_vel_CC_1"])[air].max() > 10.0


@pytest.mark.parametrize("old, new, message", [
    ("<solidMatlIndex>  0  </solidMatlIndex>", "<solidMatlIndex> 1 </solidMatlIndex>", "not an MPM material"),
    ("<fluidMatlIndex>  1  </fluidMatlIndex>", "<fluidMatlIndex> 2 </fluidMatlIndex>", "not an ICE material"),
    ('<Model type="slip">', '<Model type="scalar">', "slip"),
])
def test_bad_slip_input_refused(tmp_path, old, new, message):
    from framework.problemspec import InputError
    text = DECK.read_text(encoding="latin-1")
    assert old in text
    with pytest.raises(InputError, match=message):
        run_deck(text.replace(old, new, 1), tmp_path)
