"""Particles leaving the domain through a face without a wall: deleted as in Uintah, but said.

Every step in which some leave prints one warning line (count and mass per material), the
reduction LostParticleMass holds that step's lost mass, and <particles_leaving_domain>error
stops the run with one line instead.
"""
import os

import numpy as np

from framework.archiver import DataArchive
from tests.conftest import pysus_ranks

DECK = os.path.join(os.path.dirname(os.path.abspath(__file__)), "leaving_block.ups")


def test_leaving_particles_are_reported_and_their_mass_accounted(tmp_path):
    r = pysus_ranks(DECK, "--filebase", tmp_path / "run.uda")
    assert r.returncode == 0, r.stderr
    warnings = [l for l in r.stderr.splitlines() if "left the domain" in l]
    assert len(warnings) >= 3 and all(l.startswith("pysus: warning: timestep ") for l in warnings)
    da = DataArchive(str(tmp_path / "run.uda"))
    _, lost = da.reduction("LostParticleMass")
    _, total = da.reduction("TotalMass")
    # every step is an output here: the mass that vanished is the mass reported lost
    assert lost.sum() > 0.2
    assert total[0] - total[-1] - lost[1:].sum() == __import__("pytest").approx(0.0, abs=1e-12)
    assert len(warnings) == int(np.count_nonzero(lost))


def test_leaving_particles_can_stop_the_run(tmp_path):
    text = open(DECK).read().replace("<interpolator>linear</interpolator>",
                                     "<interpolator>linear</interpolator><particles_leaving_domain>error"
                                     "</particles_leaving_domain>")
    deck = tmp_path / "stop.ups"
    deck.write_text(text)
    r = pysus_ranks(deck, "--filebase", tmp_path / "run.uda")
    assert r.returncode == 1
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and "left the domain" in lines[0] and "particles_leaving_domain" in lines[0], r.stderr
