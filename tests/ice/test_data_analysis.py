"""<DataAnalysis> minMax and vorticity on Uintah's hotBlob2mat.ups (materials named, the two
modules added), against the same deck run by Uintah's sus for 3 steps.

sus's values below: MinMax/L-0/* files of its uda and `puda -varsummary` of vorticity at step 3.
pysus's advection on this deck still differs from sus's by ~1e-3 (Uintah's BarthJespersen
limiter and dissipation heating), so values agree to 2e-3; what the modules do with the fields
is checked exactly against pysus's own saved fields.
"""
import numpy as np
import pytest

from .conftest import UINTAH

SUS_STEP3 = {"press_CC_0": (1.013250000002364E+05, 1.096895499067821E+05),
             "uvel_FCME_1": (-1.467672123689024E+01, 1.467672123689024E+01),
             "vel_CC_1": (-9.106681870313777E+00, 9.106681870314825E+00),
             "vorticity_1": (-1.5755895097027185e+01, 1.5755895097027185e+01)}
MODULES = """<DataAnalysis>
  <Module name="minMax">
    <material>outer</material>
    <samplingFrequency>1e10</samplingFrequency>
    <timeStart>0</timeStart>
    <timeStop>100</timeStop>
    <Variables>
      <analyze label="press_CC" matl="0"/>
      <analyze label="vel_CC" matl="1"/>
      <analyze label="uvel_FCME" matl="1"/>
    </Variables>
  </Module>
  <Module name="vorticity"><material>blob</material></Module>
</DataAnalysis>
</Uintah_specification>"""


def deck():
    with open(f"{UINTAH}/hotBlob2mat.ups") as f:
        text = f.read()
    text = text.replace("</Time>", "<max_Timesteps>3</max_Timesteps></Time>")
    text = text.replace('<save label="press_equil_CC"/>',
                        '<save label="press_equil_CC"/><save label="vorticity"/><save label="vel_CC"/>')
    text = text.replace("<material>", '<material name="outer">', 1).replace("<material>", '<material name="blob">', 1)
    return text.replace("</Uintah_specification>", MODULES)


def rows(path):
    out = []
    for line in open(path):
        if not line.startswith("#"):
            out.append([float(v) for v in line.replace("[", " ").replace("]", " ").split()])
    return np.array(out)


def test_min_max_and_vorticity(run_deck):
    da = run_deck(text=deck())
    vel, _ = da.read("vel_CC", 1, -1)
    files = {n: rows(f"{da.path}/MinMax/L-0/{n}") for n in ("press_CC_0", "vel_CC_1", "uvel_FCME_1")}
    assert all(len(r) == 3 for r in files.values())               # every step (samplingFrequency 1e10)
    last = files["vel_CC_1"][-1]
    assert np.array_equal(last[1:4], vel.reshape(-1, 3).min(0)) and np.array_equal(last[4:], vel.reshape(-1, 3).max(0))
    vort, _ = da.read("vorticity", 1, -1)
    dx = 0.1
    du = [(np.roll(vel, -1, a) - np.roll(vel, 1, a))[1:-1, 1:-1, 1:-1] / (2 * dx) for a in range(3)]
    curl = np.stack([du[1][..., 2] - du[2][..., 1], du[2][..., 0] - du[0][..., 2], du[0][..., 1] - du[1][..., 0]], -1)
    assert np.allclose(vort[1:-1, 1:-1, 1:-1], curl, rtol=1e-12, atol=1e-9)
    got = {n: (r[-1][1], r[-1][-1]) for n, r in files.items()}
    got["vorticity_1"] = (vort.min(), vort.max())
    for name, (lo, hi) in SUS_STEP3.items():
        assert got[name][0] == pytest.approx(lo, rel=2e-3) and got[name][1] == pytest.approx(hi, rel=2e-3), name


def test_unknown_module_and_material_are_refused(run_deck):
    from framework.problemspec import InputError
    with pytest.raises(InputError, match=r'<Module name="lineExtractX"> is not available; accepted: vorticity, minMax'):
        run_deck(text=deck().replace('name="vorticity"', 'name="lineExtractX"'))
    with pytest.raises(InputError, match="no material named 'air'"):
        run_deck(text=deck().replace("<material>blob</material>", "<material>air</material>"))


def test_one_material_is_found_whatever_the_name(run_deck):
    """As Uintah's MaterialManager::parseAndLookupMaterial: one material is material 0."""
    with open(f"{UINTAH}/advect.ups") as f:
        text = f.read().replace("</Time>", "<max_Timesteps>1</max_Timesteps></Time>")
    text = text.replace('<save label="press_equil_CC"/>', '<save label="press_equil_CC"/><save label="vorticity"/>')
    da = run_deck(text=text.replace("</Uintah_specification>", '<DataAnalysis><Module name="vorticity">'
                                    "<material>atmoshpere</material></Module></DataAnalysis></Uintah_specification>"))
    vort, _ = da.read("vorticity", 0, -1)
    assert np.abs(vort).max() < 1e-9              # uniform flow: no vorticity


def test_modules_a_component_reads_itself_are_left_to_it():
    """MPM reads <Module name="particleExtract"> itself (components/mpm/analysis.py); the framework
    leaves it, and still refuses a module nobody has."""
    from framework.analysis import read_analysis
    from framework.problemspec import InputError, ProblemSpec

    class Component:
        analysis_modules = ("particleExtract",)

    root = ProblemSpec.from_string('<a><DataAnalysis><Module name="particleExtract"/></DataAnalysis></a>', "d.ups")
    assert read_analysis(root, Component(), None) == []
    root = ProblemSpec.from_string('<a><DataAnalysis><Module name="flatPlat_heatFlux"/></DataAnalysis></a>', "d.ups")
    with pytest.raises(InputError, match="d.ups:1: .*flatPlat_heatFlux"):
        read_analysis(root, Component(), None)


def test_turbulent_fluxes_restart_continues_the_sums(tmp_path):
    """turbulentFluxes' sums and step count are carried in checkpoints: restarting the vortex
    deck from its step-5 checkpoint gives step 10's means and variances bit for bit."""
    import pathlib
    from framework.archiver import DataArchive
    from tests.conftest import pysus, pysus_ranks
    ref = pathlib.Path(__file__).parent / "uintah_reference" / "impVortices_smag_explicit.ups"
    text = ref.read_text().replace('      <save label="vel_CC"/>',
                                   '      <checkpoint timestepInterval="5" cycle="2"/>\n      <save label="vel_CC"/>')
    deck = tmp_path / "d.ups"
    deck.write_text(text)
    r = pysus_ranks(deck, "--filebase", tmp_path / "a.uda")
    assert r.returncode == 0, r.stderr[-2000:]
    r = pysus("-restart", tmp_path / "a.uda", "-t", "0", "--filebase", tmp_path / "b.uda")
    assert r.returncode == 0, r.stderr[-2000:]
    a, b = DataArchive(tmp_path / "a.uda"), DataArchive(tmp_path / "b.uda")
    assert a.times[-1] == b.times[-1]
    for label in ("mean_press_CC", "variance_vel_CC", "covariance_press_CC", "sum_Qu_Qv_Qw_vel_CC", "vel_CC"):
        assert np.array_equal(a.read(label, 0, -1)[0], b.read(label, 0, -1)[0]), label
