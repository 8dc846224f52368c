"""Sub-face grid boundary conditions of MPM (Uintah's <Face circle|rectangle> on the nodes).

Each node of a face (and the extra nodes beyond it) takes the sub-face's velocity when the
face node's position is inside the shape (Uintah's BCGeomBase: nodes by their position), and
the side's otherwise; a sub-face that does not name a material leaves that material the side's.
"""
import numpy as np
import pytest

from components.mpm.bc import GridBCs
from framework.gridspec import level_from_spec
from framework.problemspec import InputError, ProblemSpec
from framework.variables import VarType

GRID = """<Uintah_specification><Grid>
  <BoundaryConditions>
    <Face side="x-"><BCType id="all" var="Dirichlet" label="Velocity"><value>[0,0,0]</value></BCType></Face>
    <Face circle="x-" origin="0 0.5 0.5" radius="0.25">
      <BCType id="0" var="Dirichlet" label="Velocity"><value>[7,0,0]</value></BCType></Face>
    <Face side="y+"><BCType id="all" var="Dirichlet" label="Velocity"><value>[0,0,0]</value></BCType></Face>
    <Face rectangle="y+" lower="0.5 1 0" upper="1 1 1">
      <BCType id="all" var="Neumann" label="Velocity"><value>[0,0,0]</value></BCType></Face>
    {extra}
  </BoundaryConditions>
  <Level><Box><lower>[0,0,0]</lower><upper>[1,1,1]</upper><resolution>[4,4,4]</resolution>
    <extraCells>[1,1,1]</extraCells><patches>[2,2,1]</patches></Box></Level>
</Grid></Uintah_specification>"""


def _apply(matl, extra=""):
    """g.velocity_star of every patch after the conditions (1 everywhere before), by global node."""
    root = ProblemSpec.from_string(GRID.replace("{extra}", extra))
    level = level_from_spec(root)
    bcs = GridBCs(root, level, 2)
    out = {}
    for patch in level.patches:
        shape = patch.alloc_shape(VarType.NC) + (3,)
        gvs, gacc, gvel = np.ones(shape), np.zeros(shape), np.ones(shape)
        bcs.apply(patch, matl, gvs, gacc, gvel, 1.0)
        lo, hi = patch.owned(VarType.NC)
        base = patch.low_index(VarType.NC)
        for i in range(lo[0], hi[0]):
            for j in range(lo[1], hi[1]):
                for k in range(lo[2], hi[2]):
                    out[(i, j, k)] = gvs[i - base[0], j - base[1], k - base[2]]
    return out


def test_circle_nodes_of_x_minus():
    """Nodes at (y, z) = 0.25 j, 0.25 k: inside the circle of radius 0.25 about (0.5, 0.5) are
    (2, 2), (1, 2), (3, 2), (2, 1), (2, 3); they take [7, 0, 0] for material 0 (face nodes i = 0
    and the extra nodes i = -1), the other x- nodes 0; material 1, not named there, 0 on all."""
    for matl in (0, 1):
        v = _apply(matl)
        for (i, j, k), u in v.items():
            if i > 0 or not (0 <= j <= 4 and 0 <= k <= 4) or j == 5:
                continue
            inside = (0.25 * j - 0.5) ** 2 + (0.25 * k - 0.5) ** 2 <= 0.25 ** 2 + 1e-12
            want = [7.0, 0.0, 0.0] if inside and matl == 0 else [0.0, 0.0, 0.0]
            assert list(u) == want, (matl, i, j, k)
    assert sum(1 for (i, j, k), u in _apply(0).items() if i == 0 and u[0] == 7.0) == 5


def test_rectangle_leaves_its_nodes_free():
    """y+ nodes with 0.5 <= x <= 1 are free (Neumann): they keep their velocity 1; the rest 0."""
    v = _apply(0)
    for (i, j, k), u in v.items():
        if j == 4 and 0 < i < 4 and 0 < k < 4:
            assert list(u) == ([1.0, 1.0, 1.0] if 0.25 * i >= 0.5 else [0.0, 0.0, 0.0]), (i, k)


@pytest.mark.parametrize("extra, message", [
    ('<Face circle="x-" origin="0.1 0.5 0.5" radius="0.2"><BCType id="0" var="Dirichlet" label="Velocity">'
     '<value>[1,0,0]</value></BCType></Face>', "is not on face x-"),
    ('<Face circle="x+" origin="1 0.5 0.5" radius="0.2"><BCType id="all" var="symmetry" label="Symmetric"/>'
     '</Face>', "on a sub-face is not supported"),
])
def test_bad_sub_faces(extra, message):
    with pytest.raises(InputError, match=message):
        _apply(0, extra)
