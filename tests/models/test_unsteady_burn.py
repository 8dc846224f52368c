"""Unsteady_Burn (components/models/unsteady_burn.py) on Uintah's MPMICE regression deck
TBurner_2dRT, three steps against sus, and what the burn conserves.

Deck: tests/mpmice/uintah_reference/TBurner_2dRT.ups (the R_Tester deck with 3 steps, every step
saved and sus's CGSolver instead of hypre; its header says why). It also exercises semi-implicit
ICE with a circular outlet (fixed pressure, free velocity) in a side of fixed velocity, and the
burned mass in the implicit pressure equation. data/sus_TBurner_2dRT.npz is sus's output on that
deck, one rank, made with `sus TBurner_2dRT.ups` and read with framework.uintah_uda.UintahArchive:
the times, totalMassBurned.dat and totalHeatReleased.dat, after steps 1 and 3 the
UnsteadyBurn.SurfTemp, SurfTempGrad, BurningCell and the product's modelMass_src of the two
burning columns (x cells 0 and 273; no other cell burns), press_CC, the product's temp_CC,
delP_MassX over the interior, and the sum of p.mass.

Measured (pysus against sus, the solid with its comp_neo_hook EOS as Uintah's UCNH, docs/MPMICE.md
"Solids in the equilibration"): steps equal; totalMassBurned 2.4e-10 relative, modelMass_src per
cell 3.2e-10, SurfTemp 2.1e-11, SurfTempGrad 3.1e-10, press_CC 3.2e-10 of p, the gas temperature
2e-14, delP_MassX in the burning columns 6.6e-10 (3.0e-6 with the earlier Murnaghan n = 1
stand-in for the solid, whose sound speed K/rho0, not sus's K/rho, entered sum theta kappa).
The solid's volume fraction there is sus's 0.27 (the gas started from its geometry, docs/MPMICE.md "Gas
start"; the particles' smeared start gave 0.19, delP_MassX 11 % off, press_CC 4e-6).
"""
import pathlib

import numpy as np
import pytest

from tests.conftest import run_deck

HERE = pathlib.Path(__file__).parent
DECK = HERE.parent / "mpmice" / "uintah_reference" / "TBurner_2dRT.ups"
COLS = [0, 273]
V = (0.822 / 274) * (0.069 / 23) * 0.003
QC_QG = 4.0e5 + 3.018e6


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    from framework.archiver import DataArchive
    ctl = run_deck(DECK.read_text(), tmp_path_factory.mktemp("tburner"), "tburner")
    return DataArchive(ctl.archiver.dir), np.load(HERE / "data" / "sus_TBurner_2dRT.npz")


def _cc(da, label, m, step):
    return np.squeeze(da.read(label, m, step)[0])


def test_steps_and_burned_mass_as_uintah(runs):
    """Each step burns what sus burns (the first from the steady WSB rate, the next relaxed in time)."""
    da, sus = runs
    assert np.allclose(da.times[1:], sus["times"], rtol=1e-12, atol=0)
    t, burned = da.reduction("totalMassBurned")
    assert np.allclose(burned, sus["totalMassBurned"], rtol=1e-8, atol=0)
    _, heat = da.reduction("totalHeatReleased")
    assert np.allclose(heat, sus["totalHeatReleased"], rtol=1e-8, atol=0)


@pytest.mark.parametrize("step", [1, 3])
def test_burning_cells_as_uintah(runs, step):
    """Burning cells, their steps burned in a row, Ts, beta and the burned mass per cell."""
    da, sus = runs
    burning = _cc(da, "UnsteadyBurn.BurningCell", 0, step)
    assert np.array_equal(burning[COLS], sus[f"BurningCell_{step}"])
    assert np.count_nonzero(np.delete(burning, COLS, axis=0)) == 0
    assert np.all(burning[COLS] == step)
    on = sus[f"BurningCell_{step}"] > 0
    assert np.allclose(_cc(da, "UnsteadyBurn.SurfTemp", 0, step)[COLS][on], sus[f"SurfTemp_{step}"][on],
                       rtol=1e-9, atol=0)
    assert np.allclose(_cc(da, "UnsteadyBurn.SurfTempGrad", 0, step)[COLS][on], sus[f"SurfTempGrad_{step}"][on],
                       rtol=1e-6, atol=0)
    assert np.allclose(_cc(da, "modelMass_src", 1, step)[COLS], sus[f"modelMass_src_{step}"], rtol=1e-8, atol=0)


@pytest.mark.parametrize("step", [1, 3])
def test_flow_as_uintah(runs, step):
    """The semi-implicit pressure with the outlet and the burned mass in its right-hand side."""
    da, sus = runs
    p = _cc(da, "press_CC", 0, step)
    assert np.abs(p - sus[f"press_CC_{step}"]).max() < 1e-9 * sus[f"press_CC_{step}"].max()
    T = _cc(da, "temp_CC", 1, step)
    assert np.abs(T - sus[f"temp_CC_gas_{step}"]).max() < 1e-12 * sus[f"temp_CC_gas_{step}"].max()
    # delP_MassX = m_burned (v_product - v_solid) / (V sum theta kappa), the burning cells' gas
    # fraction sus's, the solid's kappa from its own EOS (module docstring)
    dpm = _cc(da, "delP_MassX", 0, step)
    ref = sus[f"delP_MassX_{step}"]
    assert np.abs(np.delete(dpm, COLS, axis=0)).max() < 1e-8 and np.all(np.delete(ref, COLS, axis=0) == 0)
    assert np.all(ref[COLS] > 0)
    assert np.allclose(dpm[COLS], ref[COLS], rtol=1e-8, atol=0)


def test_particles_keep_the_burning_cells_state(runs):
    """The reactant's particles in burning cells carry the cell's Ts and beta (others would go
    back to 300 K, 1e12 K/m)."""
    da, _ = runs
    parts = da.particles(0, 3)
    ts, beta = parts["UnsteadyBurn.PartSurfTemp"], parts["UnsteadyBurn.PartSurfTempGrad"]
    cell = np.floor((parts["p.x"][:, 0] + 0.411) / (0.822 / 274)).astype(int)
    lit = np.isin(cell, COLS)               # all of the explosive lies in the two burning columns
    assert lit.all()
    assert np.all((ts > 700.0) & (ts < 900.0)) and np.all((beta > 1e6) & (beta < 1e12))


def test_burn_conserves_mass_and_hands_over_its_energy(runs):
    """The mass the particles lose is the product's gain, step by step (sum of p.mass as sus's);
    the product gains energy Cp T_solid + Qc + Qg per kg burned (T_solid = 300 K here)."""
    da, sus = runs
    _, burned = da.reduction("totalMassBurned")
    solid = [float(da.particles(0, i)["p.mass"].sum()) for i in range(len(da.times))]
    assert np.allclose(np.diff(solid), -burned, rtol=1e-6, atol=0)
    for step in (1, 3):
        assert solid[step] == pytest.approx(float(sus[f"pmass_{step}"]), rel=1e-13)
    _, heat = da.reduction("totalHeatReleased")
    assert np.allclose(heat, burned * QC_QG, rtol=1e-12)
    src = _cc(da, "modelMass_src", 1, 3)
    assert src.sum() == pytest.approx(burned[-1], rel=1e-12)


def test_restart_carries_the_burn_memory(tmp_path):
    """A restart from the step-2 checkpoint continues with the cells' and particles' (beta, Ts)
    and the solid's last temp_CC: steps 3-4 equal the straight run's bit for bit."""
    from framework.archiver import DataArchive
    from framework.controller import Controller
    text = DECK.read_text().replace("<max_Timesteps> 3 </max_Timesteps>", "<max_Timesteps> 4 </max_Timesteps>") \
        .replace('<outputTimestepInterval> 1 </outputTimestepInterval>',
                 '<outputTimestepInterval> 1 </outputTimestepInterval><checkpoint timestepInterval="2" cycle="2"/>')
    straight = run_deck(text, tmp_path, "straight")
    again = Controller(restart=straight.archiver.dir, restart_index=0, quiet=True, filebase=str(tmp_path / "again.uda"))
    again.run()
    a, b = DataArchive(straight.archiver.dir), DataArchive(again.archiver.dir)
    assert a.times[-1] == b.times[-1] and len(b.times) == 2
    for label, m in (("press_CC", 0), ("temp_CC", 1), ("UnsteadyBurn.SurfTemp", 0), ("UnsteadyBurn.SurfTempGrad", 0),
                     ("UnsteadyBurn.BurningCell", 0)):
        assert np.array_equal(a.read(label, m, -1)[0], b.read(label, m, -1)[0]), label
    pa, pb = a.particles(0, -1), b.particles(0, -1)
    for label in ("p.mass", "UnsteadyBurn.PartSurfTemp", "UnsteadyBurn.PartSurfTempGrad"):
        assert np.array_equal(pa[label], pb[label]), label
