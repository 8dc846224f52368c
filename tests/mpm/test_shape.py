"""Shape functions (shape.py) and the fused transfer kernels (transfer.py): partition of
unity, the uGIMP formula, conservation and exactness of p2g / g2p, and that reading the
owned and ghost particles run by run gives bitwise the sums of one merged array."""
import os

import numpy as np
import pytest
from numba import njit

from components.mpm.shape import (CHUNK, GIMP, LINEAR, _counts, _inv_dx, _scratch, _sel, _stencil, _stencil_get,
                                  _stencil_put)
from components.mpm.transfer import kernels, one_run
from framework.scheduler.particle_kernels import runs

CASES = [(k, a) for k in ("linear", "gimp") for a in (1, 3, 7, 5)]     # 5: an xz plane
# The fused transfer kernels are one numba compilation per (interpolator, axes, update, p2g's
# flags) and argument types (minutes each, cold): by default they are tested on the combinations
# the shipped decks compile anyway (scripts/warm_kernels), with the tasks' argument types and
# flags; PYSUS_TEST_VARIANTS=all tests every combination above, with every flag.
ALL_VARIANTS = os.environ.get("PYSUS_TEST_VARIANTS") == "all"
# p2g's (has_fext, has_volume) of the shipped decks: inputs/MPMICE/piston.ups (linear, x),
# inputs/MPM/thick_cylinder.ups (linear, xy), adiabatic_copper_jc.ups (linear, xyz),
# inputs/MPMICE/pressurized_cylinder.ups (GIMP, xy)
SHIPPED_P2G = {("linear", 1): (False, True), ("linear", 3): (True, True), ("linear", 7): (False, True),
               ("gimp", 3): (False, True)}
P2G_CASES = CASES if ALL_VARIANTS else list(SHIPPED_P2G)
# USL's g2p (L and F in the same pass) of the shipped decks: adiabatic_copper_jc.ups (linear, xyz);
# the others update with MUSL, whose L and F the grad pass computes (GRAD_CASES)
USL_CASES = CASES if ALL_VARIANTS else [("linear", 7)]
MUSL_CASES = [("linear", 3), ("gimp", 7)] if ALL_VARIANTS else [("linear", 3), ("gimp", 3)]
GRAD_CASES = CASES if ALL_VARIANTS else [("linear", 3), ("gimp", 3)]


@njit(cache=True)
def _weights(kind, act, px, lp, anchor, dx, node_low, ni, S, dS):
    """The stencil of shape._stencil as arrays: local node index, weight, gradient."""
    na, nb, nc = _counts(kind, act)
    ih = _inv_dx(dx)
    for p in range(px.shape[0]):
        (i, j, k, wx0, wx1, wx2, gx0, gx1, gx2, wy0, wy1, wy2, gy0, gy1, gy2,
         wz0, wz1, wz2, gz0, gz1, gz2) = _stencil(kind, act, px, lp, p, anchor, ih, node_low)
        q = 0
        for a in range(na):
            for b in range(nb):
                for c in range(nc):
                    wa, wb, wc = _sel(a, wx0, wx1, wx2), _sel(b, wy0, wy1, wy2), _sel(c, wz0, wz1, wz2)
                    ni[p, q, 0], ni[p, q, 1], ni[p, q, 2] = i + a, j + b, k + c
                    S[p, q] = wa * wb * wc
                    dS[p, q, 0] = _sel(a, gx0, gx1, gx2) * wb * wc
                    dS[p, q, 1] = wa * _sel(b, gy0, gy1, gy2) * wc
                    dS[p, q, 2] = wa * wb * _sel(c, gz0, gz1, gz2)
                    q += 1


def weights(kind, act, px, lp, anchor, dx, node_low):
    na, nb, nc = (2 if kind == "linear" else 3,) * 3
    nn = (na if act & 1 else 1) * (nb if act & 2 else 1) * (nc if act & 4 else 1)
    ni, S, dS = np.empty((len(px), nn, 3), np.int64), np.empty((len(px), nn)), np.empty((len(px), nn, 3))
    lp = np.require(lp, requirements="W")       # one numba type for _weights (a read-only size: a second)
    _weights(LINEAR if kind == "linear" else GIMP, act, px, lp, anchor, dx, node_low, ni, S, dS)
    return ni, S, dS


@njit(cache=True)
def _chunked(kind, act, px, lp, anchor, dx, node_low, out_i, out_w):
    """_stencil_put then _stencil_get chunk by chunk, as the transfer kernels run them."""
    ih = _inv_dx(dx)
    sb, sw = _scratch(kind, act)
    n = px.shape[0]
    for c0 in range(0, n, CHUNK):
        c1 = min(c0 + CHUNK, n)
        for p in range(c0, c1):
            out_i[p, 0], out_i[p, 1], out_i[p, 2] = _stencil_put(kind, act, px, lp, p, anchor, ih, node_low, p - c0, sw)
        for p in range(c0, c1):
            w = _stencil_get(kind, act, p - c0, ih, sw)
            for q in range(18):
                out_w[p, q] = w[q]


@njit(cache=True)
def _direct(kind, act, px, lp, anchor, dx, node_low, out_i, out_w):
    ih = _inv_dx(dx)
    for p in range(px.shape[0]):
        st = _stencil(kind, act, px, lp, p, anchor, ih, node_low)
        out_i[p, 0], out_i[p, 1], out_i[p, 2] = st[0], st[1], st[2]
        w = st[3:]
        for q in range(18):
            out_w[p, q] = w[q]


def select(arrays, sel):
    """The particles sel of each array, contiguous; read-only stays read-only (the kernels'
    argument types, hence their compilations, are the tasks')."""
    out = []
    for a in arrays:
        b = np.ascontiguousarray(a[sel])
        b.flags.writeable = a.flags.writeable
        out.append(b)
    return tuple(out)


def make_grid(act, ncell=6):
    """Patch with one ghost layer (two for GIMP's reach), node_low = -2 on active axes."""
    on = np.array([bool(act >> d & 1) for d in range(3)])
    dx = np.where(on, [0.5, 0.25, 0.4], 1.0)
    anchor = np.array([0.1, -0.3, 0.7])
    lo = np.where(on, -2, 0).astype(np.int64)
    shape = tuple(int(s) for s in np.where(on, ncell + 5, 1))
    return on, anchor, dx, lo, shape


def make_particles(on, anchor, dx, ncell, n=300, seed=0, kind="gimp"):
    """Positions and half sizes; linear's sizes read-only, as the tasks pass them (tasks._zeros3)."""
    rng = np.random.default_rng(seed)
    px = np.tile(anchor, (n, 1)) + np.where(on, rng.random((n, 3)) * ncell * dx, 0.0)
    lp = np.tile(dx / 4, (n, 1))                                   # 2 particles per cell
    lp.flags.writeable = kind != "linear"
    return np.ascontiguousarray(px), lp


@pytest.mark.parametrize("kind,act", CASES)
def test_partition_of_unity(kind, act):
    on, anchor, dx, lo, shape = make_grid(act)
    px, lp = make_particles(on, anchor, dx, 6)
    ni, S, dS = weights(kind, act, px, lp, anchor, dx, lo)
    assert S.shape[1] == (2 if kind == "linear" else 3) ** on.sum()
    assert np.allclose(S.sum(1), 1.0, atol=1e-13)
    assert np.allclose(dS.sum(1), 0.0, atol=1e-11)
    assert (S >= -1e-15).all()
    assert (ni >= 0).all() and (ni < np.array(shape)).all()
    assert np.all(dS[:, :, ~on] == 0.0) and np.all(ni[:, :, ~on] == 0)


@pytest.mark.parametrize("kind,act", CASES)
def test_chunked_stencil_is_stencil(kind, act):
    """The two-loop form of the kernels (_stencil_put, then _stencil_get) gives bitwise
    _stencil's base nodes, weights and gradients, over several chunks."""
    on, anchor, dx, lo, shape = make_grid(act)
    px, lp = make_particles(on, anchor, dx, 6, n=3 * CHUNK + 5)
    k = LINEAR if kind == "linear" else GIMP
    res = []
    for f in (_chunked, _direct):
        out_i, out_w = np.empty((len(px), 3), np.int64), np.empty((len(px), 18))
        f(k, act, px, lp, anchor, dx, lo, out_i, out_w)
        res.append((out_i, out_w))
    assert np.array_equal(res[0][0], res[1][0])
    assert res[0][1].tobytes() == res[1][1].tobytes()


def test_gimp_weights_match_formula():
    """uGIMP 1D piecewise formula of Bardenhagen & Kober (h = 1, lp = 1/4)."""
    def ref(r, l):
        a = abs(r)
        if a < l:
            return 1 - (r * r + l * l) / (2 * l)
        if a <= 1 - l:
            return 1 - a
        if a < 1 + l:
            return (1 + l - a) ** 2 / (4 * l)
        return 0.0
    xs = np.linspace(0.02, 4.98, 97)
    px = np.zeros((len(xs), 3))
    px[:, 0] = xs
    ni, S, dS = weights("gimp", 1, px, np.full((len(xs), 3), 0.25), np.zeros(3), np.ones(3), np.array([-1, 0, 0]))
    ni = ni - np.array([1, 0, 0])  # global indices
    for p, x in enumerate(xs):
        for q in range(3):
            assert np.isclose(S[p, q], ref(x - ni[p, q, 0], 0.25), atol=1e-14)
        h = 1e-6
        fd = (ref(x + h - ni[p, 0, 0], 0.25) - ref(x - h - ni[p, 0, 0], 0.25)) / (2 * h)
        assert np.isclose(dS[p, 0, 0], fd, atol=1e-5)


def _p2g(kind, act, parts, order_runs, shape, anchor, dx, lo, has_f):
    p2g = kernels(kind, act)[0]
    g = [np.zeros(shape), np.zeros(shape + (3,)), np.zeros(shape), np.zeros(shape + (3,)), np.zeros(shape + (3,))]
    own, ghost = parts
    p2g(own, ghost, order_runs, has_f, True, anchor, dx, lo, *g)
    return g


@pytest.mark.parametrize("kind,act", P2G_CASES)
def test_p2g_conserves_and_runs_equal_merged(kind, act):
    on, anchor, dx, lo, shape = make_grid(act)
    px, lp = make_particles(on, anchor, dx, 6, seed=3, kind=kind)
    n = len(px)
    rng = np.random.default_rng(4)
    pm, pvol = rng.random(n) + 0.5, rng.random(n) + 0.1
    pv, pf, ps = rng.random((n, 3)), rng.random((n, 3)), rng.random((n, 3, 3))
    part = (px, pm, pv, pvol, ps, pf, lp)
    has_f = ALL_VARIANTS or SHIPPED_P2G[kind, act][0]
    gm, gp, gvol, ge, gi = _p2g(kind, act, (part, part), one_run(n), shape, anchor, dx, lo, has_f)
    assert np.isclose(gm.sum(), pm.sum(), rtol=1e-13)
    assert np.isclose(gvol.sum(), pvol.sum(), rtol=1e-13)
    assert np.allclose(gp.sum((0, 1, 2)), (pm[:, None] * pv).sum(0), rtol=1e-13)
    assert np.allclose(ge.sum((0, 1, 2)), pf.sum(0) if has_f else 0.0, rtol=1e-13)
    assert np.allclose(gi.sum((0, 1, 2)), 0.0, atol=1e-10)  # sum dS = 0
    ni, S, dS = weights(kind, act, px, lp, anchor, dx, lo)
    rm, ri = np.zeros(shape), np.zeros(shape + (3,))
    idx = (ni[..., 0].ravel(), ni[..., 1].ravel(), ni[..., 2].ravel())
    np.add.at(rm, idx, (pm[:, None] * S).ravel())
    np.add.at(ri, idx, -np.einsum("p,pij,pqj->pqi", pvol, ps, dS).reshape(-1, 3))
    assert np.allclose(gm, rm, atol=1e-13) and np.allclose(gi, ri, atol=1e-12)
    # the same particles as owned + ghost arrays read run by run: the very same sums
    mine = rng.random(n) < 0.7
    order = np.empty(n, np.int64)
    order[mine] = np.arange(mine.sum())
    order[~mine] = mine.sum() + np.arange((~mine).sum())
    split = tuple(select(part, sel) for sel in (mine, ~mine))
    r = runs(order, int(mine.sum()))
    assert len(r) > 2
    for a, b in zip(_p2g(kind, act, split, r, shape, anchor, dx, lo, has_f), (gm, gp, gvol, ge, gi)):
        assert np.array_equal(a, b)


def _linear_field(kind, act):
    """Particles on a patch, a nodal velocity v = A x + b linear along the active axes, A, b."""
    on, anchor, dx, lo, shape = make_grid(act)
    px, lp = make_particles(on, anchor, dx, 6, seed=1, kind=kind)
    A = np.array([[0.3, -1.2, 0.7], [2.0, 0.5, -0.4], [-0.8, 1.1, 0.9]]) * on   # varies along active axes
    b = np.array([1.0, -2.0, 0.5])
    idx = np.stack(np.meshgrid(*[np.arange(s) for s in shape], indexing="ij"), -1)
    gvel = np.ascontiguousarray((anchor + (idx + lo) * dx) @ A.T + b)
    return px, lp, anchor, dx, lo, shape, gvel, A, b


@pytest.mark.parametrize("kind,act", USL_CASES)
def test_g2p_linear_field_reproduced(kind, act):
    """USL: a linear nodal velocity field is interpolated exactly, with its gradient."""
    px, lp, anchor, dx, lo, shape, gvel, A, b = _linear_field(kind, act)
    n = len(px)
    pv, pm, dt = np.random.default_rng(2).random((n, 3)), np.ones(n), 0.1
    x, v, L, F, V = np.empty((n, 3)), np.empty((n, 3)), np.empty((n, 3, 3)), np.empty((n, 3, 3)), np.empty(n)
    g2p = kernels(kind, act)[1]
    own = (px, pv, pm, lp)
    g2p(False, own, own, one_run(n), anchor, dx, lo, gvel, 2.0 * gvel, dt, x, v, L, np.zeros((1, 1, 1, 3)),
        np.zeros(8), 0.0, np.inf, True, np.tile(np.eye(3), (n, 1, 1)), F, V, 1.0)
    vexact = px @ A.T + b
    assert np.allclose(x, px + dt * vexact, atol=1e-12)
    assert np.allclose(v, pv + dt * 2 * vexact, atol=1e-12)
    assert np.allclose(L, np.broadcast_to(A, (n, 3, 3)), atol=1e-11)
    assert np.allclose(F, np.eye(3) + dt * A, atol=1e-12) and np.allclose(V, np.linalg.det(np.eye(3) + dt * A))


@pytest.mark.parametrize("kind,act", GRAD_CASES)
def test_musl_linear_field_reproduced(kind, act):
    """MUSL: g2p moves the particles with a linear nodal velocity field exactly; the grad pass
    gives its gradient exactly, and F = I + dt A, V = m / rho0 det F."""
    px, lp, anchor, dx, lo, shape, gvel, A, b = _linear_field(kind, act)
    n = len(px)
    pv, pm, dt = np.random.default_rng(2).random((n, 3)), np.ones(n), 0.1
    x, v, gmom = np.empty((n, 3)), np.empty((n, 3)), np.zeros(shape + (3,))
    _, g2p, grad = kernels(kind, act)
    own = (px, pv, pm, lp)
    g2p(True, own, own, one_run(n), anchor, dx, lo, gvel, 2.0 * gvel, dt, x, v, np.zeros((1, 3, 3)), gmom,
        np.zeros(8), 0.0, np.inf, False, np.zeros((1, 3, 3)), np.zeros((1, 3, 3)), np.zeros(1), 1.0)
    vexact = px @ A.T + b
    assert np.allclose(x, px + dt * vexact, atol=1e-12)
    assert np.allclose(v, pv + dt * 2 * vexact, atol=1e-12)
    L, F, V = np.empty((n, 3, 3)), np.empty((n, 3, 3)), np.empty(n)
    grad(px, lp, anchor, dx, lo, gvel, L, True, dt, pm, 1.0, np.tile(np.eye(3), (n, 1, 1)), F, V, 0, 0.0, 0.0,
         pv, np.zeros((n, 3, 3)), np.zeros(n))
    assert np.allclose(L, np.broadcast_to(A, (n, 3, 3)), atol=1e-11)
    assert np.allclose(F, np.eye(3) + dt * A, atol=1e-12) and np.allclose(V, np.linalg.det(np.eye(3) + dt * A))


@pytest.mark.parametrize("kind,act", MUSL_CASES)
def test_g2p_musl_owned_written_all_remapped(kind, act):
    """MUSL: every particle (owned or ghost) maps its new momentum back; only the owned
    ones are written, compacted, with the same values as when all are owned."""
    on, anchor, dx, lo, shape = make_grid(act)
    px, lp = make_particles(on, anchor, dx, 6, seed=5, kind=kind)
    n = len(px)
    rng = np.random.default_rng(6)
    pv, pm = rng.random((n, 3)), rng.random(n) + 0.5
    gvs, ga = rng.random(shape + (3,)), rng.random(shape + (3,))
    g2p = kernels(kind, act)[1]

    def run(own, ghost, r, n_own):
        x, v, gmom, tot = np.empty((n_own, 3)), np.empty((n_own, 3)), np.zeros(shape + (3,)), np.zeros(8)
        g2p(True, own, ghost, r, anchor, dx, lo, gvs, ga, 0.01, x, v, np.zeros((1, 3, 3)), gmom, tot, 0.0, np.inf,
            False, np.zeros((1, 3, 3)), np.zeros((1, 3, 3)), np.zeros(1), 1.0)
        return x, v, gmom, tot
    allp = (px, pv, pm, lp)
    x, v, gmom, tot = run(allp, allp, one_run(n), n)
    mine = rng.random(n) < 0.6
    order = np.empty(n, np.int64)
    order[mine] = np.arange(mine.sum())
    order[~mine] = mine.sum() + np.arange((~mine).sum())
    own, ghost = (select(allp, sel) for sel in (mine, ~mine))
    xs, vs, gs, ts = run(own, ghost, runs(order, int(mine.sum())), int(mine.sum()))
    assert np.array_equal(xs, x[mine]) and np.array_equal(vs, v[mine]) and np.array_equal(gs, gmom)
    assert np.isclose(ts[0], pm[mine].sum(), rtol=1e-14)


def test_out_of_patch_raises():
    on, anchor, dx, lo, shape = make_grid(7)          # USL on xyz: adiabatic_copper_jc.ups's g2p
    px = np.array([[anchor[0] - 5 * dx[0], anchor[1], anchor[2]]])
    from components.mpm.tasks import _zeros3
    own = (px, np.zeros((1, 3)), np.ones(1), _zeros3(1))
    g2p = kernels("linear", 7)[1]
    with pytest.raises(IndexError):
        g2p(False, own, own, one_run(1), anchor, dx, lo, np.zeros(shape + (3,)), np.zeros(shape + (3,)), 0.1,
            np.empty((1, 3)), np.empty((1, 3)), np.zeros((1, 3, 3)), np.zeros((1, 1, 1, 3)), np.zeros(8), 0.0,
            np.inf, False, np.tile(np.eye(3), (1, 1, 1)), np.empty((1, 3, 3)), np.empty(1), 1.0)


def test_linear_size_stand_in_has_one_numba_type():
    """Linear's stand-in for p.size (tasks._zeros3) has the same numba type for every particle
    count: a C-contiguous view for some counts and a strided one for others made numba compile
    p2g, g2p and grad twice in one run."""
    import numba

    from components.mpm.tasks import _zeros3
    types = {numba.typeof(_zeros3(n)) for n in (0, 1, 2, 7, 1000, 3)}
    assert len(types) == 1
    z = _zeros3(5)
    assert z.shape == (5, 3) and not z.any() and not z.flags.writeable
