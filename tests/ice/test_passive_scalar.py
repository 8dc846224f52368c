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
