"""CPDI weights (shape.py, Sadeghirad, Brannon & Burghardt 2011) through the transfer kernels:
partition of unity and exact reproduction of linear fields for a sheared, stretched particle
domain, and the gradients against Uintah's alpha vectors (cpdiInterpolator.cc), written out here
from the paper's formula independently of the kernels."""
import pathlib

import numpy as np
import pytest

from components.mpm.shape import CPDI, cpdi_domains
from components.mpm.transfer import kernels, mass_gradient, one_run

from .helpers import run

DX = np.array([0.1, 0.1, 0.1])
N = 24
F2 = np.array([[1.7, 0.6, 0.0], [-0.5, 1.2, 0.0], [0.0, 0.0, 1.0]])
F3 = np.array([[1.7, 0.6, 0.2], [-0.5, 1.2, 0.3], [0.1, -0.4, 0.9]])
CASES = [(3, F2), (7, F3)]


def _particle(act, F):
    px = np.array([[1.13, 1.07, 0.05 if act == 3 else 1.21]])
    lp = np.array([[0.05, 0.05, 0.05]])        # half-widths: 1 particle per cell
    dom = np.empty((1, 18))
    cpdi_domains(act, F[None], lp, DX, 1e10, dom)
    return px, dom


def _grid(act):
    return (N, N, 1 if act == 3 else N)


def _weights(act, F):
    """S_i (p2g's mass of a unit-mass particle) and grad S_i (mass_gradient) on the grid."""
    px, dom = _particle(act, F)
    sh = _grid(act)
    gm, gmom, gvol, gfe, gfi = np.zeros(sh), np.zeros(sh + (3,)), np.zeros(sh), np.zeros(sh + (3,)), np.zeros(sh + (3,))
    p2g = kernels("cpdi", act)[0]
    part = (px, np.ones(1), np.zeros((1, 3)), np.ones(1), np.zeros((1, 3, 3)), np.zeros((1, 3)), dom)
    # no external force, no g.volume: the p2g variant the CPDI decks' runs compile (S_i does not depend on it)
    p2g(part, part, one_run(1), False, False, np.zeros(3), DX, np.zeros(3, np.int64), gm, gmom, gvol, gfe, gfi)
    dS = np.zeros(sh + (3,))
    mass_gradient(CPDI, act, px, np.ones(1), dom, np.zeros(3), DX, np.zeros(3, np.int64), dS)
    X = np.stack(np.meshgrid(*[np.arange(n) * DX[d] for d, n in enumerate(sh)], indexing="ij"), axis=-1)
    if act == 3:
        X[..., 2] = 0.0
    return px, gm, dS, X


@pytest.mark.parametrize("act,F", CASES)
def test_partition_of_unity_and_linear_fields(act, F):
    px, S, dS, X = _weights(act, F)
    d = 2 if act == 3 else 3
    assert abs(S.sum() - 1.0) < 1e-13
    assert np.abs(np.einsum("ijk,ijkl->l", S, X)[:d] - px[0, :d]).max() < 1e-13     # sum S_i x_i = x_p
    assert np.abs(dS.sum(axis=(0, 1, 2))).max() < 1e-11                            # sum grad S_i = 0
    G = np.einsum("ijka,ijkb->ab", X, dS)[:d, :d]                                  # sum x_i (x) grad S_i = I
    assert np.abs(G - np.eye(d)).max() < 1e-12
    assert (S > 0).sum() > (9 if act == 3 else 27)      # the domain spans more nodes than a linear stencil


def test_1d_gradients_partition_of_unity_and_linear_field():
    """CPDI's 1D stencil (act = 1), the bar stretched 1.7 times: sum grad S_i = 0 and
    sum x_i grad S_i = 1 exactly (d/dx of sum S_i = 1 and of sum S_i x_i = x), over more nodes
    than a linear stencil has. mass_gradient takes kind and act at run time, so this compiles
    no 1D transfer kernel (large-deformation runs use the 2D strip)."""
    F = np.diag([1.7, 1.0, 1.0])
    px = np.array([[1.13, 0.0, 0.0]])
    dom = np.empty((1, 18))
    cpdi_domains(1, F[None], np.array([[0.05, 0.05, 0.05]]), DX, 1e10, dom)
    dS = np.zeros((N, 1, 1, 3))
    mass_gradient(CPDI, 1, px, np.ones(1), dom, np.zeros(3), DX, np.zeros(3, np.int64), dS)
    x = np.arange(N) * DX[0]
    g = dS[:, 0, 0, 0]
    assert abs(g.sum()) < 1e-11
    assert abs(x @ g - 1.0) < 1e-12
    assert (g != 0).sum() > 2
    assert np.abs(dS[..., 1:]).max() == 0.0


def _uintah_alpha(r1, r2, r3):
    """cpdiInterpolator.cc's alpha vectors of its 8 corners (signs of r1, r2, r3 in its order)."""
    V = np.linalg.det(np.stack([r1, r2, r3], axis=1))
    corners = [(-1, -1, -1), (1, -1, -1), (1, 1, -1), (-1, 1, -1), (-1, -1, 1), (1, -1, 1), (1, 1, 1), (-1, 1, 1)]
    # gradient of the trilinear map's corner function averaged over the domain: J^-T s / 8, written
    # as in the paper with cross products: alpha = (s1 r2 x r3 + s2 r3 x r1 + s3 r1 x r2 + ...) / (8 V)
    out = []
    for s1, s2, s3 in corners:
        a = (s1 * np.cross(r2, r3) + s2 * np.cross(r3, r1) + s3 * np.cross(r1, r2)) / (8.0 * V)
        out.append(((s1, s2, s3), a))
    return out


def test_gradients_match_uintah_alpha():
    """3D: grad S_i = sum_c alpha_c N_i(x_c) with Uintah's alpha_c (r_k = 0.5 (F p.size) e_k)."""
    act, F = 7, F3
    px, S, dS, X = _weights(act, F)
    size = np.diag([1.0, 1.0, 1.0]) * DX          # p.size (1 ppc) in physical units
    r = 0.5 * F @ size
    want_S = np.zeros(_grid(act))
    want = np.zeros(_grid(act) + (3,))
    for s, a in _uintah_alpha(r[:, 0], r[:, 1], r[:, 2]):
        xc = px[0] + s[0] * r[:, 0] + s[1] * r[:, 1] + s[2] * r[:, 2]
        ix = np.floor(xc / DX).astype(int)
        f = xc / DX - ix
        for o in np.ndindex(2, 2, 2):
            phi = np.prod([f[d] if o[d] else 1.0 - f[d] for d in range(3)])
            want_S[tuple(ix + o)] += phi / 8.0
            want[tuple(ix + o)] += a * phi
    assert np.abs(S - want_S).max() < 1e-14
    assert np.abs(dS - want).max() < 1e-10 * np.abs(want).max()


def test_lcrit_pulls_corners_back():
    """Uintah's cpdi_lcrit: a domain whose corners reach beyond lcrit cells is rebuilt from corners
    scaled to lcrit; a pure stretch keeps its directions, so r_1 shrinks along x only."""
    F = np.diag([9.0, 1.0, 1.0])[None]
    lp = np.array([[0.05, 0.05, 0.05]])
    dom = np.empty((1, 18))
    cpdi_domains(7, F, lp, DX, 1.0, dom)
    c = np.hypot(np.hypot(4.5, 0.5), 0.5)          # corner length in cells before scaling
    assert np.isclose(dom[0, 0], 4.5 / c * DX[0])
    assert np.isclose(dom[0, 4], 0.5 / c * DX[1])
    assert np.isclose(np.sqrt(np.sum((dom[0, 0:3] + dom[0, 3:6] + dom[0, 6:9]) ** 2 / DX ** 2)), 1.0)


# Uintah's sus on uintah_reference/disks_cpdi.ups (its StrainEnergy.dat and KineticEnergy.dat, steps 1-5)
REF = pathlib.Path(__file__).parent / "uintah_reference"
SUS_TIME = [0.0079351507912921622, 0.015870301582584324, 0.023805452373876487, 0.031740603165168649,
            0.039675753956460891]
SUS_STRAIN_ENERGY = [0.000180084758813126, 0.0007078198371150878, 0.0015560681636971171, 0.0026896662551102687,
                     0.0040690101848720028]
TOL_ENERGY = 1e-11         # measured: 1.4e-13
TOL_STRESS = 1e-8          # relative to the largest component (138 Pa); measured 2.5e-9, the file keeps 11 digits
SUS_KINETIC_ENERGY = [0.12999999999999792, 0.12964354636631689, 0.12894698847294442, 0.12793794412735687,
                      0.12665157580828271]


def test_disks_cpdi_against_sus(tmp_path):
    """Two touching disks with <interpolator>cpdi for 5 steps, Uintah's update (USL): times,
    energies and the stress of every 8th particle (matched by position) as sus wrote them."""
    text = (REF / "disks_cpdi.ups").read_text().replace(
        "<interpolator>cpdi</interpolator>", "<interpolator>cpdi</interpolator><stress_update>usl</stress_update>")
    _, da = run(text, tmp_path)
    t, se = da.reduction("StrainEnergy")
    _, ke = da.reduction("KineticEnergy")
    assert np.allclose(t[-5:], SUS_TIME, rtol=1e-12)
    assert np.allclose(se[-5:], SUS_STRAIN_ENERGY, rtol=TOL_ENERGY)
    assert np.allclose(ke[-5:], SUS_KINETIC_ENERGY, rtol=TOL_ENERGY)
    ref = np.loadtxt(REF / "disks_cpdi_sus_stress.txt")
    parts = da.particles(0, -1)
    x, s = parts["p.x"], parts["p.stress"].reshape(-1, 9)
    near = np.argmin(((x[None, :, :2] - ref[:, None, :2]) ** 2).sum(axis=2), axis=1)
    assert np.abs(x[near, :2] - ref[:, :2]).max() < 1e-9      # sus has 2 particle layers in z, pysus 1
    assert np.abs(s[near] - ref[:, 3:]).max() < TOL_STRESS * np.abs(ref[:, 3:]).max()
