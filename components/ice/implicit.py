"""Semi-implicit ICE: the pressure increment solved implicitly (paper 000 sec. 3.3, end).

`<CFD><ICE><ImplicitSolver>` switches it on. Instead of eq. 29-30's explicit
delP = -dt div(theta u*) / kap, the face velocities are made to see the increment,
u_m = u*_m - dt v_m,f grad delP (eq. 28 with p = p_eq + delP), which gives the
Poisson-type equation (eq. P)

    kap delP - dt^2 div(sum_m theta_m v_m,f grad delP) = -dt sum_m div(theta_m u*_m),

symmetric positive definite, solved over the whole level by PCG (solver/). Outer
iterations (Uintah's max_outer_iterations / outer_iteration_tolerance) repeat
"solve, update P, recompute u_m(P) (with exchange), recompute the residual" until
max |kap P + dt sum div(theta u)| (a relative volume) is below the tolerance; with
one material and no exchange the linearisation is exact and one iteration suffices.
The outer iteration is a framework Loop with the PCG Loop nested in its body. delT is
explicit ICE's (Uintah's one stable-timestep task serves both), with Uintah's implicit
default knob_for_speedSound 0.5: with knob 0 it comes from the flow speed alone.

The dilatation div(theta u) of the residual takes theta on the faces as explicit ICE does
(tasks.add_dilatation): the donor cell's, or with <advection limiter="BarthJespersen"> the
fractions advected second order with Uintah's limiter, as Uintah's setupRHS (advectQ of
vol_frac). The operator's face coefficients take the donor cells of the last outer iteration's
face velocities, as Uintah's setupMatrix takes the residual's upwinded vol_frac: the operator
is then the residual's Jacobian wherever no face velocity changes sign (with the limiter, an
approximation of it; the converged pressure is the residual's zero either way). The multigrid
preconditioner keeps the step's first stencil. As in Uintah, the face velocities
(updateVel_FC) and the residual (setupRHS) are separate tasks, so that the residual may read
its neighbours' face velocities. A step whose outer iteration misses the tolerance says so
(timestep, max|rhs|), or is recomputed with <iters_before_timestep_restart>.

Boundary faces: a fixed face velocity (Dirichlet, symmetry) or a zero-gradient
pressure leaves delP decoupled there; a Dirichlet pressure holds delP = 0 outside. Each
boundary cell takes its own conditions, so a sub-face (circle, rectangle, annulus) with a
fixed pressure behind a free velocity may sit in a side with a fixed velocity (TBurner_2dRT's
outlet).
"""
from __future__ import annotations

import sys

import numpy as np

from framework import labels as L
from framework.scheduler.loop import Loop
from framework.task import NEW, OLD, PARENT_NEW, PARENT_OLD, Task
from framework.variables import Ghost, VarType

from . import implicit_kernels as IK
from . import kernels as K
from . import labels as I
from . import slip_exchange as SL
from .bc import DIRICHLET, FACE_NAMES, FREE_SLIP, SYMMETRY, bc_scalar_part
from .solver import kernels as SK
from .solver.pcg import PCG

G = Ghost.AROUND_CELLS
CC, X, Y, Z, R = VarType.CC, VarType.SFCX, VarType.SFCY, VarType.SFCZ, VarType.REDUCTION
UNIT = np.eye(3, dtype=np.int64)
IMPLICIT_KNOB = 0.5     # Uintah's knob_for_speedSound with <ImplicitSolver> and no <TimeStepControl>

# labels named after Uintah's impICE where it has one
matrix = L.create("matrix", CC, (7,))               # the stencil of eq. P, timestep level
imp_A = L.create("imp.matrix", CC, (7,))            # the same arrays inside the outer iteration
sum_imp_delP = L.create("sum_imp_delP", CC)         # the step's whole increment (Uintah's label)
imp_P = L.create("imp.P", CC)                       # accumulated increment, outer iteration
imp_P0 = L.create("imp.P0", CC)
imp_delP = L.create("imp_delP", CC)                 # one outer iteration's increment
rhs = L.create("rhs", CC)
rhs0 = L.create("rhs0", CC)
max_RHS = L.create("max_RHS", R, reduction="max")
imp_UF = (L.create("imp.uvel_FC", X), L.create("imp.vvel_FC", Y), L.create("imp.wvel_FC", Z))
imp_UF0 = (L.create("imp.uvel_FC0", X), L.create("imp.vvel_FC0", Y), L.create("imp.wvel_FC0", Z))   # at P = 0

SOLVERS = {"cg": "cg", "pcg": "cg", "conjugategradient": "cg", "conjugate_gradient": "cg",
           "smg": "mg", "pfmg": "mg", "gmres": "cg", "hybrid": "cg", "jacobi": "cg", "automatic": "cg"}
PRECONDS = {"pfmg": "mg", "smg": "mg", "mg": "mg", "multigrid": "mg", "spfmg": "mg", "sparsemsg": "mg",
            "jacobi": "jacobi", "diagonal": "jacobi", "none": "none"}
PRECOND_WORDS = {"mg": "geometric multigrid (fine level across patches, coarse levels gathered on every rank)",
                 "jacobi": "Jacobi", "none": "no preconditioner"}
NO_EFFECT = ("skip", "jump", "relax_type", "logging", "setupFrequency", "updateCoefFrequency",
             "solveFrequency", "csolver", "initial_tolerance")


class ImplicitSettings:
    """What `<ImplicitSolver>`, its `<Parameters>` and `<Solver type>` ask for, and what runs."""

    def __init__(self, node, root):
        self.max_outer = node.get("max_outer_iterations", "int")           # required, as in Uintah
        self.outer_tol = node.get("outer_iteration_tolerance", "float")
        self.restart_iters = node.get("iters_before_timestep_restart", "int", None)
        solver = root.child("Solver")
        self.package = solver.attr("type", default="hypre") if solver is not None else "none given"
        if solver is not None:
            solver.mark_used()
        pars = node.children("Parameters")
        p = None
        for cand in pars:
            if cand.attr("variable", default="implicitPressure") == "implicitPressure":
                p = cand
        if len(pars) > 1 and p is not None:
            for cand in pars:
                if cand is not p:
                    cand.mark_used()
        get = (lambda t, ty, d: p.get(t, ty, d)) if p is not None else (lambda t, ty, d: d)
        self.solver_asked = get("solver", "str", "cg").strip()
        self.precond_asked = get("preconditioner", "str", "pfmg").strip()
        key = self.solver_asked.lower()
        if key not in SOLVERS:
            raise p.child("solver").error(f"solver '{self.solver_asked}' is not known; accepted: "
                                          + ", ".join(sorted(SOLVERS)))
        pkey = self.precond_asked.lower()
        if pkey not in PRECONDS:
            raise p.child("preconditioner").error(f"preconditioner '{self.precond_asked}' is not known; "
                                                  "accepted: " + ", ".join(sorted(PRECONDS)))
        # hypre run as a solver (smg, pfmg) becomes the preconditioner of our CG
        self.precond = "mg" if SOLVERS[key] == "mg" else PRECONDS[pkey]
        self.tolerance = get("tolerance", "float", 1e-10)
        self.max_iterations = get("maxiterations", "int", 500)
        self.npre = get("npre", "int", 1)
        self.npost = get("npost", "int", 1)
        self.norm = get("norm", "str", "L2")
        if self.norm not in ("L2", "LInfinity"):
            raise p.child("norm").error(f"norm '{self.norm}' is not accepted; accepted: L2, LInfinity")
        self.criteria = get("criteria", "str", "Relative")
        if self.criteria not in ("Relative", "Absolute"):
            raise p.child("criteria").error(f"criteria '{self.criteria}' is not accepted; accepted: Relative, Absolute")
        self.ignored = []
        if p is not None:
            for tag in NO_EFFECT:
                if p.has(tag):
                    p.child(tag).mark_used()
                    self.ignored.append(tag)
        self.sweeps = max(self.npre, self.npost, 1)

    def describe(self, precond_running, note=""):
        words = PRECOND_WORDS[precond_running]
        s = (f"pysus: ICE implicit pressure: deck asks <Solver type=\"{self.package}\"> solver={self.solver_asked} "
             f"preconditioner={self.precond_asked}; running pysus CG with {words}, "
             f"{self.sweeps} smoothing sweep(s), tolerance {self.tolerance:g} ({self.criteria.lower()} "
             f"{self.norm}), maxiterations {self.max_iterations}; outer iterations <= {self.max_outer} to "
             f"max|rhs| {self.outer_tol:g}")
        if self.npre != self.npost:
            s += f"; npre={self.npre} npost={self.npost} -> {self.sweeps} each (symmetric for CG)"
        if self.ignored:
            s += "; no effect here: " + ", ".join(self.ignored)
        if self.restart_iters is not None:
            s += (f"; a step that misses the outer tolerance, or needs more than {self.restart_iters} outer "
                  "iterations, is recomputed with half the delT")
        else:
            s += " (no iters_before_timestep_restart: a step that misses the outer tolerance continues with a warning)"
        return s + note


class ImplicitICE:
    """Tasks of the implicit pressure solve (mixed into the ICE component)."""

    # the reaction models' mass exchange in eq. P, or None: an object with requires(task, dw) and
    # term(patch, dw) (sum_m m_src,m v_m / V per cell); MPMICE sets it (components/models)
    mass_exchange = None

    def read_implicit(self, ice, root):
        node = ice.child("ImplicitSolver")
        self.implicit = node is not None
        if not self.implicit:
            solver = root.child("Solver")
            if solver is not None:
                solver.mark_used()          # a <Solver> in an explicit deck: nothing to solve
            return
        self.imp = ImplicitSettings(node, root)
        self.may_recompute = self.imp.restart_iters is not None   # the controller keeps the old warehouse
        if self.timestep_control is None:
            self.knob = IMPLICIT_KNOB
        lv = self.level
        precond = self.imp.precond
        note = ""
        if precond == "mg" and not PCG.mg_possible(lv):
            precond, note = "jacobi", " (multigrid needs even patch extents: Jacobi instead)"
        self.pcg = PCG("imp.cg", imp_A, lv, self.dims, precond, self.imp.tolerance, self.imp.max_iterations,
                       self.imp.norm, self.imp.sweeps, self.imp.criteria == "Relative",
                       test_first=self.imp.package == "CGSolver")
        self.imp_banner = self.imp.describe(precond, note + f"; delT with knob_for_speedSound {self.knob:g}")
        self.imp_logged = False
        self.outer_iterations = []
        self.outer_max_rhs = 0.0        # the last outer iteration's max |rhs|
        self._outer_first = True        # before the step's first outer iteration's test
        self._keep_cache = {}           # (patch, material) -> the boundary cells' _keep
        self._dummy = np.zeros((1, 1, 1))   # a face-velocity array of a direction the grid lacks

    # -- scheduling ------------------------------------------------------------------------------
    def schedule_implicit_pressure(self, sched, dirs, matls=None):
        """The implicit pressure tasks over `matls` (default this component's; MPMICE passes
        every material, solids included: their volume fractions, specific volumes and face
        velocities enter eq. P as the fluids' do). Material indices must be 0..N-1."""
        m0 = [0]
        matls = list(self.matls if matls is None else matls)
        assert matls == list(range(len(matls))), matls
        self._rank = sched.comm.rank
        self._nmatls = len(matls)
        self._sched = sched
        self._step_seen = None
        if not self.imp_logged and sched.comm.rank == 0:
            print(self.imp_banner, file=sys.stderr)
            self.imp_logged = True
        # the residual's ghosts: Uintah's limiter reconstructs the donors' fractions from their
        # neighbours and offsets their slabs by their other faces' velocities
        second = self.vol_frac_second_order(len(matls) == 1)
        ghost_vf, ghost_uf = (2, (G, 1)) if second else (1, ())
        t = Task("ICE::setupMatrix", self.imp_setup, matls) \
            .requires(OLD, L.delT).requires(NEW, I.vol_frac_CC, G, 1).requires(NEW, I.sp_vol_CC, G, 1) \
            .requires(NEW, I.speedSound_CC).computes(matrix, matls=m0).computes(imp_P0, matls=m0)
        for d in dirs:
            t.requires(NEW, I.FC_VEL[d], G, 1).computes(imp_UF0[d])
        if getattr(self, "slip", None) is not None:         # the slip model's K of each cell
            t.requires(NEW, SL.slipK_CC, G, 1, matls=m0)
        if self.pcg.precond == "mg":
            t.computes(self.pcg.OP)
        sched.add_task(t)
        t = Task("ICE::setupRHS", self.imp_rhs0, matls) \
            .requires(OLD, L.delT).requires(NEW, I.vol_frac_CC, G, ghost_vf).requires(NEW, matrix, matls=m0) \
            .requires(NEW, imp_P0, matls=m0).computes(rhs0, matls=m0)
        for d in dirs:
            t.requires(NEW, imp_UF0[d], *ghost_uf)
        if self.mass_exchange is not None:
            self.mass_exchange.requires(t, NEW)
        sched.add_task(t)

        seed = Task("ICE::implicitSolveSetup", self.imp_seed, m0).requires(OLD, rhs, matls=m0) \
            .requires(PARENT_NEW, matrix, matls=m0).computes(imp_A, matls=m0)
        if self.pcg.precond == "mg":
            seed.requires(PARENT_NEW, self.pcg.OP)
        if len(matls) > 1:      # the stencil from the last iteration's face velocities (their donors)
            seed.requires(PARENT_OLD, L.delT).requires(PARENT_NEW, I.vol_frac_CC, G, 1, matls=matls) \
                .requires(PARENT_NEW, I.sp_vol_CC, G, 1, matls=matls).requires(PARENT_NEW, I.speedSound_CC, matls=matls)
            for d in dirs:
                seed.requires(OLD, imp_UF[d], matls=matls)
            if getattr(self, "slip", None) is not None:
                seed.requires(PARENT_NEW, SL.slipK_CC, G, 1, matls=m0)
        self.pcg.seed_computes(seed)
        inner = self.pcg.loop("ICE::implicitPressureSolve", imp_delP)
        upd = Task("ICE::updatePressure", self.imp_update, m0).requires(OLD, imp_P, matls=m0) \
            .requires(NEW, imp_delP, matls=m0).computes(imp_P, matls=m0)
        fc = Task("ICE::updateVel_FC", self.imp_faces, matls) \
            .requires(NEW, imp_P, G, 1, matls=m0).requires(PARENT_OLD, L.delT) \
            .requires(PARENT_NEW, I.vol_frac_CC, G, 1).requires(PARENT_NEW, I.sp_vol_CC, G, 1)
        for d in dirs:
            fc.requires(PARENT_NEW, I.FC_VEL[d], G, 1).computes(imp_UF[d])
        if getattr(self, "slip", None) is not None:
            fc.requires(PARENT_NEW, SL.slipK_CC, G, 1, matls=m0)
        res = Task("ICE::setupRHS", self.imp_rhs, matls) \
            .requires(NEW, imp_P, matls=m0).requires(NEW, imp_A, matls=m0).requires(PARENT_OLD, L.delT) \
            .requires(PARENT_NEW, I.vol_frac_CC, G, ghost_vf).computes(rhs, matls=m0).computes(max_RHS)
        for d in dirs:
            res.requires(NEW, imp_UF[d], *ghost_uf)
        if self.mass_exchange is not None:
            self.mass_exchange.requires(res, PARENT_NEW)
        # rhs: the last outer iteration's residual of eq. P, handed back for <save label="rhs"> (Uintah's)
        results = {imp_P.name: (sum_imp_delP, m0), rhs.name: (rhs, m0)}
        results.update({imp_UF[d].name: I.FC_VEL_ME[d] for d in dirs})
        self.outer = Loop("ICE::implicitPressureOuter", matls, [seed, inner, upd, fc, res],
                          init={imp_P.name: imp_P0, rhs.name: rhs0, **{imp_UF[d].name: imp_UF0[d] for d in dirs}},
                          results=results,
                          converged=self._outer_converged,
                          max_iterations=self.imp.max_outer, fail="continue")
        sched.add_task(self.outer)
        t = Task("ICE::updatePressCC", self.imp_press, m0) \
            .requires(NEW, I.press_equil_CC, matls=m0).requires(NEW, sum_imp_delP, matls=m0) \
            .computes(I.press_CC, matls=m0).computes(I.delP_Dilatate, matls=m0)
        if self.mass_exchange is not None:
            self.mass_exchange.requires(t.requires(NEW, matrix, matls=m0), NEW)
        if getattr(self, "hydrostatic", False):
            t.requires(NEW, I.sp_vol_CC, matls=[self.surrounding])
        sched.add_task(t)

    def _outer_converged(self, dw, k, parent_new):
        """The outer iteration's test (max |rhs| <= outer_iteration_tolerance); keeps max |rhs|."""
        self.outer_max_rhs = dw.get_reduction(max_RHS)
        self._outer_first = False
        return self.outer_max_rhs <= self.imp.outer_tol

    # -- task bodies -------------------------------------------------------------------------------
    def _keep(self, patch, m):
        """Per extra cell of the patch's domain-boundary faces (a CC array, 0 elsewhere): does
        material m's face velocity there respond to delP (a fixed pressure behind a face velocity
        that is not fixed)? Sub-faces (circle, rectangle, annulus) have their own conditions."""
        key = (patch.id, m, patch.low_index(CC), patch.alloc_shape(CC))
        cache = self._keep_cache
        if key in cache:
            return cache[key]
        b, shape = self.boxes(patch), patch.alloc_shape(CC)
        keep = np.zeros(shape, np.int64)
        for name in patch.boundary_faces:
            if self.bcs.table.get(name) is None:
                continue
            f = FACE_NAMES.index(name)
            d, s = f // 2, f % 2
            d1, d2 = (d + 1) % 3, (d + 2) % 3
            tangential = (shape[d1], shape[d2])
            vel = self._face_kinds(patch, name, "Velocity", m, tangential)
            press = self._face_kinds(patch, name, "Pressure", 0, tangential)
            responds = ~np.isin(vel, (DIRICHLET, SYMMETRY, FREE_SLIP)) & (press == DIRICHLET)
            layer = np.moveaxis(keep, d, 0)[b.lo[d] - 1 if s == 0 else b.hi[d]]
            layer[...] = responds if d1 < d2 else responds.T
        cache[key] = keep
        return keep

    def _face_kinds(self, patch, name, var, m, shape):
        """The condition kind of var for material m on each cell of face `name` (side, then sub-faces)."""
        kinds = np.empty(shape, np.int64)
        for kind, _, sel, want in self.bcs._parts(patch, name, var, m):
            if sel.shape[0] == 0:
                kinds[...] = kind
            else:
                kinds[sel == want] = kind
        return kinds

    def _vel_fc(self, patch, matls, P, get_fc, vfs, sps, dt, out_faces, coeffs):
        """Face velocities u_m(P) of the patch's faces (eq. 28 with p = p_eq + P, the exchange, the
        boundary conditions) into out_faces(d, m), called once per direction and material; it
        allocates with zeros, so the extra cells' faces that no task computes hold 0 as explicit ICE's."""
        b = self.boxes(patch)
        dx = patch.level.dx
        for d in range(3):
            if not self.dims[d]:
                continue
            pre = []
            for m in matls:
                u0 = get_fc(d, m)
                uf = np.empty_like(u0) if self.exchange else out_faces(d, m)
                IK.face_correct(u0, sps[m], P, uf, b.sh[d], UNIT[d], b.flo[d], b.fhi[d], dt, dx[d])
                pre.append(uf)
            outs = [out_faces(d, m) for m in matls] if self.exchange else pre
            if self.exchange:
                K.exchange_faces(tuple(pre), tuple(vfs), tuple(sps), tuple(outs), b.sh[d], UNIT[d], b.flo[d],
                                 b.fhi[d], dt, *coeffs)
            for m in matls:
                self.bcs.face_velocity(patch, outs[m], d, m, b.flo[d], b.fhi[d])

    def _rhs(self, patch, matls, P, A, get_uf, vfs, dt, dw):
        """The residual of eq. P from the face velocities get_uf(d, m), with the models' mass
        exchange (dw: the timestep's warehouse); returns (rhs, max |rhs|)."""
        b = self.boxes(patch)
        one = len(matls) == 1
        dummy = np.zeros((1, 1, 1))
        div = np.zeros(patch.alloc_shape(CC))
        for m in matls:
            self.add_dilatation(patch, vfs[m], [get_uf(d, m) if self.dims[d] else dummy for d in range(3)],
                                one, dt, div)
        if self.mass_exchange is not None:      # Uintah's massExchTerm: sum_m m_src,m v_m / V
            div -= self.mass_exchange.term(patch, dw)
        r = np.zeros(patch.alloc_shape(CC))
        _, rmax = IK.pressure_rhs(A, P, div, r, b.lo, b.hi)
        return r, rmax

    def _bc_increment(self, patch, P):
        """Extra cells of an increment: 0 behind a Dirichlet pressure, else a copy (zero gradient)."""
        b = self.boxes(patch)
        for name in patch.boundary_faces:
            f = FACE_NAMES.index(name)
            d, s = f // 2, f % 2
            for kind, _, sel, want in self.bcs._parts(patch, name, "Pressure", 0):
                bc_scalar_part(P, d, s, 1 if kind == DIRICHLET else 0, 0.0, 0.0, b.lo, b.hi, b.olo, b.ohi, sel, want)

    def _stencil(self, patch, matls, A, vfs, sps, css, ufs, dt, coeffs):
        """Eq. P's stencil into A (zeroed first); ufs[m][d]: material m's face velocities, whose
        signs pick the donor cells of the face fractions theta_m,f as the residual's (Uintah's
        setupMatrix with the upwinded vol_frac)."""
        b = self.boxes(patch)
        dx = patch.level.dx
        s = np.array([dt * dt / dx[d] ** 2 if self.dims[d] else 0.0 for d in range(3)])
        atb = np.array([patch.at_low[0], patch.at_high[0], patch.at_low[1], patch.at_high[1],
                        patch.at_low[2], patch.at_high[2]], dtype=np.int64)
        A[...] = 0.0
        one = len(matls) == 1
        s_faces = np.zeros(3) if self.exchange else s        # with exchange: faces below
        sh = np.array(b.sh, dtype=np.int64)
        for m in matls:
            SK.add_material(A, vfs[m], sps[m], css[m], one, self.dims, b.lo, b.hi, s_faces, self._keep(patch, m),
                            atb, *ufs[m], sh)
        if self.exchange:
            keep = tuple(self._keep(patch, m) for m in matls)
            IK.add_exchange_faces(A, tuple(vfs), tuple(sps), tuple(tuple(ufs[m][d] for m in matls) for d in range(3)),
                                  sh, self.dims, b.lo, b.hi, s, keep, atb, dt, *coeffs)

    def imp_setup(self, patch, matls, old_dw, new_dw):
        self._outer_first = True
        dt = old_dw.get_reduction(L.delT)
        A = new_dw.allocate(matrix, 0, patch)
        vfs = [new_dw.get(I.vol_frac_CC, m, patch) for m in matls]
        sps = [new_dw.get(I.sp_vol_CC, m, patch) for m in matls]
        coeffs = self.face_exchange_coefficients(new_dw, patch)
        P = new_dw.allocate(imp_P0, 0, patch)
        uf0 = [[self._dummy] * 3 for _ in matls]

        def out(d, m):
            uf0[m][d] = new_dw.allocate(imp_UF0[d], m, patch)
            return uf0[m][d]
        self._vel_fc(patch, matls, P, lambda d, m: new_dw.get(I.FC_VEL[d], m, patch), vfs, sps, dt, out, coeffs)
        self._stencil(patch, matls, A, vfs, sps, [new_dw.get(I.speedSound_CC, m, patch) for m in matls], uf0, dt,
                      coeffs)
        if self.pcg.precond == "mg":
            self.pcg.put_coarse_operator(patch, A, new_dw)

    def imp_rhs0(self, patch, matls, old_dw, new_dw):
        """The residual of eq. P before the first outer iteration (P = 0)."""
        r, _ = self._rhs(patch, matls, new_dw.get(imp_P0, 0, patch), new_dw.get(matrix, 0, patch),
                         lambda d, m: new_dw.get(imp_UF0[d], m, patch),
                         [new_dw.get(I.vol_frac_CC, m, patch) for m in matls], old_dw.get_reduction(L.delT), new_dw)
        new_dw.put(rhs0, 0, patch, r)

    def imp_seed(self, patch, matls, old_dw, new_dw, parent_old, parent_new):
        """The iteration's stencil and PCG seeds. With several materials the stencil's face fractions
        follow the donors of the last iteration's face velocities, as the residual's (Uintah rebuilds
        its matrix every outer iteration); the multigrid hierarchy stays the step's (a preconditioner)."""
        if self._nmatls == 1 or self._outer_first:      # the first iteration's donors are the step's stencil's
            new_dw.put(imp_A, 0, patch, parent_new.get(matrix, 0, patch))
        else:
            ms = range(self._nmatls)
            ufs = [[old_dw.get(imp_UF[d], m, patch) if self.dims[d] else self._dummy for d in range(3)] for m in ms]
            self._stencil(patch, ms, new_dw.allocate(imp_A, 0, patch),
                          [parent_new.get(I.vol_frac_CC, m, patch) for m in ms],
                          [parent_new.get(I.sp_vol_CC, m, patch) for m in ms],
                          [parent_new.get(I.speedSound_CC, m, patch) for m in ms], ufs,
                          parent_old.get_reduction(L.delT), self.face_exchange_coefficients(parent_new, patch))
        if self.pcg.precond == "mg":
            self.pcg.setup_hierarchy(parent_new.get_reduction(self.pcg.OP))
        self.pcg.put_seeds(patch, old_dw.get(rhs, 0, patch), new_dw)

    def imp_update(self, patch, matls, old_dw, new_dw, parent_old, parent_new):
        b = self.boxes(patch)
        P = new_dw.allocate(imp_P, 0, patch)
        IK.add_increment(old_dw.get(imp_P, 0, patch), new_dw.get(imp_delP, 0, patch), P, b.lo, b.hi)
        self._bc_increment(patch, P)

    def imp_faces(self, patch, matls, old_dw, new_dw, parent_old, parent_new):
        self._vel_fc(patch, matls, new_dw.get(imp_P, 0, patch), lambda d, m: parent_new.get(I.FC_VEL[d], m, patch),
                    [parent_new.get(I.vol_frac_CC, m, patch) for m in matls],
                    [parent_new.get(I.sp_vol_CC, m, patch) for m in matls], parent_old.get_reduction(L.delT),
                    lambda d, m: new_dw.allocate(imp_UF[d], m, patch),
                    self.face_exchange_coefficients(parent_new, patch))

    def imp_rhs(self, patch, matls, old_dw, new_dw, parent_old, parent_new):
        r, rmax = self._rhs(patch, matls, new_dw.get(imp_P, 0, patch), new_dw.get(imp_A, 0, patch),
                            lambda d, m: new_dw.get(imp_UF[d], m, patch),
                            [parent_new.get(I.vol_frac_CC, m, patch) for m in matls],
                            parent_old.get_reduction(L.delT), parent_new)
        new_dw.put(rhs, 0, patch, r)
        new_dw.put_reduction(max_RHS, rmax)

    def imp_press(self, patch, matls, old_dw, new_dw):
        """p = p_eq + delP (eq. 30) with the pressure boundary conditions; notes the outer count."""
        b = self.boxes(patch)
        press = new_dw.allocate(I.press_CC, 0, patch)
        total = new_dw.get(sum_imp_delP, 0, patch)
        IK.add_increment(new_dw.get(I.press_equil_CC, 0, patch), total, press, b.lo, b.hi)
        dil = new_dw.allocate(I.delP_Dilatate, 0, patch)
        dil[...] = total
        if self.mass_exchange is not None:      # Uintah's delP_MassX = massExchTerm / sumKappa, taken out
            kap = new_dw.get(matrix, 0, patch)[..., 0]
            sl = tuple(slice(lo, hi) for lo, hi in zip(b.lo, b.hi))
            dil[sl] -= self.mass_exchange.term(patch, new_dw)[sl] / kap[sl]
        self.press_bc(patch, press, new_dw.get(I.sp_vol_CC, self.surrounding, patch) if self.hydrostatic else None)
        if self._step_seen is not new_dw.dw:                # once per rank and step
            self._step_seen = new_dw.dw
            self.outer_iterations.append(self.outer.iterations)
            limit = self.imp.restart_iters
            step, rmax = new_dw.dw.generation, self.outer_max_rhs
            if limit is not None and (not self.outer.converged_last or self.outer.iterations > limit):
                self._sched.request_recompute(
                    f"ICE implicit pressure: timestep {step}: {self.outer.iterations} outer iterations, "
                    f"{'converged' if self.outer.converged_last else 'not converged'} (max|rhs| {rmax:.3e}); "
                    f"iters_before_timestep_restart {limit}")
            elif not self.outer.converged_last and self._rank == 0:
                print(f"pysus: warning: ICE implicit pressure: timestep {step}: outer iteration not converged: "
                      f"max|rhs| {rmax:.3e} above outer_iteration_tolerance {self.imp.outer_tol:g} after "
                      f"{self.outer.iterations} outer iterations; continuing", file=sys.stderr)


