"""Tests of the MPM constitutive kernels (components.mpm.constitutive)."""
import numpy as np
import pytest

from components.mpm.constitutive import (comp_mooney_rivlin, comp_neo_hook, elastic_plastic,
                                         hypo_elastic, ideal_gas_fluid, membrane, rigid)

K, G = 833.3, 384.6
RHO0 = 2.0


def rot(axis, ang):
    a = np.asarray(axis, float) / np.linalg.norm(axis)
    X = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
    return np.eye(3) + np.sin(ang) * X + (1 - np.cos(ang)) * X @ X


def particles(F_new, F_old=None, dt=1.0):
    """Arrays for n particles with deformations F_new (n,3,3), L from F."""
    F_new = np.ascontiguousarray(F_new, dtype=float)
    n = len(F_new)
    F_old = np.tile(np.eye(3), (n, 1, 1)) if F_old is None else np.asarray(F_old, float)
    Fm = 0.5 * (F_old + F_new)
    L = np.ascontiguousarray(np.einsum("pij,pjk->pik", (F_new - F_old) / dt, np.linalg.inv(Fm)))
    vol0 = np.full(n, 0.1)
    vol = vol0 * np.linalg.det(F_new)
    mass = RHO0 * vol0
    vel = np.zeros((n, 3))
    return dict(L=L, F_old=F_old, F_new=F_new, vol=vol, mass=mass, vel=vel, dt=dt,
                stress_old=np.zeros((n, 3, 3)), stress_new=np.zeros((n, 3, 3)),
                energy=np.zeros(n))


MR = comp_mooney_rivlin.Params(he_constant_1=100000.0, he_constant_2=20000.0, he_PR=0.3)
MR_G = 2 * (1e5 + 2e4)
MR_K = 2 * MR_G * 1.3 / (3 * (1 - 0.6))
ELASTIC = [
    ("hypo", lambda a: hypo_elastic.update(hypo_elastic.Params(G=G, K=K), **a), K, G),
    ("neo", lambda a: comp_neo_hook.update(comp_neo_hook.Params(K, G), **a), K, G),
    ("mr", lambda a: comp_mooney_rivlin.update(MR, **a), MR_K, MR_G),
    ("j2", lambda a: elastic_plastic.update(
        elastic_plastic.Params(G, K, 1e9, 10.0), **a, eps_p_old=np.zeros(1),
        eps_p_new=np.zeros(1)), K, G),
]


@pytest.mark.parametrize("name,upd,k,g", ELASTIC, ids=[e[0] for e in ELASTIC])
def test_small_strain_hooke(name, upd, k, g):
    eps = 1e-7
    a = particles(np.diag([1 + eps, 1, 1])[None])
    ws = upd(a)
    s = a["stress_new"][0]
    assert np.isclose(s[0, 0], (k + 4 * g / 3) * eps, rtol=1e-5)
    assert np.isclose(s[1, 1], (k - 2 * g / 3) * eps, rtol=1e-5)
    assert abs(s[0, 1]) < 1e-12 * k
    # simple shear: sigma_xy = G gamma
    a = particles(np.array([[1, eps, 0], [0, 1, 0], [0, 0, 1.0]])[None])
    upd(a)
    assert np.isclose(a["stress_new"][0, 0, 1], g * eps, rtol=1e-5)
    assert ws.shape == (3,) and np.all(ws > 0)


def test_wave_speed_includes_velocity():
    a = particles(np.eye(3)[None])
    a["vel"][:] = [3.0, -4.0, 0.0]
    ws = hypo_elastic.update(hypo_elastic.Params(G=G, K=K), **a)
    c = np.sqrt((K + 4 * G / 3) / RHO0)
    assert np.allclose(ws, [c + 3, c + 4, c])


@pytest.mark.parametrize("model,params", [(comp_neo_hook, comp_neo_hook.Params(K, G)),
                                          (comp_mooney_rivlin, MR)])
def test_hyperelastic_objectivity(model, params):
    R = np.array([rot([0, 0, 1], 0.5), rot([1, 2, 3], 1.1)])
    a = particles(R)
    model.update(params, **a)
    assert np.abs(a["stress_new"]).max() < 1e-9 * MR_G
    U = np.array([[1.2, 0.1, 0.0], [0.1, 0.9, 0.05], [0.0, 0.05, 1.1]])
    a = particles(np.array([U, R[1] @ U]))
    model.update(params, **a)
    s0, s1 = a["stress_new"]
    assert np.allclose(s1, R[1] @ s0 @ R[1].T, rtol=1e-10, atol=1e-10 * np.abs(s0).max())


def test_hypo_elastic_jaumann_rotates_stress():
    """Pure spin of a pre-stressed particle: Jaumann rate -> sigma = R s0 R^T."""
    s0 = np.array([[3.0, 1.0, 0.0], [1.0, -2.0, 0.0], [0.0, 0.0, 0.5]])
    w, nstep = 0.8, 4000
    dt = 1.0 / nstep
    L = np.zeros((1, 3, 3))
    L[0, 0, 1], L[0, 1, 0] = -w, w  # rotation about z, rate w
    s = s0[None].copy()
    out = np.zeros_like(s)
    args = dict(vol=np.ones(1), mass=np.ones(1), vel=np.zeros((1, 3)), energy=np.zeros(1))
    for _ in range(nstep):
        hypo_elastic.update(hypo_elastic.Params(G=G, K=K), L, None, None, dt=dt,
                            stress_old=s, stress_new=out, **args)
        s, out = out, s
    R = rot([0, 0, 1], w)
    assert np.allclose(s[0], R @ s0 @ R.T, atol=2e-3)


def test_neo_hook_energy_consistent_with_stress_power():
    A = np.array([[0.4, 0.3, -0.1], [0.1, -0.25, 0.2], [0.05, 0.1, 0.3]])
    nstep = 2000
    work = 0.0
    P = comp_neo_hook.Params(K, G)
    for k in range(nstep):
        F0, F1 = np.eye(3) + A * k / nstep, np.eye(3) + A * (k + 1) / nstep
        Fm = 0.5 * (F0 + F1)
        a = particles(Fm[None])
        comp_neo_hook.update(P, **a)
        L = (F1 - F0) @ np.linalg.inv(Fm)
        work += np.sum(a["stress_new"][0] * L) * a["vol"][0]  # sigma:L * V dt
    a = particles((np.eye(3) + A)[None])
    comp_neo_hook.update(P, **a)
    assert comp_neo_hook.ENERGY_IS_INCREMENT is False
    assert np.isclose(a["energy"][0], work, rtol=1e-6)
    assert a["energy"][0] > 0


def test_mooney_rivlin_energy_consistent():
    A = np.array([[0.2, 0.1, 0.0], [0.0, -0.15, 0.1], [0.05, 0.0, 0.1]])
    nstep, work = 2000, 0.0
    for k in range(nstep):
        F0, F1 = np.eye(3) + A * k / nstep, np.eye(3) + A * (k + 1) / nstep
        Fm = 0.5 * (F0 + F1)
        a = particles(Fm[None])
        comp_mooney_rivlin.update(MR, **a)
        work += np.sum(a["stress_new"][0] * ((F1 - F0) @ np.linalg.inv(Fm))) * a["vol"][0]
    a = particles((np.eye(3) + A)[None])
    comp_mooney_rivlin.update(MR, **a)
    assert np.isclose(a["energy"][0], work, rtol=1e-6)


def test_j2_uniaxial_stress_yield_and_hardening():
    """Uniaxial stress path: lateral strain rate solved so sigma_yy = sigma_zz = 0."""
    sy, H = 2.0, 100.0
    P = elastic_plastic.Params(G, K, sy, H)
    E = 9 * K * G / (3 * K + G)
    dt, rate, nstep = 1.0, 2e-5, 400
    s = np.zeros((1, 3, 3))
    ep = np.zeros(1)
    base = dict(F_old=None, F_new=None, vol=np.ones(1), mass=np.ones(1),
                vel=np.zeros((1, 3)), dt=dt, energy=np.zeros(1))

    def step(lat):
        L = np.diag([rate, lat, lat])[None]
        out, epn = np.zeros((1, 3, 3)), np.zeros(1)
        elastic_plastic.update(P, L, stress_old=s, stress_new=out, eps_p_old=ep,
                               eps_p_new=epn, **base)
        return out, epn

    sxx, strain, epsp = [], [], []
    lat = -0.3 * rate
    for k in range(nstep):
        for _ in range(30):  # secant on the lateral strain rate
            o1, _ = step(lat)
            o2, _ = step(lat * (1 + 1e-3) + 1e-12)
            d = (o2[0, 1, 1] - o1[0, 1, 1]) / (lat * 1e-3 + 1e-12)
            lat -= o1[0, 1, 1] / d
            if abs(o1[0, 1, 1]) < 1e-12:
                break
        s, ep = step(lat)
        sxx.append(s[0, 0, 0])
        strain.append(rate * dt * (k + 1))
        epsp.append(ep[0])
    sxx, strain, epsp = map(np.array, (sxx, strain, epsp))
    assert abs(s[0, 2, 2]) < 1e-9 and abs(s[0, 1, 1]) < 1e-9
    first = np.argmax(epsp > 0)
    assert first > 0
    assert sxx[first - 1] <= sy + 1e-12 and sxx[first] >= sy - E * rate * dt
    assert np.allclose(sxx[:first], E * strain[:first], rtol=1e-3)
    slope = np.polyfit(strain[first + 5:], sxx[first + 5:], 1)[0]
    assert np.isclose(slope, E * H / (E + H), rtol=1e-3)
    # consistency: stress on the hardening yield surface
    assert np.allclose(sxx[first + 1:], sy + H * epsp[first + 1:], rtol=1e-9)


def test_rigid_zero_stress():
    """Zero stress, and no wave speed: as Uintah's RigidMaterial, a rigid body does not bound delT."""
    a = particles(np.array([np.diag([1.1, 0.9, 1.0])]))
    a["stress_new"][:] = 7.0
    a["vel"][:] = [1.0, 2.0, 3.0]
    ws = rigid.update(rigid.Params(46e9, 129e9), **a)
    assert np.all(a["stress_new"] == 0) and np.all(ws == 0.0)


def _gas(params, L, vol, mass, e, dt=1e-3):
    n = len(vol)
    en, s, energy = np.zeros(n), np.zeros((n, 3, 3)), np.zeros(n)
    ws = ideal_gas_fluid.update(params, np.ascontiguousarray(L), None, None, vol, mass,
                                np.zeros((n, 3)), dt, None, s, energy, e, en)
    return s, en, ws, energy


def test_ideal_gas_eos_viscosity_and_adiabat():
    gamma, mu = 1.4, 0.2
    P = ideal_gas_fluid.Params(gamma=gamma, viscosity=mu)
    e0, rho = 250.0, 1.0
    s, en, ws, _ = _gas(P, np.zeros((1, 3, 3)), np.ones(1), np.ones(1) * rho, np.full(1, e0))
    p = (gamma - 1) * rho * e0
    assert np.allclose(s[0], -p * np.eye(3)) and en[0] == e0  # eq. 22
    assert np.isclose(ws[0], np.sqrt(gamma * p / rho))
    # pure shear rate: deviatoric viscous stress 2 mu D, heating
    L = np.zeros((1, 3, 3))
    L[0, 0, 1] = 0.5
    s, en, _, de = _gas(P, L, np.ones(1), np.ones(1), np.full(1, e0))
    assert np.isclose(s[0, 0, 1], mu * 0.5) and en[0] > e0 and de[0] > 0
    # slow inviscid compression follows the adiabat p / rho^gamma = const
    P0 = ideal_gas_fluid.Params(gamma=gamma)
    vol, m, e = np.ones(1), np.ones(1), np.full(1, e0)
    rate, dt = -0.5, 1e-3
    for _ in range(800):
        vol = vol * np.exp(rate * dt)
        L = np.diag([rate, 0, 0])[None] * 1.0
        s, e, _, _ = _gas(P0, L, vol, m, e, dt)
    rho1 = m[0] / vol[0]
    assert np.isclose(-s[0, 0, 0] / rho1 ** gamma, (gamma - 1) * e0, rtol=2e-3)


def test_ideal_gas_artificial_viscosity_only_in_compression():
    P = ideal_gas_fluid.Params(gamma=1.4, artificial_viscosity=True, av_g=np.sqrt(2) * 0.01,
                               av_lambda=0.75)
    L = np.zeros((2, 3, 3))
    L[0, 0, 0], L[1, 0, 0] = -10.0, 10.0
    e = np.full(2, 250.0)
    s, en, _, _ = _gas(P, L, np.ones(2), np.ones(2), e)
    p = 0.4 * en
    q = -s[:, 0, 0] - p
    cmax = np.sqrt(1.4 * 0.4 * 250.0)
    assert np.isclose(q[0], cmax * np.sqrt(2) * 0.01 * 0.75 * 10.0 * 2.0)  # c1 = c2 = 1
    assert abs(q[1]) < 1e-12


@pytest.mark.parametrize("form", ["uniaxial", "plane"])
def test_membrane_tangent_stress(form):
    E, nu = 1e6, 0.3
    P = membrane.Params.from_young(E, nu, form)
    assert np.isclose(P.young, E) and np.isclose(P.poisson, nu)
    Eeff = E if form == "uniaxial" else E / (1 - nu ** 2)
    th = 0.6
    t = np.array([[np.cos(th), np.sin(th), 0.0]])
    eps = 1e-6
    Rm = rot([0, 0, 1], th)
    F = (Rm @ np.diag([1 + eps, 1 + 0.3 * eps, 1.0]) @ Rm.T)[None]  # stretch along t
    a = particles(F)
    tn, h, hn, vn = np.zeros((1, 3)), np.ones(1), np.zeros(1), np.zeros(1)
    ws = membrane.update(P, **a, t_old=t, t_new=tn, h_old=h, h_new=hn, vol_new=vn)
    s = a["stress_new"][0]
    assert np.allclose(s, Eeff * eps * np.outer(t[0], t[0]), rtol=1e-5, atol=1e-6 * Eeff * eps)
    assert np.allclose(tn, t, atol=1e-12)
    lat = nu if form == "uniaxial" else nu / (1 - nu)
    assert np.isclose(hn[0], 1 - lat * eps)
    assert np.isclose(ws[0], np.sqrt(Eeff / RHO0) * np.sqrt(np.linalg.det(F[0])), rtol=1e-6)
    # pure rotation: tangent rotates, stress unchanged in magnitude and along new t
    R = rot([0, 0, 1], 0.3)
    s_old = (2.0 * np.outer(t[0], t[0]))[None]
    a = particles(R[None])
    a["stress_old"] = s_old
    membrane.update(P, **a, t_old=t, t_new=tn, h_old=h, h_new=hn, vol_new=vn)
    assert np.allclose(tn[0], R @ t[0])
    assert np.allclose(a["stress_new"][0], 2.0 * np.outer(tn[0], tn[0]), rtol=1e-2)


def test_membrane_chain_tangents():
    ang = np.linspace(0, 2 * np.pi, 64, endpoint=False)
    px = np.stack([np.cos(ang), np.sin(ang), 0 * ang], 1)
    t = np.zeros_like(px)
    membrane.chain_tangents(px, True, t)
    assert np.allclose(t, np.stack([-np.sin(ang), np.cos(ang), 0 * ang], 1), atol=1e-12)


def test_params_from_ups():
    assert comp_neo_hook.Params.from_ups({"bulk_modulus": "833.3", "shear_modulus": 384.6}) \
        == comp_neo_hook.Params(833.3, 384.6)
    assert comp_mooney_rivlin.Params.from_ups(
        {"he_constant_1": 1e5, "he_constant_2": 2e4, "he_PR": 0.49}).he_PR == 0.49
    assert hypo_elastic.Params.from_ups({"G": 1, "K": 2}) == hypo_elastic.Params(1.0, 2.0)
    with pytest.raises(KeyError):
        elastic_plastic.Params.from_ups({"shear_modulus": 1})
