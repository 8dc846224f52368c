"""Axisymmetric MPM (<MPM><axisymmetric>true</axisymmetric>, Uintah's; shape.AXI): x is r, y the
axis, the one cell in z the angle; particle volumes and masses are per radian.

Exact checks: the r-weighted GIMP weights against their definition (quadrature), a uniform
radial expansion u_r = a r giving the exact hoop rate L22 = a with both interpolators, a
uniform stress in equilibrium (GIMP), the mass per radian rho H (ro^2 - ri^2) / 2, and the
thick-walled cylinder under internal pressure against Lame (inputs/MPM/thick_cylinder_axi.ups).
Against Uintah's sus: TXC_Axi_Cyl and thickCylinderAXI_MPM (tests/mpm/uintah_reference/).
"""
import pathlib

import numpy as np
import pytest

from components.mpm.shape import AXI
from components.mpm.transfer import kernels, merged_p2g, one_run

from .helpers import MPM_INPUTS, deck_text, run
from .test_input_errors import _fails

HERE = pathlib.Path(__file__).parent
REF = HERE / "uintah_reference"
DX = np.array([0.1, 0.1, 0.1])
ACT = 3 | AXI


def _stencils(kind, px, lp):
    """Per particle: the node masses of a unit-mass particle (p2g) on an (r, z) grid whose node 1 is
    at r = 0 (node 0: the extra node GIMP reaches), the node positions, and the velocity gradient and
    F of the nodal field v = (a x, b y, 0) (grad pass). Returns (that list, a, b, the axis mask)."""
    # the axis masks, argument types and p2g flags of the shipped decks that compile these kernels
    # (no test-only compilation; the hoop terms do not depend on them): linear on (r, z) with its
    # sizes read-only, no external force and the volume (inputs/MPM/airbag.ups), GIMP with one cell
    # along the axis and both (inputs/MPM/thick_cylinder_axi.ups)
    act = ACT if kind == "linear" else 1 | AXI
    sh = (12, 8, 1) if act & 2 else (12, 1, 1)
    p2g, _, grad = kernels(kind, act)
    node_low = np.array([-1, -1 if act & 2 else 0, 0], np.int64)
    if kind == "linear":
        lp = lp.copy()
        lp.flags.writeable = False
    flags = (kind == "gimp", True)
    out = []
    a, b = 0.3, -0.7
    X = np.stack(np.meshgrid(*[(np.arange(n) + node_low[d]) * DX[d] for d, n in enumerate(sh)], indexing="ij"),
                 axis=-1)
    gv = np.zeros(sh + (3,))
    gv[..., 0], gv[..., 1] = a * X[..., 0], b * X[..., 1]
    for p in range(len(px)):
        gm = np.zeros(sh)
        z3 = [np.zeros(sh + (3,)) for _ in range(3)]
        x1 = px[p:p + 1]
        part = (x1, np.ones(1), np.zeros((1, 3)), np.ones(1), np.zeros((1, 3, 3)), np.zeros((1, 3)), lp[p:p + 1])
        p2g(part, part, one_run(1), *flags, np.zeros(3), DX, node_low, gm, z3[0], np.zeros(sh), z3[1], z3[2])
        L = np.empty((1, 3, 3))
        F = np.eye(3)[None].copy()
        Fn, vol = np.empty((1, 3, 3)), np.empty(1)
        grad(x1, lp[p:p + 1], np.zeros(3), DX, node_low, gv, L, True, 0.01, np.ones(1), 1.0, F, Fn, vol, 0, 0.0,
             0.0, np.zeros((1, 3)), np.zeros((1, 3, 3)), np.zeros(1))
        out.append((gm, X, L[0], Fn[0]))
    return out, a, b, act


# particles in the first cells (the GIMP domain of the first crosses the axis), mid-cell, at a node
PX = np.array([[0.02, 0.33, 0.0], [0.07, 0.41, 0.0], [0.125, 0.25, 0.0], [0.31, 0.5, 0.0], [0.6, 0.37, 0.0]])
LP = np.full((len(PX), 3), 0.025)           # half-widths: 2 particles per cell


def _quadrature(xp, l, xn, h):
    """<N>, <dN/dr>, <N/r> of the hat of the node at xn over [max(xp - l, 0), xp + l], weight r dr."""
    c0, c1, n = max(xp - l, 0.0), xp + l, 400000
    r = c0 + (np.arange(n) + 0.5) * (c1 - c0) / n          # midpoints: never on a kink of the hat
    u = (r - xn) / h
    N = np.maximum(0.0, 1.0 - np.abs(u))
    dN = np.where(np.abs(u) < 1.0, -np.sign(u) / h, 0.0)
    return np.sum(N * r) / np.sum(r), np.sum(dN * r) / np.sum(r), np.sum(N) / np.sum(r)


def test_gimp_weights_are_the_r_weighted_averages():
    """S_i = <N_i>, grad S_i = <N_i'>, the hoop value <N_i / r> (Nairn's axisymmetric GIMP, Uintah's
    AxiGIMP), against a quadrature of those definitions; near the axis the domain is cut at r = 0."""
    from components.mpm.shape import GIMP, _ax_axi
    for xp in (0.02, 0.03, 0.07, 0.125, 0.31, 0.6):
        i, w0, w1, w2, g0, g1, g2, t0, t1, t2 = _ax_axi(GIMP, xp, 0.0, 10.0, 0.025)
        for k, (w, g, t) in enumerate(((w0, g0, t0), (w1, g1, t1), (w2, g2, t2))):
            S, G, T = _quadrature(xp, 0.025, (i + k) * 0.1, 0.1)
            assert abs(w - S) < 1e-9 and abs(g - G) < 1e-5 and abs(t - T) < 1e-6 * max(1.0, abs(T)), (xp, k, w - S, g - G, t - T)
        assert abs(w0 + w1 + w2 - 1.0) < 1e-14


@pytest.mark.parametrize("kind", ["linear", "gimp"])
def test_uniform_radial_expansion_gives_the_exact_hoop_rate(kind):
    """v = (a r, b z, 0) on the nodes: L = diag(a, b, a) exactly (the hoop rate u_r / r = a; GIMP's run
    has one cell along the axis, L = diag(a, 0, a)), and F22 after one step is 1 + a dt; the weights sum
    to 1. Linear's r-average of the node positions is r_p, GIMP's is
    <r> = int r^2 dr / int r dr (its weights are averages with the weight r dr)."""
    out, a, b, act = _stencils(kind, PX, LP)
    for p, (gm, X, L, F) in enumerate(out):
        assert abs(gm.sum() - 1.0) < 1e-14
        c0, c1 = max(PX[p, 0] - LP[p, 0], 0.0), PX[p, 0] + LP[p, 0]
        r_avg = PX[p, 0] if kind == "linear" else (c1 ** 3 - c0 ** 3) / 1.5 / (c1 ** 2 - c0 ** 2)
        assert abs(np.einsum("ijk,ijk->", gm, X[..., 0]) - r_avg) < 1e-14
        assert np.abs(L - np.diag([a, b if act & 2 else 0.0, a])).max() < 1e-13, L
        assert abs(F[2, 2] - (1.0 + 0.01 * a)) < 1e-14 and abs(F[0, 0] - (1.0 + 0.01 * a)) < 1e-14


def test_uniform_stress_is_in_equilibrium():
    """A block of GIMP particles (2 per cell, from the axis to r = 0.6) under sigma = -p I: the internal
    force int (r dN/dr + N) dr dz sigma vanishes at every node whose support lies inside the block,
    those on the axis included (the hoop term balances the radial one)."""
    p2g = merged_p2g(kernels("gimp", ACT)[0])      # with has_f: TXC_Axi_Cyl's p2g variant (no new compilation)
    h = 0.025
    r = np.arange(h, 0.6, 2 * h)
    z = np.arange(0.2 + h, 0.6, 2 * h)
    R, Z = np.meshgrid(r, z, indexing="ij")
    n = R.size
    px = np.stack([R.ravel(), Z.ravel(), np.zeros(n)], axis=1)
    vol = px[:, 0] * (2 * h) ** 2
    stress = np.broadcast_to(-1e6 * np.eye(3), (n, 3, 3)).copy()
    sh = (12, 10, 1)
    gm, fi = np.zeros(sh), np.zeros(sh + (3,))
    p2g(px, vol, np.zeros((n, 3)), vol, stress, np.zeros((n, 3)), True, np.full((n, 3), h), np.zeros(3), DX,
        np.array([-1, 0, 0], np.int64), gm, np.zeros(sh + (3,)), np.zeros(sh), np.zeros(sh + (3,)), fi)
    inner = fi[1:7, 3:6, 0, :2]                  # nodes r = 0 .. 0.5, z = 0.3 .. 0.5
    scale = 1e6 * 0.1 * 0.1 * 0.6              # p times a node's support area times the largest r
    assert np.abs(inner).max() < 1e-12 * scale, inner
    assert abs(fi[7, 4, 0, 0]) > 1e-3 * scale          # the block's outer face (r = 0.6) is loaded


@pytest.fixture(scope="module")
def lame(tmp_path_factory):
    d = tmp_path_factory.mktemp("axi")
    runs = {}
    for case, kind, update in (("gimp", "gimp", "musl"), ("linear", "linear", "usl"), ("hypo", "gimp", "usl")):
        text = deck_text(MPM_INPUTS / "thick_cylinder_axi.ups", interpolator=kind)
        text = text.replace("<axisymmetric>", f"<stress_update>{update}</stress_update><axisymmetric>")
        if case == "hypo":          # hypo_elastic: the stress from L (its hoop rate L22), not F
            text = text.replace('type="comp_neo_hook"', 'type="hypo_elastic"')
            text = text.replace("bulk_modulus>", "K>").replace("shear_modulus>", "G>")
        runs[case] = run(text, d, name=case)[1].particles(0, -1)
    text = deck_text(MPM_INPUTS / "thick_cylinder_axi.ups", resolution="[22,1,1]")
    runs["gimp22"] = run(text, d, name="gimp22")[1].particles(0, -1)
    return runs


P, RI, RO, K, MU = 19.4e6, 0.5, 1.0, 117.0e9, 43.8e9


def _lame(r):
    lam = K - 2 * MU / 3
    A = P * RI ** 2 / (2 * (lam + MU) * (RO ** 2 - RI ** 2))
    B = P * RI ** 2 * RO ** 2 / (2 * MU * (RO ** 2 - RI ** 2))
    return A * r + B / r, 2 * (lam + MU) * A - 2 * MU * B / r ** 2, 2 * (lam + MU) * A + 2 * MU * B / r ** 2, \
        2 * lam * A


@pytest.mark.parametrize("kind", ["gimp", "linear", "hypo"])
def test_thick_cylinder_against_lame(lame, kind):
    """inputs/MPM/thick_cylinder_axi.ups (40 particles across the wall, plane strain, quasi-static):
    radial displacement, hoop and axial stress against Lame, comp_neo_hook with GIMP and MUSL, with
    linear and USL, and hypo_elastic with GIMP and USL. Measured (the three): u_r within 0.95 %,
    0.96 %, 0.95 % of the largest; on average sigma_theta within 1.6 % of P, sigma_z 1.7 %, sigma_r
    2.0 % inside the wall (all three). The mass is rho H (ro^2 - ri^2) / 2 to roundoff (4e-16)."""
    p = lame[kind]
    x, s, F = p["p.x"], p["p.stress"], p["p.deformationMeasure"]
    assert len(x) == 40
    assert abs(p["p.mass"].sum() / (8900 * 0.05 * (RO ** 2 - RI ** 2) / 2) - 1) < 1e-14
    r0 = x[:, 0] / F[:, 2, 2]                   # the reference radius: F22 is the hoop stretch r / r0
    u, sr, st, sz = _lame(r0)
    err_u = np.abs(x[:, 0] - r0 - u).max() / u.max()
    assert err_u < 0.012, err_u
    assert np.mean(np.abs(s[:, 2, 2] - st)) < 0.025 * P
    assert np.mean(np.abs(s[:, 1, 1] - sz)) < 0.025 * P
    inside = (r0 > 0.6) & (r0 < 0.95)           # away from the point-loaded inner layer
    assert np.mean(np.abs(s[inside, 0, 0] - sr[inside])) < 0.03 * P


def _u_error(p):
    x, F = p["p.x"], p["p.deformationMeasure"]
    r0 = x[:, 0] / F[:, 2, 2]
    u = _lame(r0)[0]
    return np.abs(x[:, 0] - r0 - u).max() / u.max()


def test_thick_cylinder_converges(lame):
    """The displacement error halves with the cell size (GIMP, MUSL). Measured: 0.0175, 0.0095 at 22,
    44 cells (0.0052, 0.0029 at 88, 176, not run here): first order."""
    e22, e44 = _u_error(lame["gimp22"]), _u_error(lame["gimp"])
    assert e44 < 0.0105 and e22 / e44 > 1.6, (e22, e44)


def _sus(name, npz, steps, interval, tmp_path):
    text = deck_text(REF / name, outputTimestepInterval=interval)
    text = text.replace("<interpolator>gimp</interpolator>", "<interpolator>gimp</interpolator>"
                        "<stress_update>usl</stress_update>")
    assert "usl" in text
    da = run(text, tmp_path)[1]
    ref = np.load(HERE / "data" / npz)
    assert da.times[-1] == pytest.approx(float(ref["time"]), rel=1e-8)
    return da, ref


def _sorted(x, *f):
    o = np.lexsort(np.round(x, 6).T)
    return [x[o]] + [g[o] for g in f]


def _energies_match(da, ref, tol, tol_se):
    """The energies pysus wrote (a line every step) against sus's rows of the same time. While
    the strain energy is below 1e-2 of its peak (TXC_Axi_Cyl's first ~10 steps, sus's even
    negative at step 1) the two codes' sums differ by up to 3.1e-6 of the peak (measured); there
    the bound is the larger of tol and 5e-6 of the peak, elsewhere tol of the peak."""
    for lab, tol in (("KineticEnergy", tol), ("StrainEnergy", tol_se)):
        t, v = (np.asarray(a) for a in da.reduction(lab))
        r = ref["ke" if lab == "KineticEnergy" else "se"]
        k = np.abs(r[None, :, 0] - t[t > 0][:, None]).argmin(axis=1)
        assert np.allclose(r[k, 0], t[t > 0], rtol=1e-9) and len(k) == len(r)
        scale = np.abs(r[:, 1]).max()
        diff = np.abs(v[t > 0] - r[k, 1])
        small = np.abs(r[k, 1]) < 1e-2 * scale
        assert diff[~small].max() < tol * scale, lab
        assert diff[small].max(initial=0.0) < max(tol, 5e-6) * scale, lab


def test_txc_axi_cyl_equals_uintahs_sus(tmp_path):
    """Uintah's TXC_Axi_Cyl (axisymmetric GIMP, a cylinder squeezed through <axisymmetric_side> and
    <axisymmetric_end> pressures, the near-axis particles' domains cut at r = 0), 101 steps against sus:
    every 10th particle's (ordered by position) p.x, p.velocity, p.stress of puda -partvar at step 101,
    and sus's KineticEnergy.dat, StrainEnergy.dat. Measured: agreement to the 9 digits puda prints
    (5e-10 m, 5e-11 m/s on 0.017 m/s, 8e-4 Pa on 5.9e5 Pa); the kinetic energy to 1e-10, the strain
    energy to 1.2e-7 (the model's energy loses digits to cancellation at these small strains)."""
    da, ref = _sus("TXC_Axi_Cyl.ups", "sus_txc_axi_cyl.npz", 101, 101, tmp_path)
    p = da.particles(0, -1)
    x, v, s = _sorted(p["p.x"], p["p.velocity"], p["p.stress"])
    assert len(x) == int(ref["n"]) == 2000
    x, v, s = x[::10], v[::10], s[::10]
    assert np.abs(x - ref["x"]).max() < 2e-9
    assert np.abs(v - ref["velocity"]).max() < 1e-8 * np.abs(ref["velocity"]).max()
    assert np.abs(s - ref["stress"]).max() < 1e-8 * np.abs(ref["stress"]).max()
    _energies_match(da, ref, 1e-8, 1e-6)


def test_thick_cylinder_axi_equals_uintahs_sus(tmp_path):
    """Uintah's thickCylinderAXI_MPM (one cell along the axis, a pressure on a cylinder about z with
    Uintah's whole-surface area), 31 steps against sus: p.x, p.stress of all 50 particles (puda
    -partvar) and the energies. Measured: agreement to the digits puda prints (5e-10 m, 9e-5 Pa on
    9e4 Pa), the kinetic energy to 1e-10; the strain energy to 7e-4 (at strains of 1e-6 the
    model's (K/2)((J^2 - 1)/2 - ln J) loses its digits to cancellation: sus's own is negative in
    steps 3 and 4). (Later, once the stress wave's precursor reaches the free outer surface, its nodes take
    weights ~ (displacement / dx)^2 that the two codes round differently, and USL carries that into
    the outer particles' stress: 5e-5 of the largest stress at step 101.)"""
    da, ref = _sus("thickCylinderAXI_MPM.ups", "sus_thick_cylinder_axi.npz", 31, 31, tmp_path)
    p = da.particles(0, -1)
    x, s = _sorted(p["p.x"], p["p.stress"])
    rx, rs = _sorted(ref["x"], ref["stress"])
    assert len(x) == int(ref["n"]) == 50
    assert np.abs(x - rx).max() < 2e-9
    assert np.abs(s - rs).max() < 1e-8 * np.abs(rs).max()
    _energies_match(da, ref, 1e-8, 2e-3)


AXI_DECK = MPM_INPUTS / "thick_cylinder_axi.ups"


def test_refusals(tmp_path):
    """What axisymmetric MPM does not implement is refused at its tag."""
    _fails(tmp_path, deck_text(AXI_DECK, resolution="[44,1,2]", interpolator="linear"), "MPM/axisymmetric>", "one cell in z", ".ups:")
    _fails(tmp_path, deck_text(AXI_DECK, lower="[-0.1,0,-0.005]"), "lower x", ">= 0")
    _fails(tmp_path, deck_text(AXI_DECK, axisymmetric="false"), "<axisymmetric_side>", "axisymmetric>true")
    text = open(HERE.parent.parent / "inputs" / "MPMICE" / "piston.ups").read()
    text = text.replace("<MPM>", "<MPM><axisymmetric>true</axisymmetric>", 1)
    _fails(tmp_path, text, "MPM/axisymmetric>", "MPMICE", "accepted: false")


# sus on uintah_reference/test_cyl_pene_no_ero_axi_sym.ups (10 steps, read from its uda with
# framework.uintah_uda.UintahArchive): times, KineticEnergy.dat, StrainEnergy.dat; p.x,
# p.stress, p.plasticStrain, p.temperature of every particle at step 10
CYL_PENE_TOL_X = 1e-11             # m; measured 4.9e-13
CYL_PENE_TOL = 1e-7                # of the largest (stress, plastic strain, T - 294 K, energies); measured
#                                    stress 6.2e-9, plastic strain 1.4e-8, T 1.9e-8, KE 5e-11, SE 7.7e-9


def test_cyl_pene_axi_sym_equals_uintahs_sus(tmp_path):
    """Uintah's test_cyl_pene_no_ero_axi_sym (axisymmetric GIMP, a steel projectile at 800 m/s into
    an iron target, elastic_plastic_hp heating the particles without conduction, artificial
    viscosity, friction_bard contact with its normals from the density gradient, the symmetry
    face's condition on them and the compression test; 2 x 2 patches), 10 steps against sus:
    p.x, p.stress, p.plasticStrain, p.temperature of every particle and the energies agree to
    round-off (the Newton tolerance 5e-10 of the plasticity)."""
    text = (REF / "test_cyl_pene_no_ero_axi_sym.ups").read_text(encoding="iso-8859-1").replace(
        "<interpolator>                    gimp      </interpolator>",
        "<interpolator>gimp</interpolator><stress_update>usl</stress_update>")
    assert "usl" in text
    da = run(text, tmp_path)[1]
    ref = np.load(HERE / "data" / "sus_cyl_pene_axi.npz")
    assert np.allclose(np.asarray(da.times)[-10:], ref["time"], rtol=1e-12)
    for m in (0, 1):
        p = da.particles(m, -1)
        x, rx = p["p.x"], ref[f"x{m}"]
        assert len(x) == len(rx) == (800, 213)[m]
        k = np.argmin(((rx[:, None, :2] - x[None, :, :2]) ** 2).sum(axis=2), axis=1)
        assert len(set(k)) == len(k)
        assert np.abs(x[k] - rx).max() < CYL_PENE_TOL_X
        for lab, key, off in (("p.stress", "stress", 0.0), ("p.plasticStrain", "ep", 0.0), ("p.temperature", "T", 294.0)):
            r = ref[f"{key}{m}"] - off
            assert np.abs(p[lab][k] - off - r).max() < CYL_PENE_TOL * np.abs(r).max(), (m, lab)
    # pysus's StrainEnergy of a rate model is the total, sus's the step's increment (docs/MPM.md)
    for lab, key, total in (("KineticEnergy", "ke", False), ("StrainEnergy", "se", True)):
        t, v = (np.asarray(a) for a in da.reduction(lab))
        r = np.cumsum(ref[key][:, 1]) if total else ref[key][:, 1]
        assert np.allclose(t[t > 0], ref[key][:, 0], rtol=1e-12)
        assert np.abs(v[t > 0] - r).max() < CYL_PENE_TOL * np.abs(r).max(), lab


# sus on uintah_reference/axi_cpdi_plate.ups (10 steps, read from its uda with UintahArchive):
# times, KineticEnergy.dat, StrainEnergy.dat; p.x, p.stress, p.scalefactor, p.volume at step 10
AXI_CPDI_TOL_X = 1e-11             # m; measured 6e-13
AXI_CPDI_TOL = 1e-7                # of the largest; measured stress 9.6e-9, scale factor 3e-11, volume 3e-11


def test_axisymmetric_cpdi_equals_uintahs_sus(tmp_path):
    """Axisymmetric CPDI (Uintah's axiCpdiInterpolator: the in-plane domain's 4 corners, hoop
    value S/r at the particle, no cpdi_lcrit) on a ring of ColPlate_AffineTrans's material moving
    in towards the axis, 10 steps against sus: p.x, p.stress, p.scalefactor, p.volume of every
    particle and the energies. (A domain whose corner crosses the axis is not covered: there the
    two codes part, 2e-5 of the stress a step after it happens, open.)"""
    text = (REF / "axi_cpdi_plate.ups").read_text().replace(
        "<interpolator>                cpdi     </interpolator>",
        "<interpolator>cpdi</interpolator><stress_update>usl</stress_update>")
    assert "usl" in text
    da = run(text, tmp_path)[1]
    ref = np.load(HERE / "data" / "sus_axi_cpdi_plate.npz")
    assert np.allclose(np.asarray(da.times)[-10:], ref["time"], rtol=1e-12)
    p = da.particles(0, -1)
    x, rx = p["p.x"], ref["x"]
    assert len(x) == len(rx) == 160
    k = np.argmin(((rx[:, None, :2] - x[None, :, :2]) ** 2).sum(axis=2), axis=1)
    assert len(set(k)) == len(k)
    assert np.abs(x[k] - rx).max() < AXI_CPDI_TOL_X
    for lab, key in (("p.stress", "stress"), ("p.scalefactor", "scalefactor"), ("p.volume", "volume")):
        assert np.abs(p[lab][k] - ref[key]).max() < AXI_CPDI_TOL * np.abs(ref[key]).max(), lab
    for lab, key, total in (("KineticEnergy", "ke", False), ("StrainEnergy", "se", True)):
        t, v = (np.asarray(a) for a in da.reduction(lab))
        r = np.cumsum(ref[key][:, 1]) if total else ref[key][:, 1]
        assert np.allclose(t[t > 0], ref[key][:, 0], rtol=1e-12)
        assert np.abs(v[t > 0] - r).max() < AXI_CPDI_TOL * np.abs(r).max(), lab


# sus on uintah_reference/ColPlate_AffineTrans.ups (5 steps): times, TotalMomentum.dat, the particle
# count and p.x, p.velocity, p.stress, p.scalefactor of every 20th particle (ordered by position)
# at step 5 (read from sus's uda with UintahArchive)
COLPLATE_TOL_X = 1e-11             # m; measured 8e-14
COLPLATE_TOL = 1e-7                # of the largest; measured stress 3.8e-9, velocity 2.8e-10, scale factor 1.6e-11, momentum 1.5e-12


def test_colplate_affine_trans_equals_uintahs_sus(tmp_path):
    """Uintah's ColPlate_AffineTrans (axisymmetric CPDI; a plate of lattice particles turned by 50
    degrees and moved by its <affineTransformation_A0..A2, b>, so each domain is a turned
    parallelogram, p.sizeMatrix; elastic_plastic_hp with Mie-Gruneisen; the plate reaches the
    axis, where the domains' corners cross into the extra nodes, which the symmetry plane fills
    with the mirrored velocity), 5 steps against sus: the 8000 particles, their p.x, p.velocity,
    p.stress, p.scalefactor and TotalMomentum."""
    text = (REF / "ColPlate_AffineTrans.ups").read_text(encoding="iso-8859-1").replace(
        "<interpolator>                cpdi     </interpolator>",
        "<interpolator>cpdi</interpolator><stress_update>usl</stress_update>")
    assert "usl" in text
    da = run(text, tmp_path)[1]
    ref = np.load(HERE / "data" / "sus_colplate_affine.npz")
    assert np.allclose(np.asarray(da.times)[-5:], ref["time"], rtol=1e-12)
    p = da.particles(0, -1)
    x, rx = p["p.x"], ref["x"]
    assert len(x) == int(ref["n"]) == 8000
    k = np.argmin(((rx[:, None, :2] - x[None, :, :2]) ** 2).sum(axis=2), axis=1)
    assert np.abs(x[k] - rx).max() < COLPLATE_TOL_X
    for lab, key in (("p.velocity", "velocity"), ("p.stress", "stress"), ("p.scalefactor", "scalefactor")):
        assert np.abs(p[lab][k] - ref[key]).max() < COLPLATE_TOL * np.abs(ref[key]).max(), lab
    t, mom = (np.asarray(a) for a in da.reduction("TotalMomentum"))
    r = ref["momentum"]
    assert np.allclose(t[t > 0], r[:, 0], rtol=1e-12)
    assert np.abs(mom[t > 0] - r[:, 1:]).max() < COLPLATE_TOL * np.abs(r[:, 1:]).max()
