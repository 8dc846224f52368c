"""Tests of components.mpm.shape: partition of unity, linear exactness,
mass conservation and agreement of the fused kernels with the weight arrays."""
import numpy as np
import pytest

from components.mpm.shape import get_interpolator, lp_from_ppc, num_nodes

CASES = [(k, d) for k in ("linear", "gimp") for d in (1, 2, 3)]


def make_grid(dim, ncell=6, dx=(0.5, 0.25, 0.4)):
    """Patch with one ghost layer, node_low = -1 on active axes."""
    dx = np.array(dx)
    dx[dim:] = 1.0
    anchor = np.array([0.1, -0.3, 0.7])
    lo = np.array([-1 if d < dim else 0 for d in range(3)], np.int64)
    shape = tuple(ncell + 3 if d < dim else 1 for d in range(3))
    return anchor, dx, lo, shape


def make_particles(dim, anchor, dx, ncell, n=300, seed=0):
    rng = np.random.default_rng(seed)
    px = np.tile(anchor, (n, 1)).astype(np.float64)
    px[:, :dim] += rng.random((n, dim)) * ncell * dx[:dim]
    px[:, dim:] = anchor[dim:]
    return px


@pytest.mark.parametrize("kind,dim", CASES)
def test_partition_of_unity(kind, dim):
    anchor, dx, lo, shape = make_grid(dim)
    px = make_particles(dim, anchor, dx, 6)
    ip = get_interpolator(kind, dim)
    assert ip.nn == num_nodes(kind, dim) == (2 if kind == "linear" else 3) ** dim
    ni, S, dS = ip.weights(px, lp_from_ppc(len(px), dx, 2), anchor, dx, lo, shape)
    assert np.allclose(S.sum(1), 1.0, atol=1e-13)
    assert np.allclose(dS.sum(1), 0.0, atol=1e-11)
    assert (S >= -1e-15).all()
    assert (ni >= 0).all() and (ni < np.array(shape)).all()
    assert np.all(dS[:, :, dim:] == 0.0)


@pytest.mark.parametrize("kind,dim", CASES)
def test_linear_field_reproduced(kind, dim):
    anchor, dx, lo, shape = make_grid(dim)
    px = make_particles(dim, anchor, dx, 6, seed=1)
    n = len(px)
    lp = lp_from_ppc(n, dx, 2)
    ip = get_interpolator(kind, dim)
    A = np.array([[0.3, -1.2, 0.7], [2.0, 0.5, -0.4], [-0.8, 1.1, 0.9]])
    A[:, dim:] = 0.0  # field varies only along active axes
    b = np.array([1.0, -2.0, 0.5])
    I, J, K = np.meshgrid(*[np.arange(s) for s in shape], indexing="ij")
    xn = anchor + (np.stack([I, J, K], -1) + lo) * dx
    gvel = np.ascontiguousarray(xn @ A.T + b)
    gacc = np.ascontiguousarray(2.0 * gvel)
    pv = np.random.default_rng(2).random((n, 3))
    dt = 0.1
    pxn, pvn, pL = np.empty_like(px), np.empty_like(pv), np.empty((n, 3, 3))
    ip.g2p(px, pv, lp, anchor, dx, lo, gvel, gacc, dt, pxn, pvn, pL)
    vexact = px @ A.T + b
    assert np.allclose(pxn, px + dt * vexact, atol=1e-12)
    assert np.allclose(pvn, pv + dt * 2 * vexact, atol=1e-12)
    assert np.allclose(pL, np.broadcast_to(A, (n, 3, 3)), atol=1e-11)
    # the weight arrays give the same interpolation
    ni, S, dS = ip.weights(px, lp, anchor, dx, lo, shape)
    gv = gvel[ni[..., 0], ni[..., 1], ni[..., 2]]
    assert np.allclose((S[..., None] * gv).sum(1), vexact, atol=1e-12)
    assert np.allclose(np.einsum("pqi,pqj->pij", gv, dS), A, atol=1e-11)


@pytest.mark.parametrize("kind,dim", CASES)
def test_p2g_conservation_and_consistency(kind, dim):
    anchor, dx, lo, shape = make_grid(dim)
    px = make_particles(dim, anchor, dx, 6, seed=3)
    n = len(px)
    rng = np.random.default_rng(4)
    lp = lp_from_ppc(n, dx, 2)
    pm, pvol = rng.random(n) + 0.5, rng.random(n) + 0.1
    pv, pf = rng.random((n, 3)), rng.random((n, 3))
    ps = rng.random((n, 3, 3))
    ip = get_interpolator(kind, dim)
    gm, gvol = np.zeros(shape), np.zeros(shape)
    gp, ge, gi = (np.zeros(shape + (3,)) for _ in range(3))
    ip.p2g(px, pm, pv, pvol, ps, pf, lp, anchor, dx, lo, gm, gp, gvol, ge, gi)
    assert np.isclose(gm.sum(), pm.sum(), rtol=1e-13)
    assert np.isclose(gvol.sum(), pvol.sum(), rtol=1e-13)
    assert np.allclose(gp.sum((0, 1, 2)), (pm[:, None] * pv).sum(0), rtol=1e-13)
    assert np.allclose(ge.sum((0, 1, 2)), pf.sum(0), rtol=1e-13)
    assert np.allclose(gi.sum((0, 1, 2)), 0.0, atol=1e-10)  # sum dS = 0
    # reference scatter from the weight arrays (particle order shuffled)
    ni, S, dS = ip.weights(px, lp, anchor, dx, lo, shape)
    rm, ri = np.zeros(shape), np.zeros(shape + (3,))
    idx = (ni[..., 0].ravel(), ni[..., 1].ravel(), ni[..., 2].ravel())
    np.add.at(rm, idx, (pm[:, None] * S).ravel())
    fint = -np.einsum("p,pij,pqj->pqi", pvol, ps, dS).reshape(-1, 3)
    np.add.at(ri, idx, fint)
    assert np.allclose(gm, rm, atol=1e-13)
    assert np.allclose(gi, ri, atol=1e-12)
    # sorted order gives the same grid (stencil-buffer path)
    order = np.lexsort(px.T[::-1])
    gm2, gvol2 = np.zeros(shape), np.zeros(shape)
    gp2, ge2, gi2 = (np.zeros(shape + (3,)) for _ in range(3))
    ip.p2g(px[order], pm[order], pv[order], pvol[order], ps[order], pf[order],
           lp[order], anchor, dx, lo, gm2, gp2, gvol2, ge2, gi2)
    assert np.allclose(gm2, gm, atol=1e-13) and np.allclose(gi2, gi, atol=1e-12)


def test_gimp_weights_match_formula():
    """uGIMP 1D piecewise formula of Bardenhagen & Kober (h = 1, lp = 1/4)."""
    def ref(r, l):
        a = abs(r)
        if a < l:
            return 1 - (r * r + l * l) / (2 * l)
        if a <= 1 - l:
            return 1 - a
        if a < 1 + l:
            return (1 + l - a) ** 2 / (4 * l)
        return 0.0
    ip = get_interpolator("gimp", 1)
    xs = np.linspace(0.02, 4.98, 97)
    px = np.zeros((len(xs), 3))
    px[:, 0] = xs
    lp = np.full((len(xs), 3), 0.25)
    ni, S, dS = ip.weights(px, lp, np.zeros(3), np.ones(3), np.array([-1, 0, 0]), (8, 1, 1))
    ni = ni - np.array([1, 0, 0])  # global indices
    for p, x in enumerate(xs):
        for q in range(3):
            assert np.isclose(S[p, q], ref(x - ni[p, q, 0], 0.25), atol=1e-14)
        h = 1e-6
        fd = (ref(x + h - ni[p, 0, 0], 0.25) - ref(x - h - ni[p, 0, 0], 0.25)) / (2 * h)
        assert np.isclose(dS[p, 0, 0], fd, atol=1e-5)


def test_out_of_patch_raises():
    anchor, dx, lo, shape = make_grid(2)
    px = np.array([[anchor[0] - 5 * dx[0], anchor[1], anchor[2]]])
    ip = get_interpolator("linear", 2)
    with pytest.raises(IndexError):
        ip.weights(px, lp_from_ppc(1, dx, 2), anchor, dx, lo, shape)
