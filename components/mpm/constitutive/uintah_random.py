"""Uintah's random numbers for per-particle material properties: its MusilRNG generator and the
Gaussian and Weibull draws its damage models make with it.

MusilRNG is a table-driven generator of twelve 4-bit digits: a 32-bit seed fills the last eight
digits' first state (highest nibble first), the first value is thrown away, and each value is
0.b1 b2 ... b12 in base 16.  Its values are exact dyadic fractions, so the draws below are the
same numbers Uintah draws (to the rounding of log, cos, pow and gamma).

Seeds as Uintah's damage models and UCNH make them: ``(seed + id // 32 + 1) << (id % 32)`` of the
patch's Uintah ID (unsigned 32-bit), so a draw depends on the patch layout and on the order in
which Uintah created the particles of the patch (materials.uintah_creation_order).
"""
import math

import numpy as np
from numba import njit

_NEXT = np.array([4, 7, 10, 15, 6, 13, 1, 8, 12, 9, 0, 14, 5, 11, 2, 3], np.int64)
STATE_SIZE = 37                    # a[12], b[12], d[12], point


def patch_seed(seed, patch_id):
    """Uintah's unique seed of a patch: (seed + id/32 + 1) << (id % 32), as 32 bits."""
    return ((int(seed) + patch_id // 32 + 1) << (patch_id % 32)) & 0xFFFFFFFF


@njit(cache=True)
def musil_start(seed, st):
    """Seed the generator state st (STATE_SIZE ints) and discard its first value, as Uintah."""
    s = seed & 0xFFFFFFFF
    st[:] = 0
    for i in range(8):
        st[4 + i] = (s >> (28 - 4 * i)) & 0x0F
    st[36] = 4
    musil_next(st)


@njit(cache=True)
def musil_next(st):
    """The generator's next value in [0, 1)."""
    point = st[36]
    for i in range(12):
        s = st[i] + st[12 + i]
        if st[24 + i] & 1:
            s = -s
        point = (point + 20 + s) & 0x0F
        st[24 + i] = st[i]
        st[i] = st[12 + i]
        st[12 + i] = _NEXT[point]
    st[36] = point
    r = 0.0
    for i in range(11, -1, -1):
        r = (r + st[12 + i]) / 16.0
    return r


@njit(cache=True, inline="always")
def gauss(st, mean, std, scale):
    """Uintah's Gaussian::rand: Box-Muller with two values, times the volume scale (1 without
    Uintah's volume scaling)."""
    x = musil_next(st)
    y = musil_next(st)
    return scale * (np.sqrt(-2.0 * np.log(x)) * np.cos(2.0 * np.pi * y) * std + mean)


@njit(cache=True, inline="always")
def weibull(st, mean, modulus, scale):
    """Uintah's Weibull::rand: scale eta (-ln y)^(1/modulus), eta = mean / Gamma(1 + 1/modulus)."""
    y = musil_next(st)
    eta = mean / math.gamma(1.0 / modulus + 1.0)
    return scale * eta * (-np.log(y)) ** (1.0 / modulus)
