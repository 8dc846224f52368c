"""Bad EFEM input is refused with one line naming the file, line, tag and what is accepted."""
import pytest

from framework.problemspec import InputError
from tests.conftest import run_deck

from .decks import deck
from .test_conservation import BLOCK


def _fails(tmp_path, text, *words):
    with pytest.raises(InputError) as e:
        run_deck(text, tmp_path)
    msg = str(e.value)
    assert "run.ups:" in msg, msg
    for w in words:
        assert w in msg, msg


def test_solid_and_fluid_law_together(tmp_path):
    text = deck(block=BLOCK).replace("<poissons_ratio> 0.3 </poissons_ratio>",
                                     "<poissons_ratio> 0.3 </poissons_ratio><dynamic_viscosity>1</dynamic_viscosity>")
    _fails(tmp_path, text, "not both")


def test_material_without_law(tmp_path):
    _fails(tmp_path, deck().replace("<dynamic_viscosity> 0.001 </dynamic_viscosity>", ""),
           "youngs_modulus", "dynamic_viscosity")


def test_poisson_ratio_one_half(tmp_path):
    _fails(tmp_path, deck(block=dict(BLOCK, nu=0.5)), "poissons_ratio", "< 0.5")


def test_negative_density(tmp_path):
    _fails(tmp_path, deck().replace("<density> 1000 </density>", "<density> -1 </density>"), "density")


def test_unknown_face_type(tmp_path):
    _fails(tmp_path, deck(walls={"x-": "sticky"}), "sticky", "wall", "slip")


def test_unknown_tag(tmp_path):
    _fails(tmp_path, deck(settings="<cfll>0.2</cfll>"), "cfll", "<cfl>")


def test_three_dimensional_grid(tmp_path):
    _fails(tmp_path, deck().replace("[20, 20, 1]", "[20, 20, 2]"), "two-dimensional")


def test_no_extra_cells(tmp_path):
    _fails(tmp_path, deck().replace("<extraCells> [1, 1, 1]", "<extraCells> [0, 0, 0]"), "extraCells", "[1, 1, 1]")


def test_geometry_outside_domain(tmp_path):
    _fails(tmp_path, deck(block=dict(BLOCK, lo=(2, 2), hi=(3, 3))), "outside the domain")


def test_unknown_limiter(tmp_path):
    _fails(tmp_path, deck(settings="<volume_fraction_limiter> minmod </volume_fraction_limiter>"),
           "volume_fraction_limiter", "superbee")


def test_unknown_stress_remap(tmp_path):
    _fails(tmp_path, deck(settings="<stress_remap> weno </stress_remap>"), "stress_remap", "muscl")
