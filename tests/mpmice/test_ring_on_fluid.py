"""inputs/MPMICE/ring_on_fluid.ups (paper 003 sec. 7.1 on MPMICE), its 60 x 40 cells to
t = 0.04 s, before the ring reaches the pool: the layered pool starts hydrostatic and stays
at rest (but for the bottom rows: MPMICE has no hydrostatic wall condition), the ring falls
freely (y0 - v0 t - g t^2 / 2, the exact free fall; the gas it moves through is 500 times
lighter), and the liquid's mass is constant.
scripts/ring_efem_vs_mpmice.py runs the whole scene beside EFEM.
"""
import numpy as np
import pytest

from framework.archiver import DataArchive
from tests.conftest import ROOT, run_deck

DECK = ROOT / "inputs" / "MPMICE" / "ring_on_fluid.ups"
T_END, Y0, V0, G = 0.04, 0.58, 0.2, 9.81


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    text = DECK.read_text(encoding="iso-8859-1")
    text = text.replace("<maxTime> 0.9 </maxTime>", f"<maxTime> {T_END} </maxTime>")
    text = text.replace("<outputInterval> 0.05 </outputInterval>", "<outputInterval> 0.02 </outputInterval>")
    ctl = run_deck(text, tmp_path_factory.mktemp("ring"), "ring")
    return DataArchive(ctl.archiver.dir)


def test_pool_stays_at_rest_and_keeps_its_mass(run):
    dv = float(np.prod(run.dx))
    m0 = run.read("rho_CC", 1, 0)[0].sum() * dv
    for k in range(1, len(run.times)):
        f, _ = run.read("vol_frac_CC", 1, k)
        v, _ = run.read("vel_CC", 1, k)
        # m/s; measured 0.023 at 0.02 s (the bottom row), 0.042 at 0.04 s (under the ring, which
        # pushes the gas onto the surface); the ring lands at 1 m/s
        assert np.abs(v[f[..., 0] > 0.5]).max() < 0.05
        assert run.read("rho_CC", 1, k)[0].sum() * dv == pytest.approx(m0, rel=1e-12)


def test_ring_falls_freely(run):
    t = run.times[-1]
    assert t == pytest.approx(T_END, abs=1e-3)
    p0, p1 = run.particles(0, 0), run.particles(0, -1)
    y = [float((p["p.x"][:, 1] * p["p.mass"]).sum() / p["p.mass"].sum()) for p in (p0, p1)]
    drop = y[0] - y[1]
    assert y[0] == pytest.approx(Y0, abs=2e-3)
    assert drop == pytest.approx(V0 * t + 0.5 * G * t * t, rel=0.03)     # measured -1.5 %
