"""TracerParticles under MPMICE (Uintah's advect.ups model) against sus, five steps.

Deck: uintah_reference/advect_tracers.ups (advect.ups on 10^3 cells, 2 x 2 x 2 patches, with its
TracerParticles model: tracers seeded in the copper box, an interior source, p.scalar decaying
with c2 from the table advect_tracers_c2.csv; its header says what else changed).
data/sus_advect_tracers.npz is sus's output on that deck, one rank (sus advect_tracers.ups in a
folder holding the deck and the table), read with framework.uintah_uda.UintahArchive: the times,
the tracer count after each step, and after steps 2 and 5 the tracers (material 1) sorted by
p.particleID: p.x, p.clone-scalar-q_CC, p.scalar, p.scalar_totalDecay; and p.scalar_expDecayCoef.

The tracers and the copper's particles relocate in one relocation task, each set over its own
material. Measured: the same particle IDs every step; the times 2e-15 relative; after steps
2 and 5 p.x to 1.1e-16 m, the scalars 6e-16 (the gas starts around the copper from its
geometry as sus's, docs/MPMICE.md "Gas start"; with the particles' smeared start p.x was 3e-7 m
off after step 5, p.scalar 1.1e-5, delT 5.3e-5).
"""
import pathlib

import numpy as np
import pytest

from tests.conftest import run_deck

HERE = pathlib.Path(__file__).parent
DECK = HERE / "uintah_reference" / "advect_tracers.ups"


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    from framework.archiver import DataArchive
    text = DECK.read_text(encoding="latin-1").replace("advect_tracers_c2.csv", str(HERE / "uintah_reference" /
                                                                                  "advect_tracers_c2.csv"))
    ctl = run_deck(text, tmp_path_factory.mktemp("tracers"), "tracers")
    return DataArchive(ctl.archiver.dir), np.load(HERE / "data" / "sus_advect_tracers.npz")


def _tracers(da, step):
    p = da.particles(1, step)
    order = np.argsort(p["p.particleID"])
    return {k: v[order] for k, v in p.items()}


def test_tracer_counts_and_ids_as_uintah(runs):
    """The seeded and injected tracers: sus's count after every step, sus's IDs; the copper's 64
    particles stay with material 0."""
    da, sus = runs
    assert np.allclose(da.times[1:], sus["times"], rtol=1e-13, atol=0)     # measured 2e-15
    for step in range(1, 6):
        assert len(da.particles(1, step)["p.particleID"]) == int(sus[f"n_step{step}"])
        assert len(da.particles(0, step)["p.x"]) == 64
    for step in (2, 5):
        assert np.array_equal(_tracers(da, step)["p.particleID"], sus[f"id_step{step}"])


@pytest.mark.parametrize("step, tol_x, tol_s", [(2, 1e-14, 1e-14), (5, 1e-14, 1e-14)])
def test_tracer_values_as_uintah(runs, step, tol_x, tol_s):
    """Positions, the cloned scalar-q_CC and the decaying p.scalar (c2 from the table) are sus's."""
    da, sus = runs
    tr = _tracers(da, step)
    assert np.abs(tr["p.x"] - sus[f"x_step{step}"]).max() < tol_x
    assert np.abs(tr["p.clone-scalar-q_CC"] - sus[f"clone_step{step}"]).max() < tol_s
    assert np.abs(tr["p.scalar"] - sus[f"scalar_step{step}"]).max() < tol_s
    assert np.abs(tr["p.scalar_totalDecay"] - sus[f"totalDecay_step{step}"]).max() < tol_s
    assert sus[f"scalar_step{step}"].min() < 0.99             # the decay acts
    assert np.array_equal(da.read("p.scalar_expDecayCoef", 1, 1)[0], sus["expDecayCoef"])


def test_tracers_on_a_solid_refused(tmp_path):
    """Tracers ride on a fluid: an MPM material is refused with the tag."""
    from framework.problemspec import InputError
    text = DECK.read_text(encoding="latin-1").replace("advect_tracers_c2.csv", str(HERE / "uintah_reference" /
                                                                                  "advect_tracers_c2.csv"))
    model = text.index('<Model type="TracerParticles">')
    text = text[:model] + text[model:].replace("<material>atmosphere</material>", "<material>0</material>", 1)
    with pytest.raises(InputError, match="carried by an ICE material"):
        run_deck(text, tmp_path)
