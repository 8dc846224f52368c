"""Uintah's MPMICE regression deck guni2dRT (uintah_reference/guni2dRT.ups): a steel ring around a
reactant burning by Simple_Burn into its product gas, against sus, 6 steps.

data/sus_guni2dRT.npz is sus's output on that deck without pysus's three tags, one rank (sus
guni2dRT.ups), read with framework.uintah_uda.UintahArchive: the output times, press_CC,
press_equil_CC and the product's modelMass_src after steps 1-6, every material's vol_frac_CC after
steps 1, 2 and 6, the reactant's p.mass summed per cell after steps 1-6, and the steel's p.x and
p.stress after steps 2 and 6 (the particles of one of sus's two layers along z).

The deck's tags select Uintah's algorithms where pysus's defaults differ: the stress from v*
(<stress_update>usl: sus's steel stress after step 1 is 10 times pysus's MUSL one, from the GIMP
weight gradients at the edge of a particle's reach, of round-off size, times the huge v* of nodes
with round-off mass), the solids' wave-speed step over every direction
(<delT_activeDirectionsOnly>false: the deck's z cell, 0.0016933, is 2e-5 thinner than its x and y
cells, and ElasticPlasticHP takes min_d dx_d / (c + |v_d|) over all three), Uintah's
SecondOrderAdvector (limiter="BarthJespersen": it also advects the volume fractions in the
dilatation term of the pressure, ICE's delp_press). Uintah's trace rules are pysus's default: a
solid's temp_CC in a cell that holds little of it blends with the temperature its last exchange
left there (interpolateNCToCC_0's one_or_zero), the temp_CC a step leaves is the exchanged one, and
no rule of pysus's own for trace gas (the trace air in the cells the ring fills heats to 14,700 K
by step 4 in sus, and its sound speed sets sus's 5th step). With them and Uintah's symmetry planes,
which take the internal force's normal component before v* is read (as
SerialMPM::computeInternalForce; MPMICE's Lagrangian momentum reads v*), measured after steps 1 to
6 (max difference / max of sus's): press_CC 1.6e-11, 2.0e-11, 1.8e-11, 1.7e-9, 4.9e-9, 1.2e-8;
press_equil_CC 7.6e-10, 3.5e-10, 3.8e-11, 1.8e-9, 6.2e-9, 1.4e-8; the burned mass 2.6e-11, 1.2e-11,
2.7e-12, 1.6e-9, 1.2e-9, 9.2e-10; the reactant's mass per cell 3.8e-16, 3.8e-16, 1.1e-15, 5.3e-13,
8.8e-13, 1.2e-12; the steel's stress 3.5e-9 (step 2), 4.7e-8 (step 6); the times to 1.3e-11, sus's
5th step of 6.28e-8 included; the volume fractions after step 6 4.9e-11, 8.6e-10, 6.6e-8, 5.2e-14.
Without the two solid-temperature rules (temp_CC its nodes' mean, its object's temperature
where the cell holds less than the floor mass, saved before the exchange): press_CC 1.9e-7 after
step 3 and 1.9e-5 after step 6, the times 5.3e-6 apart.

Step 1 is sus's to round-off: the burned mass (Uintah's surface area V / (sum_d |n_d| dx_d)
max_d |n_d|^(-1/3)), the volume it makes (burned * v_solid) and the pressure it raises
(Uintah's delP_MassX, sum_m m_src,m v_m / V / sum_m theta_m kappa_m, with each material's
equilibrated v_m): 8.2e6 Pa where sus has 8.2e6. The particles lose the burned mass as Uintah's
(massBurnFraction at the nodes, interpolated to the particles); each solid answers the
equilibration with its own model's EOS, as Uintah's computePressEOSCM.
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
    burned = sus["modelMass_src_2_0"]
    assert (burned > 0).sum() == 50
    assert _rel(da.read("modelMass_src", 2, 1)[0], burned) < 1e-9
    for m in range(4):
        assert _rel(da.read("vol_frac_CC", m, 1)[0], sus[f"vol_frac_CC_{m}_0"]) < 1e-9
    press = sus["press_CC_0_0"]
    assert press.max() > 8e6
    assert _rel(da.read("press_CC", 0, 1)[0], press) < 1e-9


def test_steps_as_uintah(runs):
    """sus's step sizes, its 5th cut to 6.3e-8 by the trace air's sound speed (ICE's CFL step)."""
    da, sus = runs
    assert da.times[1:] == pytest.approx(sus["times"], rel=1e-10)
    assert da.times[5] - da.times[4] == pytest.approx(6.2815e-8, rel=1e-4)
    assert da.times[4] - da.times[3] == pytest.approx(8.4949e-8, rel=1e-4)


@pytest.mark.parametrize("label,matl,tols", [
    ("press_CC", 0, (1e-9, 1e-9, 1e-9, 1e-8, 3e-8, 6e-8)),
    ("press_equil_CC", 0, (1e-8, 1e-8, 1e-9, 1e-8, 3e-8, 6e-8)),
    ("modelMass_src", 2, (1e-9, 1e-9, 1e-10, 1e-8, 1e-8, 1e-8))])
def test_fields_track_uintah(runs, label, matl, tols):
    """press_CC, press_equil_CC and the burned mass after each of the 6 steps (module doc)."""
    da, sus = runs
    assert sus["press_CC_0_5"].max() > 1e8
    for s, tol in enumerate(tols):
        assert _rel(da.read(label, matl, s + 1)[0], sus[f"{label}_{matl}_{s}"]) < tol, (label, s + 1)


def test_volume_fractions_after_six_steps(runs):
    da, sus = runs
    for m, tol in enumerate((5e-10, 5e-9, 5e-7, 1e-12)):
        assert _rel(da.read("vol_frac_CC", m, 6)[0], sus[f"vol_frac_CC_{m}_5"]) < tol


@pytest.mark.parametrize("step,tol", [(1, 1e-14), (2, 1e-14), (3, 1e-14), (4, 5e-12), (5, 5e-12), (6, 1e-11)])
def test_reactant_mass_per_cell_as_uintah(runs, step, tol):
    """The reactant's particle mass summed per cell after each step (Uintah's massBurnFraction)."""
    da, sus = runs
    p = da.particles(1, step)
    cell = np.zeros((51, 51))
    ij = np.floor(p["p.x"][:, :2] / da.dx[:2]).astype(int)
    np.add.at(cell, (ij[:, 0], ij[:, 1]), p["p.mass"])
    assert _rel(cell, sus[f"p.mass_cell_1_{step - 1}"]) < tol


@pytest.mark.parametrize("step,tol", [(2, 2e-8), (6, 5e-7)])
def test_steel_stress_as_uintah(runs, step, tol):
    """The steel's particles (sus's one layer of two along z, paired by position) and their
    stress, Uintah's USL update with its GIMP weights."""
    da, sus = runs
    p = da.particles(0, step)
    want_x, want = sus[f"p.x_0_{step - 1}"], sus[f"p.stress_0_{step - 1}"]
    order = [np.lexsort((np.round(x[:, 1] / 1e-6), np.round(x[:, 0] / 1e-6))) for x in (want_x, p["p.x"])]
    assert np.abs(want_x[order[0], :2] - p["p.x"][order[1], :2]).max() < 1e-10
    assert np.abs(want).max() > 1e7
    assert _rel(p["p.stress"][order[1]], want[order[0]]) < tol
