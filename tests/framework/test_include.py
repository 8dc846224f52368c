"""<include href> as Uintah's ProblemSpecReader resolves it: next to the including file, then in
the working directory; `section` picks the element whose attributes match the include's other
attributes; excludeSectionTag keeps its children only; errors name the file and line at fault."""
import pytest

from framework.problemspec import InputError, ProblemSpec

DECK = """<?xml version="1.0" encoding="iso-8859-1"?>
<Uintah_specification>
  <Grid>
    {include}
  </Grid>
</Uintah_specification>
"""
PARTS = """<?xml version="1.0"?>
<Uintah_Include>
  <inlet type="a"><x>1</x></inlet>
  <inlet type="b"><x>2</x>
    <y>3</y></inlet>
</Uintah_Include>
"""


def write(path, text):
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)
    return str(path)


def test_section_and_attributes_pick_one_element(tmp_path):
    write(tmp_path / "parts.xml", PARTS)
    deck = write(tmp_path / "deck.ups", DECK.format(include='<include href="parts.xml" section="inlet" type="b"/>'))
    grid = ProblemSpec.load(deck).child("Grid")
    inlets = grid.children("inlet")
    assert [i.attr("type") for i in inlets] == ["b"]
    assert inlets[0].get("x") == 2.0
    # an unread element is reported in the included file, at its own line
    with pytest.raises(InputError) as e:
        grid.check_all_used()
    assert str(e.value).startswith(f"{tmp_path / 'parts.xml'}:5: ") and "<y>" in str(e.value)


def test_exclude_section_tag_and_whole_file(tmp_path):
    write(tmp_path / "parts.xml", PARTS)
    deck = write(tmp_path / "deck.ups", DECK.format(
        include='<include href="parts.xml" section="inlet" type="a" excludeSectionTag="true"/>'))
    assert ProblemSpec.load(deck).child("Grid").get("x") == 1.0
    deck = write(tmp_path / "deck.ups", DECK.format(include='<include href="parts.xml"/>'))
    assert len(ProblemSpec.load(deck).child("Grid").children("inlet")) == 2


def test_next_to_the_including_file_then_the_working_directory(tmp_path, monkeypatch):
    # the nested include "more.xml" is found next to sub/parts.xml, not next to the deck
    write(tmp_path / "sub" / "parts.xml", '<Uintah_Include><include href="more.xml"/></Uintah_Include>')
    write(tmp_path / "sub" / "more.xml", '<Uintah_Include><z>4</z></Uintah_Include>')
    write(tmp_path / "cwd" / "inputs" / "w.xml", '<Uintah_Include><w>5</w></Uintah_Include>')
    deck = write(tmp_path / "deck.ups", DECK.format(
        include='<include href="sub/parts.xml"/><include href="inputs/w.xml"/>'))
    monkeypatch.chdir(tmp_path / "cwd")
    grid = ProblemSpec.load(deck).child("Grid")
    assert grid.get("z") == 4.0 and grid.get("w") == 5.0


@pytest.mark.parametrize("include,parts,expect", [
    ('<include href="none.xml"/>', None, "deck.ups:4: "),
    ('<include href="parts.xml" section="inlet" type="c"/>', PARTS, "deck.ups:4: "),
    ('<include href="parts.xml"/>', "<Other/>", "parts.xml:1: "),
    ('<include href="parts.xml"/>', "<Uintah_Include><a></Uintah_Include>", "parts.xml:1: "),
])
def test_errors_name_the_file_and_line(tmp_path, monkeypatch, include, parts, expect):
    monkeypatch.chdir(tmp_path)
    if parts is not None:
        write(tmp_path / "parts.xml", parts)
    deck = write(tmp_path / "deck.ups", DECK.format(include=include))
    with pytest.raises(InputError) as e:
        ProblemSpec.load(deck)
    assert expect in str(e.value) and "\n" not in str(e.value)

