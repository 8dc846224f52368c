"""<CFD><ICE><delT_traceVolFrac> (pysus): in a cell where a material's volume fraction is below
the value, its sound speed does not limit ICE's step (its velocity still does). Uintah counts
every material in every cell, so that the hot trace of air inside a solid can set the step.

The pressurized cylinder (components/mpmice/scene_cylinder.py) at 12 cells, ri = 0.6 m, the z cell
as thin as dx, to 2.5 ms: measured 1125 steps with every material counted, 697 with the tag at
1e-6, eq. 43 error 0.0543 and 0.0560 (to the deck's 5 ms: 3001 and 1498 steps, 0.0537 and 0.0554;
with the deck's own 0.025 m z cell 15598 and 5975 steps, 0.0611 and 0.0533).
"""
import pytest

from components.mpmice import scene_cylinder as C
from framework.problemspec import InputError
from tests.conftest import load_script, run_deck


def _cylinder(tmp_path, name, trace=None):
    from framework.archiver import DataArchive
    ctl = run_deck(C.deck(12, ri=0.6, dz="dx", t_end=2.5e-3, trace=trace), tmp_path, name)
    return ctl.timestep, C.errors(DataArchive(ctl.archiver.dir), ri=0.6)


def test_trace_sound_speed_aside_takes_fewer_steps(tmp_path):
    steps_all, e_all = _cylinder(tmp_path, "every_material")
    steps_trace, e_trace = _cylinder(tmp_path, "trace_aside", trace=1e-6)
    assert steps_trace < 0.7 * steps_all
    assert abs(e_trace["eq43"] - e_all["eq43"]) < 0.005
    assert abs(e_trace["P_MPa"] - e_all["P_MPa"]) < 0.05


def test_out_of_range_is_refused_by_name(tmp_path):
    with pytest.raises(InputError, match="delT_traceVolFrac"):
        run_deck(C.deck(12, dz="dx", trace=1.5), tmp_path, "bad")


def test_uintah_deck_drops_it():
    acc = load_script("accuracy_cost")
    deck = C.deck(12, trace=1e-6)
    assert "<delT_traceVolFrac> 1e-06 </delT_traceVolFrac>" in deck
    assert "delT_traceVolFrac" not in acc.uintah_deck(deck)
