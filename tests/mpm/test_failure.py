"""elastic_plastic with failure (components/mpm/constitutive/elastic_plastic.py): Uintah's
<evolve_damage>, <damage_model type="johnson_cook"> (constant failure strain D1) and the
material's <erosion algorithm>: a particle fails once its plastic strain reaches
critical_scalar_damage * D1 and then carries no stress (ZeroStress), no tension
(AllowNoTension) or no shear (AllowNoShear); without the tags nothing changes."""
import numpy as np
import pytest

from components.mpm.constitutive import elastic_plastic as EP
from framework.problemspec import InputError

G, K, SY = 80e9, 160e9, 2e8


def stretch(params, n_steps, rate=1e3, dt=1e-6, sign=1.0):
    """Uniaxial stretch (sign -1: compression) of one particle; per step (stress, eps_p, F, vol)."""
    L = np.zeros((1, 3, 3))
    L[0, 0, 0] = sign * rate
    F = np.eye(3)[None].copy()
    vol0, vol = 1e-6, np.array([1e-6])
    s, ep = np.zeros((1, 3, 3)), np.zeros(1)
    out = []
    for _ in range(n_steps):
        F_new = (np.eye(3) + dt * L[0]) @ F[0]
        F_new = F_new[None].copy()
        vol = np.array([vol0 * np.linalg.det(F_new[0])])
        s_new, ep_new, e = np.empty((1, 3, 3)), np.empty(1), np.zeros(1)
        EP.update(params, L, F, F_new, vol, np.array([8e-3]), np.zeros((1, 3)), dt, s, s_new, e, ep, ep_new)
        out.append((s_new[0].copy(), ep_new[0], F_new[0].copy(), vol[0]))
        F, s, ep = F_new, s_new, ep_new
        vol0 = vol[0] / np.linalg.det(F[0])
    return out


def failing(code, eps_f=0.02):
    return EP.Params(G, K, SY, 1e8, True, 1.0, eps_f, code)


def test_no_failure_tags_is_the_plain_model():
    plain = stretch(EP.Params(G, K, SY, 1e8), 60)
    off = stretch(EP.Params(G, K, SY, 1e8, False, 1.0, np.inf, 0), 60)
    for a, b in zip(plain, off):
        assert np.array_equal(a[0], b[0]) and a[1] == b[1]
    assert plain[-1][1] > 0.03                   # plastic, and the stress stays at the yield surface
    s = plain[-1][0]
    assert np.sqrt(1.5 * np.sum((s - np.trace(s) / 3 * np.eye(3)) ** 2)) == pytest.approx(SY + 1e8 * plain[-1][1])


def test_zero_stress_after_the_failure_strain():
    out = stretch(failing(EP.EROSION["ZeroStress"]), 60)
    eps = np.array([o[1] for o in out])
    k = int(np.argmax(eps >= 0.02))
    assert 0 < k < 59
    assert np.abs(out[k - 1][0]).max() > SY / 2         # intact the step before
    for s, _, _, _ in out[k:]:
        assert np.all(s == 0.0)
    # a failed particle keeps its F and its volume from the step it failed on
    assert np.array_equal(out[k + 1][2], out[-1][2]) and out[k + 1][3] == pytest.approx(out[-1][3], rel=1e-14)


def test_allow_no_tension_keeps_compression_only():
    code = EP.EROSION["AllowNoTension"]
    pulled = stretch(failing(code), 60)
    assert np.all(pulled[-1][0] == 0.0)               # tensile mean stress: nothing
    pushed = stretch(failing(code), 60, sign=-1.0)
    assert pushed[-1][1] >= 0.02
    s = pushed[-1][0]
    assert s[0, 0] < 0 and s[0, 0] == s[1, 1] == s[2, 2] and np.all(s[~np.eye(3, dtype=bool)] == 0.0)
    noshear = stretch(failing(EP.EROSION["AllowNoShear"]), 60)[-1][0]
    assert noshear[0, 0] > 0 and noshear[0, 0] == noshear[1, 1] == noshear[2, 2]


MAT = """<material><density>8900</density>
  <constitutive_model type="{cm}"><shear_modulus>8e10</shear_modulus><bulk_modulus>1.6e11</bulk_modulus>
  {extra}</constitutive_model>{erosion}
  <geom_object><box><min>[0,0,0]</min><max>[1,1,1]</max></box><res>[1,1,1]</res></geom_object></material>"""
JC = ('<evolve_damage>true</evolve_damage><damage_model type="johnson_cook"><D1>{d1}</D1><D2>{d2}</D2>'
      '<D3>0</D3><D4>0</D4><D5>0</D5></damage_model>')


def material(cm="elastic_plastic", extra="<yield_stress>2e8</yield_stress>", erosion=""):
    from components.mpm.materials import Material
    from framework.geometry import GeometryReader
    from framework.problemspec import ProblemSpec
    node = ProblemSpec.from_string(MAT.format(cm=cm, extra=extra, erosion=erosion))
    m = Material(node, 0, GeometryReader(), False)
    node.check_all_used()
    return m


def test_deck_tags():
    m = material(extra="<yield_stress>2e8</yield_stress><critical_scalar_damage>0.5</critical_scalar_damage>"
                 + JC.format(d1=0.3, d2=0), erosion='<erosion algorithm="AllowNoTension"/>')
    assert m.params.failure_strain == pytest.approx(0.15) and m.params.erosion == EP.EROSION["AllowNoTension"]
    plain = material()
    assert plain.params.failure_strain == np.inf and plain.params.erosion == 0
    with pytest.raises(InputError, match="D2"):
        material(extra="<yield_stress>2e8</yield_stress>" + JC.format(d1=0.3, d2=1.0))
    with pytest.raises(InputError, match="evolve_damage"):
        material(extra="<yield_stress>2e8</yield_stress><evolve_damage>true</evolve_damage>")
    with pytest.raises(InputError, match="algorithm"):
        material(erosion='<erosion algorithm="Melt"/>')
    # a model without failure reads <erosion> with no effect (Uintah erodes only failed particles)
    material(cm="comp_neo_hook", extra="", erosion='<erosion algorithm="ZeroStress"/>')
    with pytest.raises(InputError, match="algorithm"):
        material(cm="comp_neo_hook", extra="", erosion='<erosion algorithm="Melt"/>')
