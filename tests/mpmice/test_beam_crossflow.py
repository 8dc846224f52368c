"""inputs/MPMICE/beam_crossflow.ups (paper 001 sec. 4.2), shortened to 60 steps on its two
patches: the air stagnating on the clamped beam pushes it downstream (the displacement
grows with height; the particles next to the clamped floor move least), the 400 K air heats the 300 K
beam (its heat sum grows, no particle leaves [300, 400] K), and the beam's mass is
constant. scripts/beam_crossflow.py follows the oscillation over a longer run.
"""
import numpy as np
import pytest

from framework.archiver import DataArchive
from tests.conftest import ROOT, run_deck

DECK = ROOT / "inputs" / "MPMICE" / "beam_crossflow.ups"


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    text = DECK.read_text(encoding="iso-8859-1").replace("<outputInterval> 2.5e-3 </outputInterval>",
                                                         "<outputTimestepInterval> 60 </outputTimestepInterval>")
    ctl = run_deck(text, tmp_path_factory.mktemp("beam"), "beam", max_timesteps=60)
    return DataArchive(ctl.archiver.dir)


def _displacement(da, band):
    """Mean displacement (x, y) of the particles that started with y in `band`."""
    p0, p1 = da.particles(0, 0), da.particles(0, -1)
    o0, o1 = np.argsort(p0["p.particleID"]), np.argsort(p1["p.particleID"])
    assert np.array_equal(p0["p.particleID"][o0], p1["p.particleID"][o1])
    x0, x1 = p0["p.x"][o0], p1["p.x"][o1]
    sel = (x0[:, 1] > band[0]) & (x0[:, 1] < band[1])
    return (x1[sel] - x0[sel]).mean(axis=0)


def test_tip_bends_downstream(run):
    assert len(run.times) == 2 and run.times[-1] > 1e-3
    tip = _displacement(run, (1.4, 1.5))
    mid = _displacement(run, (0.7, 0.8))
    base = _displacement(run, (0.0, 0.1))
    assert tip[0] > 5e-3                          # downstream: about 18 mm after 2.5 ms
    assert tip[0] > mid[0] > base[0] > 0.0        # growing with height from the clamped base
    assert base[0] < 0.15 * tip[0]


def test_beam_warms_and_keeps_its_mass(run):
    p0, p1 = run.particles(0, 0), run.particles(0, -1)
    assert np.sum(p1["p.mass"]) == pytest.approx(np.sum(p0["p.mass"]), rel=1e-14)
    T = p1["p.temperature"]
    assert np.all(T > 299.0) and np.all(T < 405.0)     # sanity: the exchange may overshoot a little
    t, e = run.reduction("ThermalEnergy")
    assert e[-1] > e[0] * (1 + 1e-4)
    gas_T, _ = run.read("temp_CC", material=1, timestep=-1)
    assert np.all(np.isfinite(gas_T)) and gas_T.min() > 250.0 and gas_T.max() < 450.0
