"""Sub-face boundary conditions (Uintah's <Face circle|rectangle|annulus>) on ICE.

Which boundary cells a sub-face takes is checked against the shapes' definitions
(framework.gridspec.SubFace: the centre of the cell's face on the domain boundary inside
the shape); the flow they drive against Uintah's sus on uintah_reference/subFaces.ups.
The sus values in data/sus_subFaces.npz are sus's output on that deck (one rank, without
the pysus-only attribute dissipationHeating="false"): the time after each step
(timestep.xml), TotalMass.dat, and press_CC, temp_CC, rho_CC, vel_CC over the interior
cells after steps 1 and 10 (read with framework.uintah_uda).
"""
import pathlib

import numpy as np
import pytest

from components.ice.bc import BoundaryConditions, read_bcs
from components.ice.tasks import Boxes
from framework.gridspec import level_from_spec
from framework.problemspec import InputError, ProblemSpec
from framework.variables import VarType

REF = pathlib.Path(__file__).parent / "uintah_reference"
DATA = pathlib.Path(__file__).parent / "data"
DECK = REF / "subFaces.ups"


def _bcs(text=None, patches=None):
    """The deck's level (its patches, or `patches`) and its ICE boundary conditions."""
    text = text if text is not None else DECK.read_text()
    if patches is not None:
        text = text.replace("<patches>      [2,2,1]", f"<patches>      {patches}")
    root = ProblemSpec.from_string(text, "subFaces.ups")
    level = level_from_spec(root)
    return level, BoundaryConditions(read_bcs(root, level, 1, ["air"]), level)


def _expected(level, face):
    """The analytic parts of a face's boundary cells (CC array of a one-patch level, extra
    cells included): 1 inside the sub-face, 0 elsewhere; centres at (i + 0.5) dx (cell -1 and
    N are the tangential extra cells)."""
    x = (np.arange(-1, 21) + 0.5) * 0.05         # cell centres along x and y (20 cells of 0.05)
    if face == "x-":                              # circle of radius 0.2 about y = 0.5, z = 0.05
        inside = np.abs(x - 0.5) <= 0.2
    elif face == "x+":                            # rectangle 0.6 <= y <= 1.0
        inside = (x >= 0.6) & (x <= 1.0)
    else:                                         # annulus 0.1 < |x - 0.5| <= 0.3 on y+
        inside = (np.abs(x - 0.5) > 0.1) & (np.abs(x - 0.5) <= 0.3)
    return inside.astype(np.int64)


@pytest.mark.parametrize("face", ["x-", "x+", "y+"])
def test_cells_of_each_sub_face(face):
    """Each boundary cell of the face takes the sub-face's conditions exactly when its
    boundary face's centre is inside the shape: the circle holds y-cells 6..13, the rectangle
    12..19, the annulus x-cells 4..7 and 12..15 (the tangential extra cells none)."""
    level, bcs = _bcs(patches="[1,1,1]")
    patch = level.patches[0]
    sel = bcs.face_parts(patch, face)
    got = sel[:, 0] if face != "y+" else sel[0, :]      # (d+1, d+2): x- (y, z), y+ (z, x)
    assert sel.shape == ((22, 1) if face != "y+" else (1, 22))
    assert np.array_equal(got, _expected(level, face))
    want = {"x-": range(6, 14), "x+": range(12, 20), "y+": list(range(4, 8)) + list(range(12, 16))}[face]
    assert list(np.flatnonzero(got) - 1) == list(want)
    assert bcs.face_parts(patch, "y-") is None            # a face without sub-faces


def test_sub_face_conditions_in_the_extra_cells():
    """The conditions land where the parts say: x- inlet cells hold 400 K and [50, 0, 0],
    the rest of x- copies the interior temperature and reflects to a zero wall velocity; the
    y+ annulus cells hold -20 m/s, the others 0; on four patches as on one."""
    for patches in ("[1,1,1]", "[2,2,1]"):
        level, bcs = _bcs(patches=patches)
        for patch in level.patches:
            b = Boxes(patch, np.array([True, True, False]))
            shape = patch.alloc_shape(VarType.CC)
            temp = np.full(shape, 300.0)
            vel = np.ones(shape + (3,))
            bcs.scalar(patch, temp, "Temperature", 0, b)
            bcs.velocity(patch, vel, 0, b)
            low = np.array(patch.low_index(VarType.CC))
            x = (np.arange(shape[0]) + low[0] + 0.5) * 0.05
            y = (np.arange(shape[1]) + low[1] + 0.5) * 0.05
            if patch.at_low[0]:
                inlet = np.abs(y - 0.5) <= 0.2
                assert inlet.any() or patch.lo[1] >= 10
                assert np.all(temp[0, inlet, 0] == 400.0) and np.all(temp[0, ~inlet, 0] == 300.0)
                assert np.all(vel[0, inlet, 0] == [50.0, 0.0, 0.0])
                assert np.all(vel[0, ~inlet, 0] == 0.0)
            if patch.at_high[1]:
                ring = (np.abs(x - 0.5) > 0.1) & (np.abs(x - 0.5) <= 0.3)
                assert ring.any()
                assert np.all(vel[ring, -1, 0] == [0.0, -20.0, 0.0])
                assert np.all(vel[~ring, -1, 0] == 0.0)
                assert np.all(temp[ring, -1, 0] == 350.0) and np.all(temp[~ring, -1, 0] == 300.0)


def test_sub_faces_as_uintah(run_deck):
    """The inlets and the outlet drive the flow: 10 steps equal sus's to round-off (measured:
    delT to 1e-16, press_CC 6e-16, temp_CC 1.4e-15, vel_CC 3e-15 of their maxima)."""
    sus = np.load(DATA / "sus_subFaces.npz")
    da = run_deck(str(DECK))
    assert np.allclose(da.times[1:], sus["times"], rtol=1e-13, atol=0)
    assert np.allclose(da.reduction("TotalMass")[1], sus["TotalMass"], rtol=1e-13, atol=0)
    assert np.allclose(da.read("temp_CC", 0, 1)[0][:, :, 0], sus["temp_CC_step1"], rtol=1e-13, atol=0)
    for label in ("press_CC", "temp_CC", "rho_CC", "vel_CC"):
        got, want = da.read(label, 0, -1)[0][:, :, 0], sus[f"{label}_step10"]
        assert np.allclose(got, want, rtol=0, atol=1e-13 * np.abs(want).max()), label
    assert sus["temp_CC_step10"][0, 6:14].min() > 330.0 > sus["temp_CC_step10"][0, 15:].max()   # the inlet's heat


@pytest.mark.parametrize("old, new, message", [
    ('origin="0.0 0.5 0.05" radius="0.2"', 'origin="0.1 0.5 0.05" radius="0.2"', "is not on face x-"),
    ('radius="0.2"', 'radius="-0.2"', "radius"),
    ('inner_radius="0.1" outer_radius="0.3"', 'inner_radius="0.3" outer_radius="0.1"', "smaller than inner_radius"),
    ('lower="1.0 0.6 0.0" upper="1.0 1.0 0.1"', 'lower="1.0 1.0 0.0" upper="1.0 0.6 0.1"', "must not exceed"),
    ('<Face circle="x-"', '<Face ellipse="x-"', 'ellipse="..."> is not supported'),
    ('<BCType id="0" label="Velocity" var="Dirichlet"><value> [50.,0.,0.] </value></BCType>', '',
     "no boundary condition for Velocity of material 0"),
])
def test_bad_sub_faces_are_refused(old, new, message):
    text = DECK.read_text()
    assert old in text
    with pytest.raises(InputError, match=message):
        _bcs(text.replace(old, new, 1))
