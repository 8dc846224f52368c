"""The kernels of these packages inline their numba helpers (inline="always"): install the faster IR copy first."""
import framework.numba_inline  # noqa: F401
