"""<smoothcyl> particles under CPDI: each particle's domain is its ring sector (Uintah's
SmoothCylGeomPiece gives it a size matrix turned with the sector; p.sizeMatrix here), checked
against the sector's geometry and against Uintah's sus on a small copy of its disks_complex deck."""
import pathlib

import numpy as np

from framework.geometry import SmoothCylinder

from .helpers import run

HERE = pathlib.Path(__file__).parent
REF = HERE / "uintah_reference"


def test_size_matrix_spans_the_ring_sector():
    """The columns of the size matrix are the sector's arc (tangential), width (radial) and
    height: det is the particle's volume, the first column is normal to the radius, the
    second along it."""
    dx = np.array([0.05, 0.04, 0.1])
    cyl = SmoothCylinder([0.5, 0.5, 0.0], [0.5, 0.5, 0.1], 0.2, 0.05, 6, 1, 0, "constant_particle_volumes")
    x, vol, size = cyl.points(dx)
    H = 0.5 * size
    assert np.allclose(np.linalg.det(2.0 * H), vol, rtol=1e-12)
    radial = (x - [0.5, 0.5, 0.05])[:, :2]
    radial /= np.linalg.norm(radial, axis=1, keepdims=True)
    assert np.abs(np.einsum("pd,pd->p", H[:, :2, 0], radial)).max() < 1e-15      # arc: tangential
    assert np.allclose(np.einsum("pd,pd->p", H[:, :2, 1], radial), 0.5 * 0.15 / 6, rtol=1e-12)
    assert np.allclose(H[:, 2, 2], 0.05)


# sus on uintah_reference/disks_complex_small.ups (5 steps): times, KineticEnergy.dat,
# StrainEnergy.dat, and p.x, p.stress of every particle, p.scalefactor of the smoothcyl disk's,
# at step 5 (tests/mpm/data/sus_disks_complex_small.npz, read from sus's uda with
# framework.uintah_uda.UintahArchive).
TOL_X = 1e-10            # m; measured 3e-12
TOL_STRESS = 1e-8        # of the largest component (2.2e5 Pa); measured 1.9e-9
TOL_SCALE = 1e-10        # of the largest (0.05 m); measured 1.4e-12
TOL_ENERGY = 1e-9        # relative; measured: kinetic 5e-12, strain 4.4e-10


def test_disks_complex_small_against_sus(tmp_path):
    """A smoothcyl disk (comp_mooney_rivlin) pressed against a lattice disk (comp_neo_hook),
    friction contact, fast_cpdi, Uintah's update (USL), 5 steps: the same particles, positions,
    stresses, scale factors and energies as sus. With the diagonal p.size (unturned domains)
    the smoothcyl disk's stress is 7.7 % off (measured), far outside TOL_STRESS."""
    text = (REF / "disks_complex_small.ups").read_text().replace(
        "<interpolator>   fast_cpdi </interpolator>",
        "<interpolator>fast_cpdi</interpolator><stress_update>usl</stress_update>")
    assert "usl" in text
    _, da = run(text, tmp_path)
    ref = np.load(HERE / "data" / "sus_disks_complex_small.npz")
    assert np.allclose(da.times[-5:], ref["time"], rtol=1e-12)     # the first delT is CMR's initial one
    for m in (0, 1):
        p = da.particles(m, -1)
        x, rx = p["p.x"], ref[f"x{m}"]
        assert len(x) == len(rx) == (197, 202)[m]
        k = np.argmin(((rx[:, None, :2] - x[None, :, :2]) ** 2).sum(axis=2), axis=1)
        assert len(set(k)) == len(k)
        assert np.abs(x[k] - rx).max() < TOL_X
        rs = ref[f"stress{m}"]
        assert np.abs(p["p.stress"][k] - rs).max() < TOL_STRESS * np.abs(rs).max()
        if m == 0:
            rf = ref["scalefactor0"]
            assert np.abs(p["p.scalefactor"][k] - rf).max() < TOL_SCALE * np.abs(rf).max()
    for lab, key in (("KineticEnergy", "ke"), ("StrainEnergy", "se")):
        t, v = (np.asarray(a) for a in da.reduction(lab))
        r = ref[key]
        assert np.allclose(t[-5:], r[:, 0], rtol=1e-12)
        assert np.abs(v[-5:] - r[:, 1]).max() < TOL_ENERGY * np.abs(r[:, 1]).max(), lab
