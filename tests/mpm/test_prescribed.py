"""Prescribed deformation (components/mpm/prescribed.py): the grid velocity gradient from the
table and the Taylor / substep update of F (Uintah's minimum_subcycles_for_F); exact solutions."""
import numpy as np
import pytest

from components.mpm import prescribed


def table(lines):
    rows = np.array(lines, float)
    P, before = np.eye(3), []
    for r in rows:
        P = prescribed._rot(np.radians(r[10]), r[11:14]) @ P
        before.append(P)
    return rows[:, 0], rows[:, 1:10].reshape(-1, 3, 3), rows[:, 10], rows[:, 11:14], np.array(before)


def test_stretch_and_rotation():
    """F from I to diag(2, 1, 1) in 1 s: M = Fdot F^-1 = diag(1/F11, 0, 0); a quarter turn
    about z superposed in the second second: M = W + Q Fdot F^-1 Q^T with W the spin pi/2."""
    t = table([[0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1],
               [1, 2, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1],
               [2, 2, 0, 0, 0, 1, 0, 0, 0, 1, 90, 0, 0, 1]])
    assert np.allclose(prescribed.velocity_gradient(t, 0.5), np.diag([1 / 1.5, 0, 0]), atol=1e-15)
    M = prescribed.velocity_gradient(t, 1.5)
    w = np.pi / 2
    assert np.allclose(M, [[0, -w, 0], [w, 0, 0], [0, 0, 0]], atol=1e-15)


@pytest.mark.parametrize("terms", [-2, -6, 1, 50])
def test_deform_series(terms):
    """exp(L dt) F to the order of the Taylor series (terms < 0) or (I + L dt/n)^n (n > 0);
    V scales with det F."""
    L = np.array([[[0.3, 0.1, 0.0], [0.0, -0.2, 0.0], [0.05, 0.0, 0.1]]])
    F_old = np.eye(3)[None].copy()
    F_new = np.eye(3)[None] * 1.0
    vol = np.ones(1)
    dt = 0.5
    prescribed.deform_series(L, F_old, dt, terms, F_new, vol)
    w, V = np.linalg.eig(L[0] * dt)
    exact = (V @ np.diag(np.exp(w)) @ np.linalg.inv(V)).real
    err = np.abs(F_new[0] - exact).max()
    bound = {-2: 0.01, -6: 1e-6, 1: 0.05, 50: 2e-3}[terms]
    assert err < bound
    assert vol[0] == pytest.approx(np.linalg.det(F_new[0]), rel=1e-14)
