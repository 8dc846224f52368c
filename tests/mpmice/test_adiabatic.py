"""<MPMICE><adiabatic_compression> (components/mpmice/adiabatic.py) on one cell of an ideal gas
in equilibrium (sp_vol and speedSound_CC from p_eq and T): what eng_L holds after the kernel,
starting from m cv T plus ICE's linear flow work, against the exact adiabat
T p^-(gamma-1)/gamma = const."""
import numpy as np
import pytest

from components.mpmice.adiabatic import limit_compression_work

CV, GAMMA, T, P_EQ, RHO_CC, V = 716.0, 1.4, 300.0, 1.0e6, 1.0e-8, 1.5e-5


def _after(delP):
    """(m e after the kernel, m cv T, linear work) for one cell whose pressure goes p_eq -> p_eq + delP."""
    a = lambda x: np.full((1, 1, 1), float(x))
    sp_vol = (GAMMA - 1.0) * CV * T / P_EQ
    c2 = GAMMA * (GAMMA - 1.0) * CV * T
    p = P_EQ + delP
    linear = V * (RHO_CC * sp_vol) * sp_vol / c2 * p * delP          # ICE's V theta kappa p delP
    e0 = RHO_CC * V * CV * T
    eng = a(e0 + linear)
    limit_compression_work(a(RHO_CC), a(T), a(RHO_CC * sp_vol), a(sp_vol), a(np.sqrt(c2)), a(p), a(delP), a(V), eng,
                           np.zeros(3, np.int64), np.ones(3, np.int64), CV, GAMMA)
    return float(eng[0, 0, 0]), e0, linear


@pytest.mark.parametrize("ratio", [1.001, 2.0, 25.0, 1.0e4])
def test_compression_takes_the_adiabat(ratio):
    e, e0, linear = _after((ratio - 1.0) * P_EQ)
    # the excess is subtracted from the linear work: round-off of it (2.9e7 m cv T at p/p_eq = 1e4)
    assert e / e0 == pytest.approx(ratio ** ((GAMMA - 1.0) / GAMMA), rel=1e-14 * max(1.0, linear / e0))
    if ratio == 25.0:                        # the trace gas's step in test_hard_cases: x180 linear, x2.5 adiabatic
        assert (e0 + linear) / e0 == pytest.approx(1.0 + (GAMMA - 1.0) / GAMMA * 25.0 * 24.0, rel=1e-12)


def test_expansion_keeps_the_linear_work():
    e, e0, linear = _after(-0.5 * P_EQ)
    assert linear < 0.0 and e == e0 + linear
