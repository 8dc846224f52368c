"""A <Level> of several <Box>es (Uintah's extrudeRT: an L-shaped level) is refused in one line."""
import pytest

from framework.gridspec import level_from_spec
from framework.problemspec import InputError, ProblemSpec

LEVEL = """<Uintah_specification><Grid><Level>{boxes}</Level></Grid></Uintah_specification>"""
BOX = ("<Box label='{i}'><lower>[{x},0,0]</lower><upper>[{y},1,1]</upper><resolution>[4,4,4]</resolution>"
       "<extraCells>[1,1,1]</extraCells></Box>")


def _read(tmp_path, nboxes):
    boxes = "".join(BOX.format(i=i, x=i, y=i + 1) for i in range(nboxes))
    (tmp_path / "d.ups").write_text(LEVEL.format(boxes=boxes))
    return level_from_spec(ProblemSpec.load(str(tmp_path / "d.ups")))


def test_one_box_is_a_level(tmp_path):
    assert tuple(_read(tmp_path, 1).ncells) == (4, 4, 4)


@pytest.mark.parametrize("n, message", [(2, "made of 2 <Box>es is not supported"),
                                        (0, "missing required tag <Box>")])
def test_several_or_no_boxes_are_one_clean_error(tmp_path, n, message):
    with pytest.raises(InputError, match=message):
        _read(tmp_path, n)
