"""Uintah's <boundary_traction_faces> reductions (components/mpm/boundary_tractions.py):
BndyForce, BndyTraction and BndyContactArea of a face, and AccStrainEnergy.

tests/mpm/friction_var_traction.ups is Uintah's frictionVar deck (GIMP, XPIC2, friction_LRVar
contact, 2 x 2 patches) with its base piece pushed onto the z- face; sus's sums over its 4
steps are in tests/mpm/data/sus_friction_var_traction.txt. The contact area is Uintah's: the
sum over the 4 patches of each one's force / traction, so about 4 m^2 on the 1 m^2 face. The
single-patch decks (adiCuJC4000s696K, test_hypoviscoelastic_rad_ret) are compared with sus in
test_artificial_viscosity.py and test_hypoviscoelastic.py.
"""
import os

import numpy as np
import pytest

from framework.problemspec import InputError

from .helpers import run

HERE = os.path.dirname(__file__)
DECK = os.path.join(HERE, "friction_var_traction.ups")
SUS = np.loadtxt(os.path.join(HERE, "data", "sus_friction_var_traction.txt"))


def test_four_patches_equal_sus(tmp_path):
    """Every step's force, traction and contact area on z- to round-off of sus's (measured:
    5e-14; they are sums of the stress the step starts with), AccStrainEnergy to 1e-9 over
    steps 1-3 (comp_neo_hook's energy: 2.4e-10 at step 1; step 4's stress update differs from
    sus's by 5e-5 at the base's particles next to the x- y- z- corner, 2e-5 in the energy); the
    traction is close to the force over the 1 m^2 face, as it should be for a piece lying on it."""
    _, da = run(open(DECK).read(), tmp_path)
    t, force = da.reduction("BndyForce_zminus")
    _, traction = da.reduction("BndyTraction_zminus")
    _, area = da.reduction("BndyContactArea_zminus")
    te, acc = da.reduction("AccStrainEnergy")
    assert len(t) == len(SUS) == 4 and te[0] == 0.0 and acc[0] == 0.0      # AccStrainEnergy starts at 0
    scale = np.abs(SUS[:, 3]).max()
    assert scale > 1e4
    for i, (tk, *rest) in enumerate(SUS):
        f, tr, a, e = np.array(rest[0:3]), np.array(rest[3:6]), rest[6], rest[7]
        assert t[i] == pytest.approx(tk, rel=1e-14)
        assert np.abs(force[i] - f).max() < 1e-12 * scale
        assert np.abs(traction[i] - tr).max() < 1e-12 * scale
        assert area[i] == pytest.approx(a, rel=1e-13)
        assert acc[i + 1] == pytest.approx(e, rel=1e-9 if i < 3 else 1e-4)
    assert traction[1:, 2] == pytest.approx(force[1:, 2], rel=0.01)
    assert area == pytest.approx(4.0, rel=0.003)


def test_two_ranks_write_the_same_sums(tmp_path):
    """The patches' sums are combined in patch order: 1 and 2 MPI ranks write the same .dat
    files, byte for byte."""
    from tests.conftest import pysus_ranks
    for n in (1, 2):
        r = pysus_ranks(DECK, "--filebase", tmp_path / f"r{n}.uda", np_=n, timeout=300)
        assert r.returncode == 0, r.stderr[-2000:]
    for name in ("BndyForce_zminus", "BndyTraction_zminus", "BndyContactArea_zminus", "AccStrainEnergy"):
        one, two = ((tmp_path / f"r{n}.uda" / f"{name}.dat").read_text() for n in (1, 2))
        assert one == two and len(one.splitlines()) >= 4, name


def _controller(tmp_path, old, new):
    from framework.controller import Controller
    text = open(DECK).read()
    assert old in text
    (tmp_path / "d.ups").write_text(text.replace(old, new))
    return Controller(str(tmp_path / "d.ups"), quiet=True, filebase=str(tmp_path / "r.uda"))


def test_computed_only_when_saved(tmp_path):
    """Without their saves no task computes the sums, nor g.volume for them."""
    saves = ('<save label="BndyForce_zminus"/>\n        <save label="BndyTraction_zminus"/>\n'
             '        <save label="BndyContactArea_zminus"/>\n        <save label="AccStrainEnergy"/>\n')
    ctl = _controller(tmp_path, saves, "")
    names = {t.name for t in ctl.sched.tasks}
    assert "MPM::computeBoundaryTractions" not in names and "MPM::computeAccStrainEnergy" not in names
    assert not ctl.component.grid_volume
    ctl = _controller(tmp_path, "", "")
    names = {t.name for t in ctl.sched.tasks}
    assert {"MPM::computeContactArea", "MPM::computeBoundaryTractions", "MPM::computeAccStrainEnergy"} <= names


@pytest.mark.parametrize("new, words", [
    ("[zminus, bottom]", "unknown face 'bottom'; accepted: xminus, xplus, yminus, yplus, zminus, zplus"),
    ("zminus", "is not a list"),
])
def test_bad_faces_are_one_clean_line(tmp_path, new, words):
    with pytest.raises(InputError) as e:
        _controller(tmp_path, "<boundary_traction_faces>[zminus]", f"<boundary_traction_faces>{new}")
    assert words in str(e.value) and "\n" not in str(e.value)


def test_face_of_a_one_cell_direction_is_refused(tmp_path):
    with pytest.raises(InputError, match="one cell along z"):
        _controller(tmp_path, "<resolution>[10,10,6]</resolution>", "<resolution>[10,10,1]</resolution>")


def test_saved_face_not_listed_is_refused(tmp_path):
    with pytest.raises(InputError, match='<save label="Bndy.*_zminus"> names a variable this deck does not compute'):
        _controller(tmp_path, "<boundary_traction_faces>[zminus]", "<boundary_traction_faces>[zplus]")
