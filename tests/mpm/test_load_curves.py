"""Load-curve BCs (pressure on a cylinder end, torque on its side, a heat flux) and a rigid
body that spins (<contact type="specified"><include_rotation>): Uintah's
loadCurve_press-torque and loadCurve_heatFlux decks, made small (tests/mpm/load_curve_*.ups
say how), against sus and against the loads' own totals."""
import os

import numpy as np
import pytest

from tests.mpm.helpers import run

HERE = os.path.dirname(__file__)
OMEGA = 50.0                     # rad/s about z, spin.txt
R = 0.5                          # the sample cylinder's radius
LOAD = [(0.0, -0.1), (0.0002, -1.0e5), (0.01001, -1.1e5), (0.015001, -1.2e5)]   # both curves


@pytest.fixture(scope="module")
def spin(tmp_path_factory):
    d = tmp_path_factory.mktemp("spin")
    (d / "spin.txt").write_text(f"0.0 0 0 0 0 0 0 0 0 {OMEGA}\n9.9 0 0 0 0 0 0 0 0 {OMEGA}\n")
    _, da = run(open(os.path.join(HERE, "load_curve_spin.ups")).read(), d)
    return da, np.load(os.path.join(HERE, "data", "sus_load_curve_spin.npz"))


def _sorted(x, *fields):
    o = np.lexsort(np.round(x, 7).T)
    return [x[o]] + [f[o] for f in fields]


def test_first_step_equals_uintahs_sus(spin):
    """p.x, p.velocity, p.stress of the sample and the spinning stem after step 1 against
    sus on the same deck (measured: 5e-8 m/s on 23 m/s, 5e-4 Pa on 1.8e5 Pa)."""
    da, ref = spin
    assert da.times[1] == pytest.approx(float(ref["time"][0]), rel=1e-12)
    p = da.particles(0, 1)
    x, v, s = _sorted(p["p.x"], p["p.velocity"], p["p.stress"])
    assert len(x) == len(ref["x0"]) == 800
    assert np.abs(x - ref["x0"]).max() < 1e-8
    assert np.abs(v - ref["velocity0"]).max() < 1e-6 * np.abs(ref["velocity0"]).max()
    assert np.abs(s - ref["stress0"]).max() < 1e-6 * np.abs(ref["stress0"]).max()
    q = da.particles(1, 1)
    x1, v1 = _sorted(q["p.x"], q["p.velocity"])
    assert np.abs(x1 - ref["x1"]).max() < 1e-8
    assert np.abs(v1 - ref["velocity1"]).max() < 1e-6 * np.abs(ref["velocity1"]).max()


def test_the_stem_turns_at_omega(spin):
    """Rigid-body rotation about z: every stem particle moves at omega r, tangentially."""
    da, _ = spin
    q = da.particles(1, 1)
    x, v = q["p.x"], q["p.velocity"]
    x0 = x - v * da.times[1]                       # where it started this step
    r = np.hypot(x0[:, 0], x0[:, 1])
    speed = np.hypot(v[:, 0], v[:, 1])
    assert np.allclose(speed, OMEGA * r, rtol=1e-3)
    assert np.abs(v[:, 2]).max() < 1e-9
    assert np.all(x0[:, 0] * v[:, 1] - x0[:, 1] * v[:, 0] > 0)     # counter-clockwise for omega > 0


def test_load_totals_are_p_area_and_the_torque(spin):
    """Step 2's loads act at t = t1: sum of forces = p(t1) pi R^2 along the axis (the end
    cap) and sum of x cross f = -T(t1) z (Uintah's TorqueBC sign); as sus's (its torque
    taken at the step's end positions, which moved over a different step 2 delT)."""
    da, ref = spin
    t1 = da.times[1]
    load = np.interp(t1, *zip(*LOAD))
    p = da.particles(0, 2)
    f, x = p["p.externalforce"], p["p.x"]
    ids = p["p.loadCurveID"]
    assert ids.shape == (800, 3)
    assert set(np.unique(ids)) == {0.0, 1.0, 2.0}
    assert np.count_nonzero(np.any(ids == 1, axis=1) & np.any(ids == 2, axis=1)) > 0   # the top rim carries both
    total = f.sum(axis=0)
    assert total[2] == pytest.approx(load * np.pi * R ** 2, rel=1e-12)
    assert total[2] == pytest.approx(ref["force_total_step2"][2], rel=1e-9)
    assert np.abs(total[:2]).max() < 1e-6
    start = da.particles(0, 1)                    # the loads act at the positions step 2 starts from
    at = dict(zip(start["p.particleID"], start["p.x"]))
    x_start = np.array([at[i] for i in p["p.particleID"]])
    torque_z = np.cross(x_start, f).sum(axis=0)[2]
    assert torque_z == pytest.approx(-load, rel=1e-12)
    assert np.cross(x, f).sum(axis=0)[2] == pytest.approx(ref["torque_total_step2"][2], rel=1e-4)   # sus: end positions
    assert np.count_nonzero(np.abs(f).sum(axis=1) > 0) == int(ref["loaded_step2"])


HEAT_FLUX = 1.0e7                # W/m^2 until t = 1 ms, on the x- face of the stem (1 x 0.5 m)
CV = 903.0


@pytest.fixture(scope="module")
def heat(tmp_path_factory):
    d = tmp_path_factory.mktemp("heat")
    (d / "zeroRotation.txt").write_text("0 0 0 0 0 0 0 0 0 0\n9.9 0 0 0 0 0 0 0 0 0\n")
    _, da = run(open(os.path.join(HERE, "load_curve_heat_flux.ups")).read(), d)
    return da, np.load(os.path.join(HERE, "data", "sus_load_curve_heat_flux.npz"))


def test_heat_flux_temperatures_equal_uintahs_sus(heat):
    """The stem's p.temperature after each of 3 steps against sus (partextract prints 9
    digits: 1e-6 K on 300 K; measured 6e-7 K)."""
    da, ref = heat
    for step in (1, 2, 3):
        assert da.times[step] == pytest.approx(float(ref[f"time_step{step}"]), rel=1e-8)
        p = da.particles(1, step)
        x, T = _sorted(p["p.x"], p["p.temperature"])
        assert np.abs(x - ref[f"x1_step{step}"]).max() < 1e-8
        assert np.abs(T - ref[f"temperature1_step{step}"]).max() < 2e-6
        assert T.max() - 300.0 > 0.02 * step                     # it heats up
    assert np.all(da.particles(0, 3)["p.temperature"] == 300.0)   # <material>1</material> only


def test_heat_flux_energy_is_q_area_time(heat):
    """sum m cv (T - T0) over the stem = q A t: conduction moves heat, the flux adds it;
    the saved p.externalHeatRate of each step sums to q A, on the x- face particles only."""
    da, _ = heat
    for step in (1, 2, 3):
        p = da.particles(1, step)
        gained = CV * np.sum(p["p.mass"] * (p["p.temperature"] - 300.0))
        assert gained == pytest.approx(HEAT_FLUX * 1.0 * 0.5 * da.times[step], rel=1e-9)
        q = p["p.externalHeatRate"]
        assert q.sum() == pytest.approx(HEAT_FLUX * 1.0 * 0.5, rel=1e-12)
        assert np.all(p["p.x"][q > 0, 0] < -0.4)


def test_rigid_reaction_equals_uintahs_sus(spin):
    """RigidReactionForce and RigidReactionTorque (the other materials' internal force at
    the stem's nodes, and its moment about the spin origin) against sus: 0 in step 1 (no
    stress yet), step 2's from the stress after step 1 (the same in both)."""
    da, ref = spin
    t, force = da.reduction("RigidReactionForce")
    _, torque = da.reduction("RigidReactionTorque")
    force, torque = np.asarray(force), np.asarray(torque)
    first, second = (int(np.argmin(np.abs(np.asarray(t) - da.times[k]))) for k in (1, 2))
    assert np.all(force[first] == 0) and np.all(torque[first] == 0)
    for mine, sus in ((force[second], ref["rigid_reaction_force"][1, 1:]),
                      (torque[second], ref["rigid_reaction_torque"][1, 1:])):
        assert abs(sus[2]) > 1e3
        assert np.abs(mine - sus).max() < 1e-7 * abs(sus[2])


def spin_xpic2_text():
    """load_curve_spin.ups as Uintah's deck has it, with <XPIC2>: the rigid contact then acts
    after interpolation too (Uintah's OneOrTwoStep 2), its master keeps FLIP's update; 3 steps,
    p.displacement and p.scalefactor saved."""
    text = open(os.path.join(HERE, "load_curve_spin.ups")).read()
    for old, new in {"<stress_update>usl</stress_update>": "<stress_update>usl</stress_update><XPIC2>true</XPIC2>",
                     '<save label="p.stress"/>':
                         '<save label="p.stress"/><save label="p.displacement"/><save label="p.scalefactor"/>',
                     "<max_Timesteps>2</max_Timesteps>": "<max_Timesteps>3</max_Timesteps>"}.items():
        assert old in text, old
        text = text.replace(old, new)
    return text


def test_spin_with_xpic2_equals_uintahs_sus(tmp_path):
    """The spinning stem and the sample with <XPIC2> against sus on the same deck without the
    stress_update line (tests/mpm/data/sus_load_curve_spin_xpic2.npz: puda -partvar LABEL
    -matl M at steps 1 and 3; every 4th sample and every 10th stem particle ordered by initial
    x, y, z). Measured: x 5e-10 m, v 2e-9 relative, stress 3e-9, p.displacement 5e-11 m,
    p.scalefactor 5e-9 relative, RigidReactionForce 4e-14; without the contact after
    interpolation the sample's velocity is 10 % off at step 3."""
    (tmp_path / "spin.txt").write_text(f"0.0 0 0 0 0 0 0 0 0 {OMEGA}\n9.9 0 0 0 0 0 0 0 0 {OMEGA}\n")
    _, da = run(spin_xpic2_text(), tmp_path)
    ref = np.load(os.path.join(HERE, "data", "sus_load_curve_spin_xpic2.npz"))
    assert np.allclose(da.times[1:], ref["time"], rtol=1e-13, atol=0)
    for step in (1, 3):
        for m, every in ((0, 4), (1, 10)):
            p = da.particles(m, step)
            o = np.lexsort(np.round(p["p.x"] - p["p.displacement"], 6).T)[::every]
            for lab, tol in (("x", 2e-9), ("velocity", 1e-8), ("stress", 1e-8), ("displacement", 1e-8),
                             ("scalefactor", 2e-8)):
                s = ref[f"step{step}_m{m}_{lab}"]
                q = p[f"p.{lab}"][o].reshape(len(s), -1)
                scale = 1.0 if lab in ("x", "displacement") else max(np.abs(s).max(), 1e-30)
                assert np.abs(q - s).max() <= tol * scale, (step, m, lab)
    for name in ("RigidReactionForce", "RigidReactionTorque"):
        t, v = da.reduction(name)
        r = ref[name]
        v = np.asarray(v)[-len(r):].reshape(len(r), -1)
        assert np.abs(v - r[:, 1:]).max() <= 1e-12 * np.abs(r[:, 1:]).max(), name
