"""A <Level> of several <Box>es (framework/gridspec.py): boxes that tile one rectangle of cells
of one size, with patches that line up, are that one box with the same cells and patches (as
Uintah's Grid makes them: box by box, res * i / patches); boxes of other cell sizes, overlapping
or off the cells are refused in one line saying why. (A union that is not one box, such as
Uintah's extrudeRT's L-shaped level: test_level_holes.py.)"""
import numpy as np
import pytest

from framework.gridspec import level_from_spec
from framework.problemspec import InputError, ProblemSpec

LEVEL = """<Uintah_specification><Grid><Level>{boxes}</Level></Grid></Uintah_specification>"""


def box(lo, hi, res, patches=(1, 1, 1), extra=(1, 1, 1), label="b"):
    v = lambda t: "[" + ",".join(str(x) for x in t) + "]"        # noqa: E731
    return (f"<Box label='{label}'><lower>{v(lo)}</lower><upper>{v(hi)}</upper><resolution>{v(res)}</resolution>"
            f"<patches>{v(patches)}</patches><extraCells>{v(extra)}</extraCells></Box>")


def _read(tmp_path, *boxes):
    (tmp_path / "d.ups").write_text(LEVEL.format(boxes="".join(boxes)))
    return level_from_spec(ProblemSpec.load(str(tmp_path / "d.ups")))


def _patch_boxes(level):
    return sorted((p.lo, p.hi) for p in level.patches)


def test_one_box_is_a_level(tmp_path):
    assert tuple(_read(tmp_path, box((0, 0, 0), (1, 1, 1), (4, 4, 4))).ncells) == (4, 4, 4)


def test_boxes_tiling_a_rectangle_are_one_box_with_their_patches(tmp_path):
    """Two boxes side by side in x (3 + 2 patches in x, the same 2 in y) and a third on top of
    both in y with patches that continue theirs: one 10 x 6 x 4 level of 5 x 3 x 1 patches
    whose cells are the boxes' own."""
    lv = _read(tmp_path,
               box((0, 0, 0), (0.6, 0.4, 0.4), (6, 4, 4), (3, 2, 1), label="a"),
               box((0.6, 0, 0), (1.0, 0.4, 0.4), (4, 4, 4), (2, 2, 1), label="b"),
               box((0, 0.4, 0), (1.0, 0.6, 0.4), (10, 2, 4), (5, 1, 1), label="c"))
    assert lv.ncells == (10, 6, 4) and lv.layout == (5, 3, 1)
    assert np.allclose(lv.anchor, 0) and np.allclose(lv.upper, (1.0, 0.6, 0.4)) and np.allclose(lv.dx, 0.1)
    expected = []
    for lo, res, patches in (((0, 0, 0), (6, 4, 4), (3, 2, 1)), ((6, 0, 0), (4, 4, 4), (2, 2, 1)),
                             ((0, 4, 0), (10, 2, 4), (5, 1, 1))):
        for i in range(patches[0]):
            for j in range(patches[1]):
                cut = [(lo[d] + res[d] * k // patches[d], lo[d] + res[d] * (k + 1) // patches[d])
                       for d, k in enumerate((i, j, 0))]
                expected.append((tuple(c[0] for c in cut), tuple(c[1] for c in cut)))
    assert _patch_boxes(lv) == sorted(expected)
    assert lv.extra == (1, 1, 1)


def test_extra_cells_are_the_largest_of_the_boxes(tmp_path):
    lv = _read(tmp_path, box((0, 0, 0), (1, 1, 1), (2, 2, 2), extra=(0, 0, 0)),
               box((1, 0, 0), (2, 1, 1), (2, 2, 2), extra=(1, 0, 1)))
    assert lv.extra == (1, 0, 1) and lv.ncells == (4, 2, 2)


@pytest.mark.parametrize("boxes, message", [
    ((box((0, 0, 0), (1, 1, 1), (4, 4, 4)), box((1, 0, 0), (2, 1, 1), (8, 8, 8))),
     "differs from the first <Box>'s"),
    ((box((0, 0, 0), (1, 1, 1), (4, 4, 4)), box((0.5, 0, 0), (1.5, 1, 1), (4, 4, 4))), "overlaps <Box>"),
    ((box((0, 0, 0), (1, 1, 1), (4, 4, 4), (1, 2, 1)), box((1, 0, 0), (2, 1, 1), (4, 4, 4), (1, 1, 1))),
     "do not line up into one grid of patches"),
    ((box((0, 0, 0), (1, 1, 1), (4, 4, 4)), box((1.1, 0, 0), (2.1, 1, 1), (4, 4, 4))),
     "not on the cell faces"),
    ((), "missing required tag <Box>"),
])
def test_other_unions_are_one_clean_error(tmp_path, boxes, message):
    with pytest.raises(InputError) as e:
        _read(tmp_path, *boxes)
    assert message in str(e.value) and "\n" not in str(e.value)


ONE_BOX = """            <Box label="1">
                <lower>[-1.5,-0.5,0.0]</lower>
                <upper>[-0.5, 0.5,0.6]</upper>
                <extraCells>[1,1,1]</extraCells>
                <patches>[2,2,1]</patches>
                <resolution>[10,10,6]</resolution>
            </Box>"""


def test_a_deck_of_two_boxes_runs_as_its_one_box(tmp_path):
    """tests/mpm/friction_var_traction.ups (2 x 2 patches) with its box cut in two along x, each
    half of 1 x 2 patches: the same cells and patches, so the same run to the last bit (sus also
    writes the same .dat files for both: measured, byte for byte)."""
    from tests.conftest import ROOT
    from tests.mpm.helpers import run
    text = open(ROOT / "tests" / "mpm" / "friction_var_traction.ups").read()
    assert ONE_BOX in text
    cut = ONE_BOX.replace("[-1.5,-0.5,0.0]", "[{lo},-0.5,0.0]").replace("[-0.5, 0.5,0.6]", "[{hi}, 0.5,0.6]")
    halves = "\n".join(cut.replace("{lo}", str(lo)).replace("{hi}", str(hi))
                       .replace("[2,2,1]", "[1,2,1]").replace("[10,10,6]", "[5,10,6]").replace('"1"', f'"{k}"')
                       for k, (lo, hi) in enumerate(((-1.5, -1.0), (-1.0, -0.5))))
    (c1, one), (c2, two) = run(text, tmp_path, "one"), run(text.replace(ONE_BOX, halves), tmp_path, "two")
    assert _patch_boxes(c1.level) == _patch_boxes(c2.level) and len(c2.level.patches) == 4
    for name in ("BndyForce_zminus", "BndyTraction_zminus", "KineticEnergy", "AccStrainEnergy"):
        assert np.array_equal(one.reduction(name)[1], two.reduction(name)[1]), name
    a, b = one.particles(0, 4), two.particles(0, 4)
    assert np.array_equal(a["p.x"], b["p.x"]) and np.array_equal(a["p.stress"], b["p.stress"])
