"""A gas-phase reaction mechanism read from its XML file (Uintah's gasCombustion format: Cantera's
CTML as Uintah's yaml2xml.py writes it, with transport fits).

    <mechanism>
      <units length="cm" quantity="mol" activation-energy="cal/mol"/>
      <phase><speciesArray> H H2 O ... N2 </speciesArray></phase>
      <speciesData><species name="H2"> <atomArray> H:2 </atomArray>
          <thermo><NASA7 Tmin Tmax><floatArray> a0 .. a6 </floatArray></NASA7> (one or two ranges)
          <viscosityFit> c0 .. c4 </viscosityFit>  <conductivityFit> c0 .. c4 </conductivityFit>
      </species> ...</speciesData>
      <reactionData><reaction reversible="yes" type="elementary|three-body|falloff">
          <reactants> H:1 O2:1 </reactants> <products> O:1 OH:1 </products>
          <rateCoeff><Arrhenius [name="k0|kInf"]><A/><b/><E units/></Arrhenius>
                     [<falloff type="Troe"> a T3 T1 [T2] </falloff>]</rateCoeff>
          [<efficiencies default="1"> H2:2.5 H2O:12 </efficiencies>]
      </reaction> ...</reactionData>
      <binaryDiffusionFits><pair s1 s2 coeffs="c0 .. c4"/> ...</binaryDiffusionFits>
    </mechanism>

Units as Uintah's ReactionMech: rate constants in cm, mol, s (concentrations mol/cm^3),
activation energies to J/mol, molecular weights from Uintah's table of atomic weights, so
that the rates are sus's to round-off. Reactions are reversible, the reverse rate from the
equilibrium constant of the NASA-7 Gibbs energies.
"""
from __future__ import annotations

import os
from dataclasses import dataclass

import numpy as np

from framework.problemspec import InputError, ProblemSpec

RU = 8.314462618            # J/(mol K), Uintah's ReactionMech::Ru
P_ATM = 101325.0            # Pa, the NASA-7 standard state
T_REF = 298.15              # K, the sensible energy's reference
ATOMIC_WEIGHTS = {"H": 1.008, "C": 12.011, "O": 15.999, "N": 14.007, "Ar": 39.948, "He": 4.0026,
                  "S": 32.06, "Cl": 35.45, "Br": 79.904, "F": 18.998}
EA_UNITS = {"cal/mol": 4.184, "kcal/mol": 4184.0, "J/mol": 1.0, "kJ/mol": 1.0e3, "K": RU}
ELEMENTARY, THREE_BODY, FALLOFF = 0, 1, 2
REACTION_TYPES = {"elementary": ELEMENTARY, "three-body": THREE_BODY, "falloff": FALLOFF}
MAX_SIDE = 3                # species (with repeats) on one side of a reaction


@dataclass
class Mechanism:
    """The arrays the kernels take (gas_kinetics.py); index k runs over all species in
    <speciesArray> order, the closure species included."""
    names: list
    closure: int            # the species set by 1 - sum of the others (not transported)
    mw: np.ndarray          # g/mol
    r_gas: np.ndarray       # J/(kg K), 1e3 Ru / mw
    t_mid: float            # the NASA-7 ranges' common switch
    t_low: float            # the range every species' polynomials cover
    t_high: float
    nasa: np.ndarray        # (2, n, 7): low and high range coefficients a0..a6
    h_coef: np.ndarray      # (2, n, 6): h/RT's a0, a1/2, a2/3, a3/4, a4/5, a5 (Uintah's pre-divided)
    g_coef: np.ndarray      # (2, n, 7): g/RT's a0, a1/2, a2/6, a3/12, a4/20, a5, a6
    h_ref: np.ndarray       # J/kg, h_k(T_REF)
    rxn_type: np.ndarray    # (r,) ELEMENTARY, THREE_BODY, FALLOFF
    reactants: np.ndarray   # (r, MAX_SIDE) species indices, -1 padded (repeats for coefficients)
    products: np.ndarray
    arrhenius: np.ndarray   # (r, 6): A, b, Ea (J/mol) and the falloff's low limit A0, b0, Ea0
    efficiencies: np.ndarray  # (r, n): third-body efficiencies (unused for elementary ones)
    eff_default: np.ndarray   # (r,): the efficiency of the species a reaction does not list
    troe: np.ndarray        # (r, 4): a, T3, T1, T2
    troe_t2: np.ndarray     # (r,) 1 where the 4-parameter form is given
    visc_fit: np.ndarray    # (n, 5): sqrt(mu) = T^0.25 poly(ln T)
    cond_fit: np.ndarray    # (n, 5): lambda = sqrt(T) poly(ln T)
    diff_fit: np.ndarray    # (n, n, 5): P D_jk = T^1.5 poly(ln T) (Pa m^2/s)

    @property
    def tracked(self):
        """All species but the closure one, in mechanism order (Uintah's tracked order)."""
        return [k for k in range(len(self.names)) if k != self.closure]


def find_mechanism_file(name, deck_file):
    """Uintah opens <mechanismFile> from the working directory (sus runs in StandAlone/, decks
    name inputs/ICE/...); pysus also looks next to the deck and in the deck's parent folders,
    so a deck inside Uintah's tree runs from any directory."""
    if os.path.isabs(name):
        return name if os.path.exists(name) else None
    here = os.path.dirname(os.path.abspath(deck_file)) if deck_file else os.getcwd()
    candidates = [os.path.join(os.getcwd(), name), os.path.join(here, name),
                  os.path.join(here, os.path.basename(name))]
    d = here
    while True:
        candidates.append(os.path.join(d, name))
        up = os.path.dirname(d)
        if up == d:
            break
        d = up
    return next((c for c in candidates if os.path.exists(c)), None)


def _tokens(node, tag):
    """'name:value' tokens of a child's text as (name, float) pairs."""
    out = []
    for tok in node.get(tag, "str").replace(",", " ").split():
        name, _, val = tok.rpartition(":")
        if not name or not val:
            raise node.child(tag).error(f"cannot read '{tok}'; accepted: name:value tokens")
        try:
            out.append((name, float(val)))
        except ValueError:
            raise node.child(tag).error(f"cannot read '{tok}'; accepted: name:value tokens") from None
    return out


def _floats(node, text):
    try:
        return [float(x) for x in text.replace(",", " ").replace("[", " ").replace("]", " ").split()]
    except ValueError:
        raise node.error(f"cannot read numbers from '{text.strip()}'") from None


def read_mechanism(filename, closure_name) -> Mechanism:
    """The mechanism in filename (errors name its file and line), closure_name its closure species."""
    root = ProblemSpec.load(filename)
    if root.tag != "mechanism":
        raise root.error(f"<{root.tag}> is not a reaction mechanism; accepted: a <mechanism> file")
    units = root.child("units")
    ea_default = ""
    if units is not None:
        length, quantity = units.attr("length", default="cm"), units.attr("quantity", default="mol")
        if length != "cm" or quantity != "mol":
            raise units.error(f"units length={length!r} quantity={quantity!r}; accepted: cm and mol")
        ea_default = units.attr("activation-energy", default="")
    phase = root.child("phase", required=True)
    names = phase.get("speciesArray", "str").split()
    n = len(names)
    if closure_name not in names:
        raise phase.child("speciesArray").error(
            f"the closure species {closure_name} is not in the mechanism; accepted: one of {' '.join(names)}")
    index = {s: k for k, s in enumerate(names)}
    data = root.child("speciesData", required=True)
    blocks = {sp.attr("name"): sp for sp in data.children("species")}
    mw = np.zeros(n)
    nasa = np.zeros((2, n, 7))
    visc, cond = np.zeros((n, 5)), np.zeros((n, 5))
    t_mid, t_low, t_high = None, -1.0, -1.0
    for k, s in enumerate(names):
        sp = blocks.get(s)
        if sp is None:
            raise data.error(f'no <species name="{s}"> (listed in <speciesArray>)')
        for atom, count in _tokens(sp, "atomArray"):
            if atom not in ATOMIC_WEIGHTS:
                raise sp.child("atomArray").error(f"unknown element {atom}; accepted: {', '.join(ATOMIC_WEIGHTS)}")
            mw[k] += count * ATOMIC_WEIGHTS[atom]
        ranges = []
        for nz in sp.child("thermo", required=True).children("NASA7"):
            a = _floats(nz, nz.get("floatArray", "str"))
            if len(a) != 7:
                raise nz.error(f"{len(a)} NASA7 coefficients; accepted: 7")
            ranges.append((nz.attr("Tmin", "float"), nz.attr("Tmax", "float"), a))
        if not ranges or len(ranges) > 2:
            raise sp.child("thermo").error(f"{len(ranges)} <NASA7> ranges; accepted: one or two")
        ranges.sort(key=lambda r: r[0])
        lo, hi = ranges[0], ranges[-1]
        if len(ranges) == 2 and abs(lo[1] - hi[0]) > 1e-6:
            raise sp.child("thermo").error(f"the low range ends at {lo[1]} K, the high one starts at {hi[0]} K")
        if t_mid is None:
            t_mid = lo[1]
        elif abs(t_mid - lo[1]) > 1e-6:
            raise sp.child("thermo").error(f"switches polynomials at {lo[1]} K, other species at {t_mid} K; "
                                           "accepted: one switch temperature")
        nasa[0, k], nasa[1, k] = lo[2], hi[2]
        t_low = max(t_low, lo[0])
        t_high = hi[1] if t_high < 0 else min(t_high, hi[1])
        for tag, arr in (("viscosityFit", visc), ("conductivityFit", cond)):
            fit = sp.child(tag)
            if fit is not None:
                c = _floats(fit, fit.text())
                if len(c) != 5:
                    raise fit.error(f"{len(c)} coefficients; accepted: 5")
                arr[k] = c
    r_gas = 1.0e3 * RU / mw
    h_coef = np.stack([nasa[..., 0], nasa[..., 1] / 2.0, nasa[..., 2] / 3.0, nasa[..., 3] / 4.0,
                       nasa[..., 4] / 5.0, nasa[..., 5]], axis=-1)
    g_coef = np.stack([nasa[..., 0], nasa[..., 1] / 2.0, nasa[..., 2] / 6.0, nasa[..., 3] / 12.0,
                       nasa[..., 4] / 20.0, nasa[..., 5], nasa[..., 6]], axis=-1)
    t, t2 = T_REF, T_REF * T_REF
    t3 = t2 * t
    t4 = t3 * t
    t5 = t4 * t
    lo = h_coef[0]
    h_ref = r_gas * (lo[:, 0] * t + lo[:, 1] * t2 + lo[:, 2] * t3 + lo[:, 3] * t4 + lo[:, 4] * t5 + lo[:, 5])
    rxns = root.child("reactionData")
    rxn_nodes = rxns.children("reaction") if rxns is not None else []
    nr = len(rxn_nodes)
    rtype = np.zeros(nr, dtype=np.int64)
    reac, prod = np.full((nr, MAX_SIDE), -1, dtype=np.int64), np.full((nr, MAX_SIDE), -1, dtype=np.int64)
    arr = np.zeros((nr, 6))
    eff, eff_default = np.ones((nr, n)), np.ones(nr)
    troe, troe_t2 = np.zeros((nr, 4)), np.zeros(nr, dtype=np.int64)
    for r, rx in enumerate(rxn_nodes):
        if rx.attr("reversible", default="yes") != "yes":
            raise rx.error("an irreversible reaction; accepted: reversible ones (the reverse rate from equilibrium)")
        rtype[r] = REACTION_TYPES[rx.attr("type", choices=tuple(REACTION_TYPES))]
        for tag, side in (("reactants", reac), ("products", prod)):
            col = 0
            for s, count in _tokens(rx, tag):
                if s not in index:
                    raise rx.child(tag).error(f"unknown species {s}; accepted: {' '.join(names)}")
                if count != round(count) or count < 1:
                    raise rx.child(tag).error(f"coefficient {count} of {s}; accepted: whole numbers")
                for _ in range(int(round(count))):
                    if col == MAX_SIDE:
                        raise rx.child(tag).error(f"more than {MAX_SIDE} species on one side")
                    side[r, col] = index[s]
                    col += 1
        rate = rx.child("rateCoeff", required=True)
        blocks = {a.attr("name", default=""): a for a in rate.children("Arrhenius")}
        want = ("kInf", "k0") if rtype[r] == FALLOFF else ("",)
        for j, which in enumerate(want):
            a = blocks.get(which)
            if a is None:
                raise rate.error("no <Arrhenius" + (f' name="{which}"' if which else "") + ">")
            e_node = a.child("E", required=True)
            e_units = e_node.attr("units", default=ea_default)
            if e_units not in EA_UNITS:
                raise e_node.error(f"activation energy units {e_units!r}; accepted: {', '.join(EA_UNITS)}")
            arr[r, 3 * j:3 * j + 3] = (a.get("A", "float"), a.get("b", "float"), a.get("E", "float") * EA_UNITS[e_units])
        if rtype[r] != ELEMENTARY:
            e = rx.child("efficiencies")
            if e is not None:
                eff_default[r] = e.attr("default", "float", 1.0)
                eff[r, :] = eff_default[r]
                for s, val in _tokens(rx, "efficiencies"):
                    if s not in index:
                        raise e.error(f"efficiency of unknown species {s}")
                    eff[r, index[s]] = val
        if rtype[r] == FALLOFF:
            f = rate.child("falloff", required=True)
            if f.attr("type", default="") != "Troe":
                raise f.error(f'falloff type "{f.attr("type", default="")}"; accepted: Troe')
            v = _floats(f, f.text())
            if len(v) not in (3, 4):
                raise f.error(f"{len(v)} Troe parameters; accepted: a T3 T1 [T2]")
            troe[r, :len(v)] = v
            troe_t2[r] = len(v) == 4
    diff = np.zeros((n, n, 5))
    fits = root.child("binaryDiffusionFits")
    if fits is not None:
        for pair in fits.children("pair"):
            a, b = pair.attr("s1"), pair.attr("s2")
            if a not in index or b not in index:
                raise pair.error(f"a pair of unknown species {a}, {b}")
            c = _floats(pair, pair.attr("coeffs"))
            if len(c) != 5:
                raise pair.error(f"{len(c)} coefficients; accepted: 5")
            diff[index[a], index[b]] = diff[index[b], index[a]] = c
    root.mark_used()
    return Mechanism(names, index[closure_name], mw, r_gas, float(t_mid), float(t_low), float(t_high), nasa,
                     np.ascontiguousarray(h_coef), np.ascontiguousarray(g_coef), h_ref,
                     rtype, reac, prod, arr, eff, eff_default, troe, troe_t2, visc, cond, diff)


__all__ = ["Mechanism", "read_mechanism", "find_mechanism_file", "InputError"]
