"""inputs/MPMICE/beam_crossflow.ups (paper 001 sec. 4.2), shortened to 60 steps on its two
patches: the air stagnating on the clamped beam pushes it downstream (the displacement
grows with height; the particles next to the clamped floor move least), the 400 K air heats the 300 K
beam (its heat sum grows), and the beam's mass is constant. scripts/beam_crossflow.py follows the
oscillation over a longer run.

The floor's Neumann 0 <Temperature> condition (id="all") sets the beam's floor nodes to the
temperature of the nodes above them, on g.temperature and g.temperatureStar, and the nodal rate
(T* - g.temperatureNoBC)/dt then takes that copied value (Uintah's MPMBoundCond and
integrateTemperatureRate): a floor node warmed by its heated particles is pulled back to the cooler
row above, which cools the particle by the beam's downstream floor corner below its 300 K start.
sus does the same: this deck for 60 steps (<max_Timesteps>60</max_Timesteps>, one output a step)
gives its coolest particle 298.631 K (at x = 1.376 m, y = 0.025 m), pysus 298.598 K; the particles'
temperatures are sus's to 0.12 K (their delT parts from sus's by up to 0.37 % from step 10 on).
Without the condition on the beam's nodes the coolest stays at 300.0096 K and the particles are up
to 2.5 K off sus's.
"""
import numpy as np
import pytest

from framework.archiver import DataArchive
from tests.conftest import ROOT, run_deck

DECK = ROOT / "inputs" / "MPMICE" / "beam_crossflow.ups"


def _run(tmp_path_factory, patches="[2,1,1]", mpmice=""):
    text = DECK.read_text(encoding="iso-8859-1").replace("<outputInterval> 2.5e-3 </outputInterval>",
                                                         "<outputTimestepInterval> 60 </outputTimestepInterval>")
    text = text.replace("<patches> [2,1,1] </patches>", f"<patches> {patches} </patches>")
    if mpmice:
        text = text.replace("  <MPM>\n", f"  <MPMICE>{mpmice}</MPMICE>\n  <MPM>\n", 1)
    ctl = run_deck(text, tmp_path_factory.mktemp("beam"), "beam", max_timesteps=60)
    return DataArchive(ctl.archiver.dir)


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    return _run(tmp_path_factory)


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
    assert T.min() == pytest.approx(298.631, abs=0.1)   # sus's coolest particle (module doc)
    assert np.all(T < 405.0)                            # sanity: the exchange may overshoot a little
    t, e = run.reduction("ThermalEnergy")
    assert e[-1] > e[0] * (1 + 1e-4)
    gas_T, _ = run.read("temp_CC", material=1, timestep=-1)
    assert np.all(np.isfinite(gas_T)) and gas_T.min() > 250.0 and gas_T.max() < 450.0


def test_four_patches_bitwise(run, tmp_path_factory):
    """On four patches (a patch edge along the beam's upstream side, x = 1 m) the 60 steps are
    bitwise the two patches' run: the floor's Temperature condition on g.temperatureStar is set on
    the ghost nodes as their owner sets them (set on the owned nodes alone, the runs part)."""
    four = _run(tmp_path_factory, "[4,1,1]")
    a, b = run.particles(0, -1), four.particles(0, -1)
    oa, ob = np.argsort(a["p.particleID"]), np.argsort(b["p.particleID"])
    for lab in ("p.temperature", "p.x"):
        assert np.array_equal(a[lab][oa], b[lab][ob]), lab
    for m in (0, 1):
        assert np.array_equal(run.read("temp_CC", m, -1)[0], four.read("temp_CC", m, -1)[0])


def test_solid_nodes_left_free_no_particle_below_its_start(tmp_path_factory):
    """<MPMICE><solid_temperature_bcs>false: the floor's condition acts on the air's cells only, and
    no particle of the 300 K beam in 400 K air leaves [300, 400] K within the exchange's overshoot
    (pysus's choice; Uintah's, above, cools one to 298.6 K as sus does)."""
    T = _run(tmp_path_factory, mpmice="<solid_temperature_bcs>false</solid_temperature_bcs>").particles(0, -1)[
        "p.temperature"]
    assert T.min() >= 300.0 and T.max() < 405.0
