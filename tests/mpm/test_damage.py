"""Uintah's Brittle damage model (components/mpm/constitutive/damage.py): its law, Uintah's sus.

Uintah's const_test_brittle_damage.ups (tests/mpm/uintah_reference/) stretches one
comp_neo_hook particle until its Brittle damage grows. sus refuses that deck as it is (no
<erosion> beside the damage model), and so does pysus; with <erosion algorithm="none"/> added
sus runs it, and the values it wrote (every 50th of its first 800 steps: time, p.stress,
p.damage, p.epsf of material 1, read from the uda's binary files) are in
tests/mpm/data/sus_const_test_brittle_damage.npz.
"""
import pathlib
import re

import numpy as np
import pytest

from components.mpm.constitutive import comp_neo_hook, damage
from framework.archiver import DataArchive
from framework.problemspec import InputError
from tests.conftest import pysus

from .helpers import run

HERE = pathlib.Path(__file__).parent
DECK = HERE / "uintah_reference" / "const_test_brittle_damage.ups"
SUS = HERE / "data" / "sus_const_test_brittle_damage.npz"
K, MU = 8.9e9, 3.52e9                                   # the deck's comp_neo_hook
R0, GF, D, DMAX = 57.0, 11.2, 0.1, 0.1                  # and its Brittle damage
E = 9 * K * MU / (3 * K + MU)
BRITTLE = damage.Brittle(R0, GF, D, DMAX, False, 1.0, False, E)


def stretch(F, d_old=0.0, r_old=R0, vol=1e-6, model=BRITTLE):
    """The comp_neo_hook stress at F, then the damage; (stress, r, d)."""
    s, e = np.zeros((1, 3, 3)), np.zeros(1)
    comp_neo_hook.update(comp_neo_hook.Params(K, MU), None, None, F[None], np.array([vol]), np.ones(1),
                         np.zeros((1, 3)), 0.0, None, s, e)
    undamaged = s[0].copy()
    r, d = np.zeros(1), np.zeros(1)
    model.apply(F[None], np.array([vol]), s, (np.array([r_old]), np.array([d_old])), (r, d))
    return s[0], undamaged, r[0], d[0]


def expected_damage(tau, vol):
    C = R0 * vol ** (1 / 3) * (1 + D) / (GF * D) * np.log(1 + D)
    return 0.999 / D * ((1 + D) / (1 + D * np.exp(-C * (tau - R0))) - 1)


def test_law_in_tension():
    """Uniaxial stretch l: the Almansi strain's largest eigenvalue is (1 - 1/l^2)/2, tau =
    sqrt(E) of it; past r0 the damage is the softening law's (below the increment cap) and the
    stress is scaled by 1 - d; below r0 nothing changes."""
    for l, damaged in ((1.0005, False), (1.0012, True), (1.0013, True)):
        F = np.diag([1.0, 1.0, l])
        s, s0, r, d = stretch(F)
        tau = np.sqrt(E) * 0.5 * (1 - 1 / l ** 2)
        if not damaged:
            assert tau < R0 and d == 0.0 and r == R0 and np.array_equal(s, s0)
            continue
        assert tau > R0
        assert r == pytest.approx(tau, rel=1e-12)
        assert d == pytest.approx(min(expected_damage(tau, 1e-6), DMAX), rel=1e-12)
        assert np.allclose(s, (1 - d) * s0, rtol=1e-14, atol=0)


def test_increment_cap_threshold_and_compression():
    """A jump far past the threshold gives at most the increment; unloading below the
    threshold keeps the damage and scales by 1 - d; compression of a damaged particle too; an
    undamaged particle in compression is untouched."""
    F = np.diag([1.0, 1.0, 1.01])
    _, _, r, d = stretch(F, d_old=0.2)
    assert d == pytest.approx(0.3, rel=1e-14) and r > R0
    s, s0, r2, d2 = stretch(np.diag([1.0, 1.0, 1.0002]), d_old=0.3, r_old=r)
    assert d2 == 0.3 and r2 == r and np.allclose(s, 0.7 * s0, rtol=1e-14, atol=0)
    s, s0, r2, d2 = stretch(np.diag([0.999, 0.999, 0.999]), d_old=0.3, r_old=r)
    assert np.trace(s0) < 0 and d2 == 0.3 and np.allclose(s, 0.7 * s0, rtol=1e-14, atol=0)
    s, s0, _, d2 = stretch(np.diag([0.999, 0.999, 0.999]))
    assert d2 == 0.0 and np.array_equal(s, s0)


def test_recovery_flags_the_damage():
    """allowRecovery: a damaged particle unloaded is scaled by the recovery coefficient and
    1 - d and its damage turns negative (Uintah's flag)."""
    rec = damage.Brittle(R0, GF, D, DMAX, True, 0.5, False, E)
    s, s0, _, d = stretch(np.diag([1.0, 1.0, 1.0002]), d_old=0.3, r_old=70.0, model=rec)
    assert d == -0.3 and np.allclose(s, 0.5 * s0, rtol=1e-14, atol=0)


def test_max_eigenvalue():
    rng = np.random.default_rng(5)
    for _ in range(50):
        A = rng.normal(size=(3, 3))
        A = A + A.T
        assert damage.max_eigenvalue_sym(A[0, 0], A[1, 1], A[2, 2], A[0, 1], A[0, 2], A[1, 2]) == pytest.approx(
            np.linalg.eigvalsh(A)[-1], rel=1e-12, abs=1e-12)
    assert damage.max_eigenvalue_sym(2.0, 2.0, 2.0, 0.0, 0.0, 0.0) == 2.0


def test_deck_unchanged_is_refused_as_by_sus(tmp_path):
    with pytest.raises(InputError) as e:
        run(open(DECK).read(), tmp_path)
    msg = str(e.value)
    assert "\n" not in msg and ".ups:" in msg
    assert "erosion" in msg and "damage_model" in msg, msg


@pytest.mark.parametrize("old,new,words", [
    ('type="Brittle"', 'type="Brittl"', ("damage_model", "Brittle")),
    ("<brittle_damage_constant_D>           0.1", "<brittle_damage_constant_D> -0.1", ("brittle_damage_constant_D",)),
    ("<brittle_damage_fracture_energy>      11.2", "<brittle_damage_fracture_energy> x",
     ("brittle_damage_fracture_energy",)),
    ('<erosion algorithm="none"/>', '<erosion algorithm="Zero"/>', ("algorithm", "ZeroStress")),
])
def test_bad_input_is_one_line(tmp_path, old, new, words):
    text = open(DECK).read().replace('<damage_model type="Brittle">',
                                     '<erosion algorithm="none"/><damage_model type="Brittle">')
    assert old in text
    with pytest.raises(InputError) as e:
        run(text.replace(old, new), tmp_path)
    msg = str(e.value)
    assert "\n" not in msg and ".ups:" in msg
    for w in words:
        assert w in msg, msg


def test_const_test_brittle_damage_as_sus(tmp_path):
    """With <erosion algorithm="none"/> added and Uintah's USL stress update: sus's 800 steps
    (the same times) and, every 50th, sus's p.stress (measured: 2e-7 relative), p.damage
    (1e-7) and p.epsf, through the onset of damage (step ~590) and its growth to 0.6."""
    text = open(DECK).read()
    for old, new in (('<damage_model type="Brittle">', '<erosion algorithm="none"/><damage_model type="Brittle">'),
                     ("<time_integrator>explicit</time_integrator>",
                      "<time_integrator>explicit</time_integrator><stress_update>usl</stress_update>"),
                     ("<maxTime>0.004</maxTime>", "<maxTime>0.004</maxTime><max_Timesteps>800</max_Timesteps>"),
                     ("<outputInterval>1.0e-4</outputInterval>", "<outputTimestepInterval>50</outputTimestepInterval>"),
                     ('<save label = "p.damage"/>', '<save label = "p.damage"/><save label = "p.epsf"/>')):
        assert old in text
        text = text.replace(old, new)
    _, da = run(text, tmp_path)
    sus = np.load(SUS)
    assert np.array_equal(da.timesteps[1:], sus["timestep"])
    assert np.allclose(da.times[1:], sus["time"], rtol=1e-10, atol=0)
    p = [da.particles(1, k) for k in range(1, len(da.timesteps))]
    s = np.array([q["p.stress"][0] for q in p])
    assert np.all(np.abs(s - sus["stress"]).max(axis=(1, 2)) < 5e-7 * np.abs(sus["stress"]).max(axis=(1, 2)))
    assert np.allclose([q["p.damage"][0] for q in p], sus["damage"], rtol=0, atol=5e-7)
    assert np.allclose([q["p.epsf"][0] for q in p], sus["epsf"], rtol=1e-7, atol=0)
    assert sus["damage"][10] == 0.0 and sus["damage"][-1] > 0.6


# -- ThresholdVar and erosion -----------------------------------------------------------
DISK = HERE / "uintah_reference" / "disk_UCNHVar.ups"
SUS_TV = HERE / "data" / "sus_disk_UCNHVar_threshold.npz"


def threshold(erosion, criterion=0, char_time=1e-99):
    return damage.ThresholdVar((0.0, 1.0), (7.0e4, 7.0e3), criterion, True, damage.EROSION[erosion], char_time)


def tv_step(model, stress, F, loc=0.0, tloc=-1e99, time=1.0):
    s = np.array([stress], float)
    state = (np.array([model.means[0]]), np.array([loc]), np.array([tloc]))
    new = (np.zeros(1), np.zeros(1), np.zeros(1))
    model.apply(np.array([F], float), np.ones(1), s, state, new, np.zeros(1), time)
    return s[0], new[1][0], new[2][0]


def test_threshold_localizes_and_zero_stress_erodes():
    """A particle whose largest principal stress passes its threshold localizes at the step's
    start time and keeps its stress that step (D = exp(0)); the next step ZeroStress takes it
    (D = exp(-dt/1e-99)); below the threshold nothing happens; with a char_time the stress
    decays as exp(-(t - t_loc)/char_time)."""
    m = threshold("ZeroStress")
    shear = np.array([[0.0, 8e4, 0], [8e4, 0, 0], [0, 0, -1e5]])          # principal: 8e4, -8e4, -1e5
    s, loc, tl = tv_step(m, shear, np.eye(3), time=2.0)
    assert loc == 1.0 and tl == 2.0 and np.array_equal(s, shear)
    s, loc, tl = tv_step(m, shear, np.eye(3), loc=1.0, tloc=2.0, time=2.5)
    assert loc == 1.0 and tl == 2.0 and np.array_equal(s, 0 * shear)
    s, loc, _ = tv_step(m, 0.8 * shear, np.eye(3))
    assert loc == 0.0 and np.array_equal(s, 0.8 * shear)
    s, _, _ = tv_step(threshold("ZeroStress", char_time=0.25), shear, np.eye(3), loc=1.0, tloc=2.0, time=2.5)
    assert np.allclose(s, np.exp(-2.0) * shear, rtol=1e-15)


def test_erosion_algorithms_of_a_localized_particle():
    """AllowNoShear keeps the pressure only; AllowNoTension too in compression, in tension it
    decays as ZeroStress; PreserveStress and none keep the stress."""
    comp = np.array([[-3e5, 1e5, 0], [1e5, -1e5, 0], [0, 0, -2e5]])
    p = np.trace(comp) / 3
    for name, expect in (("AllowNoShear", p * np.eye(3)), ("AllowNoTension", p * np.eye(3)),
                         ("PreserveStress", comp), ("none", comp)):
        s, _, _ = tv_step(threshold(name), comp, np.eye(3), loc=1.0, tloc=0.5)
        assert np.allclose(s, expect, rtol=1e-15), name
    s, _, _ = tv_step(threshold("AllowNoTension"), -comp, np.eye(3), loc=1.0, tloc=0.5)
    assert np.array_equal(s, 0 * comp)


def test_threshold_reads_one_mean(tmp_path):
    """type="Threshold": one <failure_mean> for every particle, as a one-entry ThresholdVar. USL,
    as every run of the deck here (one compiled CPDI 3D update, not two)."""
    text = re.sub(r'<damage_model type="Brittle">.*?</damage_model>',
                  '<erosion algorithm="ZeroStress"/><damage_model type="Threshold"><failure_criteria>'
                  'MaximumPrincipalStress</failure_criteria><failure_mean>1.5e6</failure_mean></damage_model>',
                  open(DECK).read(), flags=re.S)
    text = text.replace('<save label = "p.damage"/>', '<save label = "p.localizedMPM"/>')
    text = text.replace("<time_integrator>explicit</time_integrator>",
                        "<time_integrator>explicit</time_integrator><stress_update>usl</stress_update>")
    assert "<stress_update>usl" in text
    text = text.replace("<maxTime>0.004</maxTime>", "<maxTime>0.004</maxTime><max_Timesteps>300</max_Timesteps>")
    text = text.replace("<outputInterval>1.0e-4</outputInterval>",
                        "<outputTimestepInterval>100</outputTimestepInterval>")
    _, da = run(text, tmp_path)
    loc = [da.particles(1, k)["p.localizedMPM"][0] for k in range(1, 4)]
    s = [da.particles(1, k)["p.stress"][0, 2, 2] for k in range(1, 4)]
    # sigma_zz passes 1.5e6 at step 156 (155 with MUSL)
    assert loc == [0.0, 1.0, 1.0] and s[0] > 0 and s[1] == 0.0 and s[2] == 0.0


def test_strain_criterion_and_kinematics():
    """MaximumPrincipalStrain: the Almansi strain (1 - 1/l^2)/2 of a stretch l against the
    threshold; ZeroStress keeps F^n for a localized particle, AllowNoShear makes F = J^(1/3) I
    and L its trace part."""
    m = damage.ThresholdVar((0.0,), (0.1,), 1, True, damage.EROSION["ZeroStress"], 1e-99)
    _, loc, _ = tv_step(m, np.zeros((3, 3)), np.diag([1.0, 1.0, 1.2]))       # (1 - 1/1.44)/2 = 0.153
    assert loc == 1.0
    _, loc, _ = tv_step(m, np.zeros((3, 3)), np.diag([1.0, 1.0, 1.1]))       # 0.087
    assert loc == 0.0
    F_old = np.array([np.eye(3), np.eye(3)])
    F_new = np.array([np.diag([1.1, 1.0, 0.9]), np.diag([1.1, 1.0, 0.9])])
    Lg = np.array([np.diag([1.0, 2.0, 6.0])] * 2)
    L2 = m.erode_kinematics(np.array([1.0, 0.0]), F_old, F_new, Lg)
    assert np.array_equal(F_new[0], np.eye(3)) and np.array_equal(F_new[1], np.diag([1.1, 1.0, 0.9]))
    assert np.array_equal(L2[0], np.zeros((3, 3))) and np.array_equal(L2[1], Lg[1]) and Lg[0, 2, 2] == 6.0
    ns = damage.ThresholdVar((0.0,), (0.1,), 1, True, damage.EROSION["AllowNoShear"], 1e-99)
    F_new = np.array([np.diag([1.1, 1.0, 0.9])])
    L2 = ns.erode_kinematics(np.array([1.0]), F_old[:1], F_new, Lg[:1])
    assert np.allclose(F_new[0], np.cbrt(0.99) * np.eye(3), rtol=1e-15) and np.allclose(L2[0], 3 * np.eye(3))


def disk_with_threshold(steps=300, every=10):
    """disk_UCNHVar.ups with ThresholdVar's constant distribution (its gauss draws and the
    gradient-enhanced velocity projection: test_damage_draws.py), without the projection, with
    GIMP and both objects at 10 m/s (test_ucnh_var.py says why), sus's USL stress update."""
    text = open(DISK).read()
    for old, new in (("<UseGradientEnhancedVelocityProjection>true\n                         "
                      "</UseGradientEnhancedVelocityProjection>", ""),
                     ("<failure_distrib>gauss     </failure_distrib>", "<failure_distrib>constant</failure_distrib>"),
                     ("fast_cpdi", "gimp"),
                     ("<time_integrator>explicit  </time_integrator>",
                      "<time_integrator>explicit</time_integrator><stress_update>usl</stress_update>"),
                     ("<maxTime>0.30</maxTime>", f"<maxTime>0.30</maxTime><max_Timesteps>{steps}</max_Timesteps>"),
                     ("<outputInterval>.01</outputInterval>",
                      f"<outputTimestepInterval>{every}</outputTimestepInterval>"),
                     ('<save label = "p.localizedMPM"/>',
                      '<save label = "p.localizedMPM"/><save label = "p.timeofloc"/>')):
        assert old in text, old
        text = text.replace(old, new)
    text = text.replace("<velocity>[1.0,0.0,0]</velocity>", "<velocity>[10.0,0.0,0]</velocity>")
    return text


@pytest.fixture(scope="module")
def disk_threshold(tmp_path_factory):
    """disk_with_threshold() run here, 300 steps written every 10 (read by two tests)."""
    return run(disk_with_threshold(), tmp_path_factory.mktemp("disk"))[1]


def test_disk_UCNHVar_threshold_as_sus(disk_threshold):
    """UCNHVar with ThresholdVar damage and ZeroStress erosion, 300 steps: the particles sus
    localized (14 of 1612, from step 230, on its maximum principal stress criterion) and
    when, sus's count every 10 steps, p.stress of every tenth particle at steps 250 and 300
    (measured: 4e-7 of the largest) and StrainEnergy every step (7e-10, localized particles
    left out)."""
    da = disk_threshold
    sus = np.load(SUS_TV)
    steps = list(da.timesteps)
    p40 = da.particles(0, steps.index(40))
    order = np.lexsort(np.round(p40["p.x"], 9).T[::-1])
    assert np.abs(p40["p.x"][order][::10] - sus["x40"]).max() < 1e-14
    x_of = dict(zip(p40["p.particleID"], p40["p.x"]))
    count = [int(da.particles(0, steps.index(s))["p.localizedMPM"].sum()) for s in sus["count_step"]]
    assert count == list(sus["count"])
    ids = p40["p.particleID"][order][::10]
    for k, step in enumerate(sus["timestep"]):
        p = da.particles(0, steps.index(step))
        assert da.times[steps.index(step)] == pytest.approx(sus["time"][k], rel=1e-11)
        at = {v: i for i, v in enumerate(p["p.particleID"])}
        s = p["p.stress"][[at[v] for v in ids]]
        assert np.abs(s - sus["stress"][k]).max() < 2e-6 * np.abs(sus["stress"][k]).max()
    loc = p["p.localizedMPM"] != 0
    x_loc = np.array([x_of[v] for v in p["p.particleID"][loc]])
    o1, o2 = np.lexsort(np.round(x_loc, 9).T[::-1]), np.lexsort(np.round(sus["x40_localized"], 9).T[::-1])
    assert np.abs(x_loc[o1] - sus["x40_localized"][o2]).max() < 1e-14
    assert np.allclose(p["p.timeofloc"][loc][o1], sus["timeofloc"][o2], rtol=1e-11)
    t, se = da.reduction("StrainEnergy")
    assert np.allclose(t[1:], sus["se_time"], rtol=1e-11)
    assert np.allclose(se[1:], sus["StrainEnergy"], rtol=1e-8, atol=1e-9 * np.max(sus["StrainEnergy"]))


def test_erosion_without_damage_changes_nothing(tmp_path):
    """An <erosion> without a damage model (as in Uintah's TBurner_2dRT) is read and, as in
    Uintah where then no particle localizes, changes nothing. (USL, as the other runs of the deck here.)"""
    text = re.sub(r'<damage_model type="Brittle">.*?</damage_model>', "", open(DECK).read(), flags=re.S)
    text = text.replace("<time_integrator>explicit</time_integrator>",
                        "<time_integrator>explicit</time_integrator><stress_update>usl</stress_update>")
    assert "<stress_update>usl" in text
    text = text.replace("<maxTime>0.004</maxTime>", "<maxTime>0.004</maxTime><max_Timesteps>20</max_Timesteps>")
    text = text.replace('<save label = "p.damage"/>', "").replace(
        "<outputInterval>1.0e-4</outputInterval>", "<outputTimestepInterval>20</outputTimestepInterval>")
    _, plain = run(text, tmp_path / "plain")
    _, eroded = run(text.replace('<specific_heat>5</specific_heat>\n              <geom_object>\n'
                                 '                  <box label = "box">',
                                 '<specific_heat>5</specific_heat><erosion algorithm="ZeroStress"/>\n'
                                 '              <geom_object>\n                  <box label = "box">'),
                    tmp_path / "eroded")
    assert np.array_equal(eroded.times, plain.times) and plain.timesteps[-1] == 20
    assert np.array_equal(eroded.particles(1, -1)["p.stress"], plain.particles(1, -1)["p.stress"])
    assert np.abs(plain.particles(1, -1)["p.stress"]).max() > 1e5


def test_damage_state_on_two_ranks(tmp_path, disk_threshold):
    """The damage state travels with its particles: disk_UCNHVar with ThresholdVar (4 patches)
    on 1 rank (the run of disk_threshold) and 2 MPI ranks, 280 steps (12 localized), gives
    bitwise the same p.stress, p.localizedMPM and p.timeofloc per particle."""
    path = tmp_path / "disk.ups"
    path.write_text(disk_with_threshold(steps=280, every=140))
    r = pysus(path, "--filebase", tmp_path / "disk_2.uda", np_=2, timeout=300)
    assert r.returncode == 0, r.stderr[-2000:]
    two = DataArchive(tmp_path / "disk_2.uda")
    assert two.timesteps[-1] == 280
    out = {}
    one = disk_threshold.particles(0, list(disk_threshold.timesteps).index(280))
    for n, p in ((1, one), (2, two.particles(0, -1))):
        o = np.argsort(p["p.particleID"])
        out[n] = {k: p[k][o] for k in ("p.particleID", "p.stress", "p.localizedMPM", "p.timeofloc")}
    assert out[1]["p.localizedMPM"].sum() == 12
    for k in out[1]:
        assert np.array_equal(out[1][k], out[2][k]), k
