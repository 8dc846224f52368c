"""Pressurized cylinder (paper 000 sec. 4.1, inputs/MPMICE/pressurized_cylinder.ups) at two
coarse resolutions: the stresses approach Lame's solution (eq. 42) and the eq. 43 error drops.

Measured (scripts/accuracy_cost.py cylinder, t = 2.5 ms, inner gauge pressure 18.9-19.3 MPa),
with the steel's own heat capacity (cv = 716 J/(kg K)) in the exchange and its temperature
evolving (the deck's <heat> 1e6 between steel and air):
  n = 12 (dx = 0.1 m):  eq. 43 error 0.232, radial 0.085 P, hoop 0.117 P
  n = 18 (dx = 0.067):  eq. 43 error 0.152, radial 0.053 P, hoop 0.069 P   (order 1.03)
and down to 0.065 at n = 48 (the paper's dx): least-squares order 0.91 over n = 12..48
(paper: 0.89). Before the solids entered the equilibration at their EOS volume at the old
pressure (mpmice/kernels.solids_at_old_pressure): 0.261 and 0.181, order 0.83 over 12..48.
"""
import pytest

from components.mpmice import scene_cylinder as C
from tests.conftest import run_deck


# Uintah's sus on the same deck (scripts/accuracy_cost.py cylinder --res 12 18 --uintah SUS: the
# scene's deck through uintah_deck, 2780 steps to 2.5 ms): eq. 43 error 0.2340 at n = 12 and 0.1613
# at n = 18 (order 0.92); pysus there 0.2327 and 0.1548 (order 1.01).
SUS_EQ43 = {12: 0.2340, 18: 0.1613}


@pytest.fixture(scope="module")
def errs(tmp_path_factory):
    from framework.archiver import DataArchive
    out = {}
    for n in (12, 18):
        ctl = run_deck(C.deck(n), tmp_path_factory.mktemp(f"cyl{n}"), f"cyl{n}")
        out[n] = C.errors(DataArchive(ctl.archiver.dir))
    return out


def test_pressure_reached(errs):
    for e in errs.values():
        assert 18.5 < e["P_MPa"] < 19.6            # the paper's 19.4 MPa, less the heat the steel takes


def test_error_drops(errs):
    assert errs[12]["eq43"] < 0.25 and errs[18]["eq43"] < 0.17
    assert errs[18]["eq43"] < 0.75 * errs[12]["eq43"]
    for k in ("radial", "hoop"):
        assert errs[18][k] < errs[12][k] < 0.13


def test_eq43_error_below_uintahs(errs):
    for n, sus in SUS_EQ43.items():
        assert errs[n]["eq43"] < sus, (n, errs[n])
