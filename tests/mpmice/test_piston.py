"""Gas-driven piston (inputs/MPMICE/piston.ups): momentum of gas + slab against the wall impulse.

Before any wave reaches a wall (~1 ms) the walls see the initial pressures, so the total
momentum is (p_L - p_R) A t. Measured at t = 0.1 .. 0.5 ms: relative error 1e-12 .. 2e-9 (conservative to round-off);
the slab carries 99.9 % of it (the gas is light).
"""
import os

import numpy as np
import pytest

DECK = os.path.join(os.path.dirname(__file__), "..", "..", "inputs", "MPMICE", "piston.ups")
A, DX = 0.025 * 0.025, 1.0 / 40


@pytest.fixture(scope="module")
def archive(tmp_path_factory):
    from framework.archiver import DataArchive
    from framework.controller import Controller
    c = Controller(DECK, quiet=True, filebase=str(tmp_path_factory.mktemp("piston") / "piston.uda"))
    c.run()
    return DataArchive(c.archiver.dir)


def test_total_momentum_equals_wall_impulse(archive):
    for i, t in enumerate(archive.times):
        if t == 0.0:
            continue
        parts = archive.particles(0, i)
        slab = float((parts["p.mass"] * parts["p.velocity"][:, 0]).sum())
        rho, _ = archive.read("rho_CC", 1, i)
        u, _ = archive.read("vel_CC", 1, i)
        gas = float((rho * u[..., 0]).sum() * DX * A)
        exact = (1013250.0 - 101325.0) * A * t
        assert slab > 0.99 * exact
        assert abs(slab + gas - exact) < 1e-7 * exact


def test_finite(archive):
    p, _ = archive.read("press_CC", 0, -1)
    assert np.all(np.isfinite(p)) and p.min() > 0
