"""Uintah's ONR-MURI/halfSpaceUCNH_EP_JWLMPM.ups (uintah_reference/) against sus: a UCNH soil
with drawn yield stresses and Threshold gauss failure strains, a jwlpp_mpm charge, pressure
stabilization, 16 patches, GIMP; its y+ face carries ICE's Pressure and Density conditions
(read, not applied, as Uintah's MPM) and a Neumann temperature condition.

Reference: sus on the deck with an output every step (tests/mpm/data/sus_halfSpaceUCNH_EP_JWLMPM.npz,
read from its uda with framework.uintah_uda.UintahArchive): the soil's p.epsf and p.yieldStress of
every 5th particle after step 2; after steps 2, 4 and 6 the soil's particle count, the position and
p.stress of every 40th soil particle, and p.x, p.stress, p.progressF of every charge particle, and
the number of localized soil particles.
"""
import pathlib

import numpy as np

from components.mpm.bc import GridBCs
from framework.gridspec import level_from_spec
from framework.problemspec import ProblemSpec
from framework.variables import VarType

from .helpers import run

HERE = pathlib.Path(__file__).parent
DECK = HERE / "uintah_reference" / "halfSpaceUCNH_EP_JWLMPM.ups"


def _match(x, rx, chunk=256):
    """The index into x of the particle nearest each reference position (each taken once)."""
    k = np.concatenate([np.argmin(((rx[i:i + chunk, None, :] - x[None, :, :]) ** 2).sum(axis=2), axis=1)
                        for i in range(0, len(rx), chunk)])
    assert len(set(k)) == len(k)
    return k


def test_half_space_as_sus(tmp_path, capsys):
    """The deck with Uintah's update (<stress_update>usl) its only edit, 6 steps written every 2:
    sus's 10390 soil particles (two layers across the one z cell) and 104 charge particles (four),
    sus's times; the drawn p.epsf and p.yieldStress bitwise; the soil's p.stress within 1e-13 of
    the largest (measured 1.3e-14), the charge's p.stress and p.progressF 1e-13 (3.7e-15, 1e-16),
    p.x 1e-15 m (1.6e-17); the same localized particles (0, 0, 2). The Pressure and Density
    conditions get a note each."""
    text = DECK.read_text()
    a = "<time_integrator> explicit </time_integrator>"
    assert a in text
    _, da = run(text.replace(a, a + "<stress_update>usl</stress_update>"), tmp_path)
    err = capsys.readouterr().err
    for label in ("Pressure", "Density"):
        assert f'<BCType label="{label}"> is read and not applied' in err
    sus = np.load(HERE / "data" / "sus_halfSpaceUCNH_EP_JWLMPM.npz")
    assert list(da.timesteps) == [0, 2, 4, 6]
    assert np.allclose(da.times[1:], sus["time"][1::2], rtol=1e-13, atol=0)
    p = da.particles(0, 1)
    k = _match(p["p.x"], sus["soil_x_draws"])
    assert np.abs(p["p.x"][k] - sus["soil_x_draws"]).max() < 1e-15
    assert np.array_equal(p["p.epsf"][k], sus["epsf"])
    assert np.array_equal(p["p.yieldStress"][k], sus["yieldStress"])
    for i, step in enumerate(sus["steps"], start=1):
        p, c = da.particles(0, i), da.particles(1, i)
        assert len(p["p.x"]) == sus[f"n_soil_{step}"] == 10390 and len(c["p.x"]) == 104
        k = _match(p["p.x"], sus[f"soil_x_{step}"])
        assert np.abs(p["p.x"][k] - sus[f"soil_x_{step}"]).max() < 1e-15
        rs = sus[f"soil_stress_{step}"]
        assert np.abs(p["p.stress"][k] - rs).max() <= 1e-13 * np.abs(rs).max()
        assert p["p.localizedMPM"].sum() == sus[f"localized_{step}"]
        k = _match(c["p.x"], sus[f"charge_x_{step}"])
        assert np.abs(c["p.x"][k] - sus[f"charge_x_{step}"]).max() < 1e-15
        assert np.abs(c["p.progressF"][k] - sus[f"progressF_{step}"]).max() < 1e-13
        rs = sus[f"charge_stress_{step}"]
        assert np.abs(c["p.stress"][k] - rs).max() <= 1e-13 * np.abs(rs).max()
    assert [int(sus[f"localized_{s}"]) for s in sus["steps"]] == [0, 0, 2]
    assert sus["progressF_2"].min() > 0.99


def test_neumann_temperature_condition():
    """A Neumann temperature condition sets each node of the face and beyond to its inward
    neighbour's temperature less g dx (the extra node beyond takes the face node's, set);
    Dirichlet sets the value; a Pressure condition is read and changes nothing."""
    root = ProblemSpec.from_string("""<Uintah_specification><Grid><BoundaryConditions>
      <Face side="x-"><BCType id="all" var="Neumann" label="Temperature"><value>10.0</value></BCType></Face>
      <Face side="x+"><BCType id="all" var="Neumann" label="Temperature"><value>10.0</value></BCType></Face>
      <Face side="y+"><BCType id="0" var="Dirichlet" label="Temperature"><value>7.0</value></BCType>
        <BCType id="0" var="Neumann" label="Pressure"><value>0.0</value></BCType></Face>
      </BoundaryConditions>
      <Level><Box><lower>[0,0,0]</lower><upper>[1,1,1]</upper><resolution>[4,4,4]</resolution>
        <extraCells>[1,1,1]</extraCells><patches>[1,1,1]</patches></Box></Level>
    </Grid></Uintah_specification>""")
    level = level_from_spec(root)
    bcs = GridBCs(root, level, 1)
    patch = level.patches[0]
    shape = patch.alloc_shape(VarType.NC)
    T0 = np.arange(np.prod(shape), dtype=float).reshape(shape)
    T = T0.copy()
    bcs.apply_temperature(patch, 0, T)
    base = patch.low_index(VarType.NC)
    lo, hi = level.interior_box(VarType.NC)
    i0, i1, j1 = lo[0] - base[0], hi[0] - 1 - base[0], hi[1] - 1 - base[1]
    drop = 10.0 * level.dx[0]
    rows = slice(0, j1)                                          # away from the y+ face
    assert np.array_equal(T[i0, rows], T0[i0 + 1, rows] - drop)
    assert np.array_equal(T[i0 - 1, rows], T[i0, rows] - drop)
    assert np.array_equal(T[i1, rows], T0[i1 - 1, rows] - drop)
    assert np.array_equal(T[i1 + 1, rows], T[i1, rows] - drop)
    assert np.all(T[i0 + 1:i1, j1:] == 7.0)
    assert np.array_equal(T[i0 + 1:i1, :j1], T0[i0 + 1:i1, :j1])
