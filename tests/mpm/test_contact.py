"""Contact: Coulomb friction (a block sliding on a base) and rigid (a piston pushing a bar)."""
import numpy as np
import pytest

from .helpers import MPM_INPUTS, deck_text, run


def slider_velocity(tmp_path, mu):
    text = deck_text(MPM_INPUTS / "friction_block.ups", mu=mu, maxTime=0.2)
    ctl, da = run(text, tmp_path, name=f"mu{mu}")
    t = np.asarray(da.times)
    v = np.array([da.particles(0, k)["p.velocity"][:, 0].mean() for k in range(len(da.timesteps))])
    return t, v


@pytest.fixture(scope="module")
def sliding(tmp_path_factory):
    d = tmp_path_factory.mktemp("friction")
    return {mu: slider_velocity(d, mu) for mu in (0.0, 0.3)}


def test_friction_decelerates_at_mu_g(sliding):
    """Deceleration of the slider: mu g more with friction than without (g = 10 m/s^2).
    Measured (fit over 0..0.2 s): -3.27 m/s^2 (mu = 0.3) and -0.43 m/s^2 (mu = 0: the
    corners of the slider drag a little), difference -2.84 (5 % below mu g)."""
    slope = {mu: np.polyfit(t, v, 1)[0] for mu, (t, v) in sliding.items()}
    assert abs((slope[0.3] - slope[0.0]) / (-0.3 * 10) - 1) < 0.1, slope
    assert abs(slope[0.0]) < 0.2 * 3.0, slope
    t, v = sliding[0.3]
    assert np.all(np.diff(v) < 0), v                     # slides, slowing, the whole time


def test_rigid_piston(tmp_path):
    """inputs/MPM/rigid_piston.ups: the rigid piston moves at V until stop_time, then
    stands; the bar takes the impulse rho c V t A and carries a pulse of stress -rho c V.
    Measured: bar momentum at t = 0.40 s 0.960 of rho c V t A; stress integral over the
    pulse at 0.8 s 0.873 of -rho c V t_stop; ahead of the pulse |sigma| < 0.04 rho c V."""
    ctl, da = run(open(MPM_INPUTS / "rigid_piston.ups").read(), tmp_path)
    V, A, m_p, rho_c = 0.01, 1e-4, 1.0 * 0.005 * 1e-4, 1.0
    t = np.asarray(da.times)
    x0 = da.particles(0, 0)["p.x"][:, 0]
    dt = 0.5 * 0.01 / 1.0                             # timestep_multiplier dx / c
    final = da.particles(0, -1)["p.x"][:, 0] - x0
    assert V * 0.4 <= final[0] <= V * (0.4 + dt)      # moved until the first step after 0.4 s
    for k in range(len(t)):
        piston = da.particles(0, k)
        dx = piston["p.x"][:, 0] - x0
        assert np.ptp(dx) < 1e-15                     # moves as one body
        if t[k] <= 0.4:
            assert abs(dx[0] - V * t[k]) < 1e-12, (t[k], dx[0])
        if t[k] > 0.4 + dt:
            assert np.all(np.abs(piston["p.velocity"]) < 1e-12)
            assert dx[0] == final[0]
    k = int(np.argmin(np.abs(t - 0.4)))              # the output at 0.4019 s: still pushing
    bar = da.particles(1, k)
    momentum = m_p * bar["p.velocity"][:, 0].sum()
    assert abs(momentum / (rho_c * V * t[k] * A) - 1) < 0.06, momentum
    bar = da.particles(1, -1)
    x, s = bar["p.x"][:, 0], bar["p.stress"][:, 0, 0]
    pulse = (x > 0.45) & (x < 0.95)
    assert abs(s[pulse].sum() * 0.005 / (-rho_c * V * final[0] / V) - 1) < 0.2
    assert np.all(np.abs(s[x > 0.95]) < 0.05 * rho_c * V)
