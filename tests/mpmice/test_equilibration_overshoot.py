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


# A cell full of steel with the 1e-12 air traces of the 12-cell pressurized cylinder (its deck,
# components/mpmice/scene_cylinder.py deck(12, dz="dx"), at step 100, the steel stretched to
# 0.09 Pa): rho_m, T_m, the specific volumes the iteration starts from (the steel's at the old
# pressure), the old pressure
STEEL_CELL = ((8899.873740587738, 1.2123853489959332e-12, 1.212385349849578e-12),
              (300.0000000308535, 299.9978061849824, 299.9978060550776),
              (0.00011236090309147895, 886313.6724170145, 886313.6723989265), 0.0931496288186199)


def test_steel_cell_converges_by_uintahs_test():
    """Uintah's MPMICE stops where |sum theta - 1| < 100 DBL_EPSILON after an iterate; there one ulp
    of the steel's rho_micro moves p by about 1e-5 Pa, 1e-4 of p, and pysus ICE's |dp| <= 1e-11 p
    is never met (the iterate cycles at round-off to max_iter). Uintah's sus takes 1 to 4
    iterations in the cylinder's cells; so does MPMICE's equilibration here."""
    rhos, temps, sp_old, p_old = STEEL_CELL
    params = np.zeros((3, MAX_PARAMS))
    params[0, :4] = (117e9, 8900.0, 101325.0, 1.0)
    shape = (1, 1, 1)
    results = {}
    for uintah in (False, True):
        out = [tuple(np.zeros(shape) for _ in range(3)) for _ in range(3)]
        press = np.zeros(shape)
        it = equilibrate(tuple(np.full(shape, r) for r in rhos), tuple(np.full(shape, t) for t in temps),
                         tuple(np.full(shape, v) for v in sp_old), np.full(shape, p_old), out[0], out[1], out[2],
                         press, np.array([SOLID_UCNH, IDEAL_GAS, IDEAL_GAS]), params, np.full(3, CV),
                         np.array([1.0, 1.4, 1.4]), np.zeros(3, np.int64), np.ones(3, np.int64), 1e-11, 100, uintah)
        results[uintah] = (it, press[0, 0, 0], sum(f[0, 0, 0] for f in out[1]))
    assert results[False][0] == 100                      # the round-off cycle, taken at once
    it, p, theta = results[True]
    assert it <= 4 and abs(theta - 1.0) < 100 * DBL_EPSILON
    assert p == pytest.approx(results[False][1], rel=1e-3)
