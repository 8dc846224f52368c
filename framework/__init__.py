"""The framework: grid, data warehouses, scheduler, archiver, controller.

Importing it makes numba's on-disk cache of this repository's kernels follow the modules each
kernel compiled in (numba_cache_deps), and keeps kernels compiled below numba's full optimisation
level apart in it (numba_cache_opt), before any kernel module is imported; numba compiles with
Python's cyclic garbage collector paused (numba_compile_gc) and types built-in calls on scalars
once per argument types (numba_typing_memo)."""
from . import numba_cache_deps  # noqa: F401
from . import numba_cache_opt  # noqa: F401
from . import numba_compile_gc  # noqa: F401
from . import numba_typing_memo  # noqa: F401
