"""CBDI pressure loads (<use_CBDI_boundary_condition>, components/mpm/cbdi.py) and the Threshold
damage's MohrCoulomb criterion: the loaded face of one particle worked by hand, and Uintah's
loadCurve_press-torqueCBDI and PressSmoothCylCBDI decks, made small (tests/mpm/load_curve_cbdi.ups,
tests/mpm/press_smooth_cyl_cbdi.ups say how), against sus.

tests/mpm/data/sus_cbdi.npz: sus's output of those decks (read with
framework.uintah_uda.UintahArchive): `linear_*` load_curve_cbdi.ups with <interpolator>linear and
<extraCells>[0,0,0] (sus refuses linear with extra cells), step 4: every 3rd sample particle
(ordered by x, y, z) and the p.externalforce of those with a load curve; `gimp_*` the deck as it
is, step 2: the loaded particles' p.externalforce and the nodes with a g.externalforce; `cyl_*`
press_smooth_cyl_cbdi.ups, step 4: every 8th particle, the loaded ones' p.externalforce, and the
number of particles localized (p.localizedMPM 1, 2) after each of the 8 steps."""
import pathlib

import numpy as np
import pytest

from components.mpm.cbdi import NO_CORNER, cells_size, corner_loads
from components.mpm.constitutive.damage import threshold_kernel
from framework.problemspec import InputError

from .helpers import run

HERE = pathlib.Path(__file__).parent
ZERO_ROTATION = "0 0 0 0 0 0 0 0 0 0\n9.9 0 0 0 0 0 0 0 0 0\n"


@pytest.fixture(scope="module")
def ref():
    return np.load(HERE / "data" / "sus_cbdi.npz")


def _match(x, rx):
    """Index of the particle of x nearest each reference position rx (one each)."""
    k = np.argmin(((rx[:, None, :] - x[None, :, :]) ** 2).sum(axis=2), axis=1)
    assert len(set(k)) == len(k)
    return k


def _equals_sus(p, ref, case, tols):
    """The sample particles' (matched by position to sus's `case`_x) p.x, p.velocity, p.stress
    within `tols` (label, relative to sus's largest value) and the loaded particles'
    p.externalforce within 1e-12 of sus's; returns the loaded particles' indices."""
    k = _match(p["p.x"], ref[f"{case}_x"])
    for lab, tol in tols:
        r = ref[f"{case}_{lab}"]
        assert np.abs(p[f"p.{lab}"][k] - r).max() <= tol * max(np.abs(r).max(), 1.0), lab
    k = _match(p["p.x"], ref[f"{case}_loaded_x"])
    r = ref[f"{case}_loaded_fext"]
    assert np.abs(p["p.externalforce"][k] - r).max() <= 1e-12 * np.abs(r).max()
    return k


def test_one_particle_loaded_face():
    """A particle of half-widths (0.1, 0.2, 0.3) m, dx 1 m, normal +z: the face centre is x +
    0.3 z, its corners +-0.1 x +-0.2 y; with F stretching x by 2 the force doubles (the face's
    area) and the corners move out to +-0.2 x. <outward_normal>false flips n: the face below."""
    x = np.array([[1.0, 2.0, 3.0]])
    size = cells_size(np.array([[0.1, 0.2, 0.3]]), np.ones(3))
    force = np.array([[0.0, 0.0, 8.0]])
    normal = np.array([[0.0, 0.0, 1.0]])
    for stretch, outward, z in ((1.0, True, 3.3), (2.0, True, 3.3), (1.0, False, 2.7)):
        F = np.eye(3)[None].copy()
        F[0, 0, 0] = stretch
        f, corners = np.zeros((1, 3)), np.full((1, 4, 3), NO_CORNER)
        corner_loads(np.array([0]), x, force, normal, outward, F, size, np.ones(3), f, corners)
        assert f[0] == pytest.approx([0.0, 0.0, 2.0 * stretch], abs=1e-15)
        expect = {(1.0 + a * 0.1 * stretch, 2.0 + b * 0.2, z) for a in (-1, 1) for b in (-1, 1)}
        assert {tuple(np.round(c, 12)) for c in corners[0]} == {tuple(np.round(e, 12)) for e in expect}


def test_mohr_coulomb_tension_then_shear():
    """Threshold's MohrCoulomb with cohesion c = 10, phi = 30 deg, tensile cutoff 0.5 (by hand):
    diag(6, 0, 0) fails in tension (6 > 0.5 c: 1; shear 3 < c cos phi - 6 sin phi / 2 = 7.16);
    diag(2, 0, -20) holds (shear 11 < 8.66 + 18 sin phi / 2 = 13.16); diag(4, 0, -30) fails in
    shear (17 > 8.66 + 26 sin phi / 2 = 15.16: 2); diag(1, 1, 1) holds."""
    stresses = [np.diag(d) for d in ((6.0, 0.0, 0.0), (2.0, 0.0, -20.0), (4.0, 0.0, -30.0), (1.0, 1.0, 1.0))]
    stress = np.array(stresses)
    n = len(stress)
    F = np.broadcast_to(np.eye(3), (n, 3, 3)).copy()
    eps, loc, tl = np.full(n, 10.0), np.zeros(n), np.full(n, -1e99)
    out = [np.empty(n) for _ in range(3)]
    threshold_kernel(2, True, 0, 1e-99, 0.0, F, stress, eps, loc, tl, *out, 30.0, 0.5)
    assert list(out[1]) == [1.0, 0.0, 2.0, 0.0]


def test_load_curve_cbdi_linear_equals_uintahs_sus(tmp_path, ref):
    """The pressure on the cylinder's end as CBDI corner forces, the torque on its side, linear
    weights, 4 steps: delT, p.x, p.velocity, p.stress and p.externalforce as sus's. Measured:
    delT equal, p.x 1.7e-16 m, p.velocity 4.3e-15, p.stress 7.3e-13, p.externalforce 5.7e-16 of
    the largest."""
    (tmp_path / "zeroRotation.txt").write_text(ZERO_ROTATION)
    text = (HERE / "load_curve_cbdi.ups").read_text()
    for old, new in (("<interpolator>gimp</interpolator>", "<interpolator>linear</interpolator>"),
                     ("<extraCells>[1,1,1]</extraCells>", "<extraCells>[0,0,0]</extraCells>")):
        assert old in text
        text = text.replace(old, new)
    _, da = run(text, tmp_path)
    assert np.allclose(da.times[1:], ref["linear_time"], rtol=1e-13, atol=0)
    p = da.particles(0, 4)
    assert len(p["p.x"]) == 800
    k = _equals_sus(p, ref, "linear", (("x", 1e-14), ("velocity", 1e-12), ("stress", 1e-10)))
    assert np.all(p["p.loadCurveID"][k, 0] > 0)


def test_load_curve_cbdi_deck_loads_equal_uintahs_sus(tmp_path, ref):
    """The deck itself (GIMP), its second step: the particles' CBDI loads (p.externalforce) and
    the nodes' g.externalforce spread from the loaded faces' corners as sus's (measured 5.8e-16 and
    1.3e-15 of the largest, delT equal; the run follows sus to 8 steps, delT within 3.7e-11, p.x
    1.1e-11: GIMP weights in Uintah's form, exactly 0 where a node is beyond a particle's reach,
    see shape._gimp3). The grid's total is four
    times the loads of the particles with a pressure load (each corner takes the particle's
    quarter), p(t) pi R^2: the torque-only particles' forces, with no corners, reach no node
    (as in Uintah)."""
    (tmp_path / "zeroRotation.txt").write_text(ZERO_ROTATION)
    text = (HERE / "load_curve_cbdi.ups").read_text().replace("<max_Timesteps>4</max_Timesteps>",
                                                             "<max_Timesteps>2</max_Timesteps>")
    _, da = run(text, tmp_path)
    assert np.allclose(da.times[1:], ref["gimp_time"], rtol=1e-14, atol=0)     # measured equal
    p = da.particles(0, 2)
    k = _match(p["p.x"], ref["gimp_loaded_x"])
    r = ref["gimp_loaded_fext"]
    assert np.abs(p["p.externalforce"][k] - r).max() <= 1e-13 * np.abs(r).max()
    g, coords = da.read("g.externalforce", 0, 2)
    nodes = ref["gimp_gext_node"]
    idx = tuple(np.rint((nodes[:, d] - coords[d][0]) / (coords[d][1] - coords[d][0])).astype(int) for d in range(3))
    assert np.abs(g[idx] - ref["gimp_gext"]).max() <= 1e-13 * np.abs(ref["gimp_gext"]).max()
    assert np.count_nonzero(np.abs(g).sum(axis=3)) == len(nodes)
    ids, f = p["p.loadCurveID"], p["p.externalforce"]
    pressure = np.any(ids == 1, axis=1)
    total = g.reshape(-1, 3).sum(axis=0)
    assert np.allclose(total, 4.0 * f[pressure].sum(axis=0), rtol=1e-12, atol=1e-9)   # a quarter per corner
    load = np.interp(da.times[1], [0.0, 0.0002, 0.01001, 0.015001], [-0.1, -1.0e5, -1.1e5, -1.2e5])
    assert total[2] == pytest.approx(load * np.pi * 0.5 ** 2, rel=1e-5)     # p pi R^2, the faces barely changed
    assert np.abs(f[~pressure]).sum() > 1e3          # the torque-only particles' forces, left out


def test_press_smooth_cyl_cbdi_equals_uintahs_sus(tmp_path, ref):
    """A quarter tube of smoothcyl particles, cpdi, CBDI pressure on its inner side, Threshold
    damage with MohrCoulomb: after step 4 delT, p.x, p.velocity, p.stress and p.externalforce
    as sus's (measured: delT 2e-16, p.x equal, p.velocity 6.2e-14, p.stress 8.2e-13,
    p.externalforce 7.2e-16 of the largest); sus's particles localized in shear
    (p.localizedMPM = 2) after each of the 8 steps (145 at step 6, 314 at step 8); the times of
    all 8 steps as sus's (measured 1.2e-16; the wave speed under <DoPressureStabilization> from
    J/rho0 of the stabilized F, as Uintah's UCNH)."""
    _, da = run((HERE / "press_smooth_cyl_cbdi.ups").read_text(), tmp_path)
    assert np.allclose(da.times[1:9], ref["cyl_time"], rtol=1e-13, atol=0)
    p = da.particles(0, 4)
    assert len(p["p.x"]) == 3140
    _equals_sus(p, ref, "cyl", (("x", 1e-14), ("velocity", 1e-11), ("stress", 1e-10)))
    localized = np.array([[np.sum(da.particles(0, s)["p.localizedMPM"] == v) for v in (1, 2)] for s in range(1, 9)])
    assert np.array_equal(localized, ref["cyl_localized"])
    assert localized[-1, 1] > 0


def _refused(tmp_path, text, *words):
    with pytest.raises(InputError) as e:
        run(text, tmp_path)
    for w in words:
        assert w in str(e.value), str(e.value)


def test_cbdi_needs_outward_normal_and_a_pressure(tmp_path):
    """As Uintah: with CBDI a <pressure> or <torque> must say <outward_normal>; CBDI without a
    <pressure> load (Uintah would read a p.loadCurveID it never made) is refused."""
    text = (HERE / "press_smooth_cyl_cbdi.ups").read_text()
    _refused(tmp_path, text.replace("<outward_normal>false</outward_normal>", ""), "outward_normal", "<pressure>")
    plain = text.replace("<use_load_curves> true </use_load_curves>", "<use_load_curves> false </use_load_curves>")
    start, end = plain.index("<PhysicalBC>"), plain.index("</PhysicalBC>") + len("</PhysicalBC>")
    _refused(tmp_path, plain[:start] + plain[end:], "use_CBDI_boundary_condition", "accepted: false")
