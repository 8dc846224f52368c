"""elastic_plastic_hp with the Gurson yield condition and Uintah's "biswajit" return.

Uintah's test_gurson_beckerdrucker_mts.ups (tests/mpm/uintah_reference/, with its material
files under inputs/MPM/MaterialData/ there): a HY-100 steel cylinder (MTS flow stress,
Mie-Gruneisen EOS, Gurson yield with a Gaussian initial porosity) hits a rigid wall
(specified_friction contact) at 227 m/s. Checked three ways:

- against sus: the deck with the cylinder's <res>[2,2,2]</res> (3013 particles, not 27 per
  cell), <max_Timesteps>30</max_Timesteps>, output every 10 steps, p.porosity saved,
  <stress_update>usl</stress_update> (Uintah's) and the linear interpolator (with
  <extraCells>[0,0,0]</extraCells>, as Uintah requires for it); both codes run it stably for
  30 steps (the impact end goes unstable in both around step 32). tests/mpm/data/sus_gurson.npz
  holds, from sus's run of it with output every step, the times of steps 10, 20, 30 and there
  p.stress, p.plasticStrain, p.porosity and p.temperature of every fourth particle of the
  cylinder (in sus's order at step 1, with its place on the particle lattice), and p.porosity
  of all particles after step 1;
- against sus with the deck's own GIMP (and usl, extraCells 1), 30 steps:
  tests/mpm/data/sus_gurson_gimp.npz holds, from sus's run with output every step, the times
  of steps 1 and 30 and there p.x, p.velocity and p.stress of the cylinder's two bottom particle
  layers and every tenth particle, with their places on the lattice and their positions at
  t = 0. The particles are made where Uintah's ParticleCreator puts them, to the bit
  (materials.lattice_positions): one ulp off, as before, a particle whose face ends on a node
  reaches it with a GIMP weight of 1e-32, Uintah's specified_friction (friction_LR's
  prominence) then counts it there, and four particles by the wall parted from sus by 4.4e-2
  of the largest velocity in the first step;
- the initial porosity of the particles that stay elastic is sus's to the last bit (Uintah's
  seeded generator, drawn in its order of particle creation);
- the physics of the pieces: the yield function is zero on the analytic Gurson surface (pure
  hydrostatic stress at a porosity, and von Mises at f = 0), a trial stress just inside that
  surface stays elastic and one just outside yields, the return puts the deviatoric stress
  on the matrix flow stress sigma_y(ep, epdot) (Uintah's algorithm scales it there), and the
  porosity grows by the closed form (1 - f) tr D dt + A(ep) sqrt(2/3) |dev D| dt.
"""
import math
from pathlib import Path

import numpy as np
import pytest

from components.mpm.constitutive import elastic_plastic_hp as hp
from components.mpm.constitutive import plasticity_kernels as pk
from components.mpm.materials import MATERIAL
from framework.problemspec import InputError, ProblemSpec

from framework.archiver import DataArchive
from framework.controller import Controller

HERE = Path(__file__).parent
DECK = HERE / "uintah_reference" / "test_gurson_beckerdrucker_mts.ups"
SUS = HERE / "data" / "sus_gurson.npz"
SUS_GIMP = HERE / "data" / "sus_gurson_gimp.npz"
Q = np.array([1.5, 1.0, 2.25, 4.0, 0.05])          # GursonYieldSteel.xml: q1, q2, q3, k, f_c


_SUS_RUN = (("<res>[3,3,3]</res>", "<res>[2,2,2]</res>"),
            ("<timestep_multiplier>0.4</timestep_multiplier>",
             "<timestep_multiplier>0.4</timestep_multiplier><max_Timesteps>30</max_Timesteps>"))


def _deck_with(edits):
    """The deck with each (old, new) replaced, its include files found from a temporary folder."""
    text = DECK.read_text()
    for old, new in _SUS_RUN + edits:
        assert old in text, old
        text = text.replace(old, new)
    return text.replace('href="inputs/', f'href="{DECK.parent}/inputs/')


def sus_copy():
    """The deck as sus ran it for the reference (module docstring)."""
    return _deck_with((("<extraCells> [1,1,1]  </extraCells>", "<extraCells> [0,0,0]  </extraCells>"),
                       ("<outputTimestepInterval>5</outputTimestepInterval>",
                        '<outputTimestepInterval>10</outputTimestepInterval><save label = "p.porosity"/>'),
                       ("<interpolator>gimp</interpolator>",
                        "<interpolator>linear</interpolator><stress_update>usl</stress_update>")))


def sus_copy_gimp():
    """The deck as sus ran it for sus_gurson_gimp.npz (module docstring): GIMP, output every step."""
    return _deck_with((("<outputTimestepInterval>5</outputTimestepInterval>",
                        "<outputTimestepInterval>1</outputTimestepInterval>"),
                       ("<interpolator>gimp</interpolator>",
                        "<interpolator>gimp</interpolator><stress_update>usl</stress_update>")))


def run(text, tmp_path):
    """Run deck text from a file (its <include>s are read when the file is)."""
    (tmp_path / "gurson.ups").write_text(text)
    ctl = Controller(str(tmp_path / "gurson.ups"), quiet=True, filebase=str(tmp_path / "gurson.uda"))
    ctl.run()
    return ctl, DataArchive(ctl.archiver.dir)


def lattice_key(x, res=2):
    """A particle's place on its object's lattice (the deck's grid, res per cell)."""
    dx, anchor = np.array([0.5e-3, 3.7e-2 / 35, 0.5e-3]), np.array([0.0, -0.2e-2, 0.0])
    k = np.round((x - anchor) / (dx / res) - 0.5).astype(np.int64)
    return k[:, 0] + 10000 * (k[:, 1] + 10000 * k[:, 2])


# -- the pieces -----------------------------------------------------------------------------
def test_yield_function_is_zero_on_the_analytic_surface():
    """The Gurson-Tvergaard surface sigma_eq^2/sigma_y^2 + 2 q1 f* cosh(q2 tr/(2 sigma_y)) =
    1 + q3 f*^2 (f* = f_c + k (f - f_c) above f_c): at sigma_eq and porosity f, the trace on
    it is tr = (2 sigma_y/q2) acosh((1 + q3 f*^2 - (sigma_eq/sigma_y)^2)/(2 q1 f*)). There the
    yield function is zero and the effective stress is sigma_eq; a trace 0.1 % smaller (in
    size) is inside, 0.1 % larger outside, in tension and compression; at f = 0 it is von Mises.
    (At the hydrostatic apex itself, where the bracket is zero, Uintah's formula falls to von
    Mises with sigma_y, as pysus's does.)"""
    sy = 1.2e9
    for f in (0.002, 0.01, 0.04, 0.06):
        fs = f if f <= Q[4] else Q[4] + Q[3] * (f - Q[4])
        for ratio in (0.2, 0.6, 0.95 * math.sqrt(1.0 + Q[2] * fs * fs - 2.0 * Q[0] * fs)):
            seq = ratio * sy
            tr = 2.0 * sy / Q[1] * math.acosh((1.0 + Q[2] * fs * fs - ratio * ratio) / (2.0 * Q[0] * fs))
            for sign in (1.0, -1.0):
                phi, s_eff = pk.gurson_yield(Q, seq, sy, sign * tr, f)
                assert abs(phi) < 1e-10 * sy * sy and s_eff == pytest.approx(seq, rel=1e-9)
                assert pk.gurson_yield(Q, seq, sy, sign * 0.999 * tr, f)[0] < 0.0
                assert pk.gurson_yield(Q, seq, sy, sign * 1.001 * tr, f)[0] > 0.0
    assert pk.gurson_yield(Q, 0.9e9, sy, -3.0e9, 0.0) == (0.9e9 ** 2 - sy * sy, sy)


MATERIAL_XML = """<material>
  <density>7860.0</density><thermal_conductivity>38</thermal_conductivity><specific_heat>477</specific_heat>
  <room_temp>294.0</room_temp><melt_temp>2000.0</melt_temp>
  <constitutive_model type="elastic_plastic_hp">
    <shear_modulus>69.0e9</shear_modulus><bulk_modulus>150.0e9</bulk_modulus>
    <flow_model type="isotropic_hardening"><K>2.0e9</K><sigma_Y>1.0e9</sigma_Y></flow_model>
    <equation_of_state type="default_hypo"/>
    <yield_condition type="gurson"><q1>1.5</q1><q2>1.0</q2><q3>2.25</q3><k>4.0</k><f_c>0.05</f_c></yield_condition>
    <initial_mean_porosity>0.02</initial_mean_porosity>
    <plastic_convergence_algo>biswajit</plastic_convergence_algo>
  </constitutive_model>
</material>"""


def params(xml=MATERIAL_XML):
    mat = ProblemSpec.from_string(xml)
    return hp.read_params(mat.child("constitutive_model"), mat, mat.read(MATERIAL))


def one_step(P, L, stress, f, ep=0.0, epdot=0.0, edot=1e4, dt=1e-8):
    """One update of one particle at F = I; returns (stress, ep, epdot, f)."""
    F0 = np.eye(3)[None]
    F1 = (np.eye(3) + L * dt)[None]
    old = (np.array([ep]), np.array([epdot]), np.zeros(1), np.array([edot]), np.array([f]), np.zeros(1),
           np.array([294.0]))
    new = tuple(np.zeros(1) for _ in range(7))
    out = np.zeros((1, 3, 3))
    hp.update(P, L[None], F0, F1, np.array([1e-9]), np.array([7.86e-6]), np.zeros((1, 3)), dt, stress[None].copy(),
              out, np.zeros(1), old, new)
    return out[0], new[0][0], new[1][0], new[4][0]


def test_gurson_yield_check_and_return():
    """A shear sigma_eq = 0.3 sigma_y with f = 0.02 and a hydrostatic tension 1 % inside the
    Gurson surface stays elastic under a small isochoric stretch (far inside the von Mises
    surface); 1 % outside, stretched at 1e4/s, it yields by the biswajit estimate (its plastic
    rate below the last step's strain rate 1e5/s): afterwards sqrt(3/2)|s| = sigma_y(ep) of the
    matrix (Uintah scales the trial stress there), and the porosity grows by the closed form,
    with (1 - f) tr D in expansion."""
    P = params()
    sy, f, dt = 1.0e9, 0.02, 1e-8
    tr = 2.0 * sy / Q[1] * math.acosh((1.0 + Q[2] * f * f) / (2.0 * Q[0] * f))
    s_dev = np.diag([1.0, -0.5, -0.5]) * 2.0e8          # sigma_eq = 3e8
    seq = 3.0e8
    # the tr at which this shear is on the surface (the trial trace adds 2 mu tr(D) dt = 0 here)
    tr_on = 2.0 * sy / Q[1] * math.acosh((1.0 + Q[2] * f * f - (seq / sy) ** 2) / (2.0 * Q[0] * f))
    assert tr_on < tr
    L = np.diag([1.0, -0.5, -0.5]) * 1e2                 # isochoric stretch: trial s grows by 2 mu eta dt
    inside = s_dev + np.eye(3) * 0.99 * tr_on / 3.0
    s1, ep1, epdot1, f1 = one_step(P, L, inside, f)
    assert ep1 == 0.0 and f1 == f
    assert np.allclose(s1, inside + 2.0 * 69e9 * L * dt, rtol=0, atol=1e-6 * seq)
    # strain at 1e4/s from the surface: the biswajit estimate (epdot <= the last step's rate)
    L = np.diag([1.0, -0.5, -0.5]) * 1e4
    on = s_dev + np.eye(3) * 1.01 * tr_on / 3.0
    s1, ep1, epdot1, f1 = one_step(P, L, on, f, edot=1e5)
    assert ep1 > 0.0 and epdot1 <= 1e5 and ep1 == pytest.approx(epdot1 * dt, rel=1e-12)
    dev = s1 - np.trace(s1) / 3.0 * np.eye(3)
    assert math.sqrt(1.5) * np.linalg.norm(dev) == pytest.approx(1.0e9 + 2.0e9 * ep1, rel=1e-12)
    eta = L - np.trace(L) / 3.0 * np.eye(3)
    A = 0.1 / (0.1 * math.sqrt(2 * math.pi)) * math.exp(-0.5 * ((ep1 - 0.3) / 0.1) ** 2)
    assert f1 == pytest.approx(f + dt * A * math.sqrt(np.sum(eta * eta) / 1.5), rel=1e-12)
    # in expansion the voids also grow: + (1 - f) tr D dt
    L = np.diag([1.0, -0.4, -0.4]) * 1e4
    s1, ep1, epdot1, f1 = one_step(P, L, on, f, edot=1e5)
    eta = L - np.trace(L) / 3.0 * np.eye(3)
    A = 0.1 / (0.1 * math.sqrt(2 * math.pi)) * math.exp(-0.5 * ((ep1 - 0.3) / 0.1) ** 2)
    assert ep1 > 0.0
    assert f1 == pytest.approx(f + dt * ((1 - f) * np.trace(L) + A * math.sqrt(np.sum(eta * eta) / 1.5)), rel=1e-12)


def test_gaussian_is_uintahs():
    """Uintah's Gaussian(0.002, 0.002, seed 0) (MusilRNG, Box-Muller) gives, in the order sus
    made the cylinder's particles (one patch), the porosity of those still elastic after the
    first step (2759 of 3013), to the last bit."""
    sus = np.load(SUS)
    f, elastic = sus["porosity_step1_all"], sus["elastic_step1_all"]
    g = hp.initial_porosity(len(f), 0.002, 0.002)
    assert elastic.sum() > 2700 and np.array_equal(g[elastic], f[elastic])


# -- the deck against sus ----------------------------------------------------------------
def _followed(da, k, ids):
    """The steel's particles at output k and the indices of the particles with the given IDs."""
    p = da.particles(1, k)
    where = {v: i for i, v in enumerate(p["p.particleID"])}
    return p, [where[v] for v in ids]


def test_deck_as_sus(tmp_path):
    """The copy (module docstring) against sus over 30 steps (through the impact: plastic
    strain to 0.25 and porosity to 0.2, past f_c = 0.05, in the particles compared 0.117 and
    0.065): the initial porosity sus's to the bit, and at steps 10, 20, 30 the time, stress,
    plastic strain, porosity and temperature within TOL (measured: see there)."""
    _, da = run(sus_copy(), tmp_path)
    sus = np.load(SUS)
    steps = list(da.timesteps)
    assert steps == [0, 10, 20, 30]
    first = da.particles(1, 0)
    at = {k: i for i, k in enumerate(lattice_key(first["p.x"]))}
    ids = first["p.particleID"][[at[k] for k in sus["key"]]]
    elastic = sus["elastic_step1_all"][::4]
    assert np.array_equal(first["p.porosity"][[at[k] for k in sus["key"]]][elastic],
                          sus["porosity_step1_all"][::4][elastic])
    for j, step in enumerate(sus["timestep"]):
        k = steps.index(step)
        assert da.times[k] == pytest.approx(sus["time"][j], rel=1e-10)
        p, i = _followed(da, k, ids)
        s, ep, f, T = p["p.stress"][i], p["p.plasticStrain"][i], p["p.porosity"][i], p["p.temperature"][i]
        assert np.abs(s - sus["stress"][j]).max() < TOL["stress"] * np.abs(sus["stress"][j]).max(), step
        assert np.abs(ep - sus["plasticStrain"][j]).max() < TOL["plasticStrain"], step
        assert np.abs(f - sus["porosity"][j]).max() < TOL["porosity"], step
        assert np.abs(T - sus["temperature"][j]).max() < TOL["temperature"], step
    assert sus["porosity"][-1].max() > 0.06 and sus["plasticStrain"][-1].max() > 0.11


# measured: stress 2.0e-8 of the largest, plastic strain 3.1e-9, porosity 1.8e-10, temperature
# 7.8e-6 K (the heat conduction's round-off), time 6.4e-12 (relative)
TOL = {"stress": 1e-7, "plasticStrain": 2e-8, "porosity": 2e-9, "temperature": 3e-5}


def test_gimp_deck_as_sus(tmp_path):
    """The GIMP copy (module docstring) against sus: the particles made at sus's positions to the
    bit, and at steps 1 and 30 (the stress reaching 5.2e9 Pa at the wall) the
    time, the displacement, velocity and stress within TOL_GIMP of the largest (measured: see
    there; with the particles an ulp off: 4.4e-2, 4.4e-2 and 1.4e-1 at step 1)."""
    _, da = run(sus_copy_gimp(), tmp_path)
    sus = np.load(SUS_GIMP)
    steps = list(da.timesteps)
    first = da.particles(1, 0)
    at = {k: i for i, k in enumerate(lattice_key(first["p.x"]))}
    mine = [at[k] for k in sus["key"]]
    assert np.array_equal(first["p.x"][mine], sus["x0"])
    ids = first["p.particleID"][mine]
    for j, step in enumerate(sus["timestep"]):
        k = steps.index(step)
        assert da.times[k] == pytest.approx(sus["time"][j], rel=1e-12)
        p, i = _followed(da, k, ids)
        for name, got, ref in (("displacement", p["p.x"][i] - sus["x0"], sus["x"][j] - sus["x0"]),
                               ("velocity", p["p.velocity"][i], sus["velocity"][j]),
                               ("stress", p["p.stress"][i], sus["stress"][j])):
            assert np.abs(got - ref).max() < TOL_GIMP[name] * np.abs(ref).max(), (step, name)
    assert np.abs(sus["stress"][-1]).max() > 5e9


# measured (relative to the largest): displacement 4.3e-10, velocity 3.3e-9, stress 8.9e-9
TOL_GIMP = {"displacement": 4e-9, "velocity": 3e-8, "stress": 1e-7}


@pytest.mark.parametrize("old,new,words", [
    ("<plastic_convergence_algo>  biswajit  </plastic_convergence_algo>", "",
     ("gurson", "biswajit", "plastic_convergence_algo")),
    ("<plastic_convergence_algo>  biswajit  </plastic_convergence_algo>",
     "<plastic_convergence_algo>newton</plastic_convergence_algo>", ("plastic_convergence_algo", "biswajit")),
    ("<initial_porosity_distrib>      gauss </initial_porosity_distrib>",
     "<initial_porosity_distrib>weibull</initial_porosity_distrib>", ("initial_porosity_distrib", "gauss")),
    ("<mu>0.0</mu>", "<mu>0.0</mu><include_rotation>true</include_rotation>", ("include_rotation",)),
    ("<stddevstrain_nucleation>       0.1", "<stddevstrain_nucleation>       0.0", ("stddevstrain_nucleation",)),
])
def test_bad_input_is_one_line(tmp_path, old, new, words):
    text = sus_copy()
    assert old in text
    with pytest.raises(InputError) as e:
        run(text.replace(old, new), tmp_path)
    msg = str(e.value)
    assert "\n" not in msg and (".ups:" in msg or ".xml:" in msg)     # the file and line of the tag
    for w in words:
        assert w in msg, msg
