"""Ghost exchange derived from task declarations: local copies and MPI messages.

One exchange point is the set of ghosted requirements of one task. Its grid data
travels as ONE float64 buffer per rank pair (non-blocking send/receive); its ghost
particles as one pickled message per rank pair. Patches that need nothing remote can
run between `begin` and `finish`. Both sides walk the same globally ordered plan, so
sender and receiver agree on the layout of each buffer without extra messages.
"""
from __future__ import annotations

import math
import sys

import numpy as np

from ..variables import VarType
from .particle_kernels import KNOWN_RUNS, KNOWN_SORTED, ArrayMemo, GhostMerge, gather_pieces, merge_ids, select_ghosts


def world_rank() -> int:
    """This process's rank in MPI's world (rank 0 prints the notes on a deck): 0 in a process that
    mpiexec did not start and that has not started MPI, without importing mpi4py (whose import
    starts MPI, about 0.1 CPU s, in a serial run)."""
    from ..cli import under_mpi
    if "mpi4py.MPI" not in sys.modules and not under_mpi():
        return 0
    from mpi4py import MPI
    return MPI.COMM_WORLD.Get_rank()


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
            if not (plan.local or plan.sends or plan.recvs):      # no ghost of this rank's patches is another's
                dw.halo_valid[(label.name, m)] = g
                continue
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
        outgoing, sources, ghosts, send = {}, set(), {}, {}
        for (g, m), lbls in list(labels.items()):
            plan = particle_plan(ex, g)
            if not (plan.boxes or plan.sources):      # no patch of this rank sends or gets ghosts of width g
                self._store_own(g, m, lbls)
                del labels[(g, m)]
                continue
            sources |= plan.sources
            self.remote_patches |= plan.remote_dst
            # the ID order of owned+ghost particles is found once per warehouse, then reused
            send[(g, m)] = list(dict.fromkeys(lbls + ([idl] if idl is not None and (m, g) not in dw.ghost_seen
                                                      else [])))
            lay = _layout(dw, pos, m, g, plan)
            for l in send[(g, m)]:
                ghosts[(g, m, l.name)] = _gather_local(dw, l, m, plan, lay, pos)
            for r, key, data in _remote_pieces(dw, send[(g, m)], m, g, plan, lay, pos):
                outgoing.setdefault(r, []).append((key, data))
        got = comm.exchange_objects(outgoing, sources) if comm.size > 1 else {}
        remote = {}
        for r in sorted(got):
            for key, data in got[r]:
                remote.setdefault(key, []).append(data)
        for (g, m), lbls in labels.items():
            self._store_ghosts(g, m, lbls, send[(g, m)], ghosts, remote)

    def _store_own(self, g, m, lbls):
        """_store_ghosts where no local patch has ghosts: each holds its own particles only."""
        dw = self.dw
        first = (m, g) not in dw.ghost_seen
        dw.ghost_seen.add((m, g))
        for p in self.ex.local_patches:
            if first:
                dw.ghost_order[(m, p.id, g)] = (None, None)
            for l in dict.fromkeys(lbls):
                dw.ghost_particles[(l.name, m, p.id, g)] = dw.get(l, m, p)

    def _store_ghosts(self, g, m, lbls, sent, ghosts, remote):
        """Put (owned, ghost, ID order) of every label of (g, m) in the warehouse, for each local patch."""
        ex, dw = self.ex, self.dw
        plan, idl = particle_plan(ex, g), ex.particle_id_label
        lay = dw.ghost_select[(m, g)]
        first = (m, g) not in dw.ghost_seen
        dw.ghost_seen.add((m, g))
        for p in ex.local_patches:
            came = remote.get((g, m, p.id), [])
            a, b = lay.span.get(p.id, (0, 0))
            has = bool(plan.local.get(p.id)) or bool(came)
            part = {l.name: _with_remote(ghosts[(g, m, l.name)][a:b], [d[l.name] for d in came]) for l in sent}
            key = (m, p.id, g)
            if first:
                dw.ghost_order[key] = _ghost_order(dw, idl, m, p, part, has)
            order = dw.ghost_order[key][0]
            for l in dict.fromkeys(lbls):
                own = dw.get(l, m, p)
                if not has:
                    a_l = own
                elif order is None:
                    a_l = np.concatenate([own, part[l.name]])
                else:           # merged in ID order when a task asks (TaskView.get)
                    a_l = GhostMerge(own, part[l.name], order)
                dw.ghost_particles[(l.name, m, p.id, g)] = a_l


class ParticlePlan:
    """Every ghost-particle piece (destination patch, source patch, shift, cell box) of one
    ghost width that involves this rank, in the global (destination, source) order: per
    local source its boxes, per local destination its local pieces (source, box number),
    the pieces this rank sends, and the ranks it receives from."""

    def __init__(self, level, rank_of, g: int, me: int):
        self.patch = {p.id: p for p in level.patches}
        self.boxes, self.local, self.out = {}, {}, []
        self.sources, self.remote_dst = set(), set()
        for p in level.patches:
            for q, shift, cbox in level.particle_ghost_sources(p, g):
                rp, rq = rank_of[p.id], rank_of[q.id]
                if rq == me:
                    k = len(self.boxes.setdefault(q.id, []))
                    self.boxes[q.id].append((p.id, shift, cbox))
                    if rp == me:
                        self.local.setdefault(p.id, []).append((q.id, k))
                    else:
                        self.out.append((rp, p.id, q.id, k))
                elif rp == me:
                    self.sources.add(rq)
                    self.remote_dst.add(p.id)
        self.box_array = {q: np.array([cbox for _, _, cbox in b], np.int64).reshape(len(b), 2, 3)
                          for q, b in self.boxes.items()}


def particle_plan(ex, g: int) -> ParticlePlan:
    """The ghost-particle plan of width g for the current patch assignment (kept with the grid plans)."""
    key = ("particles", g, ex.lb.version)
    if key not in ex._plans:
        ex._plans[key] = ParticlePlan(ex.level, ex.lb.rank_of, g, ex.comm.rank)
    return ex._plans[key]


def ghost_widths(ex):
    """The ghost-particle widths whose plans (particle_plan) exist for the current patch assignment."""
    return sorted({k[1] for k in ex._plans if k[0] == "particles" and k[2] == ex.lb.version})


class _Layout:
    """Where the ghosts of (material, width) come from and go, for one warehouse: per local
    source the selected rows (sel, rows per box) and each box's first row in the buffer of
    local ghosts (-1: remote); each local destination's rows [a, b) of that buffer; the
    (first row, rows, position shift) of pieces coming through a periodic face."""

    def __init__(self, sel, dst, span, total, shifts):
        self.sel, self.dst, self.span, self.total, self.shifts = sel, dst, span, total, shifts


def _layout(dw, pos, m, g, plan):
    """Select the ghosts of every local source once per warehouse (positions do not change in it)."""
    key = (m, g)
    if key in dw.ghost_select:
        return dw.ghost_select[key]
    sel = {q: _select(dw, pos, m, plan.patch[q], g, plan.box_array[q]) for q in plan.boxes}
    dst = {q: np.full(len(b), -1, np.int64) for q, b in plan.boxes.items()}
    span, shifts, off = {}, [], 0
    for p, pieces in plan.local.items():
        a = off
        for q, k in pieces:
            n = int(sel[q][1][k])
            dst[q][k] = off
            shift = plan.boxes[q][k][1]
            if shift != (0, 0, 0) and n:
                shifts.append((off, n, shift))
            off += n
        span[p] = (a, off)
    lay = dw.ghost_select[key] = _Layout(sel, dst, span, off, shifts)
    return lay


def _select(dw, pos, m, q, g, boxes):
    """(indices, rows per box) of q's particles whose cell lies in each ghost box next to its faces."""
    key = (m, q.id, g)
    if key not in dw.ghost_candidates:
        lv = q.level
        dims = np.array([not c for c in lv.collapsed])
        dw.ghost_candidates[key] = select_ghosts(dw.get(pos, m, q), lv.anchor, lv.dx, np.array(q.lo), np.array(q.hi),
                                                 g, dims, boxes)
    return dw.ghost_candidates[key]


def _gather_local(dw, label, m, plan, lay, pos):
    """One buffer holding the local ghosts of label, destination after destination."""
    out = out2 = None
    k = 1
    for q, (sel, counts) in lay.sel.items():
        src = dw.get(label, m, plan.patch[q])
        if out is None:
            out = np.empty((lay.total,) + src.shape[1:], src.dtype)
            k = math.prod(src.shape[1:])
            out2 = out.reshape(len(out), k)
        if src.flags.c_contiguous and src.dtype == out.dtype and src.shape[1:] == out.shape[1:]:
            gather_pieces(src.reshape(len(src), k), sel, counts, lay.dst[q], out2)
        else:
            _gather_rows(src, sel, counts, lay.dst[q], out)
    if out is None:
        return np.empty((0,) + label.shape, label.dtype)
    if label.name == pos.name:
        dx = plan.patch[next(iter(lay.sel))].level.dx
        for a, n, shift in lay.shifts:
            out[a:a + n] += np.asarray(shift) * dx
    return out


def _gather_rows(src, sel, counts, dst, out):
    """src[sel] piece by piece into out at rows dst (numpy indexing, for a src that has no
    (n, k) row view)."""
    starts = np.concatenate([[0], np.cumsum(counts)])
    for b in range(len(counts)):
        if dst[b] >= 0:
            out[dst[b]:dst[b] + counts[b]] = src[sel[starts[b]:starts[b + 1]]]


def _remote_pieces(dw, labels, m, g, plan, lay, pos):
    """(destination rank, (g, m, destination patch), {label: rows}) of each piece sent away."""
    for r, p, q, k in plan.out:
        sel, counts = lay.sel[q]
        a = int(counts[:k].sum())
        rows = sel[a:a + counts[k]]
        data = {l.name: dw.get(l, m, plan.patch[q])[rows] for l in labels}
        shift = plan.boxes[q][k][1]
        if shift != (0, 0, 0) and pos.name in data:
            data[pos.name] = data[pos.name] + np.asarray(shift) * plan.patch[q].level.dx
        yield r, (g, m, p), data


def _with_remote(local, came):
    """A destination's local ghost rows followed by those received from other ranks."""
    return np.concatenate([local] + came) if came else local


def _ghost_order(dw, idl, m, p, part, has):
    """(ID order, owned mask) of p's owned + ghost particles; the order's runs are remembered."""
    if not has:
        return None, None
    n = dw.num_particles(m, p)
    if idl is None:
        return None, np.arange(n + len(next(iter(part.values())))) < n
    own, ghost = dw.get(idl, m, p), part[idl.name]
    prev = KNOWN_MERGES.get(own)
    if prev is not None and prev[0].shape == ghost.shape and np.array_equal(prev[0], ghost):
        return prev[1], prev[2]     # same owned ID array as a step before, same ghost IDs: same order
    ok, order, mask, r = merge_ids(own, ghost, np.argsort(ghost, kind="stable"), KNOWN_SORTED.get(own) is None)
    if not ok:
        order = np.argsort(np.concatenate([own, ghost]), kind="stable")
        return order, order < n
    KNOWN_SORTED.put(own, True)
    KNOWN_RUNS.put(order, (n, r))
    KNOWN_MERGES.put(own, (ghost.copy(), order, mask))
    return order, mask


# owned ID array -> (ghost IDs, ID order, owned mask) of its last merge. A patch nobody left
# or entered hands its ID array on to the next step unchanged (relocate), and its ghost IDs
# change only when a particle crosses the edge of a ghost band, so most steps find the
# order of the step before (the arrays are read-only once made).
KNOWN_MERGES = ArrayMemo()
