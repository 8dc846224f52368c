"""Uintah's PassiveScalar model (components/models/passive_scalar.py) on ICE, against Uintah's sus.

The sus values are small extracts of sus's output on the same decks (one rank), in
data/sus_advectScalar*.npz: the time after each step (timestep.xml), the .dat files of
totalSum_scalar-f and totalSum_scalar-q, and scalar-f / scalar-q over the interior cells
(read with framework.uintah_uda). The decks are uintah_reference/advectScalar_explicit.ups
(Uintah's advectScalar.ups made explicit) and advectScalar_variant.ups (the options the
original leaves out); sus ran them without the pysus-only advection attributes
(limiter="BarthJespersen" dissipationHeating="false" select Uintah's scheme in pysus).
"""
import pathlib

import numpy as np
import pytest

from framework.problemspec import InputError

REF = pathlib.Path(__file__).parent / "uintah_reference"
DATA = pathlib.Path(__file__).parent / "data"


def _reduction(da, name):
    return da.reduction(name)[1]


def test_advect_scalar_as_uintah(run_deck):
    """Two scalars in a uniform 10 m/s flow: a box of 1, two spheres that hold 2 (interior
    sources with maxScalar), zero-gradient faces with inflow. 5 steps equal sus's to round-off."""
    sus = np.load(DATA / "sus_advectScalar.npz")
    da = run_deck(str(REF / "advectScalar_explicit.ups"))
    assert np.allclose(da.times[1:], sus["times"], rtol=1e-13, atol=0)
    assert np.allclose(_reduction(da, "totalSum_scalar-f"), sus["totalSum_f"], rtol=1e-13, atol=0)
    assert np.allclose(_reduction(da, "totalSum_scalar-q"), sus["totalSum_q"], rtol=1e-13, atol=0)
    for step, total in enumerate(sus["f_sum"], start=1):
        assert da.read("scalar-f", 0, step)[0].sum() == pytest.approx(total, rel=1e-13)
    f = da.read("scalar-f", 0, -1)[0][:, :, 0]
    assert np.allclose(np.diagonal(f), sus["f_diagonal"], rtol=0, atol=1e-14)
    assert np.allclose(np.diagonal(f[:, ::-1]), sus["f_antidiagonal"], rtol=0, atol=1e-14)
    assert np.array_equal(da.read("scalar-q", 0, -1)[0], da.read("scalar-f", 0, -1)[0])   # the same model twice


def test_advect_scalar_variant_as_uintah(run_deck):
    """Diffusion, linear and exponential decay, linearInitialize and sinusoidalInitialize, a
    Dirichlet face and a Neumann face with a non-zero gradient (Uintah's sign: extra cell =
    interior - value dx), in the flow of an expanding hot box, whose expansion reaches the open
    faces from step 3: 10 steps equal sus's to round-off (measured 3e-15 in f and q, 3e-16 in
    the sums; before the open faces' extra cells took this step's velocity after the exchange,
    as Uintah's, 4e-12 and 4e-9)."""
    sus = np.load(DATA / "sus_advectScalar_variant.npz")
    da = run_deck(str(REF / "advectScalar_variant.ups"))
    assert np.allclose(da.times[1:], sus["times"], rtol=1e-13, atol=0)
    assert np.allclose(da.read("scalar-f", 0, 2)[0][:, :, 0], sus["f_step2"], rtol=0, atol=1e-14)
    assert np.allclose(da.read("scalar-f", 0, -1)[0][:, :, 0], sus["f_step10"], rtol=0, atol=1e-13)
    assert np.allclose(da.read("scalar-q", 0, -1)[0][:, :, 0], sus["q_step10"], rtol=0, atol=1e-13)
    assert np.allclose(_reduction(da, "totalSum_scalar-f"), sus["totalSum_f"], rtol=1e-13, atol=0)
    assert np.allclose(_reduction(da, "totalSum_scalar-q"), sus["totalSum_q"], rtol=1e-13, atol=0)
    assert da.read("scalar-q", 0, -1)[0].min() >= 0.0          # the source keeps f + src >= 0


def test_advect_scalar_default_advection(run_deck):
    """pysus's default advection (van Leer, dissipation heating): the scalar stays within [0, 2]
    and the sources fill the spheres (sus's sum after step 1)."""
    text = open(REF / "advectScalar_explicit.ups", encoding="iso-8859-1").read()
    text = _edit(text, ' limiter="BarthJespersen" dissipationHeating="false"', "")
    da = run_deck(text=text)
    f = da.read("scalar-f", 0, -1)[0]
    assert f.min() >= 0.0 and f.max() == pytest.approx(2.0, rel=1e-14)
    assert da.read("scalar-f", 0, 1)[0].sum() == pytest.approx(720.0, rel=1e-14)


def _edit(text, old, new):
    assert old in text
    return text.replace(old, new, 1)


@pytest.mark.parametrize("old, new, message", [
    ('<BCType id = "0"   label = "scalar-f"     var = "Neumann">\n                              <value> 0.0</value>\n'
     '        </BCType>', "", "no boundary condition for scalar-f"),
    ('<Model type="PassiveScalar">', '<Model type="Passive">', "PassiveScalar"),
    ("<material>BackgroundGas</material>", "<material>air</material>", "'air' is not a material"),
    ('<BCType id = "0"   label = "scalar-f"     var = "Neumann">',
     '<BCType id = "0"   label = "scalar-f"     var = "computeFromDensity">', "scalar-f accepts"),
])
def test_bad_input_one_line(run_deck, old, new, message):
    text = open(REF / "advectScalar_explicit.ups", encoding="iso-8859-1").read()
    with pytest.raises(InputError, match=message) as e:
        run_deck(text=_edit(text, old, new))
    assert "\n" not in str(e.value)


def test_scalar_label_without_model(run_deck):
    import re
    text = open(REF / "advectScalar_explicit.ups", encoding="iso-8859-1").read()
    text = re.sub(r"<Models>.*</Models>", "", text, flags=re.S)
    with pytest.raises(InputError, match='needs a <Models><Model type="PassiveScalar">'):
        run_deck(text=text)


def _c2_table(path, value_of_x, header="# x, y, z, c2\n"):
    """A c2 table for advectScalar_variant.ups's 20 x 20 x 1 cells (Uintah's readTable format)."""
    xs = -0.5 + (np.arange(20) + 0.5) * 0.05
    with open(path, "w") as f:
        f.write(header)
        for x in xs:
            for y in xs:
                f.write(f"{float(x)!r},{float(y)!r},0.0,{float(value_of_x(x))!r}\n")
    return path


def test_exponential_decay_c2_from_table(run_deck, tmp_path):
    """<c2 type="variable">: c2 per cell from a csv table (Uintah's PassiveScalar::readTable). A
    table of 5 everywhere gives sus's run of the deck with c2 = 5 (the constant) to round-off."""
    sus = np.load(DATA / "sus_advectScalar_variant.npz")
    text = open(REF / "advectScalar_variant.ups", encoding="iso-8859-1").read()
    table = _c2_table(tmp_path / "c2.csv", lambda x: 5.0)
    da = run_deck(text=_edit(text, '<c2 type="constant"> <value> 5.0 </value> </c2>',
                             f'<c2 type="variable"> <filename> {table} </filename> </c2>'))
    assert np.allclose(da.read("scalar-f", 0, -1)[0][:, :, 0], sus["f_step10"], rtol=0, atol=1e-13)
    assert np.allclose(da.read("scalar-q", 0, -1)[0][:, :, 0], sus["q_step10"], rtol=0, atol=1e-13)


def test_exponential_decay_c2_table_varies(run_deck, tmp_path):
    """A larger c2 on x > 0 decays the scalar there faster (step 1, before the flow mixes it):
    the left half up to the cell next to x = 0 equals the constant run's, the right half holds less."""
    text = open(REF / "advectScalar_variant.ups", encoding="iso-8859-1").read()
    table = _c2_table(tmp_path / "c2.csv", lambda x: 5.0 if x < 0 else 50.0)
    one = _edit(text, "<max_Timesteps>10</max_Timesteps>", "<max_Timesteps>1</max_Timesteps>")
    ref = run_deck(text=one).read("scalar-f", 0, 1)[0][:, :, 0]
    got = run_deck(text=_edit(one, '<c2 type="constant"> <value> 5.0 </value> </c2>',
                              f'<c2 type="variable"> <filename> {table} </filename> </c2>')).read("scalar-f", 0, 1)[0][:, :, 0]
    assert np.array_equal(got[:9], ref[:9])
    smaller = got[10:] < ref[10:] * (1 - 1e-6)
    assert smaller.sum() >= 10 and got[10:].sum() < ref[10:].sum()
    assert np.all(got[10:] <= ref[10:] * (1 + 1e-8))      # (most of the deck's cells are sources or emptied)


@pytest.mark.parametrize("drop_last, message", [(True, "399 of the level's 400 cells"), (False, "no file")])
def test_c2_table_bad_input_one_line(run_deck, tmp_path, drop_last, message):
    text = open(REF / "advectScalar_variant.ups", encoding="iso-8859-1").read()
    table = _c2_table(tmp_path / "c2.csv", lambda x: 5.0)
    lines = open(table).readlines()
    open(table, "w").writelines(lines[:-1] if drop_last else lines)
    name = table if message != "no file" else tmp_path / "missing.csv"
    with pytest.raises(InputError, match=message) as e:
        run_deck(text=_edit(text, '<c2 type="constant"> <value> 5.0 </value> </c2>',
                            f'<c2 type="variable"> <filename> {name} </filename> </c2>'))
    assert "\n" not in str(e.value)
