"""Uintah's ICE specific heat models: a material's cv as a function of its temperature.

`<MaterialProperties><ICE><material><SpecificHeatModel type="...">` (Uintah's
SpecificHeatModel/ factory):

  airNasa     air (3.76 mol N2 per mol O2) from the NASA 7-coefficient polynomials of O2
              and N2 (GRI-Mech data): cv = R_air (x_O2 cp_O2/R + x_N2 cp_N2/R) - R_air,
              low / high coefficients below / above 1000 K.  No tags.
  Component   a gas mixture of mole fractions <XCO2> <XH2O> <XCO> <XH2> <XO2> <XN2> <XOH>
              <XNO> <XO> <XH> (default 0, sum 1): cp/R from Heywood's polynomials (T clamped
              to 300..5000 K), cv = cp / gamma_mix with gamma_mix 1.6 / 1.4 / 1.3 for mono-,
              di- and triatomic species, per kg of the mixture's molar mass.
  Polynomial  <MaxOrder> n, <coefficient> [a0, ..., an], <Tmin> (0), <Tmax> (1e6):
              cv = T^n / (a0 + a1 T + ... + an T^n), T clamped to Tmin..Tmax (Uintah's
              formula, which divides by the polynomial).
  Debye       <Atoms> N, <DebyeTemperature> T_D: cv = 9 k_B N (T/T_D)^3 times the Debye
              integral of x^4 e^x / (e^x - 1)^2 up to T_D/T (Uintah's 1000-step Riemann sum).

What the model changes, as in Uintah's ICE: at the start of each step (and at t = 0) the
field `specific_heat` is cv(temp_CC) in every cell, extra cells included, and every cv of the
step reads it: the EOS pressure and sound speed of the equilibration (eq. 13), the internal
energy m cv T of the Lagrangian step (eq. 35), the temperature int_eng / (m cv) after
advection, the extra cells' energies and TotalIntEng. gamma stays the material's <gamma>:
Uintah's ICE meant to set it to the model's gamma(T) too, but its loop over the cells runs
with the iterator the cv loop has already exhausted, so sus keeps <gamma> (measured: sus's
saved `gamma` is the deck's value in every cell), and pysus does the same.
"""
from __future__ import annotations

import numpy as np
from numba import njit, types
from numba.extending import overload

AIR_NASA, COMPONENT, POLYNOMIAL, DEBYE = 1, 2, 3, 4
MODELS = {"airNasa": AIR_NASA, "Component": COMPONENT, "Polynomial": POLYNOMIAL, "Debye": DEBYE}

# Component: species in Uintah's order, their molar masses (g/mol, Uintah's values: H2 as
# 1.00794) and gamma class
SPECIES = ("CO2", "H2O", "CO", "H2", "O2", "N2", "OH", "NO", "O", "H")
MOLAR_MASS = (44.01, 18.01428, 28.01, 1.00794, 31.9988, 28.0134, 17.00734, 30.0061, 15.9994, 1.00794)
R_UNIVERSAL = 8.3144621         # J/(mol K), Uintah's Component.cc
K_BOLTZMANN = 1.3806503e-23     # J/K, Uintah's Debye.cc

# airNasa: the GRI-Mech NASA-7 coefficients a0..a4 of cp/R (low: T <= 1000 K, high: above)
R_AIR = 288.1865406176613
O2_HIGH = np.array([3.28253784e+00, 1.48308754e-03, -7.57966669e-07, 2.09470555e-10, -2.16717794e-14])
O2_LOW = np.array([3.78245636e+00, -2.99673416e-03, 9.84730201e-06, -9.68129509e-09, 3.24372837e-12])
N2_HIGH = np.array([0.02926640e+02, 0.14879768e-02, -0.05684760e-05, 0.10097038e-09, -0.06753351e-13])
N2_LOW = np.array([0.03298677e+02, 0.14082404e-02, -0.03963222e-04, 0.05641515e-07, -0.02444854e-10])
X_N2, X_O2 = 3.76 / 4.76, 1.0 / 4.76


# -- cv of a cell: one number, or a per-cell field -------------------------------------------
def cv_at(cv, i, j, k):
    """cv of cell (i, j, k): cv itself where it is one number (a material without a model),
    else the field's value; numba compiles each case on its own, so the constant-cv kernels
    are the ones without a model."""
    return cv if np.ndim(cv) == 0 else cv[i, j, k]


@overload(cv_at)
def _cv_at(cv, i, j, k):
    if isinstance(cv, types.Array):
        return lambda cv, i, j, k: cv[i, j, k]
    return lambda cv, i, j, k: cv


def cv_at_flat(cv, n):
    """cv_at for flattened arrays."""
    return cv if np.ndim(cv) == 0 else cv[n]


@overload(cv_at_flat)
def _cv_at_flat(cv, n):
    if isinstance(cv, types.Array):
        return lambda cv, n: cv[n]
    return lambda cv, n: cv


# -- the models ------------------------------------------------------------------------------
@njit(cache=True)
def _nasa7(a, T, T2, T3, T4):
    return a[0] + a[1] * T + a[2] * T2 + a[3] * T3 + a[4] * T4


@njit(cache=True)
def air_nasa_cv(T, o2_low, o2_high, n2_low, n2_high):
    """airNasa: cv = R_air (x_O2 cp_O2 + x_N2 cp_N2)/R - R_air (NASA 7-coefficient cp/R)."""
    T2 = T * T
    T3 = T2 * T
    T4 = T3 * T
    high = T > 1000.0
    cp_o2 = _nasa7(o2_high if high else o2_low, T, T2, T3, T4)
    cp_n2 = _nasa7(n2_high if high else n2_low, T, T2, T3, T4)
    cp = R_AIR * (X_O2 * cp_o2 + X_N2 * cp_n2)
    return cp - R_AIR


@njit(cache=True)
def component_cv(T, x, gamma_mix, mass_per_mole):
    """Component: cp/R of each species (Heywood, Internal Combustion Engine Fundamentals,
    1988, p. 131), mole-weighted, over gamma_mix, per kg of mixture (T clamped to 300..5000 K)."""
    T = min(max(T, 300.0), 5000.0)
    T2 = T * T
    T3 = T2 * T
    T4 = T3 * T
    cp = 0.0
    if T <= 1000.0:
        cp += x[0] * (0.24008e1 + 0.87351e-2 * T - 0.66071e-5 * T2 + 0.20022e-8 * T3 + 0.63274e-15 * T4)
        cp += x[1] * (0.40701e1 - 0.11084e-2 * T + 0.41521e-5 * T2 - 0.29637e-8 * T3 + 0.80702e-12 * T4)
        cp += x[2] * (0.37101e1 - 0.16191e-2 * T + 0.36924e-5 * T2 - 0.20320e-8 * T3 + 0.23953e-12 * T4)
        cp += x[3] * (0.30574e1 + 0.26765e-2 * T - 0.58099e-5 * T2 + 0.55210e-8 * T3 - 0.18123e-11 * T4)
        cp += x[4] * (0.36256e1 - 0.18782e-2 * T + 0.70555e-5 * T2 - 0.67635e-8 * T3 + 0.21556e-11 * T4)
        cp += x[5] * (0.36748e1 - 0.12082e-2 * T + 0.23240e-5 * T2 - 0.63218e-9 * T3 - 0.22577e-12 * T4)
    else:
        cp += x[0] * (0.44608e1 + 0.30982e-2 * T - 0.12393e-5 * T2 + 0.22741e-9 * T3 - 0.15526e-13 * T4)
        cp += x[1] * (0.27168e1 + 0.29451e-2 * T - 0.80224e-6 * T2 + 0.10227e-9 * T3 - 0.48472e-14 * T4)
        cp += x[2] * (0.29841e1 + 0.14891e-2 * T - 0.57900e-6 * T2 + 0.10365e-9 * T3 - 0.69354e-14 * T4)
        cp += x[3] * (0.31002e1 + 0.51119e-3 * T + 0.52644e-7 * T2 - 0.34910e-10 * T3 + 0.36945e-14 * T4)
        cp += x[4] * (0.36220e1 + 0.73618e-3 * T - 0.19652e-6 * T2 + 0.36202e-10 * T3 - 0.28946e-14 * T4)
        cp += x[5] * (0.28963e1 + 0.15155e-2 * T - 0.57235e-6 * T2 + 0.99807e-10 * T3 - 0.65224e-14 * T4)
    cp += x[6] * (0.29106e1 + 0.95932e-3 * T - 0.19442e-6 * T2 + 0.13757e-10 * T3 + 0.14225e-15 * T4)
    cp += x[7] * (0.31890e1 + 0.13382e-2 * T - 0.52899e-6 * T2 + 0.95919e-10 * T3 - 0.64848e-14 * T4)
    cp += x[8] * (0.25421e1 - 0.27551e-4 * T - 0.31028e-8 * T2 + 0.45511e-11 * T3 - 0.43681e-15 * T4)
    cp += x[9] * 0.25
    return 1000.0 * (cp / gamma_mix * R_UNIVERSAL) / mass_per_mole


@njit(cache=True)
def polynomial_cv(T, coef, t_min, t_max):
    """Polynomial: T^n / sum a_i T^i with T clamped to [Tmin, Tmax] (Uintah's formula)."""
    if T < t_min:
        T = t_min
    if T > t_max:
        T = t_max
    s = coef[0]
    x = 1.0
    for i in range(1, coef.size):
        x *= T
        s += coef[i] * x
    return x / s


@njit(cache=True)
def debye_cv(T, atoms, t_debye):
    """Debye: 9 k_B N (T/T_D)^3 int_0^{T_D/T} x^4 e^x / (e^x - 1)^2 dx, the integral as Uintah's
    left Riemann sum of 1000 steps from x = 1e-12 (terms that are not finite are skipped)."""
    ratio = T / t_debye
    inv = t_debye / T
    pre = 9.0 * K_BOLTZMANN * atoms * ratio * ratio * ratio
    dx = inv / 1000.0
    s = 0.0
    x = 1.0e-12
    while x <= inv:
        ex = np.exp(x)
        term = dx * (x * x * x * x * ex) / ((ex - 1.0) * (ex - 1.0))
        if np.isfinite(term):
            s += term
        x += dx
    return pre * s


@njit(cache=True)
def specific_heat_of(code, params, T):
    """cv(T) of a model: code (MODELS) and its parameters (SpecificHeatModel.params)."""
    if code == AIR_NASA:
        return air_nasa_cv(T, O2_LOW, O2_HIGH, N2_LOW, N2_HIGH)
    if code == COMPONENT:
        return component_cv(T, params[:10], params[10], params[11])
    if code == POLYNOMIAL:
        return polynomial_cv(T, params[2:], params[0], params[1])
    return debye_cv(T, params[0], params[1])


@njit(cache=True)
def specific_heat_fill(temp, out, code, params, lo, hi):
    """out = cv(temp) in the cells lo..hi (a patch's own cells, extra cells included)."""
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                out[i, j, k] = specific_heat_of(code, params, temp[i, j, k])


class SpecificHeatModel:
    """One material's <SpecificHeatModel>: its code and parameters for the kernels."""

    def __init__(self, kind, params, node):
        self.kind = kind
        self.code = MODELS[kind]
        self.params = np.asarray(params, dtype=np.float64)
        self.node = node

    def cv(self, temp):
        """cv at one temperature (the initial-state check)."""
        return float(specific_heat_of(self.code, self.params, float(temp)))

    def fill(self, temp, out, lo=None, hi=None):
        """out = cv(temp) in the cells lo..hi (every cell by default)."""
        lo = np.zeros(3, np.int64) if lo is None else lo
        hi = np.array(temp.shape[:3], np.int64) if hi is None else hi
        specific_heat_fill(temp, out, self.code, self.params, lo, hi)


def read_specific_heat_model(material):
    """The <SpecificHeatModel> of an ICE <material> node, or None."""
    node = material.child("SpecificHeatModel")
    if node is None:
        return None
    kind = node.attr("type", choices=tuple(MODELS))
    if kind == "airNasa":
        return SpecificHeatModel(kind, [0.0], node)
    if kind == "Component":
        x = [node.get("X" + s, "float", 0.0, at_least=0.0) for s in SPECIES]
        total = sum(x)
        if not 1.0 - 1.0e-12 <= total <= 1.0 + 1.0e-12:
            raise node.error(f"the mole fractions <XCO2> ... <XH> add up to {total:.15g}; accepted: a sum of 1 "
                             "(within 1e-12)")
        # gamma_mix and the molar mass as Uintah's Component.cc sums them
        gamma_mix = 1.6 * (x[8] + x[9]) + 1.4 * (x[7] + x[6] + x[4] + x[5] + x[3] + x[2]) + 1.3 * (x[0] + x[1])
        molar = 0.0
        for xs, ms in zip(x, MOLAR_MASS):
            molar += xs * ms
        return SpecificHeatModel(kind, x + [gamma_mix, molar], node)
    if kind == "Polynomial":
        order = node.get("MaxOrder", "int", at_least=0)
        cn = node.child("coefficient", required=True)
        raw = cn.text()
        try:
            coef = [float(v) for v in raw.strip("[]").replace(",", " ").split()]
        except ValueError:
            raise cn.error(f"'{raw}' is not a list of numbers [a0, a1, ..., aMaxOrder]") from None
        if len(coef) != order + 1 or not np.all(np.isfinite(coef)):
            raise cn.error(f"{len(coef)} coefficients for <MaxOrder> {order}; accepted: {order + 1} finite numbers "
                           "[a0, a1, ..., aMaxOrder]")
        t_max = node.get("Tmax", "float", 1.0e6)
        t_min = node.get("Tmin", "float", 0.0)
        return SpecificHeatModel(kind, [t_min, t_max] + coef, node)
    return SpecificHeatModel(kind, [node.get("Atoms", "float", above=0.0),
                                    node.get("DebyeTemperature", "float", above=0.0)], node)
