"""Pressurized cylinder (paper 000 sec. 4.1, inputs/MPMICE/pressurized_cylinder.ups): the
stresses approach Lame's solution (eq. 42), the eq. 43 error falls faster than at the paper's
order 0.89, and it stays below Uintah's sus on the same decks.

The deck (docs/MPMICE.md, "Pressurized cylinder"): the steel with <DoPressureStabilization>
and <cut_cell_particles>, no heat exchange between the steel and the air (Uintah's symAnnulus
has none), and its end at 5 ms, where the ring's breathing that the 1 ms pressurization starts
has died out. Measured (scripts/accuracy_cost.py cylinder --res 12 18 24 36 48 --opt dz=dx
--opt ri=0.4,0.5,0.6 --opt ro=0.9,1.0; the one z cell as thin as dx, the same plane-strain
problem): least-squares order 1.35 to 1.50 at all six pairs of radii; at the paper's radii
0.0578, 0.0297, 0.0224, 0.0128, 0.0085 (1.35), at ri = 0.6 m 0.0537, 0.0288, 0.0205, 0.0104,
0.0077 (1.42).
"""
import numpy as np
import pytest

from components.mpmice import scene_cylinder as C
from tests.conftest import load_script, run_deck


# Uintah's sus on the same decks (scripts/accuracy_cost.py cylinder --res 12 18 24 --opt dz=dx
# --opt ri=0.5,0.6 --opt stab=true,false --opt cut=true,false --uintah SUS): sus has no
# <cut_cell_particles>, so it runs the steel on the lattice's whole sub-cells, with the deck's
# stabilization: eq. 43 error 0.1861, 0.1317, 0.0810 at 12, 18, 24 cells (pysus on that deck,
# cut=false: 0.1572, 0.1174, 0.0708; with the tag 0.0578, 0.0297, 0.0224); at ri = 0.6 m 0.1763,
# 0.1055, 0.0976 (pysus 0.1611, 0.0903, 0.0886; with the tag 0.0537, 0.0288, 0.0205).
SUS_EQ43 = {(0.5, 12): 0.1861, (0.5, 18): 0.1317, (0.6, 12): 0.1763, (0.6, 18): 0.1055}


def _run(n, tmp_path, ri=C.RI, **opts):
    from framework.archiver import DataArchive
    ctl = run_deck(C.deck(n, ri=ri, dz="dx", **opts), tmp_path, f"cyl{n}_{ri}")
    return C.errors(DataArchive(ctl.archiver.dir), ri=ri)


@pytest.fixture(scope="module")
def errs(tmp_path_factory):
    return {(ri, n): _run(n, tmp_path_factory.mktemp(f"cyl{n}"), ri) for ri, n in ((0.5, 12), (0.6, 12), (0.6, 18))}


def test_pressure_reached(errs):
    for e in errs.values():
        assert 19.0 < e["P_MPa"] < 19.6            # the paper's 19.4 MPa


def test_eq43_error_below_uintahs(errs):
    for key, e in errs.items():
        assert e["eq43"] < 0.5 * SUS_EQ43[key], (key, e)


def test_error_falls_faster_than_the_papers_order(errs):
    """ri = 0.6 m, ro = 1.0 m, where a steel-air heat exchange or an end at 2.5 ms held the order
    to 0.84 over 12 .. 48 cells: measured 1.54 between 12 and 18 cells, 1.42 over 12 .. 48."""
    e12, e18 = errs[0.6, 12], errs[0.6, 18]
    assert np.log(e12["eq43"] / e18["eq43"]) / np.log(18 / 12) > 1.2
    for k in ("radial", "hoop"):
        assert e18[k] < e12[k] < 0.06


def test_lattice_particles_below_uintahs(errs, tmp_path):
    """The steel on the lattice's whole sub-cells (cut=false), the deck sus runs: below sus's
    error (measured 0.1611 against 0.1763 at 12 cells, ri = 0.6 m), and three times the cut-cell
    particles' (0.0537): the staircase's surface layers carry most of it."""
    e = _run(12, tmp_path, ri=0.6, cut=False)
    assert e["eq43"] < SUS_EQ43[0.6, 12]
    assert errs[0.6, 12]["eq43"] < 0.5 * e["eq43"]
    assert errs[0.6, 12]["eq43_surf"] < 0.5 * e["eq43_surf"]


def test_quasi_static_at_the_end(tmp_path):
    """The pressurization over 1 ms sets the ring breathing (period about 1.2 ms), which the
    damping takes out by 5 ms: at ri = 0.4 m, 12 cells, the mean of s_r + s_t is 3.0 % above
    Lame's at 2.5 ms and 0.6 % at 5 ms, where the steel carries the inner pressure to 0.2 %
    (measured; scene_cylinder.history, scripts/cylinder_history.py)."""
    from framework.archiver import DataArchive
    text = C.deck(12, ri=0.4, dz="dx").replace("<outputInterval> 5.0e-3 </outputInterval>",
                                                "<outputInterval> 2.5e-3 </outputInterval>")
    ctl = run_deck(text, tmp_path, "cyl12_breathing")
    (t_mid, _, level_mid, _), (t_end, P_end, level_end, load_end) = C.history(DataArchive(ctl.archiver.dir), ri=0.4)
    assert t_mid == pytest.approx(2.5e-3, rel=1e-3) and t_end == pytest.approx(5e-3, rel=1e-3)
    assert level_mid > 0.02 and abs(level_end) < 0.01
    assert abs(load_end - 1.0) < 0.005 and 19.0 < P_end < 19.6


def test_lame_other_radii():
    """Lame's solution (eq. 42) as the errors use it: s_r = -P at ri, 0 at ro, s_r + s_t = 2 P ri^2 / (ro^2 - ri^2)."""
    for ri, ro in ((0.5, 1.0), (0.4, 0.9), (0.6, 1.0)):
        s_r, s_t = C.lame(np.array([ri, 0.5 * (ri + ro), ro]), 1.0, ri, ro)
        assert s_r[0] == pytest.approx(-1.0) and s_r[2] == pytest.approx(0.0, abs=1e-12)
        assert np.allclose(s_r + s_t, 2 * ri ** 2 / (ro ** 2 - ri ** 2))


def test_deck_options():
    text, dx = C.deck(24, ri=0.4, ro=0.9, dz="dx", t_end=2.5e-3), repr(1.2 / 24)
    for want in (f"<spacing> [{dx},{dx},{dx}] </spacing>", f"<upper> [1.2,1.2,{dx}] </upper>", "<radius> 0.9 </radius>",
                 "<radius> 0.4 </radius>", "<maxTime> 0.0025 </maxTime>"):
        assert want in text, want
    with pytest.raises(ValueError):
        C.deck(12, ro=1.15)            # no air cell outside the annulus
    with pytest.raises(ValueError):
        C.deck(12, stab="yes")
    deck = C.deck(12)
    assert "<DoPressureStabilization> true </DoPressureStabilization>" in deck
    assert deck.count("<cut_cell_particles> true </cut_cell_particles>") == 1     # the steel's only
    assert "<heat> [0.0, 0.0, 1e10] </heat>" in deck and "<maxTime> 5.0e-3 </maxTime>" in deck
    text = C.deck(12, stab=False, cut="false", ppc=4, fill=-2, heat=1e6)
    steel = text[text.index('<material name="steel">'):text.index("</material>", text.index('<material name="steel">'))]
    assert "<DoPressureStabilization> false </DoPressureStabilization>" in text
    assert "<cut_cell_particles> false </cut_cell_particles>" in steel
    assert "<res> [4,4,1] </res>" in steel and text.count("<res> [2,2,1] </res>") == 2     # the airs keep theirs
    assert "<numLevelsParticleFilling> -2 </numLevelsParticleFilling>" in steel
    assert "<heat> [1000000.0, 1000000.0, 1e10] </heat>" in text
    acc = load_script("accuracy_cost")
    assert "cut_cell_particles" not in acc.uintah_deck(deck)                  # sus runs it without
    smooth = C.deck(12, ri=0.6, geom="smooth", interpolator="linear")
    assert "<smoothcyl>" in smooth and "<num_radial>8</num_radial>" in smooth   # (1.0 - 0.6) / (0.1 / 2)
    assert "<cut_cell_particles> true </cut_cell_particles>" not in smooth
