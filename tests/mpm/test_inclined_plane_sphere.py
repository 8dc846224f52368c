"""Uintah's mpm_perf_test (StandAlone/inputs/MPM/inclined_plane_sphere.ups: a soft
comp_neo_hook_plastic sphere above a hard plate, friction_bard contact, gravity along the
incline, GIMP) against Uintah's sus, made small in tests/mpm/inclined_plane_sphere.ups (its
header says how).

The expected values are sus's, in tests/mpm/data/sus_inclined_plane_sphere.npz (sus on the
same deck without the stress_update line, read from its uda with framework.uintah_uda.UintahArchive):
per step the times and delT, each material's particle count, p.x, p.velocity and p.stress of
about 40 particles a material (every ~1/40th p.particleID of sus), and the saved reductions
(KineticEnergy, TotalMass, StrainEnergy, CenterOfMassPosition, TotalMomentum .dat rows as sus
wrote them). pysus numbers its particles otherwise, so each of sus's particles is found in
pysus's output by its position.

Measured (pysus with <stress_update>usl</stress_update>): positions equal to 1.1e-16 m; the
velocity 1.4e-13 of the largest (2.1e-2 m/s); p.stress 5e-12 of the largest (1.4e4 Pa, in
the plate; the falling sphere's stress is round-off, 3e-13 Pa); times and delT to round-off;
the reductions to 5e-15 of their largest, StrainEnergy to 1.4e-9 relative (2.2e-9 J on 1.6 J).
"""
import pathlib

import numpy as np
import pytest

from .helpers import run

HERE = pathlib.Path(__file__).parent
DECK = HERE / "inclined_plane_sphere.ups"
SUS = HERE / "data" / "sus_inclined_plane_sphere.npz"
TOL_X = 1e-12                     # m; measured 1.1e-16
TOL_V = 1e-11                     # of the largest |p.velocity|; measured 1.4e-13
TOL_STRESS = 1e-9                 # of the largest |p.stress| (both materials); measured 5e-12
TOL_REDUCTION = 1e-12             # relative to the largest value in the .dat file; measured 5e-15
TOL_STRAIN_ENERGY = 1e-7          # relative; measured 1.4e-9


@pytest.fixture(scope="module")
def ref():
    return np.load(SUS)


@pytest.fixture(scope="module")
def pysus(tmp_path_factory):
    _, da = run(DECK.read_text(), tmp_path_factory.mktemp("inclined_plane_sphere"))
    return da


def test_times_and_particle_counts_equal_sus(pysus, ref):
    times = np.asarray(pysus.times)
    assert len(times) == 4 and times[0] == 0.0                 # t = 0 and the 3 steps
    assert np.allclose(times[1:], ref["times"], rtol=1e-12, atol=0)
    assert np.allclose(np.diff(times), ref["delT"], rtol=1e-10, atol=0)
    for step in (1, 2, 3):
        for m in (0, 1):
            assert len(pysus.particles(m, step)["p.x"]) == int(ref[f"count{m}_step{step}"])


@pytest.mark.parametrize("step", [1, 2, 3])
def test_particles_equal_sus(pysus, ref, step):
    """p.x, p.velocity, p.stress of sus's sample particles after each step."""
    stress_scale = max(np.abs(ref[f"stress{m}_step{step}"]).max() for m in (0, 1))
    assert stress_scale > 1e3                                  # the plate carries the sphere's weight
    for m in (0, 1):
        p = pysus.particles(m, step)
        sx = ref[f"x{m}_step{step}"]
        near = np.array([np.argmin(((p["p.x"] - x) ** 2).sum(axis=1)) for x in sx])
        assert len(set(near)) == len(near)
        assert np.abs(p["p.x"][near] - sx).max() < TOL_X
        sv = ref[f"velocity{m}_step{step}"]
        assert np.abs(p["p.velocity"][near] - sv).max() < TOL_V * np.abs(sv).max(), m
        ss = ref[f"stress{m}_step{step}"]
        assert np.abs(p["p.stress"][near] - ss).max() < TOL_STRESS * stress_scale, m


@pytest.mark.parametrize("label", ["KineticEnergy", "TotalMass", "StrainEnergy",
                                   "CenterOfMassPosition", "TotalMomentum"])
def test_reductions_equal_sus(pysus, ref, label):
    t, v = pysus.reduction(label)
    v = np.reshape(v, (len(t), -1))[1:]                         # sus writes no t = 0 row
    sus = ref[label]
    assert np.allclose(t[1:], sus[:, 0], rtol=1e-12, atol=0)
    tol = TOL_STRAIN_ENERGY if label == "StrainEnergy" else TOL_REDUCTION
    assert np.all(np.abs(v - sus[:, 1:]) <= tol * np.abs(sus[:, 1:]).max())
