"""MPM particle temperature and explicit heat conduction (components/mpm/thermal.py).

Exact solution: in an insulated bar with diffusivity alpha the amplitude of the mode
cos(pi x / L) decays as exp(-pi^2 alpha t / L^2), and sum m cv T is constant. The
conduction tasks must not depend on the patch layout or the rank count, and must not
run at all in a deck that does not ask for them. Against Uintah's sus: heatcond2mat with
conduction (its grad T_p lags a step, as Uintah's p.temperatureGradient).
<MPM><conduction_gradient>current takes grad T_p from this step's g.temperature instead:
the bar's decay as accurate as before the lag, at twice the step.
"""
import os

import numpy as np
import pytest

from framework.archiver import DataArchive
from framework.problemspec import InputError
from tests.conftest import pysus_ranks, pysus_runs, run_deck

from .helpers import MPM_INPUTS, deck_text, run

BAR = MPM_INPUTS / "heat_conduction_bar.ups"
HERE = os.path.dirname(__file__)


def _mode(p):
    """Amplitude of cos(pi x) in T - 300 (mass-weighted quadrature over the particles)."""
    x, T, m = p["p.x"][:, 0], p["p.temperature"], p["p.mass"]
    return 2.0 * np.sum(m * (T - 300.0) * np.cos(np.pi * x)) / np.sum(m)


def _with_gradient(text, gradient):
    """The deck with <MPM><conduction_gradient> set (left out for Uintah's default, previous)."""
    flag = "<DoExplicitHeatConduction>true</DoExplicitHeatConduction>"
    assert flag in text
    return text if gradient is None else text.replace(
        flag, f"{flag}<conduction_gradient>{gradient}</conduction_gradient>")


@pytest.mark.parametrize("gradient, tol, steps", [(None, 4e-3, 456), ("current", 1e-3, 228)])
def test_cosine_mode_decays_at_the_exact_rate(tmp_path, gradient, tol, steps):
    """Within tol of the exact decay over 0.1 s. Uintah's last-step grad T_p (the default):
    measured 3.7e-3 at 0.9 of its stable step rho cv / (4 k / dx^2), 456 steps; 2.8e-3 at a
    tenth of it (16 slabs' spatial error of ~2.5e-3 plus the first-order lag of grad T, which
    the step with this step's gradient partly cancels). <conduction_gradient>current: 4.4e-4 at
    0.9 of the Euler limit rho cv / (2 k / dx^2), 228 steps (the figures before the lag)."""
    ctl = run_deck(_with_gradient(deck_text(BAR), gradient), tmp_path)
    da = DataArchive(ctl.archiver.dir)
    assert len(ctl.step_times) == steps
    a0 = _mode(da.particles(0, 0))
    assert abs(a0 - 10.0) < 0.02                     # the 16 slabs lay the mode
    for i in range(1, len(da.times)):
        exact = a0 * np.exp(-np.pi ** 2 * da.times[i])
        assert abs(_mode(da.particles(0, i)) / exact - 1.0) < tol, da.times[i]
    assert da.times[-1] > 0.099
    t, e = da.reduction("ThermalEnergy")
    assert np.all(np.abs(np.asarray(e) / e[0] - 1.0) < 1e-12)


def _square(patches, gimp=False):
    """2D: a square plate [0,1]^2 in four quadrants at 280, 320, 310, 290 K, insulated."""
    quads = [((0, 0), 280.0), ((0.5, 0), 320.0), ((0, 0.5), 310.0), ((0.5, 0.5), 290.0)]
    objs = "".join(f"""<geom_object><box label="q{k}"><min>[{x},{y},0]</min><max>[{x + 0.5},{y + 0.5},0.01]</max></box>
        <res>[2,2,1]</res><velocity>[0,0,0]</velocity><temperature>{T}</temperature></geom_object>"""
                   for k, ((x, y), T) in enumerate(quads))
    text = deck_text(BAR, maxTime="0.02", resolution="[16,16,1]", patches=patches,
                     outputInterval="0.01", interpolator="gimp" if gimp else "linear",
                     extraCells="[1,1,0]" if gimp else "[0,0,0]")
    text = text.replace("<upper>[1.0,0.01,0.01]</upper>", "<upper>[1.0,1.0,0.01]</upper>")
    if gimp:        # p2g with the volume: inputs/MPMICE/pressurized_cylinder.ups's GIMP variant, none of its own
        text = text.replace('<save label="p.x"/>', '<save label="p.x"/><save label="g.volume"/>')
    start, end = text.index("<geom_object>"), text.rindex("</geom_object>") + len("</geom_object>")
    return text[:start] + objs + text[end:]


@pytest.mark.parametrize("gimp, gradient", [(False, None), (True, None), (True, "current")])
def test_plate_conserves_heat_and_is_independent_of_patches(tmp_path, gimp, gradient):
    runs = {}
    for patches in ("[1,1,1]", "[2,3,1]"):
        ctl = run_deck(_with_gradient(_square(patches, gimp), gradient), tmp_path, f"p{patches[1]}{patches[3]}")
        runs[patches] = DataArchive(ctl.archiver.dir)
    a, b = (runs[k].particles(0, -1) for k in ("[1,1,1]", "[2,3,1]"))
    oa, ob = np.argsort(a["p.particleID"]), np.argsort(b["p.particleID"])
    assert np.array_equal(a["p.temperature"][oa], b["p.temperature"][ob])
    T = a["p.temperature"]
    assert 280.0 < T.min() and T.max() < 320.0 and T.max() - T.min() < 39.0   # heat flowed, no overshoot
    t, e = runs["[1,1,1]"].reduction("ThermalEnergy")
    assert abs(e[-1] / e[0] - 1.0) < 1e-12
    assert abs(e[0] - 300.0 * 1.0 * 1.0 * 0.01) < 1e-9      # sum m cv T = rho V cv <T>


RANK_CASES = [(None, False), ("current", True)]


@pytest.fixture(scope="module")
def on_ranks(tmp_path_factory):
    """Each case's plate on 1 rank in this process, then on 2 ranks, both in one mpiexec launch:
    the directory of the udas and each run's (return code, stderr)."""
    d = tmp_path_factory.mktemp("thermal_ranks")
    for i, (gradient, gimp) in enumerate(RANK_CASES):
        (d / f"plate{i}.ups").write_text(_with_gradient(_square("[2,2,1]", gimp), gradient))
    runs = [(i, n) for i in range(len(RANK_CASES)) for n in (1, 2)]
    out = pysus_runs([((d / f"plate{i}.ups", "--filebase", d / f"p{i}r{n}.uda"), n) for i, n in runs], d)
    return d, dict(zip(runs, out))


@pytest.mark.parametrize("gradient, gimp", RANK_CASES)
def test_two_ranks_bitwise(on_ranks, gradient, gimp):
    """1 and 2 ranks agree bitwise; with <conduction_gradient>current and GIMP the grad T of a
    ghost particle reads g.temperature 4 nodes beyond the patch, from the other rank."""
    d, runs = on_ranks
    i = RANK_CASES.index((gradient, gimp))
    out = {}
    for n in (1, 2):
        rc, err = runs[i, n]
        assert rc == 0, err[-2000:]
        out[n] = DataArchive(d / f"p{i}r{n}.uda").particles(0, -1)
    oa, ob = (np.argsort(out[n]["p.particleID"]) for n in (1, 2))
    assert np.array_equal(out[1]["p.temperature"][oa], out[2]["p.temperature"][ob])


def _graph(tmp_path, text):
    path = tmp_path / "g.ups"
    path.write_text(text)
    r = pysus_ranks("--graph", path)
    assert r.returncode == 0, r.stderr
    return r.stdout


def test_tasks_only_when_asked(tmp_path):
    off = deck_text(BAR, DoExplicitHeatConduction="false")
    off = _graph(tmp_path, off.replace('<save label="p.temperature"/>', "").replace('<save label="ThermalEnergy"/>', ""))
    assert "Temperature" not in off and "HeatRate" not in off
    no_k = _graph(tmp_path, deck_text(BAR, thermal_conductivity="0.0"))
    assert "MPM::updateParticleTemperature" in no_k and "computeInternalHeatRate" not in no_k
    on = _graph(tmp_path, deck_text(BAR))
    assert "MPM::computeInternalHeatRate" in on


def test_current_gradient_reads_the_nodes_beyond_the_patch(tmp_path):
    """<conduction_gradient>current: computeInternalHeatRate requires g.temperature 2 ng nodes
    around the patch (GIMP: 4) instead of the carried p.temperatureGradient, which no task
    computes."""
    gimp = deck_text(BAR, interpolator="gimp", extraCells="[1,0,0]")
    current = _graph(tmp_path, _with_gradient(gimp, "current"))
    assert "g.temperature(new m0 +4AroundCells)" in current
    assert "temperatureGradient" not in current
    previous = _graph(tmp_path, gimp)
    assert "p.temperatureGradient(old m0 +2AroundNodes)" in previous
    assert "g.temperature(new m0 +4AroundCells)" not in previous


def test_conduction_gradient_refuses_other_values(tmp_path):
    """A one-line error naming the file, the line and the accepted values."""
    path = tmp_path / "bar.ups"
    text = _with_gradient(deck_text(BAR), "later")
    path.write_text(text)
    line = text[:text.index("<conduction_gradient>later")].count("\n") + 1
    r = pysus_ranks("-validate", path)
    assert r.returncode != 0
    assert r.stderr.strip() == (f"pysus: error: {path}:{line}: <Uintah_specification/MPM/conduction_gradient> "
                                "value 'later' is not accepted; accepted: previous, current")


def test_conduction_needs_a_specific_heat(tmp_path):
    with pytest.raises(InputError, match="specific_heat"):
        run_deck(deck_text(BAR, specific_heat="0.0"), tmp_path)


@pytest.mark.parametrize("gradient", [None, "current"])
def test_restart_carries_the_temperature(tmp_path, gradient):
    """A restart from the last checkpoint (every 100 steps) ends bitwise as the run through (the
    default carries and checkpoints p.temperatureGradient; current carries no gradient)."""
    path = tmp_path / "bar.ups"
    path.write_text(_with_gradient(deck_text(BAR), gradient).replace('<save label="ThermalEnergy"/>',
                                           '<save label="ThermalEnergy"/><checkpoint timestepInterval="100"/>'))
    r = pysus_ranks(path, "--filebase", tmp_path / "a.uda")
    assert r.returncode == 0, r.stderr[-2000:]
    r = pysus_ranks("-restart", tmp_path / "a.uda", "--filebase", tmp_path / "b.uda")
    assert r.returncode == 0, r.stderr[-2000:]
    a, b = DataArchive(tmp_path / "a.uda"), DataArchive(tmp_path / "b.uda")
    assert b.times[-1] == a.times[-1]
    pa, pb = a.particles(0, -1), b.particles(0, -1)
    oa, ob = np.argsort(pa["p.particleID"]), np.argsort(pb["p.particleID"])
    assert np.array_equal(pa["p.temperature"][oa], pb["p.temperature"][ob])


@pytest.mark.parametrize("kind, deck", [("gimp", "heatcond2mat_k.ups"), ("cpdi", "heatcond2mat_cpdi.ups")])
def test_conduction_equals_uintahs_sus(tmp_path, kind, deck):
    """p.temperature of both bars after each of 5 steps against sus (tests/mpm/data/
    sus_heatcond2mat_k.npz, read from sus's uda; gimp: heatcond2mat_k.ups, thermal_conductivity
    237 and 23.7; cpdi: heatcond2mat_cpdi.ups, 100) with conduction, thermal contact and
    Temperature BCs. grad T_p is the last step's, so step 1 conducts nothing; with this step's
    gradient the bars were 3.9 K (gimp) and 16.5 K (cpdi) off sus at step 1. CPDI agrees to
    3e-12 K, with p.temperatureGradient to 2e-14 of its largest value. GIMP agrees to 2e-13 K
    for 2 steps, then to 3e-3 K: sus's GIMP weights give the cold bar's last particles
    (x/dx = 9.750000000000002) a node beyond the bar with weight 3e-30 and gradient 4e-12,
    whose rate ~ gradient/weight brings an O(1) share into those particles' grad T (358 K/m
    of 8951 at step 2); pysus's weights there are zero."""
    ref = np.load(os.path.join(HERE, "data", "sus_heatcond2mat_k.npz"))
    text = open(os.path.join(HERE, deck)).read().replace("<max_Timesteps>3</max_Timesteps>",
                                                         "<max_Timesteps>5</max_Timesteps>")
    save = '<save label = "p.temperatureGradient"/>'
    if save not in text:
        text = text.replace('<save label = "p.temperature"/>', '<save label = "p.temperature"/>' + save)
    _, da = run(text, tmp_path)
    worst = {}
    for step in range(1, 6):
        assert da.times[step] == pytest.approx(float(ref[f"{kind}_time_step{step}"]), rel=1e-12)
        for m in (0, 1):
            p = da.particles(m, step)
            o = np.lexsort(np.round(p["p.x"], 7).T)
            assert np.abs(p["p.x"][o] - ref[f"{kind}_x{m}"]).max() < 1e-12
            worst[step, m] = np.abs(p["p.temperature"][o] - ref[f"{kind}_temperature{m}_step{step}"]).max()
            if step == 5 and kind == "cpdi":
                g = ref[f"cpdi_temperatureGradient{m}_step5"]
                assert np.abs(p["p.temperatureGradient"][o] - g).max() < 1e-12 * np.abs(g).max()
    for (step, m), dT in worst.items():
        assert dT < (1e-10 if kind == "cpdi" or step <= 2 else 5e-3), (step, m, dT)
    assert da.particles(1, 1)["p.temperature"].min() == pytest.approx(100.0)     # step 1: no conduction
    assert da.particles(1, 5)["p.temperature"].min() > 106.0                     # then the cold bar warms
