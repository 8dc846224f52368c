"""elastic_plastic_hp's Johnson-Cook damage (p.damage) and its own localization and erosion,
against Uintah's sus (references read from sus's udas with UintahArchive).

uintah_reference/ephp_erosion_bar.ups: a steel block whose halves fly apart, gauss initial
porosity and damage (Uintah's seeded draws), TEPLA rule and drucker_becker stability check,
ZeroStress erosion, Johnson-Cook damage; sus localizes 48 particles in step 1, 12 more in step
28 and 12 more in step 30. Measured over its 30 steps (USL, as Uintah): p.localizedMPM equal, p.porosity bitwise
at step 1 and 1.4e-10 of the largest after, p.damage 4.6e-8, p.stress 2.9e-8, p.x 1.8e-11."""
import pathlib

import numpy as np

from .helpers import run

HERE = pathlib.Path(__file__).parent
TOL = 1e-7             # of the largest value; measured 2.9e-8 (stress), 4.6e-8 (damage)


def _matched(x, rx):
    """Indices into x of the particles nearest to rx's."""
    return np.argmin(((rx[:, None, :2] - x[None, :, :2]) ** 2).sum(axis=2), axis=1)


def test_erosion_bar_localizes_and_damages_as_sus(tmp_path):
    text = (HERE / "uintah_reference" / "ephp_erosion_bar.ups").read_text(encoding="iso-8859-1").replace(
        "<interpolator>linear</interpolator>", "<interpolator>linear</interpolator><stress_update>usl</stress_update>")
    da = run(text, tmp_path)[1]
    ref = np.load(HERE / "data" / "sus_ephp_erosion_bar.npz")
    times = np.asarray(da.times)
    assert np.allclose(times[1:], ref["time"], rtol=1e-9)
    for step, n_loc in ((1, 48), (28, 60), (30, 72)):
        p = da.particles(0, step)
        k = _matched(p["p.x"], ref[f"x{step}"])
        assert len(p["p.x"]) == len(ref[f"x{step}"]) == 144
        assert np.abs(p["p.x"][k] - ref[f"x{step}"]).max() < 1e-10
        assert int(ref[f"loc{step}"].sum()) == n_loc
        assert np.array_equal(p["p.localizedMPM"][k] != 0, ref[f"loc{step}"] != 0)
        for lab, key in (("p.stress", "stress"), ("p.damage", "damage"), ("p.porosity", "porosity"),
                         ("p.plasticStrain", "ep")):
            r = ref[f"{key}{step}"]
            assert np.abs(p[lab][k] - r).max() <= TOL * np.abs(r).max(), (step, lab)
    assert np.array_equal(da.particles(0, 1)["p.porosity"][_matched(da.particles(0, 1)["p.x"], ref["x1"])],
                          ref["porosity1"])             # Uintah's seeded gauss draws, bitwise



def test_stability_checks_of_the_von_mises_tangent():
    """Uintah's elastic-plastic tangent C_ep = C_e - (C_e:r)(r:C_e)/(r:C_e:r - h H) (r = 3 dev
    sig, h = sig:r/sigma_y, H = dsigma_y/dep): for D = a r (isochoric, along dev(sig)),
    (C_ep:D):D = -a^2 (r:C_e:r) h H/(r:C_e:r - h H) < 0 with any hardening, so Drucker's check
    fires; with a volumetric part (uniaxial strain) it does not; in uniaxial tension with
    metal moduli Becker's quadratic has no two non-negative roots."""
    from components.mpm.constitutive.elastic_plastic_hp import BECKER, DRUCKER, DRUCKER_BECKER, _unstable
    K, mu, sy, H = 173.33e9, 80.0e9, 800.0e6, 1.0e9
    sig = np.diag([sy, 0.0, 0.0])
    along = np.diag([1.0, -0.5, -0.5])          # dev(sig) direction
    uniaxial_strain = np.diag([1.0, 0.0, 0.0])
    assert _unstable(DRUCKER, K, mu, sig, along, sy, H)
    assert _unstable(DRUCKER_BECKER, K, mu, sig, along, sy, H)
    assert not _unstable(DRUCKER, K, mu, sig, uniaxial_strain, sy, H)
    assert not _unstable(BECKER, K, mu, sig, along, sy, H)
    assert not _unstable(DRUCKER_BECKER, K, mu, sig, uniaxial_strain, sy, H)
