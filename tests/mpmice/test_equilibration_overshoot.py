"""MPMICE's equilibration where the Newton iterate falls below zero or does not converge, as
Uintah's MPMICE::computeEquilibrationPressure (components/ice/equilibration.py, uintah_mpmice):
an iterate below 100 DBL_EPSILON becomes |dp|, and a cell that runs out of iterations goes to
Uintah's binary search (binaryPressureSearch) from the old pressure, which converges on
|1 - sum theta| <= 100 DBL_EPSILON or ends with its next midpoint. pysus's ICE keeps its own
rule (a tenth of p; Uintah's ICE has none and stops the run where the iterate ends below 0).

The cell: a copper-like solid (UCNH, <useModifiedEOS>) with air, the old pressure 3 to 1000
times the root (an ideal gas's Newton step from above p = 2 root overshoots below 0). Expected
values: the root from pysus's ICE rule, and the binary search transcribed from Uintah's source
(below) for a cell of ideal gas alone.
"""
import numpy as np
import pytest

from components.ice.eos import IDEAL_GAS, MAX_PARAMS, SOLID_UCNH
from components.ice.equilibration import DBL_EPSILON, equilibrate

CV, T = 716.0, 300.0
RT = (1.4 - 1.0) * CV * T          # the ideal gas EOS's (gamma - 1) cv T, as eos.py evaluates it


def _cell(codes, params, rhos, p_old, sp_old, max_iter, uintah):
    shape = (1, 1, 1)
    n = len(codes)
    out = [tuple(np.zeros(shape) for _ in range(n)) for _ in range(3)]
    press = np.zeros(shape)
    it = equilibrate(tuple(np.full(shape, r) for r in rhos), tuple(np.full(shape, T) for _ in range(n)),
                     tuple(np.full(shape, v) for v in sp_old), np.full(shape, p_old), out[0], out[1], out[2],
                     press, np.array(codes), params, np.array([386.0, CV][-n:]), np.array([1.0, 1.4][-n:]),
                     np.zeros(3, np.int64), np.ones(3, np.int64), 1e-11, max_iter, uintah)
    return it, press[0, 0, 0], out[1]


@pytest.mark.parametrize("factor", [3.0, 10.0, 1000.0])
def test_overshoot_reaches_the_root(factor):
    params = np.zeros((2, MAX_PARAMS))
    params[0, :4] = (117e9, 8900.0, 101325.0, 1.0)
    rhos = (4450.0, 0.5)                      # half the cell copper, half air at 1 kg/m^3
    root = RT
    p_old = factor * root
    args = ([SOLID_UCNH, IDEAL_GAS], params, rhos, p_old, (1.0 / 8900.0, RT / p_old), 100)
    _, p_ice, _ = _cell(*args, False)
    assert p_ice == pytest.approx(root, rel=1e-6)
    _, p_mi, vf = _cell(*args, True)
    assert abs(1.0 - (vf[0][0, 0, 0] + vf[1][0, 0, 0])) <= 100 * DBL_EPSILON
    assert p_mi == pytest.approx(p_ice, rel=1e-13)
    assert p_mi != p_ice                      # the binary search's root, not Newton's


def uintah_binary_search(rho, p_old, max_iter):
    """Uintah's MPMICE::binaryPressureSearch for one ideal gas of cell density rho at T, as written."""
    theta = lambda p: rho / (p / ((1.4 - 1.0) * CV * T))
    count, converged, pm = 0, False, p_old
    p_left = p_right = p_temp = 0.0
    press = None
    while count < max_iter and not converged:
        count += 1
        if abs(1.0 - theta(pm)) <= 100 * DBL_EPSILON:
            converged, press = True, pm
        if count == 1:
            p_left, p_right = DBL_EPSILON, 1.0 / DBL_EPSILON
            p_temp = 0.5 * (p_left + p_right)
        if (1.0 - theta(p_right)) * (1.0 - theta(p_left)) < 0.0:
            p_temp = p_left
            p_left = 0.5 * (p_left + p_right)
        else:
            p_right = p_left
            p_left = p_temp
            p_left = 0.5 * (p_left + p_right)
        pm = 0.5 * (p_left + p_right)
    return press if converged else pm


@pytest.mark.parametrize("max_iter", [2, 5, 100])
def test_binary_search_is_uintahs(max_iter):
    """A cell of ideal gas whose Newton runs out of iterations (max_iter small, or 100 from 1000
    times the root): the pressure Uintah's binary search gives, converged or its next midpoint."""
    rho = 1.0
    p_old = 1000.0 * rho * RT
    _, p, _ = _cell([IDEAL_GAS], np.zeros((1, MAX_PARAMS)), (rho,), p_old, (RT / p_old,), max_iter, True)
    assert p == uintah_binary_search(rho, p_old, max_iter)
    if max_iter == 100:
        assert abs(1.0 - rho * RT / p) <= 100 * DBL_EPSILON


# A cell full of steel (comp_neo_hook, <useModifiedEOS>) with 1e-12 air traces from the 12-cell
# pressurized cylinder (components/mpmice/scene_cylinder.py deck(12, dz="dx"), step 200): the
# steel's density scaled to fill the cell at the old pressure, the air's, their temperatures, the
# densities the particles give the steel and the air's own, and the old pressure
CYLINDER_CELL = ((8900.03639730968, 1.1793442473375e-12, 1.179345789360752e-12),
                 (300.00009305916865, 517.2384481804248, 521.6244399184691),
                 (8899.69987141428, 3.8933657374870405, 3.8608202702359153), 579805.579607289)


def test_solid_starts_at_its_eos_volume():
    """The solid's Newton iteration starts, as Uintah's, from rho_micro(p_old), the density its
    scaled volume was taken at (mpmice/kernels.solids_at_old_pressure writes it): from the
    particles' own density, 4e-5 below it, the first step of this cell lands near p = 0 and the
    iterate doubles back for some 40 iterations; from the EOS density it converges in a few, to
    the same pressure."""
    from components.mpmice.kernels import solids_at_old_pressure
    rhos, temps, rm_particles, p_old = CYLINDER_CELL
    params = np.zeros((3, MAX_PARAMS))
    K, rho0, p_ref = 117e9, 8900.0, 101325.0
    params[0, :4] = (K, rho0, p_ref, 1.0)
    codes, cvs, gammas = np.array([SOLID_UCNH, IDEAL_GAS, IDEAL_GAS]), np.full(3, CV), np.array([1.0, 1.4, 1.4])
    shape = (1, 1, 1)
    cell = lambda x: np.full(shape, float(x))
    lo, hi = np.zeros(3, np.int64), np.ones(3, np.int64)
    sp_particles = tuple(cell(1.0 / r) for r in rm_particles)
    scaled = tuple(cell(r) for r in rhos)
    sp_start = (cell(0.0),) + sp_particles[1:]
    solids_at_old_pressure(tuple(cell(r) for r in rhos), tuple(cell(t) for t in temps), sp_particles, cell(p_old),
                           np.array([True, False, False]), codes, params, cvs, gammas, False, scaled, sp_start,
                           cell(1.0), 1.0, lo, hi)
    g = p_old - p_ref                                 # comp_neo_hook's rho_micro above p_ref (Uintah's computeRhoMicroCM)
    assert sp_start[0][0, 0, 0] == pytest.approx(1.0 / (rho0 / K * (g + np.sqrt(K * K + g * g))), rel=1e-15)
    assert sp_start[1] is sp_particles[1] and sp_start[2] is sp_particles[2]
    results = []
    for sp in (sp_particles, sp_start):
        out = [tuple(np.zeros(shape) for _ in range(3)) for _ in range(3)]
        press = np.zeros(shape)
        it = equilibrate(tuple(cell(r) for r in rhos), tuple(cell(t) for t in temps), sp, cell(p_old), out[0], out[1],
                         out[2], press, codes, params, cvs, gammas, lo, hi, 1e-11, 100, True)
        results.append((it, press[0, 0, 0]))
    assert results[0][0] > 30 and results[1][0] <= 4
    assert results[1][1] == pytest.approx(results[0][1], rel=1e-10)
