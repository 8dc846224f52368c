"""Uintah's Brittle damage model (components/mpm/constitutive/damage.py): its law, Uintah's sus.

Uintah's const_test_brittle_damage.ups (tests/mpm/uintah_reference/) stretches one
comp_neo_hook particle until its Brittle damage grows. sus refuses that deck as it is (no
<erosion> beside the damage model), and so does pysus; with <erosion algorithm="none"/> added
sus runs it, and the values it wrote (every 50th of its first 800 steps: time, p.stress,
p.damage, p.epsf of material 1, read from the uda's binary files) are in
tests/mpm/data/sus_const_test_brittle_damage.npz.
"""
import pathlib

import numpy as np
import pytest

from components.mpm.constitutive import comp_neo_hook, damage
from framework.problemspec import InputError

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
