"""Ghost exchange derived from task declarations: local copies and MPI messages.

One exchange point is the set of ghosted requirements of one task. Its grid data
travels as ONE float64 buffer per rank pair (non-blocking send/receive); its ghost
particles as one pickled message per rank pair. Patches that need nothing remote can
run between `begin` and `finish`. Both sides walk the same globally ordered plan, so
sender and receiver agree on the layout of each buffer without extra messages.
"""
from __future__ import annotations

import numpy as np

from ..variables import VarType
from .particle_kernels import GhostMerge, near_faces


class Comm:
    """A thin wrapper so the serial case needs no MPI calls at all."""

    def __init__(self, mpicomm=None):
        self.mpi = mpicomm
        self.rank = mpicomm.Get_rank() if mpicomm is not None else 0
        self.size = mpicomm.Get_size() if mpicomm is not None else 1
        self.messages = 0
        self.bytes = 0
        self._tag = 0

    def next_tag(self):
        self._tag = (self._tag + 1) % 30000
        return self._tag + 100

    def allreduce(self, value, op):
        if self.size == 1:
            return value
        from mpi4py import MPI
        mpiop = {"min": MPI.MIN, "max": MPI.MAX, "sum": MPI.SUM}[op]
        if np.ndim(value) == 0:
            return self.mpi.allreduce(float(value), op=mpiop)
        out = np.empty_like(np.asarray(value, dtype=np.float64))
        self.mpi.Allreduce(np.ascontiguousarray(value, dtype=np.float64), out, op=mpiop)
        return out

    def allgather(self, obj):
        if self.size == 1:
            return [obj]
        return self.mpi.allgather(obj)

    def bcast(self, obj, root=0):
        if self.size == 1:
            return obj
        return self.mpi.bcast(obj, root=root)

    def barrier(self):
        if self.size > 1:
            self.mpi.Barrier()

    def exchange_objects(self, outgoing: dict, sources) -> dict:
        """Send one pickled object per destination rank; receive one from each source."""
        if self.size == 1:
            return {}
        tag = self.next_tag()
        reqs = [self.mpi.isend(obj, dest=r, tag=tag) for r, obj in outgoing.items()]
        self.messages += len(outgoing)
        got = {r: self.mpi.recv(source=r, tag=tag) for r in sorted(sources)}
        for q in reqs:
            q.wait()
        return got


class GridPlan:
    """For one (type, ghost width): every (dst patch, src patch) ghost copy, globally ordered."""

    def __init__(self, level, rank_of, vt: VarType, g: int, me: int):
        self.local, self.sends, self.recvs = [], {}, {}
        self.remote_dst = set()
        for p in level.patches:
            for q, shift, box in level.ghost_sources(p, vt, g):
                rp, rq = rank_of[p.id], rank_of[q.id]
                if me not in (rp, rq):
                    continue
                src_box = (tuple(b - s for b, s in zip(box[0], shift)), tuple(b - s for b, s in zip(box[1], shift)))
                dst = p.slices(vt, box)
                src = q.slices(vt, src_box)
                n = int(np.prod([h - l for l, h in zip(*box)]))
                if rp == me and rq == me:
                    self.local.append((p, q, dst, src))
                elif rq == me:
                    self.sends.setdefault(rp, []).append((p, q, src, n))
                else:
                    self.recvs.setdefault(rq, []).append((p, q, dst, n))
                    self.remote_dst.add(p.id)


class Exchange:
    """The ghost data of one task: begin() posts and copies, finish() waits and unpacks."""

    def __init__(self, executor, dw, grid_deps, particle_deps):
        self.ex = executor
        self.dw = dw
        self.grid_deps = grid_deps
        self.particle_deps = particle_deps
        self.remote_patches = set()
        self._reqs = []
        self._recv_bufs = {}
        self._sendkeep = []

    # -- grid ------------------------------------------------------------------------
    def begin(self):
        ex, dw, comm = self.ex, self.dw, self.ex.comm
        send_parts, recv_layout = {}, {}
        todo = []
        for label, g, matls in self.grid_deps:
            for m in matls:
                if dw.halo_valid.get((label.name, m), -1) >= g:
                    continue
                todo.append((label, g, m))
        for label, g, m in todo:
            plan = ex.grid_plan(label.vartype, g)
            for p, q, dst, src in plan.local:
                dw.get(label, m, p)[dst] = dw.get(label, m, q)[src]
            for r, items in plan.sends.items():
                for p, q, src, n in items:
                    send_parts.setdefault(r, []).append(dw.get(label, m, q)[src].ravel())
            for r, items in plan.recvs.items():
                ncomp = int(np.prod(label.shape)) if label.shape else 1
                for p, q, dst, n in items:
                    recv_layout.setdefault(r, []).append((label, m, p, dst, n * ncomp))
                    self.remote_patches.add(p.id)
            dw.halo_valid[(label.name, m)] = g
        if comm.size > 1 and (send_parts or recv_layout):
            tag = comm.next_tag()
            for r, layout in recv_layout.items():
                buf = np.empty(sum(x[4] for x in layout), dtype=np.float64)
                self._recv_bufs[r] = (buf, layout)
                self._reqs.append(comm.mpi.Irecv(buf, source=r, tag=tag))
            for r, parts in send_parts.items():
                buf = np.concatenate(parts).astype(np.float64, copy=False)
                self._reqs.append(comm.mpi.Isend(buf, dest=r, tag=tag))
                self._sendkeep.append(buf)
                comm.messages += 1
                comm.bytes += buf.nbytes
        if self.particle_deps:
            self._particles()

    def finish(self):
        if self._reqs:
            from mpi4py import MPI
            MPI.Request.Waitall(self._reqs)
            for r, (buf, layout) in self._recv_bufs.items():
                off = 0
                for label, m, p, dst, n in layout:
                    a = self.dw.get(label, m, p)
                    a[dst] = buf[off:off + n].reshape(a[dst].shape)
                    off += n

    # -- particles ---------------------------------------------------------------------
    def _particles(self):
        ex, dw, comm = self.ex, self.dw, self.ex.comm
        level, rank_of, me = ex.level, ex.lb.rank_of, comm.rank
        pos = ex.position_label
        if pos is None:
            raise RuntimeError("ghost particles requested but no particle position label was registered "
                               "(Scheduler.schedule_particle_relocation)")
        labels = {}
        for label, g, matls in self.particle_deps:
            for m in matls:
                if (label.name, m, ex.local_patches[0].id, g) not in dw.ghost_particles:
                    labels.setdefault((g, m), []).append(label)
        if not labels:
            return
        idl = ex.particle_id_label
        outgoing, sources = {}, set()
        pieces = {}
        for (g, m), lbls in labels.items():
            # the ID order of owned+ghost particles is found once per warehouse, then reused
            send_lbls = list(dict.fromkeys(lbls + ([idl] if idl is not None and (m, g) not in dw.ghost_seen else [])))
            for p in level.patches:
                for q, shift, cbox in level.particle_ghost_sources(p, g):
                    rp, rq = rank_of[p.id], rank_of[q.id]
                    if rq == me:
                        sel = self._select(dw, pos, m, q, cbox, g)
                        data = {l.name: dw.get(l, m, q)[sel] for l in send_lbls}
                        if shift != (0, 0, 0) and pos.name in data:
                            data[pos.name] = data[pos.name] + np.asarray(shift) * level.dx
                        if rp == me:
                            pieces.setdefault((g, m, p.id), []).append(data)
                        else:
                            outgoing.setdefault(rp, []).append(((g, m, p.id), data))
                    elif rp == me and rq != me:
                        sources.add(rq)
                        self.remote_patches.add(p.id)
        if comm.size > 1:
            got = comm.exchange_objects(outgoing, sources)
            for r in sorted(got):
                for key, data in got[r]:
                    pieces.setdefault(key, []).append(data)
        for (g, m), lbls in labels.items():
            first = (m, g) not in dw.ghost_seen
            dw.ghost_seen.add((m, g))
            for p in ex.local_patches:
                parts = pieces.get((g, m, p.id), [])
                key = (m, p.id, g)
                if first:
                    order = mask = None
                    if idl is not None and parts:
                        ids = np.concatenate([dw.get(idl, m, p)] + [d[idl.name] for d in parts])
                        order = np.argsort(ids, kind="stable")
                        mask = order < dw.num_particles(m, p)
                    elif parts:
                        n = dw.num_particles(m, p)
                        mask = np.arange(n + sum(len(next(iter(d.values()))) for d in parts)) < n
                    dw.ghost_order[key] = (order, mask)
                order = dw.ghost_order[key][0]
                for l in dict.fromkeys(lbls):
                    own = dw.get(l, m, p)
                    if not parts:
                        a = own
                    elif order is None:
                        a = np.concatenate([own] + [d[l.name] for d in parts])
                    else:           # merged in ID order when a task asks (TaskView.get)
                        a = GhostMerge(own, np.concatenate([d[l.name] for d in parts]), order)
                    dw.ghost_particles[(l.name, m, p.id, g)] = a

    @staticmethod
    def _select(dw, pos, m, q, cbox, g):
        """Indices of q's particles whose cell lies in cbox (a ghost region next to q's faces)."""
        key = (m, q.id, cbox)
        if key in dw.ghost_select:
            return dw.ghost_select[key]
        ckey = (m, q.id, g)
        if ckey not in dw.ghost_candidates:
            lv = q.level
            dims = np.array([not c for c in lv.collapsed])
            dw.ghost_candidates[ckey] = near_faces(dw.get(pos, m, q), lv.anchor, lv.dx, np.array(q.lo),
                                                   np.array(q.hi), g, dims)
        idx, c = dw.ghost_candidates[ckey]
        inside = np.ones(len(idx), dtype=bool)
        for d in range(3):
            if q.level.collapsed[d]:
                continue
            inside &= (c[:, d] >= cbox[0][d]) & (c[:, d] < cbox[1][d])
        sel = idx[inside]
        dw.ghost_select[key] = sel
        return sel
