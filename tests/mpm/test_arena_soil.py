"""ArenaSoil (components/mpm/constitutive/arena_soil.py) on Uintah's three ARENATESTS decks; Uintah's sus.

Uintah's HydrostaticCompressionSaturated, MultiaxialStrainLoadUnload and
BoulderClaySHPB072213-014 (tests/mpm/uintah_reference/): one particle driven by a
prescribed deformation (components/mpm/prescribed.py). Each runs here for 40 steps with
<max_Timesteps>40 and an output every step (the only edits; the tables are copied to
inputs/MPM/ArenaSoilBanerjeeBrannon/ under the run's directory, the path the decks name).
sus ran the same 40 steps of the same decks (UseMomentumForm taken out: sus's validation
refuses it); tests/mpm/data/sus_arena_soil.npz holds, for each deck and output, the time and
the particle's p.stress, p.stressQS, p.plasticStrain (a tensor; p.plasticStrainTensor here),
p.plasticCumEqStrain, p.plasticVolStrain, p.capX, p.porePressure, p.porosity, p.saturation,
p.p3, p.elasticVolStrain, p.COHER, p.TGROW, p.ArenaPEAKI1 ... p.ArenaT2 and
p.deformationMeasure, read from sus's uda with framework/uintah_uda.py.

MultiaxialStrainLoadUnload runs also 300 steps (output every 100; the dry soil yields between
steps 100 and 200) against sus's steps 100, 200, 300 of its whole run (8889 steps, output every 100).

Measured: HydrostaticCompressionSaturated (saturated, plastic from the first step) and
MultiaxialStrainLoadUnload (dry, elastic over 40 steps) agree to 2.5e-15 of each variable's
largest value (the hydrostatic path's deviatoric plastic strain, 1e-20 of round-off in both,
differs by 1.4e-20), 300 steps of MultiaxialStrainLoadUnload to 1.6e-14; BoulderClay (partly saturated,
plastic from step 6, damage and rate dependence) to 1.2e-8 of the largest stress (the
difference peaks at step 16 and falls to 5e-10 by step 18: round-off passed on by the
closest-point and consistency bisections).
"""
import pathlib
import shutil

import numpy as np
import pytest

from framework.problemspec import InputError

from .helpers import run

HERE = pathlib.Path(__file__).parent
REF = HERE / "uintah_reference"
SUS = HERE / "data" / "sus_arena_soil.npz"
MULTI = ("MultiaxialStrainLoadUnload", "MultiaxialStrainLoadUnload_PrescribedDeformation.inp")
# key: (deck, its table, tolerance, steps, output every)
DECKS = {"hydro": ("HydrostaticCompressionSaturated", "HydrostaticCompression_PrescribedDeformation.inp", 1e-13, 40, 1),
         "multi": MULTI + (1e-13, 40, 1),
         "multi300": MULTI + (1e-12, 300, 100),
         "boulder": ("BoulderClaySHPB072213-014", "BoulderClay072213-014.defgrad", 3e-8, 40, 1)}
SCALARS = ["p.plasticCumEqStrain", "p.plasticVolStrain", "p.capX", "p.porosity", "p.saturation", "p.p3",
           "p.elasticVolStrain", "p.COHER", "p.TGROW", "p.ArenaPEAKI1", "p.ArenaFSLOPE", "p.ArenaSTREN",
           "p.ArenaYSLOPE", "p.ArenaBETA", "p.ArenaCR", "p.ArenaT1", "p.ArenaT2"]
TENSORS = ["p.stress", "p.stressQS", "p.plasticStrain", "p.porePressure", "p.deformationMeasure"]


def deck(name, table, tmp_path, steps=40, every=1, edits=()):
    """The deck with max_Timesteps and an output every step; its table where the deck looks."""
    d = tmp_path / "inputs" / "MPM" / "ArenaSoilBanerjeeBrannon"
    d.mkdir(parents=True, exist_ok=True)
    shutil.copy(REF / table, d / table)
    text = (REF / f"{name}.ups").read_text()
    text = text.replace("<Time>", f"<Time><max_Timesteps>{steps}</max_Timesteps>", 1)
    text = text.replace("<outputInterval>", f"<outputTimestepInterval>{every}</outputTimestepInterval><!-- ", 1)
    text = text.replace("</outputInterval>", " -->", 1)
    # g.volume saved too: p2g then computes the volume, inputs/MPM/adiabatic_copper_jc.ups's variant
    # (linear on xyz), not one of this file's own; the particle's state does not read it
    text = text.replace('<save label = "g.mass"/>', '<save label = "g.mass"/><save label = "g.volume"/>', 1)
    for old, new in edits:
        assert old in text, old
        text = text.replace(old, new)
    return text


@pytest.mark.parametrize("key", list(DECKS))
def test_deck_as_sus(key, tmp_path):
    """40 steps of the deck: sus's output times, and every saved variable of the model at
    every output within the tolerance of DECKS (relative to the variable's largest value)."""
    name, table, tol, steps, every = DECKS[key]
    _, da = run(deck(name, table, tmp_path, steps, every), tmp_path)
    sus = np.load(SUS)
    ts = sus[f"{key}/time"]
    times = np.asarray(da.times)
    first = len(times) - len(ts)          # HydrostaticCompressionSaturated saves no t = 0 output
    assert np.allclose(times[first:], ts, rtol=1e-12, atol=0)
    for label in SCALARS + TENSORS:
        ref = sus[f"{key}/{label}"]
        ours = np.array([da.particles(0, first + i)[label if label != "p.plasticStrain"
                                                     else "p.plasticStrainTensor"][0] for i in range(len(ts))])
        # round-off strains (hydrostatic: the deviator) count as 0; ln J - ep_v to the size of ep_v
        scale = max(np.abs(ref).max(), 1e-6,
                    np.abs(sus[f"{key}/p.plasticVolStrain"]).max() if label == "p.elasticVolStrain" else 0.0)
        assert np.abs(ours - ref).max() <= tol * scale, label
    if key != "multi":                      # the decks that yield in these steps
        assert sus[f"{key}/p.plasticVolStrain"][-1] < -1e-3


def test_unchanged_deck_runs_with_the_table_beside_it(tmp_path):
    """The deck as Uintah has it (but g.volume saved), run from a directory without inputs/: the table is found
    beside the deck; a missing table is a one-line error naming the tag."""
    text = (REF / "HydrostaticCompressionSaturated.ups").read_text()
    text = text.replace("<Time>", "<Time><max_Timesteps>2</max_Timesteps>", 1)
    text = text.replace('<save label = "g.mass"/>', '<save label = "g.mass"/><save label = "g.volume"/>', 1)
    (tmp_path / "d").mkdir()
    shutil.copy(REF / "HydrostaticCompression_PrescribedDeformation.inp", tmp_path / "d")
    from tests.conftest import run_deck
    from framework.controller import Controller
    ctl = Controller(str(tmp_path / "d" / "h.ups"), deck_text=text, quiet=True, filebase=str(tmp_path / "h.uda"))
    ctl.run()
    with pytest.raises(InputError, match="PrescribedDeformationFile.*not found"):
        run_deck(text, tmp_path, "h2")


@pytest.mark.parametrize("old,new,words", [
    ("<CR>     0.5    </CR>", "<CR>     1.5    </CR>", ("CR", "below 1")),
    ("<T1>     0.0    </T1>", "<T1>     1.0    </T1>", ("T1 and T2",)),
    ("<use_disaggregation_algorithm> false", "<use_disaggregation_algorithm> true", ("disaggregation",)),
    ('<elastic_moduli_model type="arena">', '<elastic_moduli_model type="tabular">', ("arena",)),
    ("<BETA>   1.0    </BETA>", "<BETA>   1.0    </BETA><weibullDist_BETA>weibull, 1, 4, 0.001, 1</weibullDist_BETA>",
     ("Weibull",)),
    ("<minimum_subcycles_for_F>       -2", "<stress_update>musl</stress_update><minimum_subcycles_for_F>       -2",
     ("usl",)),
])
def test_input_errors(old, new, words, tmp_path):
    """Bad or unimplemented input: a one-line error naming the tag."""
    from tests.conftest import run_deck
    text = deck("HydrostaticCompressionSaturated", "HydrostaticCompression_PrescribedDeformation.inp", tmp_path,
                steps=1, edits=[(old, new)])
    with pytest.raises(InputError) as e:
        run_deck(text, tmp_path)
    assert "\n" not in str(e.value)
    for w in words:
        assert w in str(e.value)
