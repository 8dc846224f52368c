"""Uintah's JWLppMPM (components/mpm/constitutive/jwlpp_mpm.py): its burn, its initial state,
and a burning charge against Uintah's sus.

tests/mpm/jwlpp_charge.ups (its header says what it is) ran in sus for 20 steps (with
<outputInitTimestep/>, without pysus's <stress_update> tag: sus's update is USL);
tests/mpm/data/sus_jwlpp_charge.npz holds, at steps 0, 5, 10, 15, 20, every particle's p.x,
p.progressF, p.stress, p.deformationMeasure and p.velocity in the order of its position,
read from sus's uda, and the times.
"""
import dataclasses
import pathlib

import numpy as np
import pytest

from components.mpm.constitutive import jwlpp_mpm as jwl
from framework.problemspec import InputError

from .helpers import run

HERE = pathlib.Path(__file__).parent
DECK = HERE / "jwlpp_charge.ups"
SUS = HERE / "data" / "sus_jwlpp_charge.npz"
PARAMS = jwl.Params(2.0e8, 1.9342e-10, 15.2, 7.73037e11, 21.629e9, 1.339e9, 4.5, 1.5, 0.33, 3.0e-4, 1.05, 1.0e-9,
                    1.0, 1.0e-3, 20, False, 2.1e8, 1844.0)


def packed(q):
    return (q.ignition_pressure, q.K, q.n, q.A, q.B, q.C, q.R1, q.R2, q.omega, q.G, q.b, q.max_burn_timestep,
            q.max_burned_frac, q.newton_tol, q.newton_max, q.fast)


def mix(q, J, f):
    pM = (J ** -q.n - 1.0) / (q.n * q.K)
    pJ = q.A * np.exp(-q.R1 * J) + q.B * np.exp(-q.R2 * J) + q.C * J ** -(1.0 + q.omega)
    return pM, pJ, (1.0 - f) * pM + f * pJ


def test_initial_state_is_the_murnaghan_pressure():
    """useInitialStress: sigma = -p0 I and F = J0^(1/3) I with the Murnaghan pressure of J0
    equal to p0."""
    F, s = jwl.initial_deformation(PARAMS, 3)
    J0 = np.linalg.det(F[0])
    assert np.allclose(F, np.cbrt(J0) * np.eye(3), rtol=1e-15) and np.allclose(s, -2.1e8 * np.eye(3), rtol=1e-15)
    assert mix(PARAMS, J0, 0.0)[0] == pytest.approx(2.1e8, rel=1e-12)
    assert jwl.initial_J(PARAMS) == pytest.approx(J0, rel=1e-15)


def test_burn():
    """Below the ignition pressure f stays and p is the mix at J; above it, one sub-step
    solves the backward-Euler burn and the mix (residuals below the tolerance); many
    sub-steps burn more than one over the same time at a falling J; doFastStressCompute is
    one backward-Euler update with the old pressure; f is capped at max_burned_fraction."""
    P = packed(PARAMS)
    f, p = jwl.burn(P, 0.98, 0.985, 0.2, 1.9e8, 1e-7)
    assert f == 0.2 and p == pytest.approx(mix(PARAMS, 0.985, 0.2)[2], rel=1e-15)
    one = packed(dataclasses.replace(PARAMS, max_burn_timestep=1.0))
    f, p = jwl.burn(one, 0.98, 0.985, 0.2, 2.5e8, 1e-7)
    pM, pJ, _ = mix(PARAMS, 0.985, f)
    assert f > 0.2
    assert abs(f - 0.2 - PARAMS.G * (1 - f) * p ** PARAMS.b * 1e-7) < 1e-3
    assert abs(p - (1 - f) * pM - f * pJ) < 1e-3 * abs(p)
    fast = packed(dataclasses.replace(PARAMS, max_burn_timestep=1.0, fast=True))
    f2, p2 = jwl.burn(fast, 0.98, 0.985, 0.2, 2.5e8, 1e-7)
    fac = 1e-7 * PARAMS.G * 2.5e8 ** PARAMS.b
    assert f2 == pytest.approx((0.2 + fac) / (1 + fac), rel=1e-15) and p2 == pytest.approx(mix(PARAMS, 0.985, f2)[2],
                                                                                              rel=1e-15)
    capped = packed(dataclasses.replace(PARAMS, max_burned_frac=0.21))
    f3, p3 = jwl.burn(capped, 0.98, 0.985, 0.2, 2.5e8, 1e-7)
    assert f3 == 0.21 and p3 == pytest.approx(mix(PARAMS, 0.985, 0.21)[2], rel=1e-15)


def test_charge_as_sus(tmp_path):
    """20 steps of the burning, expanding charge: sus's times, positions, velocities, F,
    p.progressF (0 to 0.79-0.99 in 5 steps) and p.stress (2e8 to 4e10 Pa) at steps 0, 5,
    10, 15, 20 (measured: stress 1.4e-14 of each step's largest, F 2.2e-14, f 1.3e-15)."""
    _, da = run(open(DECK).read(), tmp_path)
    sus = np.load(SUS)
    assert list(da.timesteps) == list(sus["timestep"])
    assert np.allclose(da.times, sus["time"], rtol=1e-13, atol=0)
    for k in range(len(sus["timestep"])):
        p = da.particles(0, k)
        o = np.lexsort(np.round(p["p.x"], 9).T[::-1])
        assert np.abs(p["p.x"][o] - sus["x"][k]).max() < 1e-16
        assert np.abs(p["p.velocity"][o] - sus["velocity"][k]).max() < 1e-12 * max(1.0, np.abs(sus["velocity"][k]).max())
        assert np.abs(p["p.deformationMeasure"][o] - sus["F"][k]).max() < 1e-13
        assert np.abs(p["p.progressF"][o] - sus["progressF"][k]).max() < 1e-14
        assert np.abs(p["p.stress"][o] - sus["stress"][k]).max() < 1e-13 * np.abs(sus["stress"][k]).max()
    assert sus["progressF"][1].min() > 0.78 and sus["stress"][-1].min() < -4e10


def test_missing_constant_is_one_line(tmp_path):
    with pytest.raises(InputError) as e:
        run(open(DECK).read().replace("<jwl_A> 7.73037e11 </jwl_A>", ""), tmp_path)
    msg = str(e.value)
    assert "\n" not in msg and ".ups:" in msg and "jwl_A" in msg
