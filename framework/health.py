"""The carried state's health, checked once per step: the first non-finite value, or the first
negative mass, volume, density or temperature, stops the run with one line naming the step,
variable, material and cell (or particle), instead of a later "delT = 0" or NaN output."""
import numpy as np
from numba import njit

from .errors import RunStopped
from .variables import VarType

# carried variables that are negative only in a blown-up state (Uintah label names)
NON_NEGATIVE = frozenset({"p.mass", "p.volume", "p.temperature", "rho_CC", "temp_CC", "sp_vol_CC"})


@njit(cache=True)
def first_bad(a, non_negative):
    """(i, j, k, component) of the first non-finite (or, if non_negative, negative) entry of a
    4-D view, or (-1, -1, -1, -1); NaN fails both comparisons, so one test per value."""
    ni, nj, nk, nc = a.shape
    for i in range(ni):
        for j in range(nj):
            for k in range(nk):
                for c in range(nc):
                    v = a[i, j, k, c]
                    if not (abs(v) <= 1.7976931348623157e308) or (non_negative and v < 0.0):
                        return i, j, k, c
    return -1, -1, -1, -1


def _as4d(arr, label_shape):
    """A 4-D view (no copy) of a grid or particle array: (i, j, k, component)."""
    ncomp = int(np.prod(label_shape)) if len(label_shape) else 1
    if arr.ndim == 3:
        return arr[..., None]
    if arr.ndim == 1:
        return arr.reshape(arr.shape[0], 1, 1, 1)
    if arr.ndim == 2 and arr.shape[1] == ncomp:
        return arr.reshape(arr.shape[0], 1, 1, ncomp)
    return arr.reshape(arr.shape[:3] + (-1,)) if arr.flags.c_contiguous else None


def find_blowup(dw, names, level, patches, label_registry):
    """The first bad value of the carried variables `names` on this rank's patches, as a phrase
    (variable, material, cell or particle, value), or None when the state is healthy."""
    by_id = {p.id: p for p in patches}
    for (name, m, pid), arr in dw.grid.items():
        p = by_id.get(pid)
        if p is None or name not in names or arr.dtype.kind != "f":
            continue
        label = label_registry.find(name)
        vt = label.vartype
        box = p.owned(vt)
        view = _as4d(arr[p.slices(vt, box)], label.shape)
        if view is None:
            continue
        i, j, k, c = first_bad(view, name in NON_NEGATIVE)
        if i >= 0:
            cell = (box[0][0] + i, box[0][1] + j, box[0][2] + k)
            comp = f" component {c}" if view.shape[3] > 1 else ""
            return (f"{name}{comp} of material {m} is {float(view[i, j, k, c])!r} in "
                    f"{'cell' if vt is VarType.CC else 'node/face'} {list(cell)} (patch {p.id})")
    for (name, m, pid), arr in dw.particles.items():
        if pid not in by_id or name not in names or arr.dtype.kind != "f" or arr.shape[0] == 0:
            continue
        view = _as4d(arr, label_registry.find(name).shape)
        if view is None:
            continue
        i, j, k, c = first_bad(view, name in NON_NEGATIVE)
        if i >= 0:
            ids = dw.particles.get(("p.particleID", m, pid))
            who = f"particle {int(ids[i])}" if ids is not None else f"particle index {i}"
            return f"{name} of material {m} is {float(view[i, j, k, c])!r} for {who} (patch {pid})"
    return None


def check_health(dw, names, level, patches, label_registry, comm, timestep):
    """Raise RunStopped on every rank when any rank finds a bad value; the lowest rank's finding
    is the one reported."""
    found = find_blowup(dw, names, level, patches, label_registry)
    flags = comm.allgather(found)
    first = next((f for f in flags if f is not None), None)
    if first is not None:
        raise RunStopped(f"the solution blew up at timestep {timestep}: {first}")
