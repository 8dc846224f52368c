"""Mutated copies of the shipped decks, for the bad-input fuzz test (test_deck_fuzz.py).

Each `Mutation` holds the bytes of a deck from inputs/ with one change (a number made 0,
-1, NaN, inf or huge; a tag deleted, duplicated or given a wrong type; a Latin-1 byte; a
wrong root; a geometry object moved out of the domain ...) and what must come of it:
REFUSE (one clean `pysus: error: FILE:LINE: ...` line, exit status 2), RUN (set-up passes)
or EITHER (no more is known; only a traceback or an unclear message is wrong). The set is
deterministic (a fixed seed). `python -m tests.framework.deck_mutations` runs every
mutation through `pysus -validate` in this process and prints the table of outcomes.
"""
from __future__ import annotations

import contextlib
import copy
import io
import math
import os
import random
import re
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

from lxml import etree

ROOT = Path(__file__).resolve().parents[2]
DECKS = ("ICE/sod.ups", "ICE/explosion2D.ups", "ICE/airwater.ups", "MPM/disks_50x50.ups",
         "MPM/bar_vibration.ups", "MPM/thick_cylinder.ups", "MPMICE/piston.ups", "MPMICE/slab_rest.ups",
         "examples/quickstart.ups", "examples/heat3d.ups")
REFUSE, RUN, EITHER = "refuse", "run", "either"
SEED = 18

# tags whose value must be positive wherever pysus reads them (0 and -1 must be refused)
POSITIVE = {"density", "bulk_modulus", "gamma", "cfl", "delt_max", "timestep_multiplier", "temperature",
            "K", "rho0", "delt_init", "max_initial_delt", "radius", "alpha", "width"}
NON_NEGATIVE = {"outputInterval", "outputTimestepInterval", "delt_min", "initTime", "thermal_conductivity",
                "dynamic_viscosity"}
# numbers that are not read as numbers (free text): never mutated
SKIP_UNDER = ("Meta",)


@dataclass
class Mutation:
    deck: str            # the shipped deck it was made from (relative to inputs/)
    kind: str            # the class of mutation (a row of the table)
    what: str            # what was changed
    data: bytes          # the mutated deck
    expect: str          # REFUSE, RUN or EITHER

    @property
    def id(self):
        return f"{self.deck}:{self.kind}:{self.what}"


def _parse(path):
    parser = etree.XMLParser(remove_comments=False, resolve_entities=False)
    return etree.parse(str(path), parser)


def _bytes(tree):
    return etree.tostring(tree, xml_declaration=True, encoding="UTF-8")


def _numeric(text):
    """'number', 'vector' or None for an element's text."""
    t = (text or "").strip()
    if re.fullmatch(r"\[\s*[-+0-9.eE]+(\s*,?\s*[-+0-9.eE]+){2}\s*\]", t):
        return "vector"
    try:
        float(t)
        return "number"
    except ValueError:
        return None


def _leaves(tree):
    """Elements with a numeric text and no element children, outside free-text blocks."""
    out = []
    for el in tree.getroot().iter():
        if not isinstance(el.tag, str) or len([c for c in el if isinstance(c.tag, str)]):
            continue
        if any(a.tag in SKIP_UNDER for a in el.iterancestors()):
            continue
        kind = _numeric(el.text)
        if kind:
            out.append((el, kind))
    return out


def _path_of(tree, el):
    return tree.getpath(el)


def _mutate(tree, xpath, fn):
    """A copy of the tree with fn applied to the element at xpath."""
    t = copy.deepcopy(tree)
    fn(t.xpath(xpath)[0], t)
    return t


def _set_text(value):
    def fn(el, _t):
        el.text = value
    return fn


def _vector_value(kind, v):
    return f"[{v},{v},{v}]" if kind == "vector" else v


def numeric_mutations(name, tree, rng, per_deck=6):
    """Numbers -> 0, -1, NaN, inf, huge on a sample of the deck's numeric leaves."""
    leaves = _leaves(tree)
    picks = rng.sample(leaves, min(per_deck, len(leaves)))
    for el, kind in picks:
        xp = _path_of(tree, el)
        tag = el.tag
        for label, v in (("0", "0"), ("-1", "-1"), ("NaN", "nan"), ("inf", "inf"), ("huge", "1e300")):
            if label in ("NaN", "inf"):
                expect = REFUSE
            elif label == "0" and _solid_at_zero_kelvin(name, xp):
                expect = RUN
            elif label in ("0", "-1") and tag in POSITIVE:
                expect = REFUSE
            elif label == "-1" and tag in NON_NEGATIVE:
                expect = REFUSE
            else:
                expect = EITHER
            yield Mutation(name, f"number -> {label}", f"{xp} = {v}",
                           _bytes(_mutate(tree, xp, _set_text(_vector_value(kind, v)))), expect)


def type_mutations(name, tree, rng, per_deck=3):
    """A number given as a word, a vector with two components."""
    leaves = _leaves(tree)
    for el, kind in rng.sample(leaves, min(per_deck, len(leaves))):
        xp = _path_of(tree, el)
        bad = "[1, 2]" if kind == "vector" else "fast"
        yield Mutation(name, "wrong type", f"{xp} = {bad}", _bytes(_mutate(tree, xp, _set_text(bad))), REFUSE)


REQUIRED = ("/Uintah_specification/Time/maxTime", "/Uintah_specification/Grid", "/Uintah_specification/Time",
            "/Uintah_specification/SimulationComponent")


def deletion_mutations(name, tree, rng, per_deck=4):
    """Required tags deleted (must be refused) and random elements deleted (either)."""
    for xp in REQUIRED:
        if tree.xpath(xp):
            yield Mutation(name, "required tag deleted", xp,
                           _bytes(_mutate(tree, xp, lambda el, _t: el.getparent().remove(el))), REFUSE)
    els = [e for e in tree.getroot().iter() if isinstance(e.tag, str) and e is not tree.getroot()]
    for el in rng.sample(els, min(per_deck, len(els))):
        xp = _path_of(tree, el)
        yield Mutation(name, "any tag deleted", xp,
                       _bytes(_mutate(tree, xp, lambda e, _t: e.getparent().remove(e))), EITHER)


def _duplicate(el, _t):
    el.addnext(copy.deepcopy(el))


def duplication_mutations(name, tree, rng, per_deck=3):
    """A single-valued tag or a boundary face given twice (refused); any element twice (either)."""
    for xp in ("/Uintah_specification/Time/maxTime", "/Uintah_specification/Grid/Level/Box/resolution"):
        if tree.xpath(xp):
            yield Mutation(name, "single tag duplicated", xp, _bytes(_mutate(tree, xp, _duplicate)), REFUSE)
    faces = tree.xpath("//BoundaryConditions/Face")
    if faces:
        xp = _path_of(tree, faces[0])
        yield Mutation(name, "<Face side> duplicated", xp, _bytes(_mutate(tree, xp, _duplicate)), REFUSE)
    els = [e for e in tree.getroot().iter() if isinstance(e.tag, str) and e is not tree.getroot()]
    for el in rng.sample(els, min(per_deck, len(els))):
        xp = _path_of(tree, el)
        yield Mutation(name, "any tag duplicated", xp, _bytes(_mutate(tree, xp, _duplicate)), EITHER)


# (xpath relative to the root, value, expected): the values issue 18 lists by name
TARGETED = (
    ("Time/delt_max", "0", REFUSE), ("Time/delt_max", "nan", REFUSE),
    ("Time/timestep_multiplier", "0", REFUSE), ("Time/timestep_multiplier", "-1", REFUSE),
    ("Time/timestep_multiplier", "nan", REFUSE), ("Time/maxTime", "nan", REFUSE), ("Time/maxTime", "inf", REFUSE),
    ("Time/initTime", "inf", REFUSE), ("CFD/cfl", "0", REFUSE), ("CFD/cfl", "nan", REFUSE),
    ("Grid/Level/Box/patches", "[0,1,1]", REFUSE), ("Grid/Level/Box/extraCells", "[100,100,100]", REFUSE),
    ("Grid/Level/Box/lower", "[nan,0,0]", REFUSE), ("Grid/Level/Box/upper", "[inf,1,1]", REFUSE),
    ("PhysicalConstants/gravity", "[0,nan,0]", REFUSE),
    ("DataArchiver/outputInterval", "-1", REFUSE), ("DataArchiver/outputInterval", "nan", REFUSE),
    ("DataArchiver/outputTimestepInterval", "-1", REFUSE),
    ("MaterialProperties/ICE/material/gamma", "1", REFUSE), ("MaterialProperties/ICE/material/gamma", "0.5", REFUSE),
    ("MaterialProperties/ICE/material/geom_object/temperature", "0", REFUSE),
    ("MaterialProperties/ICE/material/geom_object/temperature", "-300", REFUSE),
    ("MaterialProperties/ICE/material/geom_object/density", "0", REFUSE),
    ("MaterialProperties/ICE/material/geom_object/density", "nan", REFUSE),
    ("MaterialProperties/ICE/material/geom_object/pressure", "inf", REFUSE),
    ("MaterialProperties/ICE/material/geom_object/velocity", "[inf,0,0]", REFUSE),
    ("MaterialProperties/MPM/material/density", "0", REFUSE), ("MaterialProperties/MPM/material/density", "-1", REFUSE),
    ("MaterialProperties/MPM/material/constitutive_model/bulk_modulus", "0", REFUSE),
    ("MaterialProperties/MPM/material/constitutive_model/bulk_modulus", "nan", REFUSE),
    ("MaterialProperties/MPM/material/geom_object/velocity", "[nan,0,0]", REFUSE),
    ("MaterialProperties/MPM/material/geom_object/temperature", "0", REFUSE),
    ("MaterialProperties/MPM/material/geom_object/temperature", "-1", REFUSE),
)


def _solid_at_zero_kelvin(name, xpath):
    """An MPM solid's geom_object at 0 K: MPM alone accepts it (as Uintah's MPM decks use it),
    MPMICE refuses it (the solid's temperature enters the exchange)."""
    return (not name.startswith("MPMICE/") and "/MPM/material" in xpath
            and xpath.split("/")[-1].startswith("temperature"))


def targeted_mutations(name, tree):
    root = tree.getroot().tag
    for rel, value, expect in TARGETED:
        xp = f"/{root}/{rel}"
        if tree.xpath(xp):
            if value == "0" and _solid_at_zero_kelvin(name, xp):
                expect = RUN
            yield Mutation(name, "named bad value", f"{rel} = {value}",
                           _bytes(_mutate(tree, xp, _set_text(value))), expect)
    xp = f"/{root}/Time/delt_max"
    if not tree.xpath(xp):
        def add(el, _t):
            etree.SubElement(el, "delt_max").text = "0"
        yield Mutation(name, "named bad value", "Time/delt_max = 0 (added)",
                       _bytes(_mutate(tree, f"/{root}/Time", add)), REFUSE)
    res = tree.xpath(f"/{root}/Grid/Level/Box/resolution")
    if res:
        def spacing(value):
            def fn(el, _t):
                box = el.getparent()
                box.remove(el)
                etree.SubElement(box.getparent(), "spacing").text = value
            return fn
        for v in ("[0,0,0]", "[nan,nan,nan]"):
            yield Mutation(name, "named bad value", f"spacing {v}",
                           _bytes(_mutate(tree, _path_of(tree, res[0]), spacing(v))), REFUSE)

        def huge(el, _t):
            n = [int(x) for x in el.text.strip().strip("[]").replace(",", " ").split()]
            dims = [x for x in n if x > 1]
            f = math.ceil((4e12 / math.prod(n)) ** (1.0 / max(1, len(dims))))
            el.text = "[" + ",".join(str(x * f if x > 1 else 1) for x in n) + "]"
        yield Mutation(name, "resolution too large for memory", "resolution x f, >= 4e12 cells",
                       _bytes(_mutate(tree, _path_of(tree, res[0]), huge)), REFUSE)
    fb = tree.xpath(f"/{root}/DataArchiver/filebase")
    if fb:
        under_file = os.path.join(os.path.abspath(__file__), "out.uda")
        yield Mutation(name, "filebase under a regular file", under_file,
                       _bytes(_mutate(tree, _path_of(tree, fb[0]), _set_text(under_file))), REFUSE)


def geometry_mutations(name, tree):
    """The first geom_object of each material moved wholly outside the domain: refused, but
    for an ICE material with other materials or other objects of its own in the domain (Uintah's
    idioms: a material that starts absent, DDT.ups's first object outside), which runs with a
    note unless the moved object held a piece another refers to by label (then refused):
    either, as one clean line."""
    n_materials = len(tree.xpath("//MaterialProperties/*/material"))
    for i, go in enumerate(tree.xpath("//MaterialProperties/*/material/geom_object[1]")):
        material = go.getparent()
        absent_ice = (material.getparent().tag == "ICE"
                      and (n_materials > 1 or len(material.findall("geom_object")) > 1))
        def far(el, _t):
            for c in list(el):
                if isinstance(c.tag, str) and c.tag in ("box", "sphere", "cylinder", "union", "difference",
                                                       "intersection", "tri"):
                    el.remove(c)
            box = etree.Element("box")
            etree.SubElement(box, "min").text = "[1e6,1e6,1e6]"
            etree.SubElement(box, "max").text = "[2e6,2e6,2e6]"
            el.insert(0, box)
        yield Mutation(name, "geometry outside the domain", f"material {i}",
                       _bytes(_mutate(tree, _path_of(tree, go), far)), EITHER if absent_ice else REFUSE)


def whole_deck_mutations(name, raw, tree):
    """Root renamed, Latin-1 bytes (declared and undeclared) and harmless changes."""
    t = copy.deepcopy(tree)
    t.getroot().tag = "Uintah_spec"
    yield Mutation(name, "wrong root element", "Uintah_spec", _bytes(t), REFUSE)
    body = re.sub(rb"^\s*<\?xml[^>]*\?>", b"", raw)
    comment = "<!-- a 5 µm gap at 20 °C -->\n".encode("latin-1")
    declared = b'<?xml version="1.0" encoding="iso-8859-1"?>\n' + comment + body
    yield Mutation(name, "Latin-1 byte, declared iso-8859-1", "µ and ° in a comment", declared, RUN)
    undeclared = b'<?xml version="1.0" encoding="UTF-8"?>\n' + comment + body
    yield Mutation(name, "Latin-1 byte, declared UTF-8", "µ and ° in a comment", undeclared, REFUSE)
    mt = tree.xpath("/*/Time/maxTime")
    if mt:
        v = float(mt[0].text) * 0.5
        yield Mutation(name, "harmless change", f"maxTime = {v:g}",
                       _bytes(_mutate(tree, _path_of(tree, mt[0]), _set_text(f" {v!r} "))), RUN)
    cfl = tree.xpath("/*/CFD/cfl")
    if cfl:
        v = float(cfl[0].text) * 0.9
        yield Mutation(name, "harmless change", f"cfl = {v:g}",
                       _bytes(_mutate(tree, _path_of(tree, cfl[0]), _set_text(repr(v)))), RUN)
    for el, kind in _leaves(tree):
        if el.tag == "temperature":
            v = float(el.text) + 1.0
            yield Mutation(name, "harmless change", f"{el.tag} = {v:g}",
                           _bytes(_mutate(tree, _path_of(tree, el), _set_text(repr(v)))), RUN)
            break


def mutations(seed=SEED):
    """Every mutation of every deck in DECKS, in a fixed order."""
    rng = random.Random(seed)
    out = []
    for name in DECKS:
        path = ROOT / "inputs" / name
        raw = path.read_bytes()
        tree = _parse(path)
        for gen in (numeric_mutations(name, tree, rng), type_mutations(name, tree, rng),
                    deletion_mutations(name, tree, rng), duplication_mutations(name, tree, rng),
                    targeted_mutations(name, tree), geometry_mutations(name, tree),
                    whole_deck_mutations(name, raw, tree)):
            out.extend(gen)
    return out


CLEAN = re.compile(r"^pysus: error: (?P<file>[^:]+):(?P<line>\d+): ")


def validate(mutation, directory):
    """Run `pysus -validate` on the mutated deck in this process: (outcome, stderr).

    outcome is 'clean line' (exit 2, exactly one `pysus: error: FILE:LINE:` line naming this
    file, no traceback), 'ran' (exit 0) or 'other' (anything else)."""
    from framework.cli import main
    deck = os.path.join(directory, "deck.ups")
    with open(deck, "wb") as f:
        f.write(mutation.data)
    err, out = io.StringIO(), io.StringIO()
    cwd = os.getcwd()
    os.chdir(directory)                 # a relative <filebase> is checked against a scratch directory
    try:
        with contextlib.redirect_stderr(err), contextlib.redirect_stdout(out):
            try:
                rc = main(["-validate", "-q", deck])
            except SystemExit as e:      # argparse
                rc = e.code
    finally:
        os.chdir(cwd)
    text = err.getvalue()
    errors = [ln for ln in text.splitlines() if ln.startswith("pysus: error:")]
    if rc == 0 and not errors and "Traceback" not in text:
        return "ran", text
    m = CLEAN.match(errors[0]) if len(errors) == 1 else None
    if rc == 2 and m and m.group("file") == deck and "Traceback" not in text:
        return "clean line", text
    return "other", text


def table(results):
    """Rows (class, count, clean line, ran, other) in first-seen order."""
    rows: dict = {}
    for m, outcome in results:
        r = rows.setdefault(m.kind, {"count": 0, "clean line": 0, "ran": 0, "other": 0})
        r["count"] += 1
        r[outcome] += 1
    return rows


def main():
    ms = mutations()
    results, wrong = [], []
    with tempfile.TemporaryDirectory() as d:
        for m in ms:
            outcome, text = validate(m, d)
            results.append((m, outcome))
            if outcome == "other" or (m.expect == REFUSE and outcome != "clean line") or \
                    (m.expect == RUN and outcome != "ran"):
                wrong.append((m, outcome, text.strip().splitlines()[-1:] if text.strip() else ""))
    print("| mutation class | count | clean line | ran | other |")
    print("|---|---|---|---|---|")
    rows = table(results)
    for kind, r in rows.items():
        print(f"| {kind} | {r['count']} | {r['clean line']} | {r['ran']} | {r['other']} |")
    tot = {k: sum(r[k] for r in rows.values()) for k in ("count", "clean line", "ran", "other")}
    print(f"| all | {tot['count']} | {tot['clean line']} | {tot['ran']} | {tot['other']} |")
    for m, outcome, last in wrong:
        print(f"UNEXPECTED {outcome} (expected {m.expect}): {m.id}: {last}", file=sys.stderr)
    return 1 if wrong else 0


if __name__ == "__main__":
    sys.exit(main())
