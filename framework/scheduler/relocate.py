"""Particle relocation: hand particles that left their patch to the patch now holding them.

The component writes the new particle state under "pre-relocation" labels (p.x+ ...);
this step moves every particle to the patch containing its new position, on whatever
rank, and puts the state under the final labels (p.x ...). Particles that left the
domain through a non-periodic face, or whose position is NaN (the way a component
deletes a particle), are removed. With a particle-ID label registered, each patch's
particles are kept sorted by ID, so sums over particles do not depend on the patch
layout.

Cost: a patch nobody left or entered hands its arrays on untouched; otherwise only the
leavers are packed, and each variable of the patch is written once, by one gather of
its staying particles merged with the arrivals in their final order (found by binary
search of the arrivals' IDs among the patch's sorted ones). The one pass over the
positions that finds the leavers also finds the particles near the faces, the ghost
candidates of the next step's exchange, for the patches whose positions are handed on.
"""
from __future__ import annotations

import sys
from dataclasses import dataclass

import numpy as np

from .. import labels as L
from ..errors import RunStopped
from ..task import NEW, Task
from .comm import ghost_widths, particle_plan
from .particle_kernels import KNOWN_SORTED, complement, gather_runs, in_boxes, leavers_near, relocation_runs, runs


@dataclass
class RelocationSpec:
    pos_pre: object
    labels_pre: list
    pos: object
    labels: list
    matls: tuple
    id_label: object = None
    mass_pre: object = None          # pre-relocation mass label: lost mass is reported
    on_leaving: str = "warn"         # particles leaving the domain: "warn" or "error"


def relocation_task(specs: list[RelocationSpec]) -> Task:
    """The step's one relocation task over every particle set (each its own materials)."""
    t = Task("relocateParticles", None, sorted({m for spec in specs for m in spec.matls}))
    t.relocation = list(specs)
    for spec in specs:
        for lp in [spec.pos_pre] + spec.labels_pre:
            t.requires(NEW, lp, matls=list(spec.matls))
        for lf in [spec.pos] + spec.labels:
            t.computes(lf, matls=list(spec.matls))
    if any(spec.mass_pre is not None for spec in specs):
        t.computes(L.LostParticleMass)
    return t


def _rows(a):
    """a as a C-contiguous (n, k) view (a copy only if a is not contiguous)."""
    return np.ascontiguousarray(a).reshape(len(a), int(np.prod(a.shape[1:])))


_warm: set = set()


def _load_kernels(dtypes):
    """Compile (or load from numba's cache) the kernels that only run when particles cross,
    for these dtypes, so the first step that moves particles does not pay for it."""
    for dt in dtypes:
        if dt in _warm:
            continue
        _warm.add(dt)
        one = np.zeros((1, 1), dt)
        gather_runs(one, one, runs(np.zeros(1, np.int64), 1), np.empty((1, 1), dt))
    if None not in _warm:
        _warm.add(None)
        none = np.zeros(0, np.int64)
        complement(none, 1)
        relocation_runs(np.zeros(1, np.int64), none, none, none, np.zeros(0, np.bool_), True)


def relocate(ex, spec: RelocationSpec, dw):
    """Move particles between patches (and ranks); puts the final labels in dw."""
    level, rank_of, comm = ex.level, ex.lb.rank_of, ex.comm
    _load_kernels({np.dtype(lf.dtype) for lf in [spec.pos] + spec.labels})
    pre = [spec.pos_pre] + spec.labels_pre
    final = [spec.pos] + spec.labels
    dims = np.array([not c for c in level.collapsed])
    stay = {}       # (m, patch id) -> (particles before, indices of those leaving or None: none)
    pos_label = getattr(ex, "position_label", None)
    widths = ghost_widths(ex) if pos_label is not None and pos_label.name == spec.pos.name else []
    near = {}       # (m, patch id) -> ghost candidates (indices, cells) of a patch nobody left
    arrivals = {}   # (m, patch id) -> [(source patch id, {final name: array})]
    outgoing = {}
    lost = 0
    left = np.zeros((len(spec.matls), 2))      # per material: particles and mass that left the domain
    for m in spec.matls:
        for p in ex.local_patches:
            x = dw.get(spec.pos_pre, m, p)
            if len(x) == 0:
                continue
            out, ni, nc = leavers_near(x, level.anchor, level.dx, np.array(p.lo), np.array(p.hi),
                                       max(widths, default=0), dims)
            stay[(m, p.id)] = (len(x), out if len(out) else None)
            if len(out) == 0:
                if widths:
                    near[(m, p.id)] = (ni, nc)
                continue
            xo = x[out]
            if any(level.periodic):
                xo = level.wrap_positions(xo)
            bad = np.isnan(xo).any(axis=1)
            dest = level.patch_ids_of_cells(level.cells_of(np.where(bad[:, None], -1e300, xo)))
            dest[bad] = -1
            lost += int(np.count_nonzero(dest < 0))
            gone = (dest < 0) & ~bad                   # out of the domain, not deleted on purpose
            if gone.any():
                k = spec.matls.index(m)
                left[k, 0] += np.count_nonzero(gone)
                if spec.mass_pre is not None:
                    left[k, 1] += float(np.sum(dw.get(spec.mass_pre, m, p)[out[gone]]))
            for q in np.unique(dest[dest >= 0]):
                sel = np.flatnonzero(dest == q)
                data = {lf.name: (xo[sel] if lp is spec.pos_pre else dw.get(lp, m, p)[out[sel]])
                        for lp, lf in zip(pre, final)}
                if rank_of[q] == comm.rank:
                    arrivals.setdefault((m, int(q)), []).append((p.id, data))
                else:
                    outgoing.setdefault(rank_of[q], []).append(((m, int(q)), (p.id, data)))
    if comm.size > 1:
        # everyone tells everyone whether it sends, then the messages themselves
        flags = comm.allgather(sorted(outgoing))
        sources = {r for r, dests in enumerate(flags) if comm.rank in dests}
        got = comm.exchange_objects(outgoing, sources)
        for r in sorted(got):
            for key, item in got[r]:
                arrivals.setdefault(key, []).append(item)
        lost = comm.allreduce(lost, "sum")
        left = np.asarray(comm.allreduce(left, "sum"))
    ex.particles_removed += int(lost)
    if spec.mass_pre is not None:
        dw.put_reduction(L.LostParticleMass, float(left[:, 1].sum()))
    if left[:, 0].any():
        _report_leavers(comm, spec, left, dw.generation)
    for m in spec.matls:
        for p in ex.local_patches:
            came = arrivals.get((m, p.id), [])
            _assemble(spec, dw, m, p, pre, final, *stay.get((m, p.id), (0, None)), came)
            if (m, p.id) in near and not came:      # positions handed on as they are: so are their candidates
                for g in widths:
                    boxes = particle_plan(ex, g).box_array.get(p.id)
                    if boxes is not None:
                        dw.ghost_candidates[(m, p.id, g)] = in_boxes(*near[(m, p.id)], dims, boxes)


def _report_leavers(comm, spec, left, timestep):
    """One line per step in which particles left the domain (Uintah deletes them silently);
    with on_leaving "error" the run stops."""
    parts = [f"{int(n)} of material {m}" + (f" ({mass:.4g} kg)" if spec.mass_pre is not None else "")
             for m, (n, mass) in zip(spec.matls, left) if n]
    line = (f"timestep {timestep}: particles left the domain through a face without a wall and were "
            f"deleted: {', '.join(parts)}")
    if spec.on_leaving == "error":
        raise RunStopped(line + " (<particles_leaving_domain>error)")
    if comm.rank == 0:
        print(f"pysus: warning: {line}", file=sys.stderr)


def _assemble(spec, dw, m, p, pre, final, n_src, out, came):
    """Put the final labels of (m, p): its n_src particles but the leavers (`out`, None: none)
    and the arrivals, in source-patch order, then (with an ID label) by ID."""
    if not came and out is None:            # nobody left or came: hand the arrays on untouched
        dw.create_particles(m, p, n_src)
        for lp, lf in zip(pre, final):
            dw.put(lf, m, p, dw.get(lp, m, p) if n_src else np.empty((0,) + lf.shape, dtype=lf.dtype))
        return
    came = sorted(came, key=lambda it: it[0])
    arrived = {lf.name: np.concatenate([d[lf.name] for _, d in came]) if came else np.empty((0,) + lf.shape, lf.dtype)
               for lf in final}
    r = _merged_runs(spec, dw, m, p, pre, final, n_src, out, came, arrived) if n_src else None
    if r is None:
        r = _sorted_runs(spec, dw, m, p, pre, final, n_src, out, came, arrived)
    n = int((r[:, 2] - r[:, 1]).sum())
    dw.create_particles(m, p, n)
    for lp, lf in zip(pre, final):
        src = dw.get(lp, m, p) if n_src else arrived[lf.name][:0]
        dw.put(lf, m, p, _gather(src, arrived[lf.name], r, n))


def _merged_runs(spec, dw, m, p, pre, final, n_src, out, came, arrived):
    """The runs of the final order found by merging the arrivals' IDs into the own sorted
    ones (relocation_runs); None where that does not apply (no ID label, own IDs not sorted)."""
    leave = np.zeros(0, np.int64) if out is None else out
    names = [lf.name for lf in final]
    if not came:                        # own rows but the leavers, in their order
        none = np.zeros(0, np.int64)
        return relocation_runs(np.empty(n_src, np.int64), leave, none, none, np.zeros(0, np.bool_), False)[1]
    if spec.id_label is None:
        return None
    ids = dw.get(pre[names.index(spec.id_label.name)], m, p)
    arr = arrived[spec.id_label.name]
    if ids.dtype != np.int64 or arr.dtype != np.int64 or ids.ndim != 1:
        return None
    ids, arr = np.ascontiguousarray(ids), np.ascontiguousarray(arr)
    first = np.concatenate([np.full(len(d[spec.pos.name]), src < p.id) for src, d in came])
    ok, r = relocation_runs(ids, leave, arr, np.argsort(arr, kind="stable"), first, KNOWN_SORTED.get(ids) is None)
    if not ok:
        return None
    KNOWN_SORTED.put(ids, True)
    return r


def _sorted_runs(spec, dw, m, p, pre, final, n_src, out, came, arrived):
    """The runs of the final order by a stable argsort of the IDs of all pieces."""
    kept = np.arange(n_src) if out is None else complement(out, n_src)
    # index of every final particle into [source arrays | arrivals], pieces in source-patch order
    parts, off = [], n_src
    for src, data in came:
        k = len(data[spec.pos.name])
        parts.append((src, np.arange(off, off + k)))
        off += k
    parts.append((p.id, kept))
    parts.sort(key=lambda it: it[0])
    index = np.concatenate([ix for _, ix in parts]) if parts else np.zeros(0, np.int64)
    if spec.id_label is not None and came:
        lp = pre[[lf.name for lf in final].index(spec.id_label.name)]
        ids = _gather(dw.get(lp, m, p) if n_src else arrived[spec.id_label.name][:0], arrived[spec.id_label.name],
                      runs(index, n_src), len(index))
        index = index[np.argsort(ids, kind="stable")]
    return runs(index, n_src)          # long blocks of staying particles, the arrivals between them


def _gather(src, arrived, r, n):
    """The n rows of (src + arrived) that the runs r name, in order, without forming the
    concatenation."""
    out = np.empty((n,) + src.shape[1:], dtype=src.dtype)
    gather_runs(_rows(src), _rows(arrived.astype(src.dtype, copy=False)), r, _rows(out))
    return out
