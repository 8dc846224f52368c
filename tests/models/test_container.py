"""inputs/MPMICE/burning_container2D.ups, shortened to 150 steps: the explosive burns into
the gap inside the steel ring; total mass constant to round-off, the gap pressurizes."""
import os

import numpy as np

DECK = os.path.join(os.path.dirname(__file__), "..", "..", "inputs", "MPMICE", "burning_container2D.ups")
DX = 0.002
V = DX * DX * 0.002


def test_container_pressurizes_and_conserves_mass(tmp_path):
    from framework.archiver import DataArchive
    from framework.controller import Controller
    c = Controller(DECK, quiet=True, filebase=str(tmp_path / "bc.uda"), max_timesteps=150)
    c.run()
    a = DataArchive(c.archiver.dir)
    xc = (np.arange(40) + 0.5) * DX
    r = np.hypot(xc[:, None], xc[None, :])[..., None]
    gap = (r > 0.041) & (r < 0.049)

    def state(i):
        m = sum(float(a.particles(k, i)["p.mass"].sum()) for k in (0, 1))
        rho, _ = a.read("rho_CC", 2, i)
        p, _ = a.read("press_CC", 0, i)
        return m + float(rho.sum()) * V, float(a.particles(1, i)["p.mass"].sum()), p

    m0, e0, p0 = state(0)
    m1, e1, p1 = state(len(a.times) - 1)
    assert abs(m1 - m0) < 1e-13 * m0
    assert e1 < e0
    assert np.all(np.isfinite(p1)) and p1[gap].mean() > 1.05 * p0[gap].mean()
