"""Uintah's ICE diagnostics a deck may <save>, computed only then, and decks Uintah accepts
with inputs pysus once refused.

delP_MassX: Uintah's sus writes exactly 0 for decks without mass-exchange models (term1 = 0 in
ICE::computeDelPressAndUpdatePressCC; seen in sus's uda of hotBlob2mat.ups); pysus forms it as
p - p_eq - delP_Dilatate, so it is 0 to round-off of the pressure.
"""
import numpy as np

from framework.controller import Controller
from .conftest import UINTAH


def hot_blob(tmp_path, extra_save="", exchange=None, steps=2):
    with open(f"{UINTAH}/hotBlob2mat.ups") as f:
        text = f.read()
    text = text.replace("</Time>", f"<max_Timesteps>{steps}</max_Timesteps></Time>")
    text = text.replace('<save label="press_equil_CC"/>', f'<save label="press_equil_CC"/>{extra_save}')
    return text


def test_delP_MassX_only_when_saved(tmp_path, run_deck):
    path = tmp_path / "d.ups"
    path.write_text(hot_blob(tmp_path))
    plain = Controller(str(path), quiet=True, filebase=str(tmp_path / "a.uda"))
    assert "ICE::computeDelP_MassX" not in [t.name for t in plain.step_graph.tasks]
    da = run_deck(text=hot_blob(tmp_path, '<save label="delP_MassX"/>'))
    p, _ = da.read("press_CC", 0, -1)
    dpm, _ = da.read("delP_MassX", 0, -1)
    assert np.abs(dpm).max() <= 1e-12 * np.abs(p).max()
    dpd, _ = da.read("delP_Dilatate", 0, -1)
    assert np.abs(dpd).max() > 1.0          # the blob expands: the dilatation term is not round-off


def test_one_material_ignores_exchange_coefficients(run_deck, tmp_path):
    """Uintah's ExchangeCoefficients::problemSetup returns before reading anything for one material
    (advect_periodic.ups gives [1e10] for one): the run is the one without them."""
    with open(f"{UINTAH}/advect.ups") as f:
        text = f.read().replace("</Time>", "<max_Timesteps>2</max_Timesteps></Time>")
    exch = ("<exchange_properties><exchange_coefficients><momentum>[1e10]</momentum>"
            "<heat>[1e10]</heat></exchange_coefficients></exchange_properties></MaterialProperties>")
    a = run_deck(text=text)
    ra, _ = a.read("rho_CC", 0, -1)
    b = run_deck(text=text.replace("</MaterialProperties>", exch))
    rb, _ = b.read("rho_CC", 0, -1)
    assert np.array_equal(ra, rb)
