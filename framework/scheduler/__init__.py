"""numba set-up for the kernels of these packages: the faster IR inlining (inline="always"
helpers), constant branches folded before typing, faster liveness analysis, SSA
reconstruction and compile-flag comparison, one compilation per kernel across processes
sharing a cache, the check that a cache directory is writable made once per directory, and a
kernel loaded from the cache without numba's whole target set-up."""
import framework.numba_cache_load  # noqa: F401
import framework.numba_cache_path  # noqa: F401
import framework.numba_compile_lock  # noqa: F401
import framework.numba_inline  # noqa: F401
import framework.numba_fold  # noqa: F401
import framework.numba_liveness  # noqa: F401
import framework.numba_ssa  # noqa: F401
import framework.numba_targetconfig  # noqa: F401
