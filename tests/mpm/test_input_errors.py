"""Bad MPM input is refused with the tag, line and what is accepted."""
import pytest

from framework.problemspec import InputError
from tests.conftest import UINTAH_INPUTS

from .helpers import MPM_INPUTS, deck_text, run

SULSKY = UINTAH_INPUTS / "MPM" / "disks_sulsky.ups"


def _fails(tmp_path, text, *words):
    with pytest.raises(InputError) as e:
        run(text, tmp_path)
    msg = str(e.value)
    for w in words:
        assert w in msg, msg


def test_unknown_constitutive_model(tmp_path):
    text = open(SULSKY).read().replace('type="comp_neo_hook"', 'type="soil_foam"')
    _fails(tmp_path, text, "soil_foam", "accepted", "comp_neo_hook", ".ups:")


def test_unknown_contact(tmp_path):
    text = open(SULSKY).read().replace("<type>null</type>", "<type>penalty</type>")
    _fails(tmp_path, text, "penalty", "single_velocity")


def test_unknown_mpm_tag(tmp_path):
    text = open(SULSKY).read().replace("<interpolator>linear</interpolator>",
                                       "<interpolator>linear</interpolator><XPIC3>true</XPIC3>")
    _fails(tmp_path, text, "XPIC3")


def test_bad_interpolator(tmp_path):
    _fails(tmp_path, deck_text(SULSKY, interpolator="cpti"), "cpti", "cpdi", "preprocessing")


def test_gimp_needs_extra_cells(tmp_path):
    _fails(tmp_path, deck_text(SULSKY, interpolator="gimp"), "extraCells")


def test_unknown_model_parameter(tmp_path):
    text = open(SULSKY).read().replace("<shear_modulus>384.6</shear_modulus>",
                                       "<shear_modulus>384.6</shear_modulus><youngs>1</youngs>")
    _fails(tmp_path, text, "youngs")


CYLINDER = MPM_INPUTS / "thick_cylinder.ups"


def test_pressure_needs_load_curves(tmp_path):
    _fails(tmp_path, deck_text(CYLINDER, use_load_curves="false"), "use_load_curves", "<pressure>")


def test_pressure_surface_must_be_box_or_cylinder(tmp_path):
    text = open(CYLINDER).read().replace(
        '<cylinder label="inner surface"><bottom>[0,0,0]</bottom><top>[0,0,0.01]</top><radius>0.5</radius></cylinder>',
        "<sphere><origin>[0,0,0]</origin><radius>0.5</radius></sphere>")
    _fails(tmp_path, text, "<box>", "<cylinder>")


def test_friction_needs_mu(tmp_path):
    text = open(MPM_INPUTS / "friction_block.ups").read().replace("<mu>0.3</mu>", "")
    _fails(tmp_path, text, "<mu>")


def test_rigid_master_material_exists(tmp_path):
    text = open(MPM_INPUTS / "rigid_piston.ups").read().replace(
        "<type>rigid</type>", "<type>rigid</type><master_material>5</master_material>")
    _fails(tmp_path, text, "material 5")


def test_heat_conduction_with_axisymmetric(tmp_path):
    """cpdi conducts heat (tests/mpm/test_cpdi_heat.py); an axisymmetric deck does not."""
    text = open(MPM_INPUTS / "thick_cylinder_axi.ups").read().replace(
        "<axisymmetric>true</axisymmetric>",
        "<axisymmetric>true</axisymmetric><DoExplicitHeatConduction>true</DoExplicitHeatConduction>", 1).replace(
        "<density>8900</density>", "<density>8900</density><thermal_conductivity>50</thermal_conductivity>"
        "<specific_heat>450</specific_heat>")
    _fails(tmp_path, text, "axisymmetric", "heat conduction", "accepted")


def test_cut_cell_particles_alone(tmp_path):
    """<cut_cell_particles> lays the lattice's particles itself: not with Uintah's finer filling."""
    text = open(SULSKY).read().replace("<res>", "<cut_cell_particles> true </cut_cell_particles>"
                                       "<numLevelsParticleFilling> 2 </numLevelsParticleFilling><res>", 1)
    _fails(tmp_path, text, "cut_cell_particles", "numLevelsParticleFilling", ".ups:")
