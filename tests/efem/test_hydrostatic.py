"""A pool at rest stays at rest: the projection balances gravity on every node (eq. 17), the
pressure is the hydrostatic rho g (h - y) of the exact solution, and the spurious velocity
is of the order of the pressure solver's tolerance."""
import numpy as np

from framework.archiver import DataArchive
from tests.conftest import run_deck

from .decks import deck

RHO, G, H = 1000.0, 9.81, 0.6


def _run(tmp_path, walls, steps=40):
    ctl = run_deck(deck(res=(20, 20), steps=steps, walls=walls, every=steps, saves=("g.velocity", "press_CC")), tmp_path)
    return DataArchive(ctl.archiver.dir)


def test_pool_with_slip_walls_stays_at_rest_hydrostatic(tmp_path):
    a = _run(tmp_path, {"x-": "slip", "x+": "slip"})
    v, _ = a.read("g.velocity", 0, -1)
    assert np.abs(v).max() < 1e-8          # measured 3e-11 m/s after 40 steps of 0.01 s
    p, (x, y, z) = a.read("press_CC", 0, -1)
    full = y < H
    exact = RHO * G * (H - y[full])
    np.testing.assert_allclose(p[:, full, 0], np.broadcast_to(exact, p[:, full, 0].shape), rtol=1e-7)
    assert np.all(p[:, ~full, 0] == 0.0)   # void elements


def test_pool_with_no_slip_walls_spurious_velocity_bounded(tmp_path):
    """No-slip walls pin the nodes on them after the projection; the pool still stays at rest."""
    a = _run(tmp_path, {})
    v, _ = a.read("g.velocity", 0, -1)
    assert np.abs(v).max() < 1e-6          # measured 3e-11 m/s
