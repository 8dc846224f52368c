"""comp_neo_hook_plastic / UCNH (Uintah's UCNH): closed forms, the return map, Uintah's sus.

Uintah's const_test_nhp.ups (tests/mpm/uintah_reference/) compresses one particle in
uniaxial stress past yield. Its expected response, derived here from the model's
continuum equations: with axial stretch l, lateral stretch m, J = l m^2 and the elastic
bElBar = diag(a, a, c),
  elastic:  bElBar = J^(-2/3) diag(m^2, m^2, l^2), sigma_xx(m) = 0 solved for m,
            sigma_zz = mu (c - a) / J;
  plastic:  the consistency condition mu (a - c) = sigma_y + H alpha, sigma_xx = 0 gives
            K/2 (J^2 - 1) = -(sigma_y + H alpha)/3, sigma_zz = -(sigma_y + H alpha)/J, and the
            flow rule d(bElBar)/dt = dev(L) b + b dev(L)^T - 2/3 gamma' tr(b) n,
            alpha' = sqrt(2/3) gamma' gives, per d(ln l),
            d alpha = -(a + 2c) / (H/mu + (a + 2c) H / (9 K J^2) + 2a + c),
            d a = 2a/3 (d ln m - d ln l) - 2/3 d gamma (2a + c)/sqrt(6),
  integrated with RK4 (2,000 steps: converged far below the tolerances used).
Uintah's sus on the same deck agrees with this curve to 2e-5 (elastic) and 3e-4 (plastic,
after the yield transient): the values sus wrote are in tests/mpm/data/sus_const_test_nhp.npz
(sus with <outputTimestepInterval>1 and p.deformationMeasure, p.plasticStrain, p.bElBar
saved; puda -partvar ... -matl 1, nine significant digits; the times and StrainEnergy from
StrainEnergy.dat as written).
"""
import pathlib

import numpy as np
import pytest

from components.mpm.constitutive import comp_neo_hook, comp_neo_hook_plastic as cnhp, ucnh
from framework.problemspec import InputError

from .helpers import run

HERE = pathlib.Path(__file__).parent
DECK = HERE / "uintah_reference" / "const_test_nhp.ups"
SUS = HERE / "data" / "sus_const_test_nhp.npz"
K, MU, SY, H = 2000.0, 1500.0, 1000.0, 500.0          # the deck's comp_neo_hook_plastic


def step(params, F_old, F_new, alpha, be):
    """One update of n particles; returns (stress, alpha, bElBar, energy)."""
    n = len(F_new)
    s, e, a2, b2 = np.zeros((n, 3, 3)), np.zeros(n), np.zeros(n), np.zeros((n, 3, 3))
    vol = np.linalg.det(F_new)
    cnhp.update(params, None, np.ascontiguousarray(F_old), np.ascontiguousarray(F_new), vol, np.ones(n),
                np.zeros((n, 3)), 0.0, None, s, e, (alpha, be), (a2, b2))
    return s, a2, b2, e


def path(params, Fs):
    """Drive one particle through the deformation gradients Fs; every step's output."""
    alpha, be = cnhp.initial_state(params, 1)
    out = []
    F_old = np.eye(3)
    for F in Fs:
        s, alpha, be, e = step(params, F_old[None], F[None], alpha, be)
        out.append((s[0], alpha[0], be[0], e[0]))
        F_old = F
    return out


# -- closed forms -----------------------------------------------------------------------
def test_elastic_is_comp_neo_hook():
    """Below yield bElBar = J^(-2/3) F F^T whatever the path: the stress and energy are
    comp_neo_hook's at the final F; UCNH without plasticity is comp_neo_hook."""
    rng = np.random.default_rng(3)
    A = rng.uniform(-0.15, 0.15, (3, 3))
    Fs = [np.eye(3) + A * k / 40 for k in range(1, 41)]
    s, alpha, _, e = path(cnhp.Params(K, MU, 1e12, H), Fs)[-1]
    ref = np.zeros((1, 3, 3))
    en = np.zeros(1)
    comp_neo_hook.update(comp_neo_hook.Params(K, MU), None, None, Fs[-1][None], np.array([np.linalg.det(Fs[-1])]),
                         np.ones(1), np.zeros((1, 3)), 0.0, None, ref, en)
    assert alpha == 0.0
    assert np.allclose(s, ref[0], rtol=0, atol=1e-11 * np.abs(ref).max())
    assert e == pytest.approx(en[0], rel=1e-11)
    el = ucnh.Params.from_ups({"bulk_modulus": K, "shear_modulus": MU})
    assert el.usePlasticity is False and cnhp.Params.from_ups(
        {"bulk_modulus": K, "shear_modulus": MU, "yield_stress": SY, "hardening_modulus": H}).usePlasticity
    out = np.zeros((1, 3, 3))
    ucnh.update(el, None, None, Fs[-1][None], np.ones(1), np.ones(1), np.zeros((1, 3)), 0.0, None, out, en)
    assert np.array_equal(out, ref)


def test_simple_shear_elastic_closed_form():
    """Isochoric simple shear F = I + gamma e_x e_y in 50 increments: sigma_xy = mu gamma,
    sigma_xx = 2/3 mu gamma^2, sigma_yy = sigma_zz = -1/3 mu gamma^2 (neo-Hooke, J = 1)."""
    g = 0.6
    Fs = [np.eye(3) + np.array([[0, g * k / 50, 0], [0, 0, 0], [0, 0, 0]]) for k in range(1, 51)]
    s = path(cnhp.Params(K, MU, 1e12, H), Fs)[-1][0]
    expect = MU * np.array([[2 * g * g / 3, g, 0], [g, -g * g / 3, 0], [0, 0, -g * g / 3]])
    assert np.allclose(s, expect, rtol=0, atol=1e-12 * MU)


def test_return_map_consistency_and_hardening():
    """Past yield the deviatoric Kirchhoff stress sits on the hardened yield surface,
    |dev(J sigma)| = sqrt(2/3) (sigma_y + H alpha), alpha never decreases, and the pressure
    is the elastic K/2 (J - 1/J) (plastic flow is isochoric)."""
    g = 1.5
    Fs = [np.diag([1.02 ** k, 1.0, 1.0]) @ (np.eye(3) + np.array([[0, g * k / 60, 0], [0, 0, 0], [0, 0, 0]]))
          for k in range(1, 61)]
    out = path(cnhp.Params(K, MU, SY, H, alpha=0.05), Fs)
    alphas = [o[1] for o in out]
    assert alphas[0] == 0.05 and alphas[-1] > 0.5 and np.all(np.diff(alphas) >= 0)
    for F, (s, alpha, _, _) in zip(Fs, out):
        J = np.linalg.det(F)
        tau = J * s
        dev = tau - np.trace(tau) / 3 * np.eye(3)
        assert np.trace(s) / 3 == pytest.approx(0.5 * K * (J - 1 / J), rel=1e-12)
        if alpha > 0.05:
            assert np.linalg.norm(dev) == pytest.approx(np.sqrt(2 / 3) * (SY + H * alpha), rel=1e-12)
        else:
            assert np.linalg.norm(dev) <= np.sqrt(2 / 3) * (SY + H * alpha) * (1 + 1e-12)


# -- Uintah's const_test_nhp: the expected curve, sus -----------------------------------
def _lateral_stretch(l):
    """Elastic uniaxial stress: the lateral stretch m with sigma_xx(l, m) = 0 (bisection)."""
    lo, hi = 0.5, 2.0
    for _ in range(100):
        m = 0.5 * (lo + hi)
        J = l * m * m
        a, c = J ** (-2 / 3) * m * m, J ** (-2 / 3) * l * l
        if 0.5 * K * (J - 1 / J) + MU / J * (a - (2 * a + c) / 3) > 0:
            hi = m
        else:
            lo = m
    return m


def _elastic(l):
    m = _lateral_stretch(l)
    J = l * m * m
    a, c = J ** (-2 / 3) * m * m, J ** (-2 / 3) * l * l
    return MU * (c - a) / J, a, c


def uniaxial_stress_curve(l):
    """sigma_zz and alpha at axial stretch l (module docstring)."""
    lo, hi = 0.3, 1.0                     # the onset of yield: mu (a - c) = sigma_y
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        _, a, c = _elastic(mid)
        lo, hi = (mid, hi) if MU * (a - c) > SY else (lo, mid)
    l_y = 0.5 * (lo + hi)
    if l >= l_y:
        return _elastic(l)[0], 0.0

    def rhs(y):
        a, al = y
        c = a - (SY + H * al) / MU
        J2 = 1 - 2 * (SY + H * al) / (3 * K)
        dal = -(a + 2 * c) / (H / MU + (a + 2 * c) * H / (9 * K * J2) + 2 * a + c)
        dm = 0.5 * (-(H / (3 * K)) / J2 * dal - 3.0)          # d ln m - d ln l
        return np.array([2 * a * dm / 3 - (2 / 3) * dal / np.sqrt(2 / 3) * (2 * a + c) / np.sqrt(6), dal])

    y = np.array([_elastic(l_y)[1], 0.0])
    n = 2000
    h = (np.log(l) - np.log(l_y)) / n
    for _ in range(n):
        k1 = rhs(y)
        k2 = rhs(y + h / 2 * k1)
        k3 = rhs(y + h / 2 * k2)
        k4 = rhs(y + h * k3)
        y = y + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
    alpha = y[1]
    return -(SY + H * alpha) / np.sqrt(1 - 2 * (SY + H * alpha) / (3 * K)), alpha


def test_sus_agrees_with_the_expected_curve():
    """The check of the curve itself: Uintah's own run of the deck follows it."""
    d = np.load(SUS)
    for k in (40, 100, 140, 200, 234):        # not the yield transient (steps 145-190)
        szz, alpha = uniaxial_stress_curve(d["F"][k, 2, 2])
        assert d["stress"][k, 2, 2] == pytest.approx(szz, rel=1e-4 if alpha == 0 else 5e-4)
        assert d["plasticStrain"][k] == pytest.approx(alpha, rel=2e-3, abs=1e-6)


def test_kernel_follows_sus_step_by_step():
    """Driven by sus's F of every step of const_test_nhp (elastic, then plastic from step
    ~150), the kernel gives sus's p.stress, p.plasticStrain and p.bElBar to the nine digits
    puda prints."""
    d = np.load(SUS)
    out = path(cnhp.Params(K, MU, SY, H), d["F"])
    s = np.array([o[0] for o in out])
    scale = np.abs(d["stress"]).max(axis=(1, 2))
    assert np.all(np.abs(s - d["stress"]).max(axis=(1, 2)) < 1e-6 * scale)
    assert np.allclose([o[1] for o in out], d["plasticStrain"], rtol=0, atol=1e-8)
    assert np.allclose([o[2] for o in out], d["bElBar"], rtol=0, atol=2e-8)
    assert d["plasticStrain"][-1] > 0.13


def _deck(**edits):
    """const_test_nhp.ups saving F and g.volume too (p2g then computes the volume, the variant of
    inputs/MPM/adiabatic_copper_jc.ups: no p2g of this file's own), with optional (old, new) text edits."""
    text = open(DECK).read().replace('<save label = "p.stress"/>',
                                     '<save label = "p.stress"/><save label = "p.deformationMeasure"/>'
                                     '<save label = "g.volume"/>')
    for old, new in edits.values():
        assert old in text
        text = text.replace(old, new)
    return text


USL = ("<time_integrator>explicit</time_integrator>",
       "<time_integrator>explicit</time_integrator><stress_update>usl</stress_update>")


def test_const_test_nhp_deck(tmp_path):
    """The deck, unchanged but for saving F and Uintah's USL stress update (the curve does not
    depend on the update; on this 3D grid USL's kernels are inputs/MPM/adiabatic_copper_jc.ups's,
    MUSL's would be this file's own): sigma_zz on the expected curve (the free sides oscillate a
    little: sigma_xx is not exactly 0) and the strain energy as sus's at the same time."""
    _, da = run(_deck(usl=USL), tmp_path)
    assert da.times[-1] >= 0.5 and len(da.times) == 6
    sus = np.load(SUS)
    t, se = da.reduction("StrainEnergy")
    for k in range(1, len(da.times)):
        p = da.particles(1, k)
        s, F = p["p.stress"][0], p["p.deformationMeasure"][0]
        szz, _ = uniaxial_stress_curve(F[2, 2])
        assert s[2, 2] == pytest.approx(szz, rel=0.006)        # measured: 0.4 % at most
        assert abs(s[0, 0]) < 0.01 * abs(s[2, 2])
    se_sus = np.interp(t[1:], sus["time"], sus["StrainEnergy"])
    assert np.allclose(se[1:], se_sus, rtol=5e-4)           # measured: 5e-5 at most


def test_const_test_nhp_steps_as_sus(tmp_path):
    """Uintah computes the stress from the velocity gradient of the updated grid velocities
    (USL): with <stress_update>usl</stress_update>, pysus takes sus's 235 steps (the same
    times) and every tenth step has sus's p.stress (to the nine digits puda prints), through
    yield and hardening, and so has the strain energy."""
    text = _deck(usl=USL,
                 out=("<outputInterval>.1</outputInterval>", "<outputTimestepInterval>10</outputTimestepInterval>"))
    _, da = run(text, tmp_path)
    sus = np.load(SUS)
    steps = np.array(da.timesteps[1:])
    assert np.array_equal(steps[:23], np.arange(10, 240, 10))
    assert np.allclose(da.times[1:], sus["time"][steps - 1], rtol=1e-12, atol=0)
    s = np.array([da.particles(1, k)["p.stress"][0] for k in range(1, len(steps) + 1)])
    ref = sus["stress"][steps - 1]
    assert np.all(np.abs(s - ref).max(axis=(1, 2)) < 2e-8 * np.abs(ref).max(axis=(1, 2)))
    t, se = da.reduction("StrainEnergy")             # a line every step, as sus's
    assert len(t) - 1 == len(sus["time"]) == 235 and np.allclose(t[1:], sus["time"], rtol=1e-12)
    assert np.allclose(se[1:], sus["StrainEnergy"], rtol=1e-8)


# -- input ----------------------------------------------------------------------------
@pytest.mark.parametrize("old,new,words", [
    ("<yield_stress>1000.0</yield_stress>", "", ("yield_stress",)),
    ("<alpha> 0.0 </alpha>", "<alpha> 0.0 </alpha><yield_distrib>uniform</yield_distrib>",
     ("yield_range",)),
    ("<hardening_modulus>500.0</hardening_modulus>", "<hardening_modulus>-5</hardening_modulus>",
     ("hardening_modulus",)),
    ("<alpha> 0.0 </alpha>", "<alpha> -0.1 </alpha>", ("alpha",)),
])
def test_bad_input_is_one_line(tmp_path, old, new, words):
    text = open(DECK).read()
    assert old in text
    with pytest.raises(InputError) as e:
        run(text.replace(old, new), tmp_path)
    msg = str(e.value)
    assert "\n" not in msg and ".ups:" in msg
    for w in words:
        assert w in msg, msg
