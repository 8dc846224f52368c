"""elastic_plastic with <deviatoric_stress_model type="hypoViscoElastic"> (Maxwell elements;
constitutive/elastic_plastic_hp.py) on Uintah's test_hypoviscoelastic_rad_ret.ups
(inputs/MPM/hypoviscoelastic_radial_return.ups, the same deck):

- against sus: tests/mpm/data/hypoviscoelastic_rr_sus.txt holds sus's stress of the particle
  at its 21 outputs over the whole run (4779 steps); pysus must take the same steps (the output
  step numbers and times, so delT) and give its stress to 1e-5 of the largest component (seen:
  4e-6, the same as the deck with the plain hypoElastic model gives against sus: the difference
  lies in the shared kinematics, not in the Maxwell element); its BndyTraction_zminus over every
  step the same (tests/mpm/data/hypoviscoelastic_rr_bndy_sus.txt);
- against the Maxwell solution: the piston drives d_zz = -v/dx = -0.5 per us in the particle's
  cell (uniaxial strain), so until it yields s_zz - s_xx = 2 mu tau d_zz (1 - exp(-t/tau)),
  to the first-order error dt/(2 tau) = 2e-4 of the explicit update; after it, von Mises holds
  |s_zz - s_xx| at the yield stress 250 + 10 ep.
"""
from pathlib import Path

import numpy as np
import pytest

from framework.errors import RunStopped
from framework.problemspec import InputError

from .helpers import MPM_INPUTS, run

DECK = MPM_INPUTS / "hypoviscoelastic_radial_return.ups"
SUS = np.loadtxt(Path(__file__).parent / "data" / "hypoviscoelastic_rr_sus.txt")
MU, TAU, D_ZZ = 3750.0, 0.1, -0.005 / 0.01


@pytest.fixture(scope="module")
def archive(tmp_path_factory):
    return run(open(DECK).read(), tmp_path_factory.mktemp("hve"))[1]


def _stress(da):
    """(steps, times, (n, 3, 3) stress of the particle) at pysus's outputs."""
    s = np.array([da.particles(1, k)["p.stress"][0] for k in range(len(da.timesteps))])
    return np.array(da.timesteps), np.array(da.times), s


def test_against_sus(archive):
    steps, times, s = _stress(archive)
    for step, t, sxx, syy, szz in SUS[1:]:               # sus's first output is step 1, pysus's step 0
        k = list(steps).index(int(step))
        assert times[k] == pytest.approx(t, rel=1e-9)
        got, want = s[k].diagonal(), np.array([sxx, syy, szz])
        assert np.abs(got - want).max() < 1e-5 * np.abs(want).max(), (step, got, want)
        assert np.abs(s[k] - np.diag(s[k].diagonal())).max() < 1e-12 * np.abs(want).max()


TRACTION = np.loadtxt(Path(__file__).parent / "data" / "hypoviscoelastic_rr_bndy_sus.txt")


def test_boundary_traction_equals_sus(archive):
    """BndyTraction_zminus (components/mpm/boundary_tractions.py), a line every step: the
    particle's -s_zz over the z- face, as sus writes it (measured over every step: 4e-6 of the
    largest, as the stress)."""
    t, traction = archive.reduction("BndyTraction_zminus")
    assert len(t) == int(TRACTION[-1, 0])
    scale = np.abs(TRACTION[:, 2]).max()
    for k, tk, tz in TRACTION:
        i = int(k) - 1
        assert t[i] == pytest.approx(tk, rel=1e-9), k
        assert abs(traction[i, 2] - tz) < 1e-5 * scale and traction[i, 0] == traction[i, 1] == 0.0, k


def test_maxwell_relaxation_and_yield(archive):
    _, times, s = _stress(archive)
    q = s[:, 2, 2] - s[:, 0, 0]
    elastic = (times > 0) & (times < 0.105)            # yield at 375 (1 - exp(-t/tau)) = 250: t = 0.11
    maxwell = 2.0 * MU * TAU * D_ZZ * (1.0 - np.exp(-times[elastic] / TAU))
    assert elastic.sum() >= 10
    assert np.allclose(q[elastic], maxwell, rtol=5e-4, atol=0.0)
    plastic = times > 0.115
    assert plastic.sum() >= 8
    assert np.all((-q[plastic] > 250.0) & (-q[plastic] < 251.0))


def _variant(old, new):
    text = open(DECK).read()
    assert old in text
    return text.replace(old, new)


@pytest.mark.parametrize("old,new,words", [
    ("<tau> [0.1] </tau>", "<tau> [0.1, 0.2] </tau>", "one mu and one tau per Maxwell element"),
    ("<tau> [0.1] </tau>", "<tau> 0.1 </tau>", "a list [a, b, ...] of positive numbers"),
    ("<mu> [3750.0] </mu>", "<mu> [-3750.0] </mu>", "a list [a, b, ...] of positive numbers"),
    ('type="hypoViscoElastic"', 'type="maxwell"', "hypoViscoElastic"),
])
def test_input_errors(tmp_path, old, new, words):
    with pytest.raises(InputError) as e:
        run(_variant(old, new), tmp_path)
    assert words in str(e.value)


def test_step_longer_than_tau_stops(tmp_path):
    """Uintah stops when delT exceeds a Maxwell element's tau; so does pysus, with one line."""
    text = _variant("<tau> [0.1] </tau>", "<tau> [1.0e-5] </tau>").replace(
        "<maxTime>0.2</maxTime>", "<maxTime>0.001</maxTime>")
    with pytest.raises(RunStopped) as e:
        run(text, tmp_path)
    assert "tau" in str(e.value)
