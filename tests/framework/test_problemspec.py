"""Deck reading: typed values, and every class of bad input gives one clean line."""
import pytest

from framework.problemspec import InputError, Param, ProblemSpec
from tests.framework import decks
from tests.conftest import pysus_ranks


def spec(text):
    return ProblemSpec.from_string(text, "deck.ups")


def test_typed_values_and_defaults():
    ps = spec("<a><x>1.5</x><n>3</n><v>[1, 2,3]</v><b>true</b></a>")
    got = ps.read({"x": Param("float"), "n": Param("int"), "v": Param("vector"), "b": Param("bool"),
                   "d": Param("float", 7.0)})
    assert got == {"x": 1.5, "n": 3, "v": (1.0, 2.0, 3.0), "b": True, "d": 7.0}
    ps.check_all_used()


@pytest.mark.parametrize("text,expect", [
    ("<a><x>abc</x></a>", "value 'abc' is not a finite number"),
    ("<a><v>[1,2]</v></a>", "is not a vector"),
    ("<a></a>", "missing required tag <x>"),
])
def test_bad_values_name_line_and_path(text, expect):
    ps = spec(text)
    with pytest.raises(InputError) as e:
        ps.read({"v": Param("vector", None), "x": Param("float")})
    assert expect in str(e.value) and "deck.ups:1" in str(e.value)


def test_unread_tag_is_an_error_listing_accepted_tags():
    ps = spec("<a>\n<x>1</x>\n<typo>2</typo>\n</a>")
    ps.get("x")
    with pytest.raises(InputError) as e:
        ps.check_all_used()
    msg = str(e.value)
    assert "deck.ups:3" in msg and "<a/typo>" in msg and "unsupported tag <typo>" in msg and "<x>" in msg


def test_choices():
    ps = spec('<a type="Third"/>')
    with pytest.raises(InputError, match="accepted: First, Second"):
        ps.attr("type", choices=("First", "Second"))


BAD = {
    "malformed": ("<Uintah_specification><Time></Uintah_specification>", "malformed XML"),
    "unknown tag": (decks.heat().replace("<Meta>", "<Bogus>1</Bogus><Meta>"), "unsupported tag <Bogus>"),
    "wrong type": (decks.heat().replace("<alpha>0.01</alpha>", "<alpha>fast</alpha>"), "is not a finite number"),
    "missing value": (decks.heat().replace("<maxTime>0.2</maxTime>", ""), "missing required tag <maxTime>"),
    "bad choice": (decks.heat().replace('type="examples"', 'type="nonsense"'), "is not available"),
    "bad save": (decks.heat().replace('<save label="temp_CC"/>', '<save label="press_CC"/>'),
                 "names a variable this deck does not compute"),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_cli_bad_input_is_one_line_exit_2(case, deckfile):
    text, expect = BAD[case]
    path = deckfile(text)
    r = pysus_ranks(path)
    assert r.returncode == 2, r.stderr
    assert "Traceback" not in r.stderr
    lines = [l for l in r.stderr.splitlines() if l.strip()]
    assert len(lines) == 1 and expect in lines[0] and str(path) in lines[0], r.stderr


def test_missing_deck_file_is_clean():
    r = pysus_ranks("/nonexistent/deck.ups")
    assert r.returncode == 2 and "Traceback" not in r.stderr and "cannot read" in r.stderr


@pytest.mark.parametrize("text", ["nan", "inf", "-Infinity", "[1, nan, 2]", "[inf,0,0]"])
def test_nan_and_inf_are_refused(text):
    ps = spec(f"<a><x>{text}</x></a>")
    kind = "vector" if text.startswith("[") else "float"
    with pytest.raises(InputError, match="finite number"):
        ps.get("x", kind)


def test_ranges_declared_per_parameter():
    ps = spec("<a><p>0</p><q>-1</q><v>[1,0,2]</v><n>1e300</n></a>")
    with pytest.raises(InputError, match=r"<a/p> value '0' is out of range; accepted: a finite number > 0"):
        ps.read({"p": Param("float", above=0.0)})
    with pytest.raises(InputError, match=r"accepted: a finite number >= 0"):
        ps.get("q", at_least=0.0)
    with pytest.raises(InputError, match=r"> 0 in every component"):
        ps.get("v", "vector", above=0.0)
    with pytest.raises(InputError, match="is not an integer"):
        ps.get("n", "int")
    assert ps.get("q", at_least=-1.0) == -1.0 and ps.get("p", at_least=0.0) == 0.0


def test_wrong_root_element_is_refused(tmp_path):
    from framework.controller import Controller
    text = decks.heat().replace("Uintah_specification>", "Uintah_spec>")
    with pytest.raises(InputError, match="root element is not <Uintah_specification>"):
        Controller(str(tmp_path / "d.ups"), deck_text=text, quiet=True)
