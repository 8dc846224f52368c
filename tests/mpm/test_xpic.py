"""<XPIC2> (Hammerquist & Nairn 2017, Uintah's SerialMPM): the particle velocity 2 v+ - v++ + a dt
and position from the grid velocity smoothed once (v+) and twice (v++) through the particles.

A uniform translation is a fixed point of the smoothing (v+ = v++ = v_p, a = 0), so XPIC(2)
moves the particles as FLIP does; Uintah's NairnFrictionTest with <XPIC2> against sus (the
deck is tests/mpm/nairn_friction.ups, its header says how it was changed, here with <XPIC2>
added and 4 steps); 1 and 2 MPI ranks agree bitwise; the inputs it is refused with."""
import os

import numpy as np
import pytest

from framework.archiver import DataArchive
from framework.problemspec import InputError
from tests.conftest import ROOT, pysus_ranks

from .helpers import run

HERE = os.path.dirname(__file__)
NAIRN = os.path.join(HERE, "nairn_friction.ups")


def nairn(steps=4):
    text = open(NAIRN).read()
    for old, new in {"<stress_update>usl</stress_update>": "<stress_update>usl</stress_update><XPIC2>true</XPIC2>",
                     "<max_Timesteps>3</max_Timesteps>": f"<max_Timesteps>{steps}</max_Timesteps>"}.items():
        assert old in text, old
        text = text.replace(old, new)
    return text


def translation(xpic):
    """A 2D GIMP block moving at (3, -2) m/s, unstressed, away from the walls, on 2 patches."""
    return f"""<?xml version="1.0" encoding="iso-8859-1"?>
<Uintah_specification><Meta><title>uniform translation</title></Meta>
  <SimulationComponent type="mpm"/>
  <Time><maxTime>1</maxTime><initTime>0</initTime><delt_min>0</delt_min><delt_max>1</delt_max>
    <timestep_multiplier>0.4</timestep_multiplier><max_Timesteps>3</max_Timesteps></Time>
  <DataArchiver><filebase>t.uda</filebase><outputTimestepInterval>1</outputTimestepInterval>
    <save label="p.x"/><save label="p.velocity"/><save label="p.stress"/></DataArchiver>
  <MPM><interpolator>gimp</interpolator><stress_update>usl</stress_update><XPIC2>{xpic}</XPIC2></MPM>
  <PhysicalConstants><gravity>[0,0,0]</gravity></PhysicalConstants>
  <MaterialProperties><MPM><material name="block"><density>1000</density>
    <constitutive_model type="comp_neo_hook"><bulk_modulus>2.0e9</bulk_modulus>
      <shear_modulus>1.0e9</shear_modulus></constitutive_model>
    <thermal_conductivity>1</thermal_conductivity><specific_heat>1</specific_heat>
    <geom_object><box label="b"><min>[0.031,0.032,0]</min><max>[0.067,0.061,0.005]</max></box>
      <res>[2,2,1]</res><velocity>[3.0,-2.0,0]</velocity><temperature>300</temperature></geom_object>
  </material><contact><type>null</type></contact></MPM></MaterialProperties>
  <Grid><Level><Box label="1"><lower>[0,0,0]</lower><upper>[0.1,0.1,0.005]</upper>
    <resolution>[20,20,1]</resolution><patches>[2,1,1]</patches><extraCells>[1,1,1]</extraCells>
  </Box></Level></Grid>
</Uintah_specification>"""


def test_uniform_translation_moves_as_flip(tmp_path):
    """v+ = sum S v_i = v_p and v++ = v_p where every node's velocity is v_p (partition of
    unity), a = 0: XPIC(2) gives FLIP's v and x up to round-off; the stress stays zero."""
    (_, a), (_, b) = (run(translation(x), tmp_path, x) for x in ("true", "false"))
    for k in (1, 3):
        pa, pb = a.particles(0, k), b.particles(0, k)
        assert len(pa["p.x"]) == 165
        assert np.abs(pa["p.velocity"] - [3.0, -2.0, 0.0]).max() < 1e-12
        assert np.abs(pa["p.x"] - pb["p.x"]).max() < 1e-15
        assert np.abs(pa["p.velocity"] - pb["p.velocity"]).max() < 1e-12
        assert np.abs(pa["p.stress"]).max() < 1e-3         # Pa, of a 1e9 Pa modulus
    assert np.abs(a.particles(0, 3)["p.x"] - a.particles(0, 0)["p.x"] - 3 * a.times[1] * np.array([3.0, -2.0, 0])
                  ).max() < 1e-14


def test_nairn_friction_xpic2_equals_uintahs_sus(tmp_path):
    """p.x and p.velocity of block and plane after steps 2, 3, 4 against sus's run of the same deck
    (tests/mpm/data/sus_nairn_friction_xpic2.npz, puda's 9 digits; measured: x within 5e-11 m,
    v within 3.2e-9 of the largest, 7e-3 m/s at step 4). XPIC(2) changes the block's velocity
    by 5 % from FLIP's at step 3 (3.81e-3 against 3.99e-3 m/s), so FLIP would fail here."""
    ref = np.load(os.path.join(HERE, "data", "sus_nairn_friction_xpic2.npz"))
    _, da = run(nairn(), tmp_path)
    for step in (2, 3, 4):
        assert da.times[step] == pytest.approx(float(ref[f"time_step{step}"]), rel=1e-12)
        vmax = np.abs(ref[f"velocity0_step{step}"]).max()
        for m in (0, 1):
            p = da.particles(m, step)
            sx, sv = ref[f"x{m}_step{step}"], ref[f"velocity{m}_step{step}"]
            assert len(p["p.x"]) == len(sx)
            match = np.argmin(((p["p.x"][:, None, :] - sx[None, :, :]) ** 2).sum(-1), axis=1)
            assert np.abs(p["p.x"] - sx[match]).max() < 1e-10, (step, m)
            assert np.abs(p["p.velocity"] - sv[match]).max() < 1e-8 * vmax, (step, m)


def test_two_ranks_bitwise(tmp_path):
    """The deck's two patches on 1 and 2 ranks, with MUSL (pysus's default, whose remap updates
    the ghost particles too): g.velSPSSP's sums run in particle-ID order over owned and ghost
    particles, so the particles agree to the bit."""
    path = tmp_path / "nairn.ups"
    path.write_text(nairn(steps=3).replace("<stress_update>usl</stress_update>", ""))
    runs = {}
    for n in (1, 2):
        uda = tmp_path / f"nairn_{n}.uda"
        r = pysus_ranks(path, "--filebase", uda, np_=n, timeout=300)
        assert r.returncode == 0, r.stderr[-2000:]
        runs[n] = DataArchive(uda)
    for m in (0, 1):
        a, b = runs[1].particles(m, -1), runs[2].particles(m, -1)
        oa, ob = np.argsort(a["p.particleID"]), np.argsort(b["p.particleID"])
        assert np.array_equal(a["p.particleID"][oa], b["p.particleID"][ob]) and len(oa) > 90
        for lab in ("p.x", "p.velocity", "p.stress"):
            assert np.array_equal(a[lab][oa], b[lab][ob]), (m, lab)


@pytest.mark.parametrize("deck, edit, words", [
    ("MPM/thick_cylinder_axi.ups", "<axisymmetric>true</axisymmetric>", ("XPIC2", "axisymmetric", "accepted: false")),
    ("MPMICE/slab_rest.ups", "<interpolator>linear</interpolator>", ("XPIC2", "MPMICE", "accepted: false")),
])
def test_refused_inputs(tmp_path, deck, edit, words):
    """Axisymmetric MPM and MPMICE (whose Uintah counterpart schedules no XPIC passes) refuse it."""
    text = open(ROOT / "inputs" / deck).read()
    assert edit in text
    with pytest.raises(InputError) as e:
        run(text.replace(edit, edit + "<XPIC2>true</XPIC2>", 1), tmp_path)
    for w in words:
        assert w in str(e.value), str(e.value)
