"""The ghost exchange's merge of owned and ghost IDs gives exactly the stable argsort of
their concatenation (and its runs), and runs() answers the remembered runs of an order."""
import numpy as np

from framework.scheduler.particle_kernels import KNOWN_RUNS, _runs, merge_ids, runs


def test_merge_ids_is_stable_argsort():
    rng = np.random.default_rng(1)
    for _ in range(2000):
        n_own, n_gh, hi = rng.integers(0, 40), rng.integers(0, 15), rng.integers(1, 60)
        own = np.sort(rng.integers(0, hi, n_own)).astype(np.int64)
        gh = rng.integers(0, hi, n_gh).astype(np.int64)
        ok, order, mask, r = merge_ids(own, gh, np.argsort(gh, kind="stable"), True)
        ref = np.argsort(np.concatenate([own, gh]), kind="stable")
        assert ok and np.array_equal(order, ref) and np.array_equal(mask, ref < n_own)
        assert np.array_equal(r, _runs(ref, n_own))
        if n_own > 1 and own[0] != own[-1]:
            assert not merge_ids(own[::-1].copy(), gh, np.argsort(gh, kind="stable"), True)[0]


def test_runs_remembered_per_array():
    order = np.array([0, 3, 1, 2], np.int64)
    fake = np.zeros((1, 3), np.int64)
    KNOWN_RUNS.put(order, (3, fake))
    assert runs(order, 3) is fake
    assert np.array_equal(runs(order.copy(), 3), _runs(order, 3))
    assert np.array_equal(runs(order, 2), _runs(order, 2))


def _cells(x, anchor, dx):
    return np.floor((x - anchor) / dx)


def test_leavers_near_against_numpy():
    """Relocation's one pass: the leavers (cell outside the patch or NaN) and, of the others,
    the ghost candidates that near_faces finds, with their cells; with boxes, in_boxes
    selects what select_ghosts does."""
    from framework.scheduler.particle_kernels import in_boxes, leavers_near, near_faces, select_ghosts
    rng = np.random.default_rng(2)
    anchor, dx = np.array([-0.3, 0.1, 0.0]), np.array([0.25, 0.5, 1.0])
    lo, hi = np.array([2, 1, 0], np.int64), np.array([9, 7, 1], np.int64)
    for dims in (np.array([True, True, False]), np.array([True, False, False]), np.array([True, True, True])):
        for g in (0, 1, 2):
            x = anchor + rng.uniform(0, 10, (3000, 3)) * dx
            x[::37, 1] = np.nan
            # some positions exactly on cell faces
            x[5::41, 0] = anchor[0] + rng.integers(0, 11, len(x[5::41])) * dx[0]
            out, ni, nc = leavers_near(x, anchor, dx, lo, hi, g, dims)
            c = _cells(x, anchor, dx)
            c[:, ~dims] = 0
            bad = np.isnan(x[:, dims]).any(axis=1)
            outside = bad | ((c < lo) | (c >= hi))[:, dims].any(axis=1)
            assert np.array_equal(out, np.flatnonzero(outside))
            near = ~outside & ((c < lo + g) | (c >= hi - g))[:, dims].any(axis=1)
            assert np.array_equal(ni, np.flatnonzero(near))
            assert np.array_equal(nc, c[near].astype(np.int64))
            inside = np.flatnonzero(~outside)
            ri, rc = near_faces(np.ascontiguousarray(x[inside]), anchor, dx, lo, hi, g, dims)
            assert np.array_equal(inside[ri], ni) and np.array_equal(rc, nc)
            boxes = np.array([[[lo[0], lo[1], 0], [lo[0] + g, hi[1], 1]],
                              [[hi[0] - g, lo[1], 0], [hi[0], lo[1] + g, 1]],
                              [[lo[0], hi[1] - g, 0], [hi[0], hi[1], 1]]], np.int64)
            sel, counts = in_boxes(ni, nc, dims, boxes)
            rsel, rcounts = select_ghosts(np.ascontiguousarray(x[inside]), anchor, dx, lo, hi, g, dims, boxes)
            assert np.array_equal(sel, inside[rsel]) and np.array_equal(counts, rcounts)


def test_ghost_merge_reused_only_for_equal_ghost_ids():
    """_ghost_order hands back the merge of the step before only for the same owned ID array
    and equal ghost IDs."""
    from framework.scheduler import comm

    class DW:
        def __init__(self, own):
            self.own = own

        def num_particles(self, m, p):
            return len(self.own)

        def get(self, label, m, p):
            return self.own

    class Lab:
        name = "id"

    own = np.arange(0, 100, 2, dtype=np.int64)
    gh = np.array([7, 3, 51], np.int64)
    o1, m1 = comm._ghost_order(DW(own), Lab, 0, None, {"id": gh}, True)
    o2, m2 = comm._ghost_order(DW(own), Lab, 0, None, {"id": gh.copy()}, True)
    assert o2 is o1 and m2 is m1
    gh2 = np.array([7, 5, 51], np.int64)
    o3, m3 = comm._ghost_order(DW(own), Lab, 0, None, {"id": gh2}, True)
    assert o3 is not o1
    assert np.array_equal(o3, np.argsort(np.concatenate([own, gh2]), kind="stable"))
    o4, _ = comm._ghost_order(DW(own.copy()), Lab, 0, None, {"id": gh2}, True)
    assert o4 is not o3 and np.array_equal(o4, o3)


def test_relocation_runs_is_stable_argsort_of_pieces():
    """relocation_runs gives the runs of the stable ID argsort of [own rows but the leavers,
    arrivals] with the pieces in source-patch order (own patch among the sources)."""
    from framework.scheduler.particle_kernels import relocation_runs
    rng = np.random.default_rng(3)
    for _ in range(3000):
        n_own, hi = int(rng.integers(0, 40)), int(rng.integers(1, 50))
        own = np.sort(rng.integers(0, hi, n_own)).astype(np.int64)
        leave = np.flatnonzero(rng.random(n_own) < rng.random() * 0.5).astype(np.int64)
        pieces = [(5, np.setdiff1d(np.arange(n_own), leave))]      # own patch id 5
        arr, first, off = [], [], n_own
        for src in rng.permutation([1, 3, 7, 9])[:rng.integers(0, 4)]:
            k = int(rng.integers(0, 6))
            arr.append((src, rng.integers(0, hi, k).astype(np.int64)))
        arr.sort(key=lambda it: it[0])
        for src, a in arr:
            pieces.append((src, np.arange(off, off + len(a))))
            first.append(np.full(len(a), src < 5))
            off += len(a)
        aid = np.concatenate([a for _, a in arr]) if arr else np.zeros(0, np.int64)
        first = np.concatenate(first) if first else np.zeros(0, np.bool_)
        pieces.sort(key=lambda it: it[0])
        index = np.concatenate([ix for _, ix in pieces]).astype(np.int64)
        allids = np.concatenate([own, aid])
        ref = index[np.argsort(allids[index], kind="stable")]
        ok, r = relocation_runs(own, leave, aid, np.argsort(aid, kind="stable"), first, True)
        assert ok
        assert np.array_equal(r, _runs(ref, n_own)), (own, leave, aid, first)
        if n_own > 1 and own[0] != own[-1]:
            assert not relocation_runs(own[::-1].copy(), leave, aid, np.argsort(aid, kind="stable"), first, True)[0]
