"""The newer MPM decks (inputs/MPM) shortened, on 1 and 2 MPI ranks: bitwise equal
particle state (p.x, p.velocity, p.stress, matched by p.particleID).

Particle-to-grid sums run in particle-ID order over owned plus ghost particles and
relocation keeps each patch's particles sorted by ID, so the rank count changes no
arithmetic. The fluid points' artificial viscosity (sod_fluid_points) scales with
max |div v| and the largest sound speed of one material on one PATCH: that depends on
the patch layout (fixed by the deck, see test_layout.py), not on the rank count, so
1 and 2 ranks agree bitwise here too. piston_container has one patch in the deck; it
runs here on 2 patches so that the second rank has work.
"""
import numpy as np
import pytest

from framework.archiver import DataArchive
from tests.conftest import run_cases

from .helpers import MPM_INPUTS, deck_text

CASES = {
    "thick_cylinder": {"resolution": "[22,22,1]", "maxTime": "2e-4"},
    "friction_block": {"maxTime": "0.05"},
    "rigid_piston": {"maxTime": "0.2"},
    "sod_fluid_points": {"maxTime": "0.03"},
    "piston_container": {"maxTime": "0.001", "patches": "[2,1,1]"},
    "airbag": {"maxTime": "0.002", "patches": "[2,2,1]"},
}


@pytest.fixture(scope="module")
def launched(tmp_path_factory):
    """Every case's deck on 1 rank in this process, then on 2 ranks in one mpiexec launch: the
    directory of the udas and each run's (return code, stderr)."""
    d = tmp_path_factory.mktemp("mpm_decks_ranks")
    for case in CASES:
        text = deck_text(MPM_INPUTS / f"{case}.ups", **CASES[case])
        saves = "".join(f'<save label="{lab}"/>' for lab in ("p.x", "p.particleID", "p.velocity", "p.stress")
                        if f'"{lab}"' not in text)
        (d / f"{case}.ups").write_text(text.replace("</DataArchiver>", saves + "</DataArchiver>", 1))
    return d, run_cases(d, sorted(CASES), (1, 2))


@pytest.mark.parametrize("case", sorted(CASES))
def test_deck_two_ranks_bitwise(launched, case):
    d, out = launched
    for n in (1, 2):
        rc, err = out[case, n]
        assert rc == 0, err[-2000:]
    runs = {n: DataArchive(d / f"{case}_{n}.uda") for n in (1, 2)}
    assert np.array_equal(runs[1].times, runs[2].times)
    total = 0
    for m in range(len(runs[1].materials)):
        a, b = runs[1].particles(m, -1), runs[2].particles(m, -1)
        oa, ob = np.argsort(a["p.particleID"]), np.argsort(b["p.particleID"])
        assert np.array_equal(a["p.particleID"][oa], b["p.particleID"][ob])
        total += len(oa)
        for lab in ("p.x", "p.velocity", "p.stress"):
            assert np.array_equal(a[lab][oa], b[lab][ob]), (case, m, lab)
    assert total > 10
