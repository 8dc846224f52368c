"""Uintah's mass_momentum_energy_src and TracerParticles models (components/models) on ICE,
against Uintah's sus.

The deck is tests/ice/uintah_reference/stagnationPoint_explicit.ups (Uintah's stagnationPoint.ups
made explicit, with a heater, a timeStop and particle injection; its comment says how). The sus
values in data/sus_stagnationPoint.npz are small extracts of sus's output on the same deck
without the pysus-only advection attributes (limiter="BarthJespersen" dissipationHeating="false",
which select Uintah's scheme in pysus), one rank:
    sus stagnationPoint_explicit.ups
read with framework.uintah_uda.UintahArchive: the time after each step, press_CC min/max, the x
and y ranges of vel_CC, temp_CC max, the .dat files of TotalMom_src and TotalEng_src, the
particle count after each step, and every 20th tracer (by p.particleID) after step 6.
"""
import pathlib

import numpy as np
import pytest

from framework.problemspec import InputError

DECK = pathlib.Path(__file__).parents[1] / "ice" / "uintah_reference" / "stagnationPoint_explicit.ups"
DATA = pathlib.Path(__file__).parent / "data"


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    from framework.archiver import DataArchive
    from framework.controller import Controller
    tmp = tmp_path_factory.mktemp("stagnation")
    c = Controller(str(DECK), quiet=True, filebase=str(tmp / "run.uda"))
    c.run()
    return DataArchive(c.archiver.dir), np.load(DATA / "sus_stagnationPoint.npz")


def test_flow_as_uintah(runs):
    """Four fans (velocity held at 2 m/s), one of them a 400 K heater, one stopping at t = 5e-6:
    delT, pressure, velocity and temperature of 6 steps equal sus's to round-off (measured:
    times 3e-16, press 5e-15, vel 5e-13 of the fan speed)."""
    da, sus = runs
    assert np.allclose(da.times[1:], sus["times"], rtol=1e-14, atol=0)
    for k in range(len(sus["times"])):
        p = da.read("press_CC", 0, k + 1)[0]
        v = da.read("vel_CC", 0, k + 1)[0][..., :2].reshape(-1, 2)
        assert np.allclose([p.min(), p.max()], sus["press_range"][k], rtol=1e-13, atol=0), k
        assert np.allclose([v.min(0), v.max(0)], sus["vel_xy_range"][k], rtol=0, atol=1e-11), k
        assert da.read("temp_CC", 0, k + 1)[0].max() == pytest.approx(sus["temp_max"][k], rel=1e-13)


def test_source_totals_as_uintah(runs):
    """TotalMom_src and TotalEng_src are sus's divided by 3: Uintah's sum also counts the two
    extra-cell layers of the collapsed z direction of this 2D grid (the fans reach them), which
    a pysus 2D grid does not have; the sources in the cells that exist are the same."""
    da, sus = runs
    mom = da.reduction("TotalMom_src")[1]
    eng = da.reduction("TotalEng_src")[1]
    assert np.allclose(3.0 * mom, sus["TotalMom_src"], rtol=1e-10, atol=1e-16)     # sums in another order
    assert np.allclose(3.0 * eng, sus["TotalEng_src"], rtol=1e-12, atol=1e-13)
    assert eng[0] > 1.0 and mom[1].tolist() == [0.0, 0.0, 0.0]     # heater on; fans at speed after step 1


def test_tracers_as_uintah(runs):
    """2560 tracers seeded at t = 0 (8 per cell of the four fans), 80 more per injecting fan
    in steps 2 and 5: the count after every step, and the IDs, positions, displacements,
    velocities, cloned press_CC / scalar-f and the decaying scalar p.age (with p.age_totalDecay)
    of every 20th particle after step 6 equal sus's
    (positions to 1e-16 m: the same random points, the same motion; velocities 5e-12 m/s)."""
    da, sus = runs
    counts = [len(da.particles(0, k + 1)["p.particleID"]) for k in range(len(sus["times"]))]
    assert counts == sus["n_particles"].tolist() == [2560, 2720, 2720, 2720, 2880, 2880]
    P = da.particles(0, -1)
    order = np.argsort(P["p.particleID"])[::20]
    assert np.array_equal(P["p.particleID"][order], sus["ids"])
    assert np.any((sus["ids"] & 0xFFFF) >= 8)                    # some of them were injected
    assert np.allclose(P["p.x"][order], sus["x"], rtol=0, atol=1e-15)
    assert np.allclose(P["p.displacement"][order], sus["disp"], rtol=0, atol=1e-15)
    assert np.allclose(P["p.velocity"][order], sus["pvel"], rtol=0, atol=1e-10)      # |u| up to 6 m/s
    assert np.allclose(P["p.clone-press_CC"][order], sus["clone_press"], rtol=1e-13, atol=0)
    assert np.allclose(P["p.clone-scalar-f"][order], sus["clone_f"], rtol=0, atol=1e-14)
    assert np.allclose(P["p.age"][order], sus["age"], rtol=1e-14, atol=0)                # exp(-(c1 c2 + c3) dt) per step
    assert np.allclose(P["p.age_totalDecay"][order], sus["age_total"], rtol=1e-14, atol=0)
    assert len(np.unique(np.round(sus["age"], 12))) == 2                 # seeded at t = 0, injected in step 2


@pytest.mark.parametrize("old, new, words", [
    ("<density_src>      0               </density_src>", "<density_src> 1.2 </density_src>",
     "mass source"),
    ('<CCVarLabel label="press_CC"/>', '<CCVarLabel label="vel_CC"/>', "cell-centred scalar"),
    ('<c2 type="constant"> <value> 10 </value> </c2>', '<c2 type="variable"> <filename>c2.csv</filename> </c2>',
     "no file c2.csv"),
])
def test_bad_model_input(tmp_path, old, new, words):
    """What the models do not accept is refused at start-up with the tag and what is accepted."""
    from framework.controller import Controller
    text = DECK.read_text()
    assert old in text
    deck = tmp_path / "bad.ups"
    deck.write_text(text.replace(old, new, 1))
    with pytest.raises(InputError, match=words):
        Controller(str(deck), quiet=True, filebase=str(tmp_path / "bad.uda"))


def test_tracers_restart_equals_straight_run(tmp_path):
    """A restart at step 3 (between the injections of steps 2 and 5) gives the run that never
    stopped: the particles, their cell counts nPPC and the injection clock are in the checkpoint."""
    from tests.conftest import pysus, pysus_ranks
    from framework.archiver import DataArchive
    deck = tmp_path / "stag.ups"
    deck.write_text(DECK.read_text().replace('<save label="TotalEng_src"/>', '<save label="TotalEng_src"/>'
                                             '<checkpoint timestepInterval="3" cycle="2"/>'))
    straight = tmp_path / "straight.uda"
    r = pysus_ranks(deck, "--filebase", straight)
    assert r.returncode == 0, r.stderr[-2000:]
    r = pysus("-restart", straight, "-t", 0, "--filebase", tmp_path / "again.uda")
    assert r.returncode == 0, r.stderr[-2000:]
    a, b = DataArchive(straight), DataArchive(tmp_path / "again.uda")
    assert a.times[-1] == b.times[-1]
    assert np.array_equal(a.read("vel_CC", 0, -1)[0], b.read("vel_CC", 0, -1)[0])
    pa, pb = a.particles(0, -1), b.particles(0, -1)
    assert len(pa["p.particleID"]) == 2880
    oa, ob = np.argsort(pa["p.particleID"]), np.argsort(pb["p.particleID"])
    for lab in pa:
        assert np.array_equal(pa[lab][oa], pb[lab][ob]), lab


def test_implicit_deck_as_uintah(tmp_path):
    """Uintah's deck itself (semi-implicit; 3 steps, Uintah's advection) against sus run with its
    CGSolver (data/sus_stagnationPoint_implicit.npz, read as above from
    `sus stagnationPoint_implicit.ups` with <Solver type="CGSolver"/>). The steps agree to the
    pressure solves' tolerance (1e-10 absolute): delT from the equilibration's sound speed as
    Uintah's (measured: times 4.6e-11, press 8.5e-13, vel 3.6e-10 of 2 m/s, tracer positions
    2.4e-13 m, clone-press 9e-13 after step 3)."""
    from framework.archiver import DataArchive
    from framework.controller import Controller
    sus = np.load(DATA / "sus_stagnationPoint_implicit.npz")
    c = Controller(str(DECK.with_name("stagnationPoint_implicit.ups")), quiet=True, filebase=str(tmp_path / "i.uda"))
    c.run()
    da = DataArchive(c.archiver.dir)
    assert np.allclose(da.times[1:3], sus["times"][:2], rtol=1e-15, atol=0)
    assert da.times[3] == pytest.approx(sus["times"][2], rel=1e-9)
    for k, (rp, av) in enumerate(((1e-13, 1e-8), (1e-11, 1e-8), (1e-11, 1e-8))):
        p = da.read("press_CC", 0, k + 1)[0]
        v = da.read("vel_CC", 0, k + 1)[0][..., :2].reshape(-1, 2)
        assert np.allclose([p.min(), p.max()], sus["press_range"][k], rtol=rp, atol=0), k
        assert np.allclose([v.min(0), v.max(0)], sus["vel_xy_range"][k], rtol=0, atol=av), k
    assert np.allclose(da.reduction("totalSum_scalar-f")[1][:3], sus["totalSum_f"], rtol=1e-11)
    counts = [len(da.particles(0, k + 1)["p.particleID"]) for k in range(3)]
    assert counts == sus["n_particles"].tolist() == [2560] * 3
    P = da.particles(0, -1)
    order = np.argsort(P["p.particleID"])[::20]
    assert np.array_equal(P["p.particleID"][order], sus["ids"])
    assert np.allclose(P["p.x"][order], sus["x"], rtol=0, atol=1e-11)
    assert np.allclose(P["p.clone-press_CC"][order], sus["clone_press"], rtol=1e-12, atol=0)
