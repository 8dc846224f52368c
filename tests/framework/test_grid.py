"""Level and Patch index boxes: ownership tiles the level, ghost sources cover the halo."""
import itertools

import numpy as np
import pytest

from framework.grid import Level, box_intersect
from framework.variables import GRID_TYPES, VarType


def count_owned(level, vt):
    lo, hi = level.total_box(vt)
    cnt = np.zeros([h - l for l, h in zip(lo, hi)], int)
    for p in level.patches:
        plo, phi = p.owned(vt)
        cnt[tuple(slice(a - o, b - o) for a, b, o in zip(plo, phi, lo))] += 1
    return cnt


@pytest.mark.parametrize("vt", GRID_TYPES)
@pytest.mark.parametrize("periodic", [(False, False, False), (True, False, True)])
def test_every_index_owned_exactly_once(vt, periodic):
    lv = Level((0, 0, 0), (1, 2, 3), (10, 7, 6), patches=(3, 2, 2), extra=(1, 1, 1), periodic=periodic)
    assert (count_owned(lv, vt) == 1).all()


def test_collapsed_direction_has_no_extra_cells_and_one_node_layer():
    lv = Level((0, 0, 0), (1, 1, 0.1), (8, 8, 1), patches=(2, 2, 1), extra=(1, 1, 1))
    assert lv.extra == (1, 1, 0) and lv.dim == 2
    assert lv.total_box(VarType.CC) == ((-1, -1, 0), (9, 9, 1))
    assert lv.total_box(VarType.NC) == ((-1, -1, 0), (10, 10, 1))


def test_patch_split_and_boundary_faces():
    lv = Level((0, 0, 0), (1, 1, 1), (10, 10, 10), patches=(3, 1, 1), extra=(1, 1, 1))
    assert [p.lo[0] for p in lv.patches] == [0, 3, 6]
    assert "x-" in lv.patches[0].boundary_faces and "x+" not in lv.patches[0].boundary_faces
    assert "x+" in lv.patches[2].boundary_faces and set(lv.patches[1].boundary_faces) == {"y-", "y+", "z-", "z+"}


@pytest.mark.parametrize("vt", GRID_TYPES)
@pytest.mark.parametrize("g", [1, 2])
@pytest.mark.parametrize("periodic", [(False, False, False), (True, True, False)])
def test_ghost_sources_cover_window_exactly_once(vt, g, periodic):
    lv = Level((0, 0, 0), (1, 1, 1), (9, 8, 4), patches=(3, 2, 1), extra=(1, 1, 1), periodic=periodic)
    for p in lv.patches:
        win = p.window(vt, g)
        cnt = np.zeros([h - l for l, h in zip(*win)], int)
        sl = lambda b: tuple(slice(a - o, c - o) for a, c, o in zip(b[0], b[1], win[0]))
        cnt[sl(p.owned(vt))] += 1
        for q, s, box in lv.ghost_sources(p, vt, g):
            cnt[sl(box)] += 1
            src = (tuple(a - d for a, d in zip(box[0], s)), tuple(a - d for a, d in zip(box[1], s)))
            assert box_intersect(src, q.owned(vt)) == src
        assert (cnt == 1).all(), (p, vt, g)


def test_patch_lookup_of_positions():
    lv = Level((0, 0, 0), (1, 1, 1), (10, 10, 10), patches=(2, 2, 2))
    x = np.array([[0.05, 0.05, 0.05], [0.95, 0.05, 0.55], [1.5, 0.5, 0.5]])
    ids = lv.patch_ids_of_cells(lv.cells_of(x))
    assert ids[0] == 0 and ids[1] == lv.patch_at((1, 0, 1)).id and ids[2] == -1
