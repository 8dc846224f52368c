"""Uintah's disks_complex.ups against sus: its recursive particle filling
(<numLevelsParticleFilling> -2), its drawn failure stresses, and comp_mooney_rivlin's artificial
viscosity (on a small copy where the disks touch from the first step).

References: sus on uintah_reference/disks_complex.ups with <max_Timesteps>5 and an output every
step (tests/mpm/data/sus_disks_complex.npz: the particles at t = 0, every 5th position at step 5,
the .dat sums), and sus on disks_complex_small.ups with the original deck's artificial viscosity
(coefficients 0.3, 3.0), p.q saved and 5 steps (sus_disks_complex_small_av.npz: p.x, p.stress, p.q
of every particle at step 5 and the energies), and sus on uintah_reference/disks_complex_contact.ups
as stored (sus_disks_complex_contact.npz: p.x, p.stress of the particles within 0.12 m of the
contact line at step 10, the particle counts and the energies), all read from sus's udas with
framework.uintah_uda.UintahArchive.
"""
import pathlib

import numpy as np
import pytest

from components.mpm.constitutive.comp_mooney_rivlin import viscosity_bulk_modulus
from framework.problemspec import InputError

from .helpers import run

HERE = pathlib.Path(__file__).parent
REF = HERE / "uintah_reference"


def _match(x, rx):
    """The index into x of the particle nearest each reference position (each taken once)."""
    k = np.argmin(((rx[:, None, :] - x[None, :, :]) ** 2).sum(axis=2), axis=1)
    assert len(set(k)) == len(k)
    return k


def test_disks_complex_as_sus(tmp_path):
    """The deck unchanged but for 5 steps with an output each: sus's 1246 smoothcyl particles
    and 996 lattice ones, 216 of them the filling's (an eighth of the volume: two layers across
    the one z cell) at the disk's rim, at sus's positions (measured 1.6e-16 m), with its volumes,
    colours and drawn failure stresses bitwise; sus's times and sums; no stress before the disks
    meet (sus's and pysus's are round-off, 1e-11 Pa)."""
    text = (REF / "disks_complex.ups").read_text()
    for a, b in (("<maxTime>0.18</maxTime>", "<maxTime>0.18</maxTime><max_Timesteps>5</max_Timesteps>"),
                 ("<outputInterval>.01</outputInterval>", "<outputTimestepInterval>1</outputTimestepInterval>")):
        assert a in text
        text = text.replace(a, b)
    _, da = run(text, tmp_path)
    ref = np.load(HERE / "data" / "sus_disks_complex.npz")
    assert np.allclose(da.times, ref["time"], rtol=1e-12, atol=0)
    for m, n in ((0, 1246), (1, 996)):
        p = da.particles(m, 0)
        assert len(p["p.x"]) == len(ref[f"x0_{m}"]) == n
        k = _match(p["p.x"], ref[f"x0_{m}"])
        assert np.abs(p["p.x"][k] - ref[f"x0_{m}"]).max() < 1e-15
        assert np.array_equal(p["p.volume"][k], ref[f"vol0_{m}"])
        if m == 1:
            assert np.array_equal(p["p.epsf"][k], ref["epsf0_1"])
            assert np.array_equal(p["p.color"][k], ref["color0_1"])
            small = np.isclose(p["p.volume"], p["p.volume"].max() / 8, rtol=1e-12)
            assert small.sum() == 216
            assert sorted(set(np.round(p["p.x"][small, 2], 12))) == [0.0625, 0.0875]
        p = da.particles(m, 5)
        assert len(p["p.x"]) == ref[f"n5_{m}"]
        k = _match(p["p.x"], ref[f"x5_{m}"])
        assert np.abs(p["p.x"][k] - ref[f"x5_{m}"]).max() < 1e-14
        assert np.abs(p["p.stress"]).max() < 1e-9 and ref[f"stress5_max_{m}"] < 1e-9
    for label, tol in (("KineticEnergy", 1e-13), ("TotalMass", 1e-14), ("TotalMomentum", 1e-13)):
        t, v = (np.asarray(a) for a in da.reduction(label))
        r = ref[label]
        assert np.allclose(t[-5:], r[:, 0], rtol=1e-12)
        v = v.reshape(len(t), -1)[-5:]
        assert np.abs(v - r[:, 1:]).max() <= tol * np.abs(r[:, 1:]).max(), label


def test_disks_complex_contact_with_filling_as_sus(tmp_path):
    """disks_complex moved so that the disks meet from the first step, on a grid whose index
    arithmetic is exact (1/32 m cells; uintah_reference/disks_complex_contact.ups), with
    Uintah's update (usl): through 10 steps of contact, with the filling's particles at the rim
    of the lattice disk pressed, every particle within 0.12 m of the contact line at sus's
    position within 1e-13 m (measured 4.4e-16) and sus's stress within 1e-10 of the largest
    (1.3e-13); the energies 1e-11 (sus_disks_complex_contact.npz: sus on the deck as stored).
    On the original 0.025 m grid sus's fast_cpdi puts the weights of a corner that lies on a
    node plane within round-off on the neighbouring node (docs/MPM.md), which pysus does not."""
    text = (REF / "disks_complex_contact.ups").read_text()
    a = "<interpolator>   fast_cpdi </interpolator>"
    assert a in text
    _, da = run(text.replace(a, "<interpolator>fast_cpdi</interpolator><stress_update>usl</stress_update>"),
                tmp_path)
    ref = np.load(HERE / "data" / "sus_disks_complex_contact.npz")
    assert np.allclose(da.times, ref["time"], rtol=1e-12, atol=0)
    for m in (0, 1):
        p = da.particles(m, -1)
        assert len(p["p.x"]) == ref[f"n{m}"]
        k = _match(p["p.x"], ref[f"x{m}"])
        assert np.abs(p["p.x"][k] - ref[f"x{m}"]).max() < 1e-13
        rs = ref[f"stress{m}"]
        assert np.abs(rs).max() == ref[f"stress_max{m}"] > 1e5
        assert np.abs(p["p.stress"][k] - rs).max() < 1e-10 * np.abs(rs).max()
        if m == 1:                      # the filling's particles are among the pressed ones
            fill = p["p.volume"][k] < p["p.volume"].max() / 4      # an eighth of the others
            assert fill.sum() > 10
            assert np.abs(rs[fill]).max() > 0.2 * np.abs(rs).max()
    for label in ("KineticEnergy", "StrainEnergy"):
        t, v = (np.asarray(a) for a in da.reduction(label))
        r = ref[label]
        assert np.allclose(t[-10:], r[:, 0], rtol=1e-12)
        assert np.abs(v[-10:] - r[:, 1]).max() < 1e-11 * np.abs(r[:, 1]).max(), label


def test_mooney_rivlin_viscosity_bulk_modulus():
    """Uintah's CompMooneyRivlin takes K = 4 (C1 + C2 I2)/J for the viscosity's sound speed."""
    F = np.array([[[1.1, 0.2, 0.0], [0.05, 0.9, 0.1], [0.0, -0.1, 1.02]]])
    B = F[0] @ F[0].T
    I2 = 0.5 * (np.trace(B) ** 2 - np.trace(B @ B))
    K = np.empty(1)
    viscosity_bulk_modulus(2.0e5, 4.0e4, F, K)
    assert np.isclose(K[0], 4.0 * (2.0e5 + 4.0e4 * I2) / np.linalg.det(F[0]), rtol=1e-14)


def test_mooney_rivlin_artificial_viscosity_as_sus(tmp_path):
    """disks_complex_small with disks_complex's artificial viscosity and Uintah's update (USL),
    5 steps: comp_mooney_rivlin's p.q (and comp_neo_hook's) as sus's within 1e-7 of the largest
    (measured 1.4e-9), p.stress 1e-8 (5.8e-9), energies 1e-9 (3.4e-10). The viscosity matters:
    without it (sus_disks_complex_small.npz) sus's stress differs by more than 1 % of the largest."""
    text = (REF / "disks_complex_small.ups").read_text()
    for a, b in (("<interpolator>   fast_cpdi </interpolator>",
                  "<interpolator>fast_cpdi</interpolator><stress_update>usl</stress_update>"
                  "<artificial_viscosity>true</artificial_viscosity>"
                  "<artificial_viscosity_coeff1>0.3</artificial_viscosity_coeff1>"
                  "<artificial_viscosity_coeff2>3.0</artificial_viscosity_coeff2>"),
                 ('<save label = "p.stress"/>', '<save label = "p.stress"/><save label = "p.q"/>')):
        assert a in text
        text = text.replace(a, b)
    _, da = run(text, tmp_path)
    ref = np.load(HERE / "data" / "sus_disks_complex_small_av.npz")
    plain = np.load(HERE / "data" / "sus_disks_complex_small.npz")
    assert np.allclose(da.times[-5:], ref["time"], rtol=1e-12)
    for m in (0, 1):
        p = da.particles(m, -1)
        k = _match(p["p.x"], ref[f"x{m}"])
        assert np.abs(p["p.x"][k] - ref[f"x{m}"]).max() < 1e-10
        rq, rs = ref[f"q{m}"], ref[f"stress{m}"]
        assert rq.max() > 5e3
        assert np.abs(p["p.q"][k] - rq).max() < 1e-7 * rq.max()
        assert np.abs(p["p.stress"][k] - rs).max() < 1e-8 * np.abs(rs).max()
        j = _match(ref[f"x{m}"], plain[f"x{m}"])
        assert np.abs(plain[f"stress{m}"] - rs[j]).max() > 0.01 * np.abs(rs).max()
    for label in ("KineticEnergy", "StrainEnergy"):
        t, v = (np.asarray(a) for a in da.reduction(label))
        r = ref[label]
        assert np.allclose(t[-5:], r[:, 0], rtol=1e-12)
        assert np.abs(v[-5:] - r[:, 1]).max() < 1e-9 * np.abs(r[:, 1]).max(), label


@pytest.mark.parametrize("deck, words", [
    ("disks_complex_small.ups", ("smoothcyl", "numLevelsParticleFilling")),
    ("ColPlate_AffineTrans.ups", ("affine-transformed", "numLevelsParticleFilling")),
])
def test_filling_refused_where_not_implemented(deck, words):
    """<numLevelsParticleFilling> with a <smoothcyl> (its own particles) or an affine
    transformation is refused in one line."""
    from framework.controller import Controller
    text = (REF / deck).read_text()
    fill = "<res>[2,2,1]</res><numLevelsParticleFilling>-2</numLevelsParticleFilling>"
    text = text.replace("<res>[2,2,1]</res>", fill, 1)
    with pytest.raises(InputError) as e:
        Controller(str(REF / deck), deck_text=text, quiet=True)
    msg = str(e.value)
    assert "\n" not in msg and ".ups:" in msg
    for w in words:
        assert w in msg, msg
