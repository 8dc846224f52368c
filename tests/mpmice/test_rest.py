"""A steel slab at rest in air at the reference pressure stays at rest (inputs/MPMICE/slab_rest.ups).

Measured (200 steps): velocities of solid and gas below 5e-10 m/s; the pressure is exact
(0.0 Pa off) in every cell with gas and 0.12 Pa high in the cells the steel fills: there
the gas keeps its 1e-12 volume-fraction floor, which the steel (K = 117 GPa) makes room
for by compressing 1e-12 (K * 1e-12 = 0.12 Pa, relative 1.2e-6).
"""
import os

import numpy as np
import pytest

DECK = os.path.join(os.path.dirname(__file__), "..", "..", "inputs", "MPMICE", "slab_rest.ups")


@pytest.fixture(scope="module")
def archive(tmp_path_factory):
    from framework.archiver import DataArchive
    from framework.controller import Controller
    c = Controller(DECK, quiet=True, filebase=str(tmp_path_factory.mktemp("rest") / "rest.uda"))
    c.run()
    return DataArchive(c.archiver.dir)


def test_nothing_moves(archive):
    for m in (0, 1):
        v, _ = archive.read("vel_CC", m, -1)
        assert np.abs(v).max() < 5e-9
    parts0, parts = archive.particles(0, 0), archive.particles(0, -1)
    assert np.abs(parts["p.velocity"]).max() < 5e-9
    assert np.abs(parts["p.x"] - parts0["p.x"]).max() < 1e-12


def test_pressure_uniform(archive):
    p, _ = archive.read("press_CC", 0, -1)
    gas, _ = archive.read("vol_frac_CC", 1, -1)
    dev = np.abs(p - 101325.0)
    assert dev[gas > 1e-6].max() < 1e-8 * 101325.0          # round-off where there is gas
    assert dev.max() < 2e-12 * 117e9 + 1e-6                 # the 1e-12 gas trace in steel cells


def test_volume_fractions_sum_to_one(archive):
    th = archive.read("vol_frac_CC", 0, -1)[0] + archive.read("vol_frac_CC", 1, -1)[0]
    assert np.abs(th - 1.0).max() < 1e-9
