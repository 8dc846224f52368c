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
