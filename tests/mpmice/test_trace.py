"""Trace materials in MPMICE. kernels.trace_temperatures (pysus's rule, on with
<MPMICE><trace_temperatures>true): in cells the solids fill (every fluid's volume fraction below
the threshold) the fluids take the m cv-weighted temperature of the solids that exchange
heat, and those solids pay for it; other cells are untouched; energy is conserved exactly.
Uintah's rules for a solid's trace in a cell: its step-1 temperature and the extra cells'
temperature rate (kernels.nc_to_cc_scalar, kernels.temperature_rates_extra)."""
import numpy as np
import pytest

from components.mpmice.kernels import trace_temperatures


def test_fluid_slivers_take_the_solid_temperature():
    shape = (3, 1, 1)
    mass = (np.array([1.0, 1.0, 1e-9]).reshape(shape), np.array([1e-12, 0.5, 1.0]).reshape(shape))
    cvs = np.array([500.0, 700.0])
    T = (np.array([300.0, 300.0, 300.0]), np.array([5000.0, 400.0, 400.0]))
    eng = tuple((m * cv * t.reshape(shape)).copy() for m, cv, t in zip(mass, cvs, T))
    vf = (np.array([1.0 - 1e-9, 0.5, 1e-12]).reshape(shape), np.array([1e-9, 0.5, 1.0]).reshape(shape))
    e0 = sum(e.copy() for e in eng)
    trace_temperatures(mass, eng, vf, cvs, np.array([2, 1]), 1e-6, np.zeros((0, 0, 0), np.bool_),
                       np.zeros(3, np.int64), np.array(shape, np.int64))
    assert np.allclose(sum(eng), e0, rtol=1e-15, atol=0)            # energy conserved per cell
    t_gas = eng[1] / (mass[1] * cvs[1])
    t_sol = eng[0] / (mass[0] * cvs[0])
    assert abs(t_gas[0, 0, 0] - t_sol[0, 0, 0]) < 1e-7                # cell 0: solid-filled
    assert abs(t_sol[0, 0, 0] - 300.0) < 1e-6                         # the solid barely notices
    assert t_gas[1, 0, 0] == 400.0 and t_gas[2, 0, 0] == 400.0        # cells with gas: untouched


def test_cells_a_reaction_feeds_keep_their_temperatures():
    """A solid-filled cell where a reaction model adds product this step (fed) is left as the
    exchange made it: the new product keeps its own temperature (Uintah has no trace rule)."""
    shape = (2, 1, 1)
    mass = (np.array([1.0, 1.0]).reshape(shape), np.array([1e-12, 1e-12]).reshape(shape))
    cvs = np.array([500.0, 700.0])
    eng = (mass[0] * 500.0 * 600.0, mass[1] * 700.0 * 3000.0)
    vf = (np.full(shape, 1.0 - 1e-9), np.full(shape, 1e-9))
    fed = np.array([True, False]).reshape(shape)
    trace_temperatures(mass, eng, vf, cvs, np.array([2, 1]), 1e-6, fed, np.zeros(3, np.int64),
                       np.array(shape, np.int64))
    t_gas = eng[1] / (mass[1] * cvs[1])
    assert t_gas[0, 0, 0] == 3000.0                                   # fed: untouched
    assert abs(t_gas[1, 0, 0] - 600.0) < 1e-6                         # not fed: the solid's


def test_rule_is_off_by_default_as_uintah(tmp_path):
    """Uintah's exchange has no trace rule: pysus's is on only with <MPMICE><trace_temperatures>true
    (on Uintah's decks it parts from sus: guni2dRT's trace air heats to 14,700 K in sus and sets its
    5th step, tests/mpmice/test_guni2drt.py; JWLppCuRS2d, tests/mpmice/test_jwlpp_cu_rs2d.py)."""
    from framework.controller import Controller
    from tests.mpmice.test_solid_eos_decks import deck
    text = deck("ideal", 1)
    assert not Controller(str(tmp_path / "a.ups"), deck_text=text, quiet=True).component.trace_temperatures
    text = text.replace("    <MPM>\n", "    <MPMICE><trace_temperatures>true</trace_temperatures></MPMICE>\n"
                        "    <MPM>\n", 1)
    assert Controller(str(tmp_path / "b.ups"), deck_text=text, quiet=True).component.trace_temperatures


def test_solid_temperature_blends_with_the_last_exchange():
    """Step 1's temp_CC of a solid, Uintah's interpolateNCToCC_0: with the floor mass t, cMass =
    m + t and f = m / cMass, (1 - f) T_old + f (sum_w m_i T_i) / cMass. A cell with no solid keeps
    T_old (the temperature its last exchange left); one holding as much solid as the floor gets
    T_old / 2 + T_nodes / 4 (Uintah's formula, as written there); a full cell its nodes' mean."""
    from components.mpmice.kernels import nc_to_cc_scalar
    tiny = 1e-12
    gmass = np.array([0.0, 0.0, 2e-12, 1.0]).reshape(4, 1, 1)
    gtemp = np.array([0.0, 0.0, 300.0, 500.0]).reshape(4, 1, 1)
    old = np.full((3, 1, 1), 400.0)
    out = np.zeros((3, 1, 1))
    zeros, no = np.zeros(3, np.int64), np.zeros(3, np.bool_)
    nc_to_cc_scalar(gmass, gtemp, zeros, zeros, zeros, np.array([3, 1, 1]), np.array([1, 0, 0]), no, no,
                    zeros, np.array([3, 0, 0]), tiny, 0.0, old, out)
    assert out[0, 0, 0] == 400.0
    assert out[1, 0, 0] == pytest.approx(0.5 * 400.0 + 0.25 * 300.0, rel=1e-12)
    m, s = 0.5 * (2e-12 + 1.0), 0.5 * (2e-12 * 300.0 + 500.0)
    assert out[2, 0, 0] == pytest.approx(tiny / (m + tiny) * 400.0 + m / (m + tiny) * s / (m + tiny), rel=1e-14)
    assert abs(out[2, 0, 0] / (s / m) - 1.0) < 5e-12                   # the nodes' mean, to 2 t / m
    nc_to_cc_scalar(gmass, gtemp, zeros, zeros, zeros, np.array([3, 1, 1]), np.array([1, 0, 0]), no, no,
                    zeros, np.array([3, 0, 0]), tiny, 123.0, np.zeros((1, 1, 1)), out)
    assert out[0, 0, 0] == 123.0 and out[1, 0, 0] == 300.0          # without `old`: the nodes' mean


def test_extra_cell_temperature_rate():
    """dTdt_CC in an extra cell (Uintah's computeCCVelAndTempRates there): the exchanged
    temperature the face's condition put in it less its own Lagrangian temperature, over dt."""
    from components.mpmice.kernels import temperature_rates_extra
    temp_me = np.array([310.0, 305.0, 320.0]).reshape(3, 1, 1)
    mass = np.array([2.0, 1.0, 0.0]).reshape(3, 1, 1)
    eng_L = mass * 500.0 * np.array([300.0, 300.0, 300.0]).reshape(3, 1, 1)
    out = np.full((3, 1, 1), -1.0)
    temperature_rates_extra(temp_me, eng_L, mass, 500.0, 0.5, np.array([1, 0, 0]), np.array([2, 1, 1]),
                            np.zeros(3, np.int64), np.array([3, 1, 1]), out)
    assert out[0, 0, 0] == pytest.approx(20.0, rel=1e-14)           # (310 - 300) / 0.5
    assert out[1, 0, 0] == -1.0                                       # interior: left
    assert out[2, 0, 0] == -1.0                                       # no mass: left
