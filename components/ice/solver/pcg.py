"""Preconditioned conjugate gradients as a framework Loop (one iteration = one sub-graph run).

Body of one iteration (x, r, p, rz from the previous iteration's warehouse, OLD):
  z = M^-1 r, rz = r.z               preconditioner tasks (below)
  p = z + (rz / rz_old) p_old        (p_old = 0 in the first iteration)
  q = A p, pq = p.q                  p read with one ghost layer
  x += alpha p, r -= alpha q         alpha = rz / pq; reductions r.r and max |r|
Preconditioners: "none"; "jacobi" (z = r / diag A); "mg": a two-level V-cycle whose
fine level is damped Jacobi across patches (one ghost exchange per sweep after the
first) and whose coarse levels (2x coarser and below) are gathered on every rank by one
sum reduction and cycled there (mg.py). Pre- and post-smoothing use the same sweeps,
so M is symmetric and plain CG applies. The stencil is read from the enclosing
warehouse (PARENT_NEW) under `A_label`; seeds x0 = 0, r0 = b, p0 = 0, rz0 > 0 and the
norms of b (rr0, rmax0) are put there by the caller before the loop.
"""
from __future__ import annotations

import numpy as np

from framework import labels as L
from framework.scheduler.loop import Loop
from framework.task import NEW, OLD, PARENT_NEW, Task
from framework.variables import Ghost, VarType

from . import kernels as K
from .mg import Hierarchy

G = Ghost.AROUND_CELLS
CC, R = VarType.CC, VarType.REDUCTION
OMEGA = 0.8             # damped Jacobi weight of the fine-level smoother


def _box(patch):
    lo, hi = patch.interior(VarType.CC)
    return np.array(lo, dtype=np.int64), np.array(hi, dtype=np.int64)


class PCG:
    """Labels, tasks and convergence test of one PCG solve A x = b on the level."""

    def __init__(self, prefix, A_label, level, dims, precond="mg", tolerance=1e-10, max_iterations=500,
                 norm="L2", sweeps=1, relative=True, test_first=False):
        self.A = A_label
        self.test_first = test_first        # Uintah's CGSolver: no iteration when |b| < tolerance
        self.level = level
        self.dims = np.asarray(dims, dtype=np.int64)
        self.precond = precond
        self.tol = tolerance
        self.max_iterations = max_iterations
        self.norm = norm
        self.relative = relative
        self.sweeps = max(1, int(sweeps))
        n = prefix
        self.X0, self.R0, self.P0 = (L.create(f"{n}.{s}0", CC) for s in "xrp")
        self.RZ0 = L.create(f"{n}.rz0", R, reduction="sum")
        self.RR0 = L.create(f"{n}.rr0", R, reduction="sum")
        self.RMAX0 = L.create(f"{n}.rmax0", R, reduction="max")
        self.X, self.R, self.Z, self.P, self.Q = (L.create(f"{n}.{s}", CC) for s in "xrzpq")
        self.RZ = L.create(f"{n}.rz", R, reduction="sum")
        self.PQ = L.create(f"{n}.pq", R, reduction="sum")
        self.RR = L.create(f"{n}.rr", R, reduction="sum")
        self.RMAX = L.create(f"{n}.rmax", R, reduction="max")
        self.nc = tuple(level.ncells[d] // 2 if dims[d] else 1 for d in range(3))
        if precond == "mg":
            self.ZS = [L.create(f"{n}.zpre{s}", CC) for s in range(self.sweeps)]
            self.ZC = L.create(f"{n}.zc", CC)
            self.ZP = [L.create(f"{n}.zpost{s}", CC) for s in range(self.sweeps - 1)]
            shape = "x".join(map(str, self.nc))
            # the rank's coarse residual array, every coarse cell from one patch: a plain rank sum
            self.RC = L.create(f"{n}.rc.{shape}", R, self.nc, reduction="sum", patch_order=False)
            self.OP = L.create(f"{n}.op.{shape}", R, (4,) + tuple(c + 1 for c in self.nc), reduction="sum")
        self.hierarchy = None
        self._op_seen = None
        self._ec_key = None
        self._rc_dw = None
        self.iterations = []               # per solve, for reporting

    @staticmethod
    def mg_possible(level):
        """Fine-to-coarse restriction stays inside patches only when every patch extent is even."""
        for p in level.patches:
            for d in range(3):
                if not level.collapsed[d] and (p.hi[d] - p.lo[d]) % 2:
                    return False
        return True

    # -- set-up (called by the owner's tasks) -------------------------------------------------
    def put_coarse_operator(self, patch, A, dw):
        """This patch's part of the 2x coarser operator, summed over patches into OP."""
        op = np.zeros(self.OP.shape)
        lo, hi = _box(patch)
        K.coarse_operator(A, op, np.array(patch.lo, dtype=np.int64) - lo, self.dims,
                          np.array(self.level.periodic, dtype=np.int64), np.array(self.level.ncells, dtype=np.int64),
                          lo, hi)
        dw.put_reduction(self.OP, op)

    def setup_hierarchy(self, op):
        """Build the coarse levels once per distinct operator (same on every rank)."""
        if self._op_seen is not None and (self._op_seen is op or np.array_equal(self._op_seen, op)):
            return
        nc = self.nc
        kap = np.ascontiguousarray(op[0, :nc[0], :nc[1], :nc[2]])
        self.hierarchy = Hierarchy(kap, np.ascontiguousarray(op[1:]), self.dims, self.level.periodic, self.sweeps)
        self._op_seen = op

    def put_seeds(self, patch, b, dw):
        """x0 = 0, r0 = b, p0 = 0 and the norms of b."""
        lo, hi = _box(patch)
        dw.allocate(self.X0, 0, patch)
        dw.allocate(self.P0, 0, patch)
        dw.put(self.R0, 0, patch, b)
        rr, rmax = K.dot_sq_max(b, lo, hi)
        dw.put_reduction(self.RR0, rr)
        dw.put_reduction(self.RMAX0, rmax)
        dw.put_reduction(self.RZ0, 1.0)

    def seed_computes(self, task):
        for lab in (self.X0, self.R0, self.P0):
            task.computes(lab, matls=[0])
        for lab in (self.RZ0, self.RR0, self.RMAX0):
            task.computes(lab)
        return task

    # -- the loop ----------------------------------------------------------------------------
    def loop(self, name, result_label):
        body = self._preconditioner_tasks(name)
        body += [
            Task(f"{name}::direction", self.direction, [0])
            .requires(OLD, self.P).requires(OLD, self.RZ).requires(NEW, self.Z).requires(NEW, self.RZ)
            .computes(self.P),
            Task(f"{name}::apply", self.apply, [0])
            .requires(NEW, self.P, G, 1).requires(PARENT_NEW, self.A).computes(self.Q).computes(self.PQ),
            Task(f"{name}::update", self.update, [0])
            .requires(OLD, self.X).requires(OLD, self.R).requires(NEW, self.P).requires(NEW, self.Q)
            .requires(NEW, self.RZ).requires(NEW, self.PQ)
            .computes(self.X).computes(self.R).computes(self.RR),
        ]
        if self.norm == "LInfinity":               # one reduction (one allreduce) less for L2
            body[-1].computes(self.RMAX)
        self.solve = Loop(name, [0], body,
                          init={self.X.name: self.X0, self.R.name: self.R0, self.P.name: self.P0,
                                self.RZ.name: self.RZ0},
                          results={self.X.name: result_label}, converged=self.converged,
                          max_iterations=self.max_iterations, fail="continue",
                          done_before=self.below_tolerance if self.test_first else None)
        return self.solve

    def below_tolerance(self, parent_new):
        """Uintah's CGSolver tests the seed's residual against the tolerance (unscaled, whatever
        the criteria) before its first iteration: x = 0 when it is already below."""
        if self.norm == "LInfinity":
            r0 = parent_new.get_reduction(self.RMAX0)
        else:
            r0 = np.sqrt(parent_new.get_reduction(self.RR0))
        if r0 < self.tol:
            self.iterations.append(0)
            return True
        return False

    def converged(self, dw, k, parent_new):
        if self.norm == "LInfinity":
            r, r0 = dw.get_reduction(self.RMAX), parent_new.get_reduction(self.RMAX0)
        else:
            r, r0 = np.sqrt(dw.get_reduction(self.RR)), np.sqrt(parent_new.get_reduction(self.RR0))
        done = r <= self.tol * (r0 if self.relative else 1.0) or r0 == 0.0
        if done or k >= self.max_iterations:
            self.iterations.append(k)
        return done

    def _preconditioner_tasks(self, name):
        A = self.A
        if self.precond != "mg":
            return [Task(f"{name}::jacobi", self.jacobi, [0]).requires(OLD, self.R).requires(PARENT_NEW, A)
                    .computes(self.Z).computes(self.RZ)]
        zs = self.ZS
        tasks = [Task(f"{name}::smoothPre0", self.smooth_first, [0]).requires(OLD, self.R)
                 .requires(PARENT_NEW, A).computes(zs[0])]
        for s in range(1, len(zs)):
            tasks.append(Task(f"{name}::smoothPre{s}", self._smoother(zs[s - 1], zs[s], None), [0])
                         .requires(NEW, zs[s - 1], G, 1).requires(OLD, self.R).requires(PARENT_NEW, A)
                         .computes(zs[s]))
        tasks.append(Task(f"{name}::restrict", self.restrict, [0]).requires(NEW, zs[-1], G, 1)
                     .requires(OLD, self.R).requires(PARENT_NEW, A).computes(self.RC))
        tasks.append(Task(f"{name}::coarseCorrect", self.coarse_correct, [0]).requires(NEW, zs[-1])
                     .requires(NEW, self.RC).computes(self.ZC))
        chain = [self.ZC] + self.ZP + [self.Z]
        for s in range(self.sweeps):
            src, dst = chain[s], chain[s + 1]
            t = Task(f"{name}::smoothPost{s}", self._smoother(src, dst, self.RZ if dst is self.Z else None), [0]) \
                .requires(NEW, src, G, 1).requires(OLD, self.R).requires(PARENT_NEW, A).computes(dst)
            if dst is self.Z:
                t.computes(self.RZ)
            tasks.append(t)
        return tasks

    # -- task bodies -----------------------------------------------------------------------
    def jacobi(self, patch, matls, old_dw, new_dw, parent_old, parent_new):
        lo, hi = _box(patch)
        r = old_dw.get(self.R, 0, patch)
        z = new_dw.allocate(self.Z, 0, patch)
        if self.precond == "none":
            z[...] = r
            rr, _ = K.dot_sq_max(r, lo, hi)
            new_dw.put_reduction(self.RZ, rr)
        else:
            new_dw.put_reduction(self.RZ, K.jacobi(parent_new.get(self.A, 0, patch), r, z, 1.0, lo, hi))

    def smooth_first(self, patch, matls, old_dw, new_dw, parent_old, parent_new):
        lo, hi = _box(patch)
        z = new_dw.allocate(self.ZS[0], 0, patch)
        K.jacobi(parent_new.get(self.A, 0, patch), old_dw.get(self.R, 0, patch), z, OMEGA, lo, hi)

    def _smoother(self, src, dst, rz_label):
        def body(patch, matls, old_dw, new_dw, parent_old, parent_new):
            lo, hi = _box(patch)
            zn = new_dw.allocate(dst, 0, patch)
            rz = K.smooth(parent_new.get(self.A, 0, patch), old_dw.get(self.R, 0, patch), new_dw.get(src, 0, patch),
                          zn, OMEGA, self.dims, lo, hi)
            if rz_label is not None:
                new_dw.put_reduction(rz_label, rz)
        return body

    def restrict(self, patch, matls, old_dw, new_dw, parent_old, parent_new):
        """Residual onto the coarse grid. One rank-local array per iteration takes every local
        patch's part (each coarse cell has one contributor, so the order does not matter);
        it is the rank's partial sum that the executor then reduces over ranks."""
        lo, hi = _box(patch)
        if self._rc_dw is not new_dw.dw:
            self._rc_dw = new_dw.dw
            new_dw.put_reduction(self.RC, np.zeros(self.nc))
            self._rc = new_dw.dw.get_reduction(self.RC)        # accumulate into the stored array
        K.restrict_residual(parent_new.get(self.A, 0, patch), old_dw.get(self.R, 0, patch),
                            new_dw.get(self.ZS[-1], 0, patch), self._rc, np.array(patch.lo, dtype=np.int64) - lo,
                            self.dims, lo, hi)

    def coarse_correct(self, patch, matls, old_dw, new_dw, parent_old, parent_new):
        rc = new_dw.get_reduction(self.RC)
        if self._ec_key is not rc:                   # once per rank and iteration
            self._ec = self.hierarchy.vcycle(np.ascontiguousarray(rc))
            self._ec_key = rc
        lo, hi = _box(patch)
        zn = new_dw.allocate(self.ZC, 0, patch)
        K.prolong_add(new_dw.get(self.ZS[-1], 0, patch), self._ec, zn, np.array(patch.lo, dtype=np.int64) - lo,
                      self.dims, lo, hi)

    def direction(self, patch, matls, old_dw, new_dw, parent_old, parent_new):
        lo, hi = _box(patch)
        rz_old = old_dw.get_reduction(self.RZ)
        beta = new_dw.get_reduction(self.RZ) / rz_old if rz_old != 0.0 else 0.0
        pn = new_dw.allocate(self.P, 0, patch)
        K.cg_direction(new_dw.get(self.Z, 0, patch), old_dw.get(self.P, 0, patch), pn, beta, lo, hi)

    def apply(self, patch, matls, old_dw, new_dw, parent_old, parent_new):
        lo, hi = _box(patch)
        q = new_dw.allocate(self.Q, 0, patch)
        new_dw.put_reduction(self.PQ, K.apply(parent_new.get(self.A, 0, patch), new_dw.get(self.P, 0, patch), q,
                                              self.dims, lo, hi))

    def update(self, patch, matls, old_dw, new_dw, parent_old, parent_new):
        lo, hi = _box(patch)
        pq = new_dw.get_reduction(self.PQ)
        alpha = new_dw.get_reduction(self.RZ) / pq if pq != 0.0 else 0.0
        xn = new_dw.allocate(self.X, 0, patch)
        rn = new_dw.allocate(self.R, 0, patch)
        rr, rmax = K.cg_update(old_dw.get(self.X, 0, patch), old_dw.get(self.R, 0, patch),
                               new_dw.get(self.P, 0, patch), new_dw.get(self.Q, 0, patch), xn, rn, alpha, lo, hi)
        new_dw.put_reduction(self.RR, rr)
        if self.norm == "LInfinity":
            new_dw.put_reduction(self.RMAX, rmax)
