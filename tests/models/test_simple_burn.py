"""Simple_Burn (components/models): a hot explosive slab burns into its product gas (1D).

tests/models/burn1d.ups: 8 particles in cells 18-21 of 40, 600 K > ThresholdTemp, in
product gas between closed ends; 160 steps. The particles lose the burned mass as Uintah's do
(MPMICE's massBurnFraction: |modelMass_src| / cMass averaged over the cells around each node,
interpolated to the particles). Measured: total mass (particles + gas) 0.11283167663233 kg
constant to 1.3e-15 relative at every output while 76 % of the solid burns; every particle
keeps some mass (none deleted), the outer ones 0.0141 -> 0.0019 kg; gas in the slab's cells
5.9e-13 -> 530 kg/m^3; pressure 1 atm -> 3.6e8 Pa.
"""
import os

import numpy as np
import pytest

HERE = os.path.dirname(__file__)
DECK = os.path.join(HERE, "burn1d.ups")
V = 0.025 ** 3


@pytest.fixture(scope="module")
def archive(tmp_path_factory):
    from framework.archiver import DataArchive
    from framework.controller import Controller
    c = Controller(DECK, quiet=True, filebase=str(tmp_path_factory.mktemp("burn") / "burn1d.uda"))
    c.run()
    return DataArchive(c.archiver.dir)


def _masses(a, i):
    solid = float(a.particles(0, i)["p.mass"].sum())
    rho, _ = a.read("rho_CC", 1, i)
    return solid, float(rho.sum() * V)


def test_total_mass_conserved_while_solid_burns(archive):
    s0, g0 = _masses(archive, 0)
    for i in range(1, len(archive.times)):
        s, g = _masses(archive, i)
        assert abs((s + g) - (s0 + g0)) < 1e-13 * (s0 + g0)
    assert s < 0.5 * s0 and g > 100 * g0


def test_particles_lose_the_burned_mass(archive):
    """Every particle burns (the outer ones most) and none burns out in 160 steps."""
    m0, m = archive.particles(0, 0)["p.mass"], archive.particles(0, -1)["p.mass"]
    assert len(m0) == len(m) == 8 and np.all(m < 0.9 * m0) and np.all(m > 0)
    assert m[0] < 0.2 * m0[0] and m[3] > 0.4 * m0[3]
    assert np.all(np.isfinite(archive.particles(0, -1)["p.x"]))


def test_gas_appears_where_there_was_none(archive):
    rho0 = archive.read("rho_CC", 1, 0)[0].ravel()
    rho = archive.read("rho_CC", 1, -1)[0].ravel()
    inside = slice(19, 21)           # cells 19, 20: no gas at the start
    assert rho0[inside].max() < 1e-9
    assert rho[inside].min() > 100.0


def test_pressurizes(archive):
    p0 = archive.read("press_CC", 0, 0)[0]
    p = archive.read("press_CC", 0, -1)[0]
    assert np.allclose(p0, 101325.0) and p.max() > 1e8 and np.all(np.isfinite(p))


def test_node_burn_fraction_and_particle_share():
    """kernels.mass_burn_fraction: a node's fraction is the mean |m_src| / cMass of the cells
    around it, a cell beyond a symmetry plane its mirror, beyond another face nothing (Uintah's
    massBurnFraction); burn_particles scales mass, volume and size by 1 - f and deletes a
    particle left with no more than the minimum mass."""
    from components.models import kernels as K
    ms = np.zeros((4, 1, 1))
    cm = np.full((4, 1, 1), 2.0)
    ms[0, 0, 0], ms[3, 0, 0] = -1.0, -2.0          # cells 0 (next to x-) and 3 (next to x+) burn
    dims, lo_cell = np.array([1, 0, 0]), np.array([0, 0, 0])
    for sym_lo, want0 in ((True, 0.5), (False, 0.25)):
        out = np.zeros((5, 1, 1))
        K.mass_burn_fraction(ms, cm, np.zeros(3, np.int64), np.zeros(3, np.int64), dims, lo_cell,
                             np.array([0, 0, 0]), np.array([4, 0, 0]), np.array([sym_lo, False, False]),
                             np.zeros(3, np.bool_), out)
        assert np.allclose(out.ravel(), [want0, 0.25, 0.0, 0.5, 0.5])
    frac = np.array([0.0, 0.25, 1.0, 1.5])
    m, vol, size, x = np.ones(4), np.full(4, 1e-3), np.full((4, 3), 0.5), np.zeros((4, 3))
    K.burn_particles(frac, 0.0, m, vol, size, x)
    assert np.allclose(m, [1, 0.75, 0, 0]) and np.allclose(vol, [1e-3, 0.75e-3, 0, 0])
    assert np.allclose(size[:2, 0], [0.5, 0.375]) and np.isnan(x[2:]).all() and np.isfinite(x[:2]).all()


def test_no_models_no_burn_tasks():
    with open(DECK) as f:
        text = f.read()
    start, end = text.index("<Models>"), text.index("</Models>") + len("</Models>")
    plain = (text[:start] + text[end:]).replace('<save label="totalMassBurned"/>', "")
    assert "Simple_Burn" not in _task_names(plain)
    names = _task_names(text).split()
    for t in ("computeModelSources", "addPressureSource", "addLagrangianSources", "burnParticles"):
        assert "Simple_Burn::" + t in names, t


def _task_names(text):
    import tempfile

    from framework.controller import Controller
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "deck.ups")
        with open(path, "w") as f:
            f.write(text)
        c = Controller(path, quiet=True, filebase=os.path.join(d, "x.uda"))
        return " ".join(t.name for t in c.step_graph.tasks)


def test_bad_material_is_an_input_error(tmp_path):
    from framework.controller import Controller
    from framework.problemspec import InputError
    with open(DECK) as f:
        text = f.read().replace("<toMaterial> product </toMaterial>", "<toMaterial> gas </toMaterial>")
    path = tmp_path / "bad.ups"
    path.write_text(text)
    with pytest.raises(InputError, match="toMaterial"):
        Controller(str(path), quiet=True, filebase=str(tmp_path / "bad.uda")).run()


def test_total_mass_burned_reduction(archive):
    """totalMassBurned (saved at the output steps) is the mass the gas gained in that step."""
    t, burned = archive.reduction("totalMassBurned")
    assert burned.max() > 0 and np.all(burned >= 0)


def test_first_step_follows_the_burn_law(tmp_path):
    """Step 1 at p = refPressure: burned = dt K A (p / p_ref)^0.778 on each of the slab's two
    faces, A = dy dz = 0.025^2 m^2, K = 300 kg/(m^2 s), dt = delt_init = 1e-7 s."""
    from framework.archiver import DataArchive
    from framework.controller import Controller
    text = open(DECK).read().replace("<outputTimestepInterval> 20 </outputTimestepInterval>",
                                     "<outputTimestepInterval> 1 </outputTimestepInterval>")
    deck = tmp_path / "one.ups"
    deck.write_text(text)
    c = Controller(str(deck), quiet=True, filebase=str(tmp_path / "one.uda"), max_timesteps=1)
    c.run()
    t, burned = DataArchive(c.archiver.dir).reduction("totalMassBurned")
    assert abs(float(np.atleast_1d(burned)[0]) - 2 * 1e-7 * 300.0 * 0.025 ** 2) < 1e-12 * 3.75e-8


def test_delp_massx_saved_in_mpmice(tmp_path):
    """<save label="delP_MassX"/> in MPMICE: press_CC less p_eq and delP_Dilatate, i.e. the
    burn's pressure source (Uintah's diagnostic); nonzero only where the slab burns."""
    from framework.archiver import DataArchive
    from tests.conftest import run_deck
    with open(DECK) as f:
        text = f.read()
    text = text.replace("<max_Timesteps> 160 </max_Timesteps>", "<max_Timesteps> 4 </max_Timesteps>") \
        .replace("<outputTimestepInterval> 20 </outputTimestepInterval>", "<outputTimestepInterval> 4 </outputTimestepInterval>") \
        .replace('<save label="press_CC"/>', '<save label="press_CC"/><save label="delP_MassX"/>'
                 '<save label="press_equil_CC"/><save label="delP_Dilatate"/>')
    a = DataArchive(run_deck(text, tmp_path).archiver.dir)
    get = lambda lab: a.read(lab, 0, -1)[0].ravel()
    dpx = get("delP_MassX")
    np.testing.assert_allclose(dpx, get("press_CC") - get("press_equil_CC") - get("delP_Dilatate"),
                               rtol=0, atol=1e-9 * get("press_CC").max())
    assert dpx[[18, 21]].min() > 100.0 and np.abs(dpx[:17]).max() < 1e-6
