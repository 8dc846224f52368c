"""Axial vibration of a fixed-free elastic bar: period 4L/c within 1 %."""
import numpy as np

from .helpers import MPM_INPUTS, run


def period(da):
    """Twice the time between the first two zero crossings of the x momentum."""
    t, P = da.reduction("TotalMomentum")
    px = np.asarray(P)[:, 0]
    i = np.where(np.sign(px[1:]) != np.sign(px[:-1]))[0]
    tc = [t[k] - px[k] * (t[k + 1] - t[k]) / (px[k + 1] - px[k]) for k in i]
    return 2.0 * (tc[1] - tc[0])


def test_bar_period(tmp_path):
    ctl, da = run(open(MPM_INPUTS / "bar_vibration.ups").read(), tmp_path)
    T = period(da)
    assert abs(T / 4.0 - 1.0) < 0.01, T      # exact: 4 L / c = 4 s


def test_maximum_particle_velocity_deletes(tmp_path):
    """Particles faster than <maximum_particle_velocity> are deleted in the first step
    (the bar starts at 0.001 m/s; the fixed end holds the first particles back)."""
    from .helpers import deck_text
    text = deck_text(MPM_INPUTS / "bar_vibration.ups", maxTime=0.1, outputInterval=0.05).replace(
        "<interpolator>linear</interpolator>",
        "<interpolator>linear</interpolator><maximum_particle_velocity>0.0005</maximum_particle_velocity>").replace(
        '<save label="KineticEnergy"/>', '<save label="KineticEnergy"/><save label="TotalMass"/>')
    ctl, da = run(text, tmp_path)
    t, M = da.reduction("TotalMass")
    kept = np.asarray(M)[-1]
    assert 0 < kept < 0.05 * np.asarray(M)[0], M      # only the particles next to the fixed node stay
