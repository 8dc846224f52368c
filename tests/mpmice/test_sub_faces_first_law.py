"""Sub-face boundary conditions and Uintah's firstLawThermo module under MPMICE, against sus.

Deck: uintah_reference/subFaces_firstLaw.ups (tests/ice/uintah_reference/subFaces.ups, air in
a box of walls with a circular inlet on x-, a rectangular outlet on x+ and an annular inlet
on y+, plus a copper block at rest in the middle and firstLawThermo every step, y+ a
partialFace). The sus values in data/sus_subFaces_firstLaw.npz are sus's output on that deck
(one rank): the time after each step (timestep.xml), its 1stLawThermo.dat (time, ICE and MPM
internal energy, their sum, the energy flux), and press_CC, temp_CC and vel_CC of the air
(material 1) over the interior cells after steps 1 and 10 (read with framework.uintah_uda).

The gas starts from its geometry as in sus (docs/MPMICE.md, "Gas start"): after step 1
vol_frac_CC equals sus's to 2e-16, vel_CC of the air 2.7e-12 of its maximum, press_CC 5e-10 and
temp_CC 4e-10 (in the block's edge cells, where the copper's stiffness turns round-off of its
volume into pressure), the boundary columns to round-off, the 1stLawThermo energies and flux
4e-16 after steps 1-2. From step 3 the circular inlet's edge cells (x-, rows 6 and 13) part
from sus (the same with the particles' smeared start, not yet looked into); after 10 steps:
flux 3.1e-7, ICE energy 2.2e-8 (all of it in the inlet column), the fields 5e-5 (pressure),
3.3e-5 (temperature) and 2e-6 (velocity) of their maxima, the time to 3.7e-14. (With the
smeared start: flux 2.7e-6, energy 5.8e-9 where the block cells' errors, +-28 J each, and the
inlet's partly cancelled, velocity 4.6e-4.)
"""
import pathlib

import numpy as np
import pytest

from tests.conftest import run_deck

HERE = pathlib.Path(__file__).parent
DECK = HERE / "uintah_reference" / "subFaces_firstLaw.ups"
VOL, CV, CP_COPPER = 0.05 * 0.05 * 0.1, 716.0, 386.0


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    from framework.archiver import DataArchive
    ctl = run_deck(DECK.read_text(), tmp_path_factory.mktemp("subfaces"), "subfaces")
    return (DataArchive(ctl.archiver.dir), np.load(HERE / "data" / "sus_subFaces_firstLaw.npz"),
            pathlib.Path(ctl.archiver.dir))


def test_sub_faces_as_uintah(runs):
    """The inlets and the outlet act on the air's boundary cells as in sus: the columns next
    to x- and x+ and the row under y+ equal sus's after step 1 to round-off in pressure and
    temperature (measured 1.4e-14 of the maximum), the velocity to 6e-17."""
    da, sus, _ = runs
    assert np.allclose(da.times[1:], sus["times"], rtol=1e-13, atol=0)
    for label, m in (("press_CC", 0), ("temp_CC", 1), ("vel_CC", 1)):
        got, want = da.read(label, m, 1)[0][:, :, 0], sus[f"{label}_step1"]
        scale = np.abs(want).max()
        for edge in (np.s_[0], np.s_[-1], np.s_[:, -1]):
            assert np.allclose(got[edge], want[edge], rtol=0, atol=5e-14 * scale), (label, edge)
        assert np.allclose(got, want, rtol=0, atol=(1e-11 if label == "vel_CC" else 1e-9) * scale), label
        got, want = da.read(label, m, -1)[0][:, :, 0], sus[f"{label}_step10"]
        assert np.allclose(got, want, rtol=0, atol=1e-4 * np.abs(want).max()), label
    temp = sus["temp_CC_step10"]
    assert temp[0, 6:14].min() > 310.0 > temp[0, 15:].max()       # the circle's inflow, not the wall's


def test_first_law_thermo_as_uintah(runs):
    """1stLawThermo.dat: Uintah's header and columns, the energies and the flux of sus."""
    da, sus, uda = runs
    text = (uda / "1stLawThermo.dat").read_text()
    assert text.startswith("# This assumes:\n#    - mpm matls have constant specific heat\n")
    assert "KJ ->J 1.000000E-03\n#Time                      ICE_totalIntEng" in text
    ours, theirs = np.loadtxt(uda / "1stLawThermo.dat"), sus["first_law"]
    assert ours.shape == theirs.shape == (10, 5)
    assert np.allclose(ours[:, 0], theirs[:, 0], rtol=1e-13, atol=0)
    assert np.array_equal(ours[:, 2], theirs[:, 2])                 # the block: m cp T of its particles
    assert np.allclose(ours[:2, 1:], theirs[:2, 1:], rtol=1e-14, atol=0)
    assert np.allclose(ours[:, 1], theirs[:, 1], rtol=5e-8, atol=0)      # the inlet's edge cells (module doc)
    assert np.allclose(ours[:, 4], theirs[:, 4], rtol=1e-6, atol=0)
    assert np.all(ours[:, 4] < -1e6)                                # the inlets bring energy in (Uintah's sign)


def test_first_law_thermo_sums(runs):
    """The columns are what their definitions give from the saved fields: sum rho V cv T of the
    air, sum m cp T of the particles (300 K), and the total."""
    da, _, uda = runs
    rows = np.loadtxt(uda / "1stLawThermo.dat")
    for step in (1, 10):
        ice = (da.read("rho_CC", 1, step)[0] * da.read("temp_CC", 1, step)[0]).sum() * VOL * CV
        mass = da.particles(0, step)["p.mass"]
        assert rows[step - 1, 1] == pytest.approx(ice, rel=1e-13)
        assert rows[step - 1, 2] == pytest.approx(mass.sum() * CP_COPPER * 300.0, rel=1e-13)
        assert rows[step - 1, 3] == pytest.approx(rows[step - 1, 1] + rows[step - 1, 2], rel=1e-15)
