"""Geometry pieces: inside tests, combinations, labelled reuse and cell fractions."""
import numpy as np
import pytest

from framework.geometry import GeometryReader, cell_fractions
from framework.grid import Level
from framework.problemspec import InputError, ProblemSpec

DECK = """<m>
 <geom_object>
  <difference>
    <box label="all"><min>[0,0,0]</min><max>[1,1,1]</max></box>
    <sphere label="ball"><origin>[0.5,0.5,0.5]</origin><radius>0.25</radius></sphere>
  </difference>
 </geom_object>
 <geom_object><sphere label="ball"></sphere></geom_object>
 <geom_object><cylinder><bottom>[0,0,0]</bottom><top>[0,0,1]</top><radius>0.1</radius></cylinder></geom_object>
 <geom_object><intersection><box label="all"/><box><min>[0.5,0,0]</min><max>[2,2,2]</max></box></intersection>
 </geom_object>
</m>"""


def test_pieces_and_labels():
    root = ProblemSpec.from_string(DECK)
    g = GeometryReader()
    hollow, ball, cyl, half = [g.read_object(o) for o in root.children("geom_object")]
    pts = np.array([[0.5, 0.5, 0.5], [0.1, 0.1, 0.1], [0.05, 0.0, 0.5], [0.7, 0.2, 0.2], [2, 2, 2.]])
    assert hollow.inside(pts).tolist() == [False, True, True, True, False]
    assert ball.inside(pts).tolist() == [True, False, False, False, False]
    assert cyl.inside(pts).tolist() == [False, False, True, False, False]
    assert half.inside(pts).tolist() == [True, False, False, True, False]


def test_unknown_label_is_an_error():
    root = ProblemSpec.from_string("<m><geom_object><box label='nope'/></geom_object></m>")
    with pytest.raises(InputError, match="no earlier piece"):
        GeometryReader().read_object(root.child("geom_object"))


def test_cell_fractions_sphere_volume():
    """Sampled volume of a sphere of radius 0.3 approaches 4/3 pi r^3 (exact)."""
    lv = Level((0, 0, 0), (1, 1, 1), (20, 20, 20))
    root = ProblemSpec.from_string("<g><sphere><origin>[0.5,0.5,0.5]</origin><radius>0.3</radius></sphere></g>")
    f = cell_fractions(GeometryReader().read_object(root), lv, ((0, 0, 0), (20, 20, 20)), (4, 4, 4))
    vol = f.sum() * np.prod(lv.dx)
    assert abs(vol - 4 / 3 * np.pi * 0.3 ** 3) < 0.01 * vol
