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
