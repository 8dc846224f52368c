"""<SpecificHeatModel> (components/ice/specific_heat.py): cv(T) per cell, as Uintah's ICE.

Expected values come from Uintah's sus (one rank):
- BwSmall: sus on uintah_reference/BwSmall_coarse.ups with limiter="BarthJespersen"
  dissipationHeating="false" removed (`sus BwSmall_coarse_sus.ups`), read with
  framework.uintah_uda.UintahArchive (output i = after step i + 1) and its .dat files.
- the four models: sus on the same deck with <SpecificHeatModel> replaced by each model below:
  `specific_heat` after step 2 (cv of the temperature after step 1) at the coldest cell and
  three hot ones, paired with that cell's temp_CC after step 1.
"""
import pathlib

import numpy as np
import pytest

from components.ice.specific_heat import read_specific_heat_model, specific_heat_of
from framework.problemspec import InputError, ProblemSpec

REF = pathlib.Path(__file__).parent / "uintah_reference"
DECK = REF / "BwSmall_coarse.ups"

# sus: times of the 5 outputs (one per step)
SUS_TIMES = [1e-09, 9.576613350016187e-06, 1.8421438539911693e-05, 2.6811906149736366e-05, 3.491532049471752e-05]
# sus: (min, max) over the interior cells after each step
SUS_MINMAX = {
    "press_CC": [(10132.500000010132, 142729.7429337005), (10132.500000010132, 142729.09383119),
                 (10132.500000010132, 135433.9848460234), (10132.500000010132, 123909.77600556967),
                 (10132.500000010132, 110659.7329185709)],
    "temp_CC": [(300.0, 3000.0), (300.0, 2999.996107348261), (300.0, 2958.4833437001407),
                (300.0, 2892.771791996001), (300.0, 2813.0421330847835)],
    "rho_CC": [(0.11719839476815805, 0.11719839498031366), (0.1026082272040427, 0.12206178417875778),
               (0.09231131135587058, 0.12631137364608908), (0.08401668513168217, 0.12947336535570161),
               (0.0768777434442406, 0.13109652069760075)],
    "specific_heat": [(721.8712622036788, 1016.8517116748482), (721.8712622036788, 1016.8517116748482),
                      (721.8712622036788, 1016.851587114534), (721.8712622036788, 1015.5090432902663),
                      (721.8712622036788, 1013.3244783594865)],
}
SUS_TOTAL_INT_ENG = [28037.762137438454, 27980.278509071097, 27931.588975680148, 27896.991344144997,
                     27877.59315209809]
SUS_KINETIC_ENERGY = [1.800232380698856e-07, 13.320504407218348, 43.07808711463875, 79.16352025830386,
                      116.07374508412528]

MODELS = {
    "airNasa": '<SpecificHeatModel type="airNasa"/>',
    "Component": """<SpecificHeatModel type="Component">
        <XCO2> 0.1 </XCO2> <XH2O> 0.1 </XH2O> <XCO> 0.05 </XCO> <XH2> 0.05 </XH2> <XO2> 0.1 </XO2>
        <XN2> 0.5 </XN2> <XOH> 0.03 </XOH> <XNO> 0.03 </XNO> <XO> 0.02 </XO> <XH> 0.02 </XH>
      </SpecificHeatModel>""",
    "Polynomial": """<SpecificHeatModel type="Polynomial">
        <MaxOrder> 2 </MaxOrder> <Tmin> 350 </Tmin> <Tmax> 2500 </Tmax>
        <coefficient> [10.0, 1.0e-3, 1.3e-3] </coefficient>
      </SpecificHeatModel>""",
    "Debye": """<SpecificHeatModel type="Debye">
        <Atoms> 1.69e25 </Atoms> <DebyeTemperature> 1000 </DebyeTemperature>
      </SpecificHeatModel>""",
}
# sus: (temp_CC after step 1, specific_heat after step 2) at four cells; the tolerance (Debye:
# glibc's exp and LLVM's differ in the last bit over its 1000-term sum, measured 1.8e-14)
SUS_CV = {
    "airNasa": ([300.0, 2878.3366916453524, 2955.070902993207, 2999.996107348261],
                [721.8712622036788, 1012.8345142516752, 1015.39740971186, 1016.851587114534], 1e-15),
    "Component": ([299.99999999999994, 2878.5143593630182, 2955.146215967872, 2999.9959540204636],
                  [801.974065473272, 1098.8943174482765, 1101.3035181102152, 1102.6604257666977], 1e-15),
    "Polynomial": ([300.0, 2880.705800472496, 2956.072986760909, 2999.996700877425],
                   [722.2877358490566, 768.0491551459294, 768.0491551459294, 768.0491551459294], 1e-15),
    "Debye": ([300.0, 2877.333817654686, 2954.644782833496, 2999.996747520291],
              [424.9381764772249, 694.7412584852838, 694.9572313867815, 695.076268520194], 1e-13),
}


def _model(text):
    mat = ProblemSpec.from_string(f"<material>{text}</material>")
    return read_specific_heat_model(mat)


@pytest.mark.parametrize("kind", list(MODELS))
def test_models_as_sus(kind):
    """Each model's cv(T) at temperatures sus reached, to round-off (the T clamps included:
    Component's 300 K floor, Polynomial's Tmin 350 and Tmax 2500)."""
    model = _model(MODELS[kind])
    temps, want, tol = SUS_CV[kind]
    got = [specific_heat_of(model.code, model.params, t) for t in temps]
    assert np.allclose(got, want, rtol=tol, atol=0), (kind, np.array(got) - want)


def test_bwsmall_as_sus(run_deck):
    """BwSmall (coarsened, Uintah's advection) over 5 steps: the same algorithm as sus, so
    delT to 1e-15, the fields' extrema to 1e-14 and TotalIntEng to 5e-14 (measured: 2e-16, 6e-16,
    1.9e-14: sums of 8000 cells)."""
    da = run_deck(str(DECK))
    assert np.allclose(da.times[1:], SUS_TIMES, rtol=1e-15, atol=0)
    for step in range(5):
        for label, rows in SUS_MINMAX.items():
            a = da.read(label, 0, step + 1)[0]
            assert np.allclose((a.min(), a.max()), rows[step], rtol=1e-14, atol=0), (step, label)
    assert np.allclose(da.reduction("TotalIntEng")[1], SUS_TOTAL_INT_ENG, rtol=5e-14, atol=0)
    assert np.allclose(da.reduction("KineticEnergy")[1], SUS_KINETIC_ENERGY, rtol=1e-13, atol=1e-12)
    # gamma stays <gamma> (sus's too): the hot cells' pressure is (gamma - 1) rho cv(3000 K) T
    press = da.read("press_CC", 0, 0)[0]
    assert press.max() == pytest.approx(0.3992215173352451 * 0.11719839492715754 * 1016.8517116748482 * 3000.0,
                                        rel=1e-14)


@pytest.mark.parametrize("old, new, message", [
    ('<SpecificHeatModel type="airNasa"/>', '<SpecificHeatModel type="NASA"/>', "accepted: airNasa, Component"),
    ('<SpecificHeatModel type="airNasa"/>', '<SpecificHeatModel type="Component"> <XN2> 0.79 </XN2> '
     '<XO2> 0.2 </XO2> </SpecificHeatModel>', "add up to 0.99"),
    ('<SpecificHeatModel type="airNasa"/>', '<SpecificHeatModel type="Polynomial"> <MaxOrder> 2 </MaxOrder> '
     '<coefficient> [1, 2] </coefficient> </SpecificHeatModel>', "2 coefficients for <MaxOrder> 2"),
    ('<SpecificHeatModel type="airNasa"/>', '<SpecificHeatModel type="Debye"> <Atoms> 2 </Atoms> '
     '</SpecificHeatModel>', "<DebyeTemperature>"),
    ('</material>', '</material>\n<material> <EOS type="ideal_gas"/> <specific_heat> 717.5 </specific_heat> '
     '<gamma> 1.4 </gamma> <geom_object> <box> <min>[0,0,0]</min> <max>[0.1,0.1,0.1]</max> </box> '
     '<res>[2,2,2]</res> <velocity>[0,0,0]</velocity> <density>1</density> <pressure>1e5</pressure> '
     '<temperature>300</temperature> </geom_object> </material>', "one ICE material"),
])
def test_bad_input(tmp_path, old, new, message):
    """Bad model input: one line naming the file, the line and what is accepted."""
    from framework.controller import Controller
    text = DECK.read_text(encoding="iso-8859-1").replace('id = "0"', 'id = "all"')
    assert text.count(old) == 1
    (tmp_path / "d.ups").write_text(text.replace(old, new), encoding="iso-8859-1")
    with pytest.raises(InputError) as e:
        Controller(str(tmp_path / "d.ups"), quiet=True, filebase=str(tmp_path / "run.uda"))
    text = str(e.value)
    assert "\n" not in text.strip() and "d.ups" in text and message in text, text


def test_without_model(tmp_path, run_deck):
    """Without <SpecificHeatModel> the specific-heat task runs only when specific_heat or gamma
    is saved (the kernels get the material's one <specific_heat>, as before), and then holds the
    material's constants, as sus's; with a model it runs every step, before the equilibration."""
    from framework.controller import Controller
    text = DECK.read_text(encoding="iso-8859-1")
    plain = text.replace('<SpecificHeatModel type="airNasa"/>', "")
    unsaved = plain.replace('<save label="specific_heat"/>', "")
    for deck, want in ((text, True), (plain, True), (unsaved, False)):
        c = Controller(deck_text=deck, quiet=True, filebase=str(tmp_path / "run.uda"))
        names = [t.name for t in c.step_graph.tasks]
        assert ("ICE::computeSpecificHeat" in names) == want
        if want:
            assert names.index("ICE::computeSpecificHeat") < names.index("ICE::computeEquilibrationPressure")
    short = plain.replace("<max_Timesteps>      5", "<max_Timesteps>      1").replace(
        '<save label="specific_heat"/>', '<save label="specific_heat"/> <save label="gamma"/>')
    da = run_deck(text=short)
    for step in (0, 1):
        assert np.all(da.read("specific_heat", 0, step)[0] == 721.8712622036791)
        assert np.all(da.read("gamma", 0, step)[0] == 1.3992215173352451)
