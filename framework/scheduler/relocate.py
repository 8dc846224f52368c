"""Particle relocation: hand particles that left their patch to the patch now holding them.

The component writes the new particle state under "pre-relocation" labels (p.x+ ...);
this step moves every particle to the patch containing its new position, on whatever
rank, and puts the state under the final labels (p.x ...). Particles that left the
domain through a non-periodic face, or whose position is NaN (the way a component
deletes a particle), are removed. With a particle-ID label registered, each patch's
particles are kept sorted by ID, so sums over particles do not depend on the patch
layout.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..task import NEW, Task
from .particle_kernels import leavers


@dataclass
class RelocationSpec:
    pos_pre: object
    labels_pre: list
    pos: object
    labels: list
    matls: tuple
    id_label: object = None


def relocation_task(spec: RelocationSpec) -> Task:
    t = Task("relocateParticles", None, spec.matls)
    t.relocation = spec
    for lp in [spec.pos_pre] + spec.labels_pre:
        t.requires(NEW, lp)
    for lf in [spec.pos] + spec.labels:
        t.computes(lf)
    return t


def relocate(ex, spec: RelocationSpec, dw):
    """Move particles between patches (and ranks); puts the final labels in dw."""
    level, rank_of, comm = ex.level, ex.lb.rank_of, ex.comm
    pre = [spec.pos_pre] + spec.labels_pre
    final = [spec.pos] + spec.labels
    pieces = {}
    outgoing = {}
    lost = 0
    for m in spec.matls:
        for p in ex.local_patches:
            x = dw.get(spec.pos_pre, m, p)
            if len(x) == 0:
                pieces.setdefault((m, p.id), []).append((p.id, None))
                continue
            dims = np.array([not c for c in level.collapsed])
            out = leavers(x, level.anchor, level.dx, np.array(p.lo), np.array(p.hi), dims)
            if len(out) == 0:       # nobody left: hand the arrays on untouched
                data = {lf.name: dw.get(lp, m, p) for lp, lf in zip(pre, final)}
                pieces.setdefault((m, p.id), []).append((p.id, data))
                continue
            xo = x[out]
            if any(level.periodic):
                xo = level.wrap_positions(xo)
            bad = np.isnan(xo).any(axis=1)
            dest_out = level.patch_ids_of_cells(level.cells_of(np.where(bad[:, None], -1e300, xo)))
            dest_out[bad] = -1
            lost += int(np.count_nonzero(dest_out < 0))
            dest = np.full(len(x), p.id, dtype=np.int64)
            dest[out] = dest_out
            if any(level.periodic):
                x = x.copy()
                x[out] = xo
            order = np.argsort(dest, kind="stable")
            ds = dest[order]
            bounds = np.searchsorted(ds, np.unique(ds[ds >= 0]), side="left")
            for q, b in zip(np.unique(ds[ds >= 0]), bounds):
                idx = order[b:np.searchsorted(ds, q, side="right")]
                data = {lf.name: (x[idx] if lp is spec.pos_pre else dw.get(lp, m, p)[idx])
                        for lp, lf in zip(pre, final)}
                if rank_of[q] == comm.rank:
                    pieces.setdefault((m, int(q)), []).append((p.id, data))
                else:
                    outgoing.setdefault(rank_of[q], []).append(((m, int(q)), (p.id, data)))
    if comm.size > 1:
        # everyone tells everyone whether it sends, then the messages themselves
        flags = comm.allgather(sorted(outgoing))
        sources = {r for r, dests in enumerate(flags) if comm.rank in dests}
        got = comm.exchange_objects(outgoing, sources)
        for r in sorted(got):
            for key, item in got[r]:
                pieces.setdefault(key, []).append(item)
        lost = comm.allreduce(lost, "sum")
    ex.particles_removed += int(lost)
    for m in spec.matls:
        for p in ex.local_patches:
            items = sorted((it for it in pieces.get((m, p.id), []) if it[1] is not None), key=lambda it: it[0])
            n = sum(len(it[1][spec.pos.name]) for it in items)
            dw.create_particles(m, p, n)
            arrived = any(src != p.id for src, _ in items)
            order = None
            if spec.id_label is not None and arrived:
                ids = np.concatenate([it[1][spec.id_label.name] for it in items])
                order = np.argsort(ids, kind="stable")
            for lf in final:
                if items:
                    a = np.concatenate([it[1][lf.name] for it in items]) if len(items) > 1 else items[0][1][lf.name]
                    if order is not None:
                        a = a[order]
                else:
                    a = np.empty((0,) + lf.shape, dtype=lf.dtype)
                dw.put(lf, m, p, a)
