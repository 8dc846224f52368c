"""kernels.trace_temperatures: in cells the solids fill (every fluid's volume fraction below
the threshold) the fluids take the m cv-weighted temperature of the solids that exchange
heat, and those solids pay for it; other cells are untouched; energy is conserved exactly."""
import numpy as np

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
