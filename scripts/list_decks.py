#!/usr/bin/env python
"""Writes inputs/README.md: every deck under inputs/ with the first sentence of its header comment.

    .venv/bin/python scripts/list_decks.py          # rewrite inputs/README.md
    .venv/bin/python scripts/list_decks.py --check  # exit 1 if it is out of date (tests/decks/test_inputs_readme.py)

Every deck starts with an XML comment: the scene, what it checks, its runtime and the
command. A deck without one is an error here, so the list never silently loses a deck.
"""
from __future__ import annotations

import argparse
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
INPUTS = ROOT / "inputs"
HEAD = """# Decks

Each deck starts with a comment: the scene, what it checks, how long it takes, the command.
Run any of them with `./pysus inputs/<dir>/<deck>.ups`. This file is written by
`scripts/list_decks.py` from those comments (tests/decks/test_inputs_readme.py checks it is current)."""
WIDTH = 220


def decks():
    """{folder: [deck paths]} in a stable order."""
    out = {}
    for path in sorted(INPUTS.rglob("*.ups")):
        out.setdefault(path.parent.relative_to(INPUTS).as_posix(), []).append(path)
    return out


def scene(path) -> str:
    """The header comment's first sentence (one line, at most WIDTH characters)."""
    text = path.read_text(encoding="iso-8859-1")
    m = re.search(r"<!--(.*?)-->", text, re.S)
    if m is None or text.index("<!--") > text.index("<Uintah_specification"):
        raise SystemExit(f"{path}: no header comment before <Uintah_specification>")
    lines = []
    for line in (ln.strip() for ln in m.group(1).strip().split("\n")):
        if not line or (lines and re.match(r"[A-Z][A-Za-z ]*:\s", line)):   # blank, or "Checks: ..."
            break
        lines.append(line)
    para = " ".join(" ".join(lines).split())
    first = re.split(r"(?<=[a-z0-9)\]])\.\s+(?=[A-Z(])", para, maxsplit=1)[0].rstrip(".") + "."
    return first if len(first) <= WIDTH else first[:WIDTH - 3].rstrip() + "..."


def render() -> str:
    parts = [HEAD]
    for folder, paths in decks().items():
        parts.append(f"\n## {folder}\n\n| deck | scene |\n|---|---|")
        parts += [f"| `{p.name}` | {scene(p).replace('|', '/')} |" for p in paths]
    return "\n".join(parts) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--check", action="store_true")
    args = ap.parse_args()
    text = render()
    target = INPUTS / "README.md"
    if args.check:
        if not target.exists() or target.read_text() != text:
            print("inputs/README.md is out of date: run .venv/bin/python scripts/list_decks.py", file=sys.stderr)
            return 1
        return 0
    target.write_text(text)
    print(f"wrote {target.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
