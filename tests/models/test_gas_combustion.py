"""gasCombustion (components/models/gas_combustion.py, gas_mechanism.py, gas_kinetics.py): a
reacting hydrogen-air mixture in ICE, against sus and against the physics of a closed reactor.

tests/models/cv_hydrogen.ups is Uintah's cvHydrogen2.ups (RX_MODELS: stoichiometric hydrogen-air
at 1500 K in a closed box, Burke et al.'s mechanism, Uintah's Burke2012Modified.xml, copied here)
on one cell instead of 27 uniform ones, run to 30 us: the mixture ignites after about 10 us and
heats to 2496 K. data/sus_cv_hydrogen.npz is sus's output on that deck (one rank, `sus
cv_hydrogen.ups`, read with framework.uintah_uda): every output's temp_CC, press_CC, rho_CC,
specific_heat, five species and HeatReleaseRate, and the time of each of its 306 steps.

tests/models/gas_pocket3d.ups: a pocket of hydrogen-rich gas (Y_H2 0.1, O2 0.15) in stoichiometric
air at 1000 K, 10 x 4 x 4 cells, no chemistry: its higher R_mix pushes the gas out while the
species diffuse (mixture-averaged, with the enthalpy they carry), so the test runs ICE's whole
step with the model's caloric EOS, advected species and the diffusion. data/sus_gas_pocket3d.npz:
sus's fields after each of its 10 steps on the same deck without the advection attributes
(pysus's `limiter="BarthJespersen" dissipationHeating="false"` is Uintah's scheme, which sus's
parser does not accept as attributes). Measured: every field to 1.2e-14 of its range.

tests/models/hydrogen_flame.ups: Uintah's hydrogenFlame1 (a stoichiometric laminar flame between LODI
faces, initialised from a 1D profile file, the mixture's viscosity and thermal conductivity in
ICE's terms) on 150 cells around the flame, 3 patches, 60 steps; data/flame_profile_phi1.00.dat is
every 8th row of Uintah's profile there. data/sus_hydrogen_flame.npz: sus's fields after steps 30
and 60 on that deck without the advection attributes. Measured: every field to 2e-13 of its maximum.

Measured on cv_hydrogen: the same 306 steps to round-off, temperature and pressure to 3e-14 of
sus's maxima through the ignition, the species and HeatReleaseRate to 1.1e-13 (dt_chemistry, the
smallest adaptive sub-step, to 1e-2: it follows the integrator's accept/reject decisions, not a result).
"""
import os

import numpy as np
import pytest

from components.models import gas_kinetics as GK
from components.models.gas_mechanism import ATOMIC_WEIGHTS, FALLOFF, read_mechanism
from framework.problemspec import InputError

HERE = os.path.dirname(__file__)
DECK = os.path.join(HERE, "cv_hydrogen.ups")
MECH = os.path.join(HERE, "Burke2012Modified.xml")


@pytest.fixture(scope="module")
def mech():
    return read_mechanism(MECH, "N2")


def test_mechanism_is_read(mech):
    """Burke's 9 species and 23 reactions, molecular weights from Uintah's atomic weights."""
    assert mech.names == ["H", "H2", "O", "OH", "H2O", "O2", "HO2", "H2O2", "N2"]
    assert mech.closure == 8
    assert mech.mw[4] == 2 * ATOMIC_WEIGHTS["H"] + ATOMIC_WEIGHTS["O"]
    assert len(mech.rxn_type) == 23 and np.count_nonzero(mech.rxn_type == FALLOFF) == 2
    assert (mech.t_low, mech.t_mid, mech.t_high) == (300.0, 1000.0, 3500.0)     # N2 from 300 K


def test_mechanism_errors_name_file_and_line(tmp_path):
    text = open(MECH).read()
    with pytest.raises(InputError, match="closure species Ar is not in the mechanism"):
        read_mechanism(MECH, "Ar")
    bad = tmp_path / "bad.xml"
    bad.write_text(text.replace("<reactants>H:1 O2:1</reactants>", "<reactants>H:1 XO2:1</reactants>", 1))
    with pytest.raises(InputError, match="unknown species XO2") as e:
        read_mechanism(str(bad), "N2")
    assert e.value.filename.endswith("bad.xml") and e.value.line == 202


def _uintah_rates(mech, t, conc):
    """Uintah's ReactionMech::globalRates written out directly: A T^b exp(-Ea / RT), the dense
    third-body sum, Troe's blend and Kc = exp(sum_R g - sum_P g) (1e-6 P_ATM / RT)^dn."""
    from components.models.gas_mechanism import P_ATM, RU
    rt = RU * t
    lo = 1 if t > mech.t_mid else 0
    a = mech.nasa[lo]
    g = a[:, 0] * (1 - np.log(t)) - a[:, 1] / 2 * t - a[:, 2] / 6 * t ** 2 - a[:, 3] / 12 * t ** 3 \
        - a[:, 4] / 20 * t ** 4 + a[:, 5] / t - a[:, 6]
    q = np.zeros(len(mech.rxn_type))
    for r, kind in enumerate(mech.rxn_type):
        A, b, ea, A0, b0, ea0 = mech.arrhenius[r]
        kf = A * t ** b * np.exp(-ea / rt)
        m = mech.efficiencies[r] @ conc if kind else 1.0
        if kind == FALLOFF:
            pr = max(A0 * t ** b0 * np.exp(-ea0 / rt) * m / kf, 1e-300)
            ta, t3, t1, t2 = mech.troe[r]
            fc = (1 - ta) * np.exp(-t / t3) + ta * np.exp(-t / t1) + (np.exp(-t2 / t) if mech.troe_t2[r] else 0.0)
            c, n = -0.4 - 0.67 * np.log10(fc), 0.75 - 1.27 * np.log10(fc)
            f = 10 ** (np.log10(fc) / (1 + ((np.log10(pr) + c) / (n - 0.14 * (np.log10(pr) + c))) ** 2))
            kf, m = kf * pr * f / (1 + pr), 1.0
        reac, prod = [k for k in mech.reactants[r] if k >= 0], [k for k in mech.products[r] if k >= 0]
        kc = np.exp(g[reac].sum() - g[prod].sum()) * (1e-6 * P_ATM / rt) ** (len(prod) - len(reac))
        q[r] = m * (kf * np.prod(conc[reac]) - kf / kc * np.prod(conc[prod]))
    return q


@pytest.mark.parametrize("t", [800.0, 1500.0, 2500.0])
def test_rates_are_uintahs(mech, t):
    """The kernel's rates (one exponential per forward and per reverse rate, sparse third-body
    efficiencies) are Uintah's formulas to round-off: each net rate within 1e-12 of its forward
    rate, on a mixture with every species present."""
    kin = GK.kinetics(mech)
    conc = np.array([2e-9, 3e-6, 1e-9, 4e-9, 2e-6, 1.5e-6, 3e-10, 1e-10, 8e-6]) * (1500.0 / t)
    g, q = np.zeros(9), np.zeros(23)
    GK.rates_of_progress(kin, t, conc, g, q)
    ref = _uintah_rates(mech, t, conc)
    fwd = np.array([abs(mech.arrhenius[r, 0]) * t ** mech.arrhenius[r, 1] * np.exp(-mech.arrhenius[r, 2] / (GK.RU * t))
                    * np.prod([conc[k] for k in mech.reactants[r] if k >= 0]) for r in range(23)])
    assert np.all(np.abs(q - ref) <= 1e-12 * np.maximum(fwd, np.abs(ref)))
    assert np.any(np.abs(ref) > 0)


def _one_cell(mech, t0, y0, rho, dt, steps):
    """A closed constant-volume reactor integrated by the model's kernel: (T, Y) after each step,
    T from the sensible energy that the sources give (as ICE does)."""
    kin = GK.kinetics(mech)
    nt = len(mech.names) - 1
    shape = (1, 1, 1)
    lo, hi = np.zeros(3, np.int64), np.ones(3, np.int64)
    temp = np.full(shape, t0)
    y = np.array(y0, float).reshape(nt, 1, 1, 1)
    rho_a = np.full(shape, rho)
    out = []
    for _ in range(steps):
        src, eng = np.zeros_like(y), np.zeros(shape)
        hrr, dtc, lim = np.zeros(shape), np.zeros(shape), np.zeros(shape)
        es = np.zeros(shape)
        GK.energy_cells(kin, y, lo, hi, (temp, es))
        st = GK.chemistry_cells(kin, y, temp, rho_a, src, eng, dtc, lim, hrr, lo, hi, dt, 1.0, 1e-10, 1e-12,
                                1e-12, 0.9, 2.0, 0.1, np.array([200.0, 3500.0]), np.array([120.0, 4900.0]), True)
        assert st[0] == GK.OK
        y = y + src
        es += eng / rho
        GK.temperature_cells(kin, y, lo, hi, (es, temp, 200.0, 3500.0))
        out.append((float(temp[0, 0, 0]), y[:, 0, 0, 0].copy()))
    return out


def test_closed_reactor_conserves_elements_and_energy(mech):
    """Stoichiometric hydrogen-air at 1500 K, 0.17 kg/m^3: the H and O atoms and the absolute
    internal energy sum Y_k u_k(T) / M_k (formation included) stay constant through the ignition,
    and the burned gas ends at chemical equilibrium (every reaction's net rate small next to
    its forward rate)."""
    y0 = [0.0, 0.028522387527567396, 0.0, 0.0, 0.0, 0.22635400697103147, 0.0, 0.0]
    rho = 0.1698944217103173
    hist = _one_cell(mech, 1500.0, y0, rho, 1e-6, 400)
    kin = GK.kinetics(mech)
    counts = {"H": [1, 2, 0, 1, 2, 0, 1, 2, 0], "O": [0, 0, 1, 1, 1, 2, 2, 2, 0]}

    def full(yt):
        return np.append(yt, 1.0 - yt.sum())

    def atoms(y, el):
        return sum(y[k] * counts[el][k] / mech.mw[k] for k in range(9))

    def u_abs(t, y):
        return sum(y[k] * GK.energy_molar(kin, k, t) / mech.mw[k] * 1e3 for k in range(9))

    y_first = full(np.array(y0))
    t_end, y_end = hist[-1][0], full(hist[-1][1])
    assert t_end > 2800.0                                   # it burned
    for el in counts:
        assert atoms(y_end, el) == pytest.approx(atoms(y_first, el), rel=1e-12)
    assert u_abs(t_end, y_end) == pytest.approx(u_abs(1500.0, y_first), rel=1e-10, abs=1e-3 * 2e6)
    conc = np.array([1e-3 * rho * y_end[k] / mech.mw[k] for k in range(9)])
    g, q = np.zeros(9), np.zeros(23)
    GK.rates_of_progress(kin, t_end, conc, g, q)
    fwd = np.zeros(23)
    rt = GK.RU * t_end
    for r in range(23):
        a = mech.arrhenius[r]
        fwd[r] = a[0] * t_end ** a[1] * np.exp(-a[2] / rt) * np.prod([conc[k] for k in mech.reactants[r] if k >= 0])
    main = fwd > 1e-6 * fwd.max()
    assert np.all(np.abs(q[main]) < 1e-3 * fwd[main])


def test_cv_hydrogen_against_sus(tmp_path):
    """The deck's 306 steps and every output through the ignition, against sus."""
    from framework.archiver import DataArchive
    from framework.controller import Controller
    ref = np.load(os.path.join(HERE, "data", "sus_cv_hydrogen.npz"))
    c = Controller(DECK, quiet=True, filebase=str(tmp_path / "cv.uda"))
    c.run()
    da = DataArchive(c.archiver.dir)
    assert c.timestep == len(ref["step_times"]) - 1            # sus's log counts its initialization as step 0
    assert c.t == pytest.approx(ref["step_times"][-1], rel=1e-12)
    checked = 0
    for i, t in enumerate(da.times):
        j = np.flatnonzero(np.isclose(ref["times"], t, rtol=1e-12, atol=0))
        if t == 0.0 or not j.size:
            continue
        j = j[0]
        for lab, tol in (("temp_CC", 1e-12), ("press_CC", 1e-12), ("rho_CC", 1e-13), ("specific_heat", 1e-12),
                         ("scalar-YH2", 1e-11), ("scalar-YO2", 1e-12), ("scalar-YH2O", 1e-11),
                         ("scalar-YOH", 1e-11), ("scalar-YH", 1e-11), ("HeatReleaseRate", 1e-11)):
            ours = float(np.squeeze(da.read(lab, 0, i)[0]))
            scale = max(abs(ref[lab]).max(), 1e-300)
            assert abs(ours - ref[lab][j]) <= tol * scale, (lab, t, ours, ref[lab][j])
        checked += 1
    assert checked == 15
    assert ref["temp_CC"][-1] > 2400.0                       # the comparison spans the ignition


def test_pocket3d_against_sus(tmp_path):
    """Flow, advected species, diffusion and the caloric EOS over 10 steps in 3D, against sus."""
    from framework.archiver import DataArchive
    from framework.controller import Controller
    ref = np.load(os.path.join(HERE, "data", "sus_gas_pocket3d.npz"))
    c = Controller(os.path.join(HERE, "gas_pocket3d.ups"), quiet=True, filebase=str(tmp_path / "p.uda"))
    c.run()
    da = DataArchive(c.archiver.dir)
    times = [t for t in da.times if t > 0.0]
    assert np.allclose(times, ref["times"], rtol=1e-13, atol=0)
    for j in range(len(times)):
        for lab in ("temp_CC", "press_CC", "rho_CC", "vel_CC", "scalar-YH2", "scalar-YO2", "specific_heat"):
            ours = da.read(lab, 0, j + 1)[0]
            theirs = ref[lab][j]
            span = np.ptp(ref[lab]) if np.ptp(ref[lab]) > 0 else 1.0
            assert np.max(np.abs(ours.reshape(theirs.shape) - theirs)) <= 1e-13 * span, (lab, j)
    moved = da.read("scalar-YH2", 0, -1)[0] - da.read("scalar-YH2", 0, 0)[0]
    assert np.abs(moved).max() > 1e-3                      # the species did move


def test_hydrogen_flame_against_sus(tmp_path):
    """A laminar flame from <initProfile> between LODI faces, with the mixture's per-cell viscosity
    and thermal conductivity in ICE's stress, conduction and delT, over 60 steps against sus."""
    from framework.archiver import DataArchive
    from framework.controller import Controller
    ref = np.load(os.path.join(HERE, "data", "sus_hydrogen_flame.npz"))
    c = Controller(os.path.join(HERE, "hydrogen_flame.ups"), quiet=True, filebase=str(tmp_path / "f.uda"))
    c.run()
    da = DataArchive(c.archiver.dir)
    # t = 0: the profile file's rows interpolated to the cell centres
    rows = np.loadtxt(os.path.join(HERE, "data", "flame_profile_phi1.00.dat"))
    temp0, xyz = da.read("temp_CC", 0, 0)
    assert np.allclose(temp0[:, 0, 0], np.interp(xyz[0], rows[:, 0], rows[:, 1]), rtol=1e-13, atol=0)
    assert np.allclose(da.read("scalar-YOH", 0, 0)[0][:, 0, 0], np.interp(xyz[0], rows[:, 0], rows[:, 8]),
                       rtol=1e-12, atol=1e-18)
    assert np.allclose(da.times[1:], ref["times"], rtol=1e-13, atol=0)
    for j in range(len(ref["times"])):
        for lab in ("temp_CC", "press_CC", "rho_CC", "vel_CC", "scalar-YH2", "scalar-YOH", "viscosity", "thermalCond"):
            ours = da.read(lab, 0, j + 1)[0]
            ours = (ours[..., 0] if ours.ndim == 4 else ours)[:, 0, 0]
            theirs = ref[lab][j]
            assert np.max(np.abs(ours - theirs)) <= 1e-12 * np.abs(theirs).max(), (lab, j)
    assert ref["vel_CC"][-1].max() > 5 * ref["vel_CC"][-1].min() > 0       # burnt gas leaves faster than it came


def _mutated(tmp_path, old, new):
    """The deck with one edit, its mechanism file named by its absolute path."""
    text = open(DECK).read().replace("<mechanismFile> Burke2012Modified.xml", f"<mechanismFile> {MECH}")
    assert old in text
    p = tmp_path / "deck.ups"
    p.write_text(text.replace(old, new))
    return str(p)


@pytest.mark.parametrize("old,new,message", [
    ("<Y_init> [0.0, 0.028522387527567396,", "<Y_init> [0.028522387527567396,",
     "7 mass fractions; accepted: 8, the tracked species H H2 O OH H2O O2 HO2 H2O2"),
    ("<closureSpecies> N2 </closureSpecies>", "<closureSpecies> Ar </closureSpecies>",
     "closure species Ar is not in the mechanism"),
    ("<closureSpecies>", "<initProfile> <filename> nowhere.dat </filename> <axis> x </axis> </initProfile>"
     " <closureSpecies>", "profile file nowhere.dat not found"),
    ("<closureSpecies>", "<initProfile> <filename> nowhere.dat </filename> <axis> r </axis> </initProfile>"
     " <closureSpecies>", "<axis> r; accepted: x, y, z"),
    (f"<mechanismFile> {MECH}", "<mechanismFile> nowhere/Burke2012Modified.xml", "not found"),
])
def test_deck_errors(tmp_path, old, new, message):
    """Each refusal is one line naming the deck's tag."""
    from framework.controller import Controller
    with pytest.raises(InputError) as e:
        Controller(_mutated(tmp_path, old, new), quiet=True, filebase=str(tmp_path / "x.uda"))
    assert message in str(e.value)
