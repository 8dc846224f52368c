"""The framework: grid, data warehouses, scheduler, archiver, controller.

Importing it makes numba's on-disk cache of this repository's kernels follow the modules each
kernel compiled in (numba_cache_deps), before any kernel module is imported."""
from . import numba_cache_deps  # noqa: F401
