"""framework.numba_targetconfig: numba's compile flags give the same values (in the same
order), equality and hash as numba's own TargetConfig methods, for the flags a kernel's options give
and for configs differing in one option, set or left at its default."""
import itertools

from numba import njit
from numba.core import targetconfig
from numba.core.compiler import Flags

import framework.numba_targetconfig as numba_targetconfig


def _own_eq(a, b):
    return numba_targetconfig._numba_values(a) == numba_targetconfig._numba_values(b)


def test_same_values_equality_and_hash():
    import components  # noqa: F401  (installs the patch as every run does)
    assert targetconfig.TargetConfig.values is numba_targetconfig.values

    @njit
    def kernel(x):
        return x + 1

    kernel_flags = kernel.targetdescr.options.parse_as_flags(Flags(), {"nopython": True, "fastmath": True,
                                                                   "error_model": "numpy"})
    plain = Flags()
    nrt = Flags()
    nrt.nrt = True
    nrt_default = Flags()
    nrt_default.nrt = False                 # set, to its default: equal to `plain`
    copied = Flags(copy_from=kernel_flags)
    configs = [kernel_flags, plain, nrt, nrt_default, copied, kernel_flags.copy()]
    for c in configs:
        assert c.values() == numba_targetconfig._numba_values(c)
        assert list(c.values().items()) == list(numba_targetconfig._numba_values(c).items())
        assert hash(c) == numba_targetconfig._numba_hash(c)
    for a, b in itertools.product(configs, repeat=2):
        assert (a == b) == _own_eq(a, b), (a, b)
    assert plain == nrt_default and plain != nrt and kernel_flags == copied
