"""Uintah's MPMICE advect.ups (R_Tester MPMICE.py, test advect) run unchanged for 2 steps, against sus.

Deck: uintah_reference/advect.ups, Uintah's file as it is (50^3 cells on 2 x 2 x 2 patches, a
copper box in air, two PassiveScalar models, TracerParticles, and the DataAnalysis modules
planeAverage, statistics and minMax); the run sets <max_Timesteps> 2 and output every step, as
sus's reference run did. Its c2 table inputs/MPMICE/testExpDecay_Coeff.csv (3.3 MB) is written
in the run's folder byte for byte as Uintah's: c2 = x y z at the cell centres (0.025 + 0.05 i),
'%g' (checked against Uintah's file when this test was written).

data/sus_advect_2steps.npz is sus's output on that deck (one rank, read with
framework.uintah_uda.UintahArchive): along the line j = k = 25 (through the copper box, cells
20-29) after steps 1 and 2 press_CC, scalar-f_CC, scalar-q_CC, the statistics' mean_ and
variance_ of both scalars and scalar-q_CC_expDecayCoef (with their min and max over the level),
the expDecayCoef every 7th cell, the planeAverage files of step 1 (sampled every 1e-3 s: step 1
only), the tracer count and every 40th tracer by p.particleID: p.x and p.scalar.

Measured: scalar-f and its statistics to 1e-15; expDecayCoef exactly; scalar-f's plane averages
to 4e-15, scalar-q's to 1e-12; the tracers' IDs the same, p.x exactly, p.scalar to 2e-16. press_CC on the line to
2e-12 after step 1 and 4e-12 after step 2, scalar-q there to 8e-16 (the gas starts around the
copper from its geometry as sus's, docs/MPMICE.md "Gas start"; the particles' smeared start
gave 3e-3 and 4e-4 after step 2).
"""
import pathlib

import numpy as np
import pytest

from tests.conftest import run_deck

HERE = pathlib.Path(__file__).parent
DECK = HERE / "uintah_reference" / "advect.ups"


def write_c2_table(folder):
    """Uintah's inputs/MPMICE/testExpDecay_Coeff.csv: x, y, z, x y z at every cell centre, x slowest."""
    c = [i * 0.05 + 0.025 for i in range(50)]
    path = folder / "inputs" / "MPMICE" / "testExpDecay_Coeff.csv"
    path.parent.mkdir(parents=True)
    path.write_text("".join("%g,%g,%g,%g\n" % (x, y, z, x * y * z) for x in c for y in c for z in c))


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    import os
    from framework.archiver import DataArchive
    folder = tmp_path_factory.mktemp("advect")
    write_c2_table(folder)
    text = DECK.read_text(encoding="iso-8859-1")
    text = text.replace("<max_Timesteps>       100          </max_Timesteps>", "<max_Timesteps>2</max_Timesteps>")
    text = text.replace("<outputTimestepInterval>10</outputTimestepInterval>",
                        "<outputTimestepInterval>1</outputTimestepInterval>")
    here = os.getcwd()
    os.chdir(folder)                        # the table's path is relative to the working folder, as in Uintah
    try:
        ctl = run_deck(text, folder, "advect")
    finally:
        os.chdir(here)
    return DataArchive(ctl.archiver.dir), np.load(HERE / "data" / "sus_advect_2steps.npz")


def rows(path):
    return np.array([[float(x) for x in line.split()] for line in open(path) if not line.startswith("#")])


def test_advect_fields_as_uintah(runs):
    da, sus = runs
    line = lambda label, m, step: da.read(label, m, step)[0][:, 25, 25]
    p1 = line("press_CC", 0, 1)
    assert np.allclose(p1, sus["press_CC@1"], rtol=1e-10, atol=0)
    assert np.allclose(line("press_CC", 0, 2), sus["press_CC@2"], rtol=1e-10, atol=0)
    for label in ("scalar-f_CC", "mean_scalar-f_CC", "variance_scalar-f_CC"):
        for step in (1, 2):
            assert np.allclose(line(label, 1, step), sus[f"{label}@{step}"], rtol=0, atol=2e-15), (label, step)
    for label in ("scalar-q_CC", "mean_scalar-q_CC", "variance_scalar-q_CC"):
        for step in (1, 2):
            full = da.read(label, 1, step)[0]
            assert np.allclose(line(label, 1, step), sus[f"{label}@{step}"], rtol=0, atol=1e-13), (label, step)
            assert np.allclose((full.min(), full.max()), sus[f"{label}@{step}:minmax"], rtol=0, atol=1e-13)
    # statistics: step 1 is the window's first sample (mean = Q, variance 0), step 2 the mean of two
    f1, f2 = line("scalar-f_CC", 1, 1), line("scalar-f_CC", 1, 2)
    assert np.array_equal(line("mean_scalar-f_CC", 1, 1), f1) and not np.any(line("variance_scalar-f_CC", 1, 1))
    assert np.allclose(line("mean_scalar-f_CC", 1, 2), (f1 + f2) / 2, rtol=1e-15, atol=0)
    coef = da.read("scalar-q_CC_expDecayCoef", 1, 1)[0]
    assert np.array_equal(coef[::7, ::7, ::7], sus["coef_full"])
    assert np.array_equal(da.read("scalar-q_CC_expDecayCoef", 1, 2)[0], coef)


def test_advect_plane_averages_and_tracers_as_uintah(runs):
    da, sus = runs
    folder = pathlib.Path(da.path) / "planeAverage"
    assert [p.name for p in folder.iterdir()] == ["t00001"]          # samplingFrequency 1000: once in 2 steps
    for name, key, tol in (("scalar-f_CC_1", "plane_f@1", 1e-14), ("scalar-q_CC_1", "plane_q@1", 1e-12)):
        got, ref = rows(folder / "t00001" / "L-0" / name), sus[key]
        assert got.shape == ref.shape == (50, 5) and np.array_equal(got[:, [0, 1, 2, 4]], ref[:, [0, 1, 2, 4]])
        assert np.allclose(got[:, 3], ref[:, 3], rtol=tol, atol=0), (name, np.abs(got[:, 3] / ref[:, 3] - 1).max())
    for step in (1, 2):
        p = da.particles(1, step)
        assert len(p["p.particleID"]) == int(sus[f"tracer_count@{step}"])
        where = {i: n for n, i in enumerate(p["p.particleID"])}
        idx = [where[i] for i in sus[f"tracer_ids@{step}"]]
        assert np.allclose(p["p.x"][idx], sus[f"tracer_x@{step}"], rtol=0, atol=1e-12)
        assert np.allclose(p["p.scalar"][idx], sus[f"tracer_scalar@{step}"], rtol=0, atol=1e-14)


# sus's TotalMass.dat and TotalMass_1.dat on this deck, 2 steps, one rank: (time, total, air). Uintah's
# MPM puts the copper's particles and ICE's conservationTest the air into the one reduction.
SUS_TOTAL_MASS = ((2.1018671035656177e-05, 1130.7788353573812, 18.278835357380363),
                  (4.2037342071312354e-05, 1130.778835357381, 18.278835357380359))


def test_advect_total_mass_as_uintah(runs):
    """TotalMass is the particles' plus the air's (measured 2e-14 of sus's after step 1), the air's
    own in TotalMass_1.dat; a line per step, none at t = 0."""
    da, _ = runs
    ref = np.array(SUS_TOTAL_MASS)
    t, total = da.reduction("TotalMass")
    _, air = da.reduction("TotalMass", 1)
    assert np.allclose(t, ref[:, 0], rtol=1e-12, atol=0)
    assert np.allclose(total, ref[:, 1], rtol=1e-12, atol=0)
    assert np.allclose(air, ref[:, 2], rtol=1e-12, atol=0)
