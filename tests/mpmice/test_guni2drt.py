"""Uintah's MPMICE regression deck guni2dRT (uintah_reference/guni2dRT.ups): a steel ring around a
reactant burning by Simple_Burn into its product gas, against sus, 3 steps.

data/sus_guni2dRT.npz is sus's output on that deck, one rank (sus guni2dRT.ups), read with
framework.uintah_uda.UintahArchive: press_CC, press_equil_CC, the product's modelMass_src after
steps 1-3, every material's vol_frac_CC after steps 1 and 2, the reactant's p.mass summed per
cell after steps 1-3, and the steel's p.x and p.stress after step 2.

Step 1 is sus's to round-off: the burned mass (Uintah's surface area V / (sum_d |n_d| dx_d)
max_d |n_d|^(-1/3)), the volume it makes (burned * v_solid) and the pressure it raises
(Uintah's delP_MassX, sum_m m_src,m v_m / V / sum_m theta_m kappa_m, with each material's
equilibrated v_m): 8.2e6 Pa where sus has 8.2e6. The particles lose the burned mass as Uintah's
(massBurnFraction at the nodes, interpolated to the particles): the reactant's mass per cell after
steps 1, 2, 3 is sus's to 3.8e-16, 5.1e-9, 5.6e-7 (1.4e-7 at step 2 when each particle in a cell
gave the same fraction). Each solid answers the equilibration with its own model's EOS, as
Uintah's computePressEOSCM (components/mpmice/setup.py solid_eos). Measured after steps 1, 2, 3
(max difference / max of sus's): press_CC 1.7e-11, 3.6e-4, 7.0e-4; press_equil_CC 7.6e-10,
1.9e-8, 3.3e-4; the burned mass 2.6e-11, 2.0e-5, 6.3e-5 (at step 2 it was 3.4e-3 before the
product's thermal expansion in eq. 40 took the start-of-step temperature, Uintah's getAlpha, and
press_CC 1.3e-3 with a stand-in EOS linear in rho for the solids). After 5 steps the runs part:
sus cuts the 5th step's delT to 6.3e-8, pysus keeps 8.5e-8.
"""
import pathlib

import numpy as np
import pytest

from tests.conftest import run_deck

HERE = pathlib.Path(__file__).parent
DECK = HERE / "uintah_reference" / "guni2dRT.ups"


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    from framework.archiver import DataArchive
    ctl = run_deck(DECK.read_text(encoding="latin-1"), tmp_path_factory.mktemp("guni"), "guni")
    return DataArchive(ctl.archiver.dir), np.load(HERE / "data" / "sus_guni2dRT.npz")


def _rel(got, want):
    return np.abs(np.asarray(got) - want).max() / np.abs(want).max()


def test_first_step_burn_as_uintah(runs):
    """Step 1: the burned mass, the volume fractions and the pressure are sus's to round-off."""
    da, sus = runs
    assert da.times[1:] == pytest.approx(sus["times"], rel=1e-4)
    burned = sus["modelMass_src_2_0"]
    assert (burned > 0).sum() == 50
    assert _rel(da.read("modelMass_src", 2, 1)[0], burned) < 1e-9
    for m in range(4):
        assert _rel(da.read("vol_frac_CC", m, 1)[0], sus[f"vol_frac_CC_{m}_0"]) < 1e-9
    press = sus["press_CC_0_0"]
    assert press.max() > 8e6
    assert _rel(da.read("press_CC", 0, 1)[0], press) < 1e-9


def test_second_and_third_steps_near_uintah(runs):
    """Steps 2 and 3 (module doc): pressures, the burned mass and the particles' mass per cell."""
    da, sus = runs
    assert sus["press_CC_0_1"].max() > 1e8
    assert _rel(da.read("press_CC", 0, 2)[0], sus["press_CC_0_1"]) < 6e-4
    assert _rel(da.read("press_equil_CC", 0, 2)[0], sus["press_equil_CC_0_1"]) < 1e-7
    assert _rel(da.read("modelMass_src", 2, 2)[0], sus["modelMass_src_2_1"]) < 1e-4
    assert _rel(da.read("press_CC", 0, 3)[0], sus["press_CC_0_2"]) < 1.5e-3
    assert _rel(da.read("press_equil_CC", 0, 3)[0], sus["press_equil_CC_0_2"]) < 1e-3
    assert _rel(da.read("modelMass_src", 2, 3)[0], sus["modelMass_src_2_2"]) < 2e-4


@pytest.mark.parametrize("step,tol", [(1, 1e-14), (2, 1e-8), (3, 1e-6)])
def test_reactant_mass_per_cell_as_uintah(runs, step, tol):
    """The reactant's particle mass summed per cell after each step (Uintah's massBurnFraction)."""
    da, sus = runs
    p = da.particles(1, step)
    cell = np.zeros((51, 51))
    ij = np.floor(p["p.x"][:, :2] / da.dx[:2]).astype(int)
    np.add.at(cell, (ij[:, 0], ij[:, 1]), p["p.mass"])
    assert _rel(cell, sus[f"p.mass_cell_1_{step - 1}"]) < tol
