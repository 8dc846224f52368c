"""Reading `.ups` decks with line-numbered errors.

A `ProblemSpec` wraps one XML element. Components read their part of the deck through
typed getters (or a declarative `Param` table) and every element and attribute they
read is marked as used; `check_all_used()` then turns anything left over into an
`InputError` naming the file, line and tag path, so no input is ever ignored silently.
lxml is used because it keeps source line numbers, which the standard library does not.
"""
from __future__ import annotations

import io
import math
import os
import re
from copy import deepcopy
from dataclasses import dataclass
from typing import Any, Callable

from lxml import etree

REQUIRED = object()


class InputError(Exception):
    """A problem with the deck: file, line, tag path and what would be accepted."""

    def __init__(self, message, filename=None, line=None, path=None):
        self.filename, self.line, self.path, self.message = filename, line, path, message
        where = ""
        if filename:
            where = f"{filename}:{line}: " if line else f"{filename}: "
        tag = f"<{path}> " if path else ""
        super().__init__(f"{where}{tag}{message}")


def _parse_float(text):
    """A finite number: NaN and infinity are never a meaningful deck value."""
    v = float(text.strip())
    if not math.isfinite(v):
        raise ValueError(text)
    return v


INT_LIMIT = 2**62


def _parse_int(text):
    """An integer (written as 3 or 3.0) small enough to be an array index or a count."""
    t = text.strip()
    v = float(t)
    if not math.isfinite(v) or v != int(v) or abs(v) > INT_LIMIT:
        raise ValueError(t)
    return int(v)


def _parse_bool(text):
    t = text.strip().lower()
    if t in ("true", "1", "yes"):
        return True
    if t in ("false", "0", "no"):
        return False
    raise ValueError(t)


def _parse_vector(text, conv=_parse_float):
    t = text.strip()
    if not (t.startswith("[") and t.endswith("]")):
        raise ValueError(t)
    parts = [p for p in t[1:-1].replace(",", " ").split()]
    if len(parts) != 3:
        raise ValueError(t)
    return tuple(conv(p) for p in parts)


PARSERS: dict[str, tuple[Callable[[str], Any], str]] = {
    "float": (_parse_float, "a finite number"),
    "int": (_parse_int, "an integer (at most 2^62 in size)"),
    "bool": (_parse_bool, "true or false"),
    "str": (lambda t: t.strip(), "text"),
    "vector": (_parse_vector, "a vector [x, y, z] of finite numbers"),
    "ivector": (lambda t: _parse_vector(t, _parse_int), "an integer vector [i, j, k] (at most 2^62 each)"),
}


def _bound_check(v, above, at_least):
    """The words for the accepted range when a number (or any vector component) is outside it."""
    vals = v if isinstance(v, tuple) else (v,)
    if above is not None and any(not (x > above) for x in vals):
        return f"> {above:g}"
    if at_least is not None and any(not (x >= at_least) for x in vals):
        return f">= {at_least:g}"
    return None


@dataclass(frozen=True)
class Param:
    """One accepted child tag: its type, default (REQUIRED if none), allowed values and range.

    `above` (strictly greater) and `at_least` (greater or equal) bound a number, or every
    component of a vector; a value outside is an InputError saying what is accepted.
    """

    type: str = "float"
    default: Any = REQUIRED
    choices: tuple | None = None
    doc: str = ""
    above: float | None = None
    at_least: float | None = None


_DECLARED_ENCODING = re.compile(rb"""^\s*<\?xml[^>]*encoding\s*=\s*["']([A-Za-z0-9._-]+)["']""")


def deck_bytes(text: str | bytes, filename="<string>") -> bytes:
    """A deck as the bytes of its file: text is encoded as its `<?xml encoding=...?>` declares."""
    if isinstance(text, bytes):
        return text
    m = _DECLARED_ENCODING.match(text.encode("ascii", "replace"))
    encoding = m.group(1).decode() if m else "utf-8"
    try:
        return text.encode(encoding)
    except (LookupError, UnicodeEncodeError) as e:
        raise InputError(f"the deck text cannot be written in its declared encoding {encoding}: {e}; "
                         "accepted: characters of that encoding", filename, 1) from None


class _Doc:
    """Book-keeping shared by all nodes of one parsed file."""

    def __init__(self, filename, root, origin=None):
        self.filename = filename
        # lxml proxies may be recreated with new ids unless kept alive: keep them all
        self.alive = list(root.iter())
        self.used: set = set()
        self.queried: dict = {}
        # {id(element): file} for elements an <include href> brought in
        self.origin: dict = origin or {}

    def file_of(self, el) -> str:
        return self.origin.get(id(el), self.filename)


def _parse_file(filename, what="the deck"):
    """The root element of an XML file; unreadable or malformed files are InputErrors."""
    parser = etree.XMLParser(remove_comments=False, resolve_entities=False)
    try:
        with open(filename, "rb") as f:
            data = f.read()
    except OSError as e:
        raise InputError(f"cannot read {what}: {e.strerror}", filename) from None
    try:
        # from the bytes, so that an encoding error is a syntax error with its line
        return etree.parse(io.BytesIO(data), parser, base_url=filename).getroot()
    except etree.XMLSyntaxError as e:
        line = e.lineno if hasattr(e, "lineno") else None
        hint = ("; accepted: bytes of the encoding the <?xml ... encoding=\"...\"?> line declares "
                "(UTF-8 when none)") if "encoding" in e.msg else ""
        raise InputError(f"malformed XML: {e.msg}{hint}", filename, line) from None


_INCLUDE_CONTROL = ("href", "section", "excludeSectionTag", "need_applies_to")


def _include_target(href, including_file, el):
    """Uintah's rule: an absolute href as is; else next to the including file, then the working directory."""
    if os.path.isabs(href):
        if os.path.isfile(href):
            return href
        raise InputError(f'<include href="{href}">: no such file; accepted: an existing file',
                         including_file, el.sourceline)
    near = os.path.join(os.path.dirname(os.path.abspath(including_file)), href)
    if os.path.isfile(near):
        return near
    if os.path.isfile(href):
        return os.path.abspath(href)
    raise InputError(f'<include href="{href}">: no file {near} next to this file nor {os.path.abspath(href)} '
                     "in the working directory; accepted: a path relative to either, or absolute",
                     including_file, el.sourceline)


def _include_nodes(el, target, including_file):
    """The elements an <include> stands for: the file's top level, or its `section` path whose
    last element carries every other attribute of the <include> (children only with excludeSectionTag)."""
    inc_root = _parse_file(target, "the included file")
    if inc_root.tag not in ("Uintah_Include", "Uintah_specification"):
        raise InputError(f"the root element is <{inc_root.tag}>; accepted: <Uintah_Include> or "
                         "<Uintah_specification>", target, inc_root.sourceline)
    section = el.get("section", "")
    if not section:
        return list(inc_root)
    want = {k: v for k, v in el.attrib.items() if k not in _INCLUDE_CONTROL}
    nodes = [inc_root]
    for name in section.split("/"):
        nodes = [c for n in nodes for c in n if c.tag == name]
    found = [n for n in nodes if all(n.get(k) == v for k, v in want.items())]
    if not found:
        attrs = " ".join(f'{k}="{v}"' for k, v in want.items())
        raise InputError(f'<include section="{section}" {attrs}>: no such element in {target}; '
                         "accepted: a section path and attributes that one element of that file has",
                         including_file, el.sourceline)
    return list(found[0]) if el.get("excludeSectionTag") else [found[0]]


def _resolve_includes(root, filename, origin, keep):
    """Replaces every <include href> under root by what it names, an included file's own includes
    resolved next to it (as Uintah does); origin records the file each brought-in element came
    from (keep holds those elements, so that their ids stay theirs)."""
    count = 0
    while (el := next(root.iter("include"), None)) is not None:
        including = origin.get(id(el), filename)
        count += 1
        if count > 1000:
            raise InputError(f'<include href="{el.get("href")}">: over 1000 includes; '
                             "accepted: includes that do not include themselves", including, el.sourceline)
        target = _include_target(el.get("href", ""), including, el)
        parent = el.getparent()
        at = parent.index(el)
        for node in _include_nodes(el, target, including):
            copy = deepcopy(node)
            for sub in copy.iter():
                origin[id(sub)] = target
                keep.append(sub)
            parent.insert(at, copy)
            at += 1
        parent.remove(el)


class ProblemSpec:
    """One element of a deck, with typed access and usage tracking."""

    def __init__(self, element, doc: _Doc, path: str):
        self.element = element
        self.doc = doc
        self.path = path
        doc.used.add(id(element))

    # -- construction -------------------------------------------------------------
    @classmethod
    def load(cls, filename) -> "ProblemSpec":
        """Parse a deck file; malformed XML becomes an InputError with its line."""
        filename = os.fspath(filename)
        root = _parse_file(filename)
        origin, keep = {}, []
        _resolve_includes(root, filename, origin, keep)
        node = cls(root, _Doc(filename, root, origin), root.tag)
        node._keep = root.getroottree()
        return node

    def resolved_bytes(self) -> bytes:
        """The whole deck, includes resolved, in the deck's declared encoding."""
        tree = self.element.getroottree()
        return etree.tostring(tree, xml_declaration=True, encoding=tree.docinfo.encoding or "utf-8")

    @property
    def has_includes(self) -> bool:
        """True when <include href> brought elements of other files into this deck."""
        return bool(self.doc.origin)

    @classmethod
    def from_string(cls, text: str | bytes, filename="<string>") -> "ProblemSpec":
        try:
            root = etree.fromstring(deck_bytes(text, filename))
        except etree.XMLSyntaxError as e:
            raise InputError(f"malformed XML: {e.msg}", filename, getattr(e, "lineno", None)) from None
        return cls(root, _Doc(filename, root), root.tag)

    # -- basic facts -----------------------------------------------------------
    @property
    def tag(self) -> str:
        return self.element.tag

    @property
    def line(self) -> int:
        return self.element.sourceline

    @property
    def filename(self) -> str:
        return self.doc.filename

    def error(self, message) -> InputError:
        """An InputError located at this element."""
        return InputError(message, self.doc.file_of(self.element), self.line, self.path)

    def _elements(self, tag=None):
        for child in self.element:
            if not isinstance(child.tag, str):
                continue
            if tag is None or child.tag == tag:
                yield child

    def _note_query(self, tag):
        self.doc.queried.setdefault(id(self.element), set()).add(tag)

    # -- children ----------------------------------------------------------------
    def child(self, tag, required=False) -> "ProblemSpec | None":
        """The single child `tag`, None if absent (or an error if required)."""
        self._note_query(tag)
        found = list(self._elements(tag))
        if not found:
            if required:
                raise self.error(f"missing required tag <{tag}>")
            return None
        if len(found) > 1:
            extra = ProblemSpec(found[1], self.doc, f"{self.path}/{tag}")
            raise extra.error(f"<{tag}> given more than once; only one is accepted here")
        return ProblemSpec(found[0], self.doc, f"{self.path}/{tag}")

    def children(self, tag=None) -> list["ProblemSpec"]:
        """All children with this tag (every element child when tag is None)."""
        if tag is not None:
            self._note_query(tag)
        return [ProblemSpec(e, self.doc, f"{self.path}/{e.tag}") for e in self._elements(tag)]

    def has(self, tag) -> bool:
        self._note_query(tag)
        return any(True for _ in self._elements(tag))

    # -- values ------------------------------------------------------------------
    def text(self) -> str:
        return (self.element.text or "").strip()

    def value(self, type_="float", choices=None, above=None, at_least=None):
        """This element's own text converted to `type_` (and checked against its range)."""
        parse, what = PARSERS[type_]
        raw = self.text()
        try:
            v = parse(raw)
        except (ValueError, TypeError, OverflowError):
            raise self.error(f"value '{raw}' is not {what}") from None
        if choices is not None and v not in choices:
            raise self.error(f"value '{raw}' is not accepted; accepted: {', '.join(map(str, choices))}")
        bound = _bound_check(v, above, at_least)
        if bound is not None:
            each = " in every component" if isinstance(v, tuple) else ""
            raise self.error(f"value '{raw}' is out of range; accepted: {what} {bound}{each}")
        return v

    def get(self, tag, type_="float", default=REQUIRED, choices=None, above=None, at_least=None):
        """The value of child `tag`, or `default`; a missing required tag is an error."""
        node = self.child(tag)
        if node is None:
            if default is REQUIRED:
                raise self.error(f"missing required tag <{tag}> ({PARSERS[type_][1]})")
            return default
        return node.value(type_, choices, above, at_least)

    def attr(self, name, type_="str", default=REQUIRED, choices=None, above=None, at_least=None):
        """The value of attribute `name` of this element."""
        self.doc.used.add((id(self.element), name))
        raw = self.element.get(name)
        if raw is None:
            if default is REQUIRED:
                raise self.error(f"missing required attribute {name}=\"...\"")
            return default
        parse, what = PARSERS[type_]
        try:
            v = parse(raw)
        except (ValueError, TypeError, OverflowError):
            raise self.error(f"attribute {name}=\"{raw}\" is not {what}") from None
        if choices is not None and v not in choices:
            raise self.error(f"attribute {name}=\"{raw}\" is not accepted; accepted: {', '.join(map(str, choices))}")
        bound = _bound_check(v, above, at_least)
        if bound is not None:
            raise self.error(f"attribute {name}=\"{raw}\" is out of range; accepted: {what} {bound}")
        return v

    def read(self, table: dict[str, Param]) -> dict:
        """Read every tag of a declarative table; returns {tag: value}."""
        out = {}
        for tag, p in table.items():
            out[tag] = self.get(tag, p.type, p.default, p.choices, p.above, p.at_least)
        return out

    def mark_used(self, recursive=True):
        """Mark this element (and its subtree) as read, e.g. for <Meta>."""
        self.doc.used.add(id(self.element))
        for name in self.element.attrib:
            self.doc.used.add((id(self.element), name))
        if recursive:
            for c in self._elements():
                ProblemSpec(c, self.doc, f"{self.path}/{c.tag}").mark_used(True)

    # -- the final check -----------------------------------------------------------
    def check_all_used(self):
        """Raise an InputError for the first element or attribute nobody read."""
        self._check(self.element, self.path)

    def _check(self, el, path):
        for name in el.attrib:
            if (id(el), name) not in self.doc.used:
                raise InputError(f"attribute {name}=\"{el.get(name)}\" is not supported here",
                                 self.doc.file_of(el), el.sourceline, path)
        for c in el:
            if not isinstance(c.tag, str):
                continue
            cpath = f"{path}/{c.tag}"
            if id(c) not in self.doc.used:
                accepted = sorted(self.doc.queried.get(id(el), ()))
                hint = f"; accepted here: {', '.join('<%s>' % a for a in accepted)}" if accepted else ""
                raise InputError(f"unsupported tag <{c.tag}>{hint}", self.doc.file_of(c), c.sourceline, cpath)
            self._check(c, cpath)

    def to_string(self) -> str:
        return etree.tostring(self.element, encoding="unicode")
