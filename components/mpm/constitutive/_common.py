"""Small 3x3 tensor helpers shared by the constitutive kernels."""
import numpy as np
from numba import njit


@njit(cache=True, inline="always")
def det3(A):
    return (A[0, 0] * (A[1, 1] * A[2, 2] - A[1, 2] * A[2, 1])
            - A[0, 1] * (A[1, 0] * A[2, 2] - A[1, 2] * A[2, 0])
            + A[0, 2] * (A[1, 0] * A[2, 1] - A[1, 1] * A[2, 0]))


@njit(cache=True)
def matmul3(a, b):
    """a b of 3x3 arrays (numba's @ needs scipy's BLAS)."""
    c = np.empty((3, 3))
    for i in range(3):
        for j in range(3):
            c[i, j] = a[i, 0] * b[0, j] + a[i, 1] * b[1, j] + a[i, 2] * b[2, j]
    return c


@njit(cache=True, inline="always")
def inv3(A, out):
    """out = A^-1 (3x3)."""
    d = 1.0 / det3(A)
    out[0, 0] = (A[1, 1] * A[2, 2] - A[1, 2] * A[2, 1]) * d
    out[0, 1] = (A[0, 2] * A[2, 1] - A[0, 1] * A[2, 2]) * d
    out[0, 2] = (A[0, 1] * A[1, 2] - A[0, 2] * A[1, 1]) * d
    out[1, 0] = (A[1, 2] * A[2, 0] - A[1, 0] * A[2, 2]) * d
    out[1, 1] = (A[0, 0] * A[2, 2] - A[0, 2] * A[2, 0]) * d
    out[1, 2] = (A[0, 2] * A[1, 0] - A[0, 0] * A[1, 2]) * d
    out[2, 0] = (A[1, 0] * A[2, 1] - A[1, 1] * A[2, 0]) * d
    out[2, 1] = (A[0, 1] * A[2, 0] - A[0, 0] * A[2, 1]) * d
    out[2, 2] = (A[0, 0] * A[1, 1] - A[0, 1] * A[1, 0]) * d


@njit(cache=True, inline="always")
def max_wavespeed(ws, c, vel, p):
    """Uintah's WaveSpeed: componentwise max over particles of c + |v_i|."""
    for d in range(3):
        s = c + abs(vel[p, d])
        if s > ws[d]:
            ws[d] = s


def new_wavespeed():
    return np.zeros(3)


def _get(d, tag, default=None):
    if tag in d:
        return float(d[tag])
    if default is None:
        raise KeyError(f"constitutive_model: missing <{tag}>")
    return float(default)
