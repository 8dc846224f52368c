"""Uintah's advect.ups and hotBlob2mat.ups run unchanged and conserve.

advect.ups: uniform flow [1,1,1] m/s through a 5^3 box with zero-gradient faces: the
compatible advection keeps the state exactly uniform, so inflow equals outflow and
mass and internal energy stay constant. hotBlob2mat.ups: two gases in pressure
equilibrium (a 400 K blob in 300 K gas): nothing moves, pressure stays uniform,
volume fractions sum to one and each material's mass is conserved.
"""
import numpy as np
import pytest

from .conftest import UINTAH


def test_advect(run_deck):
    da = run_deck(f"{UINTAH}/advect.ups")
    rho0, _ = da.read("rho_CC", 0, 0)
    rho, _ = da.read("rho_CC", 0, -1)
    vel, _ = da.read("vel_CC", 0, -1)
    assert np.allclose(rho, rho0[0, 0, 0], rtol=1e-9)
    assert np.allclose(vel, 1.0, rtol=1e-9)
    _, ie = da.reduction("TotalIntEng")
    assert np.allclose(ie, ie[0], rtol=1e-9)
    fc, _ = da.read("uvel_FCME", 0, -1)
    assert np.allclose(fc, 1.0, rtol=1e-9)


def test_hot_blob_two_materials(run_deck):
    da = run_deck(f"{UINTAH}/hotBlob2mat.ups")
    p, _ = da.read("press_CC", 0, -1)
    assert np.allclose(p, 101325.0, rtol=1e-9)
    th = da.read("vol_frac_CC", 0, -1)[0] + da.read("vol_frac_CC", 1, -1)[0]
    assert np.allclose(th, 1.0, atol=1e-12)
    for m in (0, 1):
        r0, _ = da.read("rho_CC", m, 0)
        r, _ = da.read("rho_CC", m, -1)
        assert r.sum() == pytest.approx(r0.sum(), rel=1e-13)
    T, _ = da.read("temp_CC", 1, -1)
    assert T.max() == pytest.approx(400.0, rel=1e-9)
    _, ie = da.reduction("TotalIntEng")
    assert np.allclose(ie, ie[0], rtol=1e-12)
