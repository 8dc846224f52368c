"""Bad input fuzz: mutated shipped decks give one clean error line or pass set-up, nothing else.

The mutations (deck_mutations.py) run through `pysus -validate`: problem set-up, grid and
task-graph compile, no timestep and no numba kernel, so the few hundred take seconds.
"""
from __future__ import annotations

import pytest

from framework.controller import Controller
from framework.problemspec import InputError, ProblemSpec, deck_bytes

from .deck_mutations import REFUSE, RUN, ROOT, mutations, validate

MUTATIONS = mutations()


@pytest.fixture(scope="module")
def scratch(tmp_path_factory):
    return tmp_path_factory.mktemp("fuzz")


def test_the_generator_covers_every_class():
    kinds = {m.kind for m in MUTATIONS}
    assert len(MUTATIONS) >= 300
    assert {"number -> NaN", "number -> inf", "wrong root element", "geometry outside the domain",
            "Latin-1 byte, declared iso-8859-1", "resolution too large for memory",
            "filebase under a regular file", "<Face side> duplicated", "harmless change"} <= kinds
    assert {m.deck.split("/")[0] for m in MUTATIONS} >= {"ICE", "MPM", "MPMICE", "examples"}


@pytest.mark.parametrize("mutation", MUTATIONS, ids=[f"{i:03d}" for i in range(len(MUTATIONS))])
def test_mutation(mutation, scratch):
    outcome, text = validate(mutation, str(scratch))
    assert outcome != "other", f"{mutation.id}: not one clean line:\n{text}"
    if mutation.expect == REFUSE:
        assert outcome == "clean line", f"{mutation.id}: accepted"
    elif mutation.expect == RUN:
        assert outcome == "ran", f"{mutation.id}: refused:\n{text}"


def test_error_line_names_file_line_tag_and_what_is_accepted(scratch):
    m = next(m for m in MUTATIONS if m.kind == "named bad value" and m.what == "Time/delt_max = 0")
    _, text = validate(m, str(scratch))
    line = text.strip().splitlines()[-1]
    assert line.startswith(f"pysus: error: {scratch}/deck.ups:")
    assert "<Uintah_specification/Time/delt_max> value '0' is out of range; accepted: a finite number > 0" in line


def test_memory_estimate_is_given(scratch):
    m = next(m for m in MUTATIONS if m.kind == "resolution too large for memory" and m.deck == "ICE/sod.ups")
    _, text = validate(m, str(scratch))
    assert "GiB for grid variables" in text and "whose arrays fit in memory" in text


LATIN1 = ('<?xml version="1.0" encoding="iso-8859-1"?>\n<!-- 5 \xb5m at 20 \xb0C -->\n').encode("latin-1")


def test_latin1_deck_is_kept_byte_exact_in_the_uda(tmp_path):
    body = (ROOT / "inputs/ICE/sod.ups").read_bytes().split(b"?>", 1)[1]
    deck = tmp_path / "latin.ups"
    deck.write_bytes(LATIN1 + body)
    ctl = Controller(str(deck), quiet=True, filebase=str(tmp_path / "latin.uda"))
    ctl.archiver.setup(0.0)
    assert (tmp_path / "latin.uda" / "input.ups").read_bytes() == LATIN1 + body
    # the copy reads back with the same comment (what a restart parses)
    again = ProblemSpec.load(str(tmp_path / "latin.uda" / "input.ups"))
    comments = [c.text for c in again.element.itersiblings(preceding=True)]
    assert " 5 \xb5m at 20 \xb0C " in comments


def test_deck_text_is_encoded_as_declared():
    assert deck_bytes('<?xml version="1.0" encoding="iso-8859-1"?><a>\xb5</a>').endswith(b"<a>\xb5</a>")
    assert deck_bytes("<a>\xb5</a>") == "<a>\xb5</a>".encode()
    with pytest.raises(InputError, match="declared encoding"):
        deck_bytes('<?xml version="1.0" encoding="ascii"?><a>\xb5</a>', "d.ups")


def test_cylinder_axis_overflowing_is_refused_by_name(scratch):
    """A cylinder end at 1e300 m: its axis's length squared overflows, which the deck reader
    refuses on the cylinder's line instead of letting inf reach the particle fill."""
    m = next(m for m in MUTATIONS if m.kind == "number -> huge" and m.what.split(" = ")[0].endswith("cylinder/bottom"))
    outcome, text = validate(m, str(scratch))
    assert outcome == "clean line", text
    assert "/cylinder> <bottom>" in text and "too far apart" in text and "RuntimeWarning" not in text
