"""The multigrid's coarsest-level matrix (components/ice/solver/mg.py dense): built column by
column from the rows a cell's stencil reaches, it is the operator applied to every unit vector
(the full product, computed here in Python), and its inverse solves the level's equations."""
import numpy as np
import pytest

from components.ice.solver import mg


def _full_product(kap, F, dims, per):
    sh, n = kap.shape, kap.size
    M = np.zeros((n, n))
    u = np.zeros(sh)
    for col in range(n):
        u.ravel()[col] = 1.0
        for i in range(sh[0]):
            for j in range(sh[1]):
                for k in range(sh[2]):
                    dg, off = mg._row(kap, F, u, i, j, k, dims, per, sh)
                    M[(i * sh[1] + j) * sh[2] + k, col] = dg * u[i, j, k] - off
        u.ravel()[col] = 0.0
    return M


@pytest.mark.parametrize("shape,dims,per", [((5, 4, 1), (1, 1, 0), (0, 0, 0)), ((5, 4, 1), (1, 1, 0), (1, 0, 0)),
                                            ((3, 4, 5), (1, 1, 1), (0, 1, 1)), ((2, 3, 1), (1, 1, 0), (1, 1, 0)),
                                            ((1, 6, 1), (0, 1, 0), (0, 1, 0))])
def test_dense_is_the_operator_on_unit_vectors(shape, dims, per):
    rng = np.random.default_rng(len(shape) + sum(shape))
    kap, F = rng.random(shape), rng.random((3,) + tuple(c + 1 for c in shape))
    dims, per = np.array(dims), np.array(per)
    M = np.zeros((kap.size, kap.size))
    mg.dense(kap, F, dims, per, M)
    assert np.array_equal(M, _full_product(kap, F, dims, per))
    x = rng.random(shape)
    b = np.empty(shape)
    mg.residual(kap, F, x, np.zeros(shape), b, dims, per)      # b = -A x
    assert np.allclose(np.linalg.solve(M, -b.ravel()), x.ravel(), rtol=1e-10, atol=1e-12)


@pytest.mark.parametrize("shape,dims,per", [((25, 25, 1), (1, 1, 0), (0, 0, 0)), ((7, 6, 1), (1, 1, 0), (1, 0, 0)),
                                            ((5, 4, 7), (1, 1, 1), (0, 1, 1)), ((9, 1, 1), (1, 0, 0), (0, 0, 0))])
def test_coarse_operator_is_the_aggregated_fine_one(shape, dims, per):
    """coarsen() on odd and even extents: the coarse matrix is P^T A' P, with P the injection of
    a coarse cell's value into its (one or two) children along each coarsened direction and A'
    the fine operator with its faces along a coarsened direction halved (re-discretisation for
    twice the spacing). An odd extent's last coarse cell has one child and keeps the boundary
    face (a Dirichlet face when its coefficient is not zero)."""
    rng = np.random.default_rng(sum(shape))
    kap, F = rng.random(shape), rng.random((3,) + tuple(c + 1 for c in shape))
    dims, per = np.array(dims), np.array(per)
    cf = np.array([dims[d] and shape[d] >= 4 for d in range(3)], dtype=np.int64)
    csh = tuple((shape[d] + 1) // 2 if cf[d] else shape[d] for d in range(3))
    kc, Fc = np.zeros(csh), np.zeros((3,) + tuple(c + 1 for c in csh))
    mg.coarsen(kap, F, cf, kc, Fc)
    Fw = F * np.where(cf == 1, 0.5, 1.0)[:, None, None, None]
    A = np.zeros((kap.size, kap.size))
    mg.dense(kap, Fw, dims, per, A)
    P = np.zeros((kap.size, kc.size))
    for i, j, k in np.ndindex(shape):
        a, b, c = (i // 2 if cf[0] else i), (j // 2 if cf[1] else j), (k // 2 if cf[2] else k)
        P[(i * shape[1] + j) * shape[2] + k, (a * csh[1] + b) * csh[2] + c] = 1.0
    Ac = np.zeros((kc.size, kc.size))
    mg.dense(kc, Fc, dims, per, Ac)
    assert np.allclose(P.T @ A @ P, Ac, rtol=1e-13, atol=1e-13)


def test_an_odd_level_coarsens_to_a_small_dense_solve():
    """50 x 50 cells (a 25 x 25 first coarse level) no longer stop at 625 cells solved densely."""
    kap, F = np.ones((25, 25, 1)), np.ones((3, 26, 26, 2))
    h = mg.Hierarchy(kap, F, (1, 1, 0), (0, 0, 0))
    assert [s[:2] for s in h.shapes] == [(25, 25), (13, 13), (7, 7)]
    b = np.random.default_rng(0).random((25, 25, 1))
    assert np.all(np.isfinite(h.vcycle(b)))
