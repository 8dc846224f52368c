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


def test_implicit_rhs_is_the_last_outer_residual(run_deck):
    """<save label="rhs"> (Uintah's impHotBlob.ups saves it): the residual of the pressure equation
    after the last outer iteration, so within the outer tolerance when the loop converged and
    above it after one outer iteration whose inner solve was loose (1e-4)."""
    from components.ice.scene_lowmach import vortex_deck

    def rhs(outer):
        text = vortex_deck(8, implicit=True, max_timesteps=2, outer=outer, outer_tol=1e-9, tolerance=1e-4,
                           precond="jacobi")
        da = run_deck(text=text.replace('<save label="vel_CC"/>', '<save label="vel_CC"/><save label="rhs"/>'
                                            '<outputLastTimestep>true</outputLastTimestep>'))
        return np.abs(da.read("rhs", 0, -1)[0]).max()
    assert rhs(20) <= 1e-9 < rhs(1)


def test_mom_source_CC_against_sus(run_deck):
    """<save label="mom_source_CC"> (Uintah's rayleigh_*.ups save it) on hotBlob2mat.ups, 2 steps:
    sus's uda gives max |component| 1.0146741173582096e-02 (material 0) and 7.3983061472667885e-03
    (material 1), the same for every component (the blob is symmetric). pysus's advection still
    differs from sus's by ~1e-3 on this deck (Uintah's limiter), hence 2e-3."""
    with open(f"{UINTAH}/hotBlob2mat.ups") as f:
        text = f.read().replace("</Time>", "<max_Timesteps>2</max_Timesteps></Time>")
    da = run_deck(text=text.replace('<save label="press_equil_CC"/>',
                                    '<save label="press_equil_CC"/><save label="mom_source_CC"/>'))
    for m, sus in ((0, 1.0146741173582096e-02), (1, 7.3983061472667885e-03)):
        src = da.read("mom_source_CC", m, -1)[0].reshape(-1, 3)
        assert np.allclose(src.max(0), sus, rtol=2e-3) and np.allclose(src.min(0), -sus, rtol=2e-3)
