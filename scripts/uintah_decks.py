#!/usr/bin/env python
"""Runs the decks of Uintah's regression lists (R_Tester ICE.py, MPM.py, MPMICE.py) on pysus.

    .venv/bin/python scripts/uintah_decks.py UINTAH_SRC [--sus SUS] [--steps N]
        [--lists ICE,MPM,MPMICE] [--np N|listed] [--timeout S] [--only NAME,...]

UINTAH_SRC is Uintah's src/ folder (holding R_Tester/ and StandAlone/inputs/). Each test's deck
gets the edits its list makes with modUPS (a sed of the line holding a tag) and modUPS2 (an XPath
update or delete), then <max_Timesteps>N</max_Timesteps> in <Time>, and runs in a temporary
folder that links inputs/ to StandAlone/inputs (Uintah resolves <include href> against the
working directory when the including file's folder does not hold it). Out of scope, and said
why: multi-level (AMR) decks, Arches decks, decks that need a preprocessing command. With --sus,
sus runs the same deck (one rank; not the decks that ask for hypre, which that build may lack)
and each row adds the largest relative difference of delT over the steps, of press_CC's min and
max over material 0 at the last step, and of the .dat reductions both wrote.

The table: list, test, deck, ranks, status (ran / refused: pysus's one-line message / failed: the
exception or signal / timeout / skipped: why), wall seconds, and the agreement columns.
"""
from __future__ import annotations

import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
import types

from lxml import etree

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, ROOT)
SUS_ENV = {"OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1"}


class ModDeck:
    """A deck as a list edits it: modUPS's sed lines (kind 'sed') or modUPS2's XPath edits."""

    def __init__(self, folder, filename, changes, kind):
        self.folder, self.filename, self.changes, self.kind = folder, filename, changes, kind

    def apply(self, text: bytes) -> bytes:
        if self.kind == "sed":
            return apply_sed(text, self.changes)
        return apply_xpath(text, self.changes)


def apply_sed(text: bytes, changes) -> bytes:
    """modUPS: each change replaces, on every line, `<tag` up to the line's last '>' by the change."""
    lines = text.decode("iso-8859-1").split("\n")
    for change in changes:
        prefix = re.split(r"[= >]", change, maxsplit=1)[0]
        pat = re.compile(re.escape(prefix) + ".*>")
        lines = [pat.sub(lambda m: change, ln, count=1) for ln in lines]
    return "\n".join(lines).encode("iso-8859-1")


def apply_xpath(text: bytes, changes) -> bytes:
    """modUPS2: ("update", "XPATH :value") sets an element's text or an attribute; ("delete", XPATH)."""
    tree = etree.fromstring(text, etree.XMLParser(remove_comments=False))
    doc = tree.getroottree()
    for op, arg in changes:
        path, _, value = arg.partition(":")
        path, value = path.strip(), value.replace(" ", "")
        for hit in doc.xpath(path):
            if op.upper() == "DELETE":
                hit.getparent().remove(hit)
            elif isinstance(hit, etree._ElementUnicodeResult) and hit.is_attribute:
                hit.getparent().set(hit.attrname, value)
            else:
                for c in list(hit):
                    hit.remove(c)
                hit.text = value
    return etree.tostring(doc, xml_declaration=True, encoding="iso-8859-1")


def read_list(src, name):
    """[(test, deck path or ModDeck, ranks, flags)] of R_Tester/<name>.py, every list it defines."""
    inputs = os.path.join(src, "StandAlone", "inputs")
    helpers = types.ModuleType("helpers")
    run_tests = types.ModuleType("helpers.runSusTests_git")
    run_tests.runSusTests = lambda *a, **k: 0
    run_tests.ignorePerformanceTests = lambda tests: tests
    run_tests.getInputsDir = lambda: inputs
    mod_ups = types.ModuleType("helpers.modUPS")
    mod_ups.modUPS = lambda folder, fn, changes: ModDeck(folder, fn, changes, "sed")
    mod_ups.modUPS2 = lambda folder, fn, changes: ModDeck(folder, fn, changes, "xpath")
    saved = {k: sys.modules.get(k) for k in ("helpers", "helpers.runSusTests_git", "helpers.modUPS")}
    sys.modules.update({"helpers": helpers, "helpers.runSusTests_git": run_tests, "helpers.modUPS": mod_ups})
    try:
        scope = {"__name__": f"R_Tester_{name}"}
        path = os.path.join(src, "R_Tester", f"{name}.py")
        exec(compile(open(path).read(), path, "exec"), scope)
    finally:
        for k, v in saved.items():
            if v is None:
                sys.modules.pop(k, None)
            else:
                sys.modules[k] = v
    tests, seen = [], set()
    for value in scope.values():
        if not isinstance(value, list):
            continue
        for t in value:
            if isinstance(t, tuple) and len(t) >= 4 and isinstance(t[0], str) and t[0] not in seen:
                seen.add(t[0])
                deck = t[1]
                if isinstance(deck, str):
                    deck = os.path.join(inputs, name, deck)
                tests.append((t[0], deck, int(t[2]), list(t[4]) if len(t) > 4 else []))
    return tests


def deck_text(deck, steps, every_step):
    """The deck's bytes as the test runs it, with <max_Timesteps> (and output every step)."""
    if isinstance(deck, ModDeck):
        path = os.path.join(deck.folder, deck.filename)
        text = deck.apply(open(path, "rb").read())
    else:
        path = deck
        text = open(path, "rb").read()
    root = etree.fromstring(text, etree.XMLParser(remove_comments=False))
    time_el = root.find("Time")
    if time_el is not None:
        for old in time_el.findall("max_Timesteps"):
            time_el.remove(old)
        etree.SubElement(time_el, "max_Timesteps").text = str(steps)
    for inc in root.iter("include"):
        href = inc.get("href", "")
        near = os.path.join(os.path.dirname(path), href)
        if href and not href.startswith("/") and os.path.exists(near):
            inc.set("href", os.path.abspath(near))
    da = root.find("DataArchiver")
    if every_step and da is not None:
        for tag in ("outputInterval", "outputTimestepInterval"):
            for old in da.findall(tag):
                da.remove(old)
        etree.SubElement(da, "outputTimestepInterval").text = "1"
    return etree.tostring(root.getroottree(), xml_declaration=True, encoding="iso-8859-1"), root, path


def out_of_scope(root, flags):
    """Why a test is not run here, or None."""
    grid = root.find("Grid")
    if root.find("AMR") is not None or (grid is not None and len(grid.findall("Level")) > 1):
        return "multi-level (AMR)"
    cfd = root.find("CFD")
    if cfd is not None and cfd.find("ARCHES") is not None:
        return "Arches"
    if any(f.startswith("preProcessCmd") for f in flags):
        return "needs a preprocessing command"
    return None


def needs_hypre(root):
    return any(el.get("type", "").lower() == "hypre" for el in root.iter("Solver", "solver"))


def first_line(text):
    for ln in text.splitlines():
        if ln.startswith("pysus: error:"):
            return ln[len("pysus: error: "):]
    return None


def failure_line(out, rc):
    """The exception line of a traceback, or the signal."""
    if rc < 0:
        return f"signal {-rc}"
    lines = [ln for ln in out.splitlines() if ln.strip()]
    for ln in reversed(lines):
        if re.match(r"^[A-Za-z_.]*(Error|Exception|Interrupt)\b", ln):
            return ln.strip()
    return lines[-1].strip() if lines else f"exit {rc}"


def run(cmd, cwd, timeout, env=None):
    t0 = time.time()
    try:
        p = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                           timeout=timeout, env={**os.environ, **(env or {})})
        return p.returncode, p.stdout.decode(errors="replace"), time.time() - t0
    except subprocess.TimeoutExpired as e:
        return None, (e.stdout or b"").decode(errors="replace"), time.time() - t0


def find_uda(folder):
    udas = sorted((d for d in os.listdir(folder) if ".uda" in d and os.path.isdir(os.path.join(folder, d))),
                  key=lambda d: os.path.getmtime(os.path.join(folder, d)))
    return os.path.join(folder, udas[-1]) if udas else None


def sus_times(uda):
    """Simulation time after each saved step from the sus uda's t*/timestep.xml (full precision)."""
    out = {}
    for d in os.listdir(uda):
        path = os.path.join(uda, d, "timestep.xml")
        if re.fullmatch(r"t\d+", d) and os.path.exists(path):
            t = etree.parse(path).getroot().find("Time")
            out[int(t.findtext("timestepNumber"))] = float(t.findtext("currentTime"))
    return out


def pysus_times(uda):
    out = {}
    with open(os.path.join(uda, "timesteps.jsonl")) as f:
        for ln in f:
            rec = json.loads(ln)
            out[rec["timestep"]] = rec["time"]
    return out


def rel(a, b):
    return abs(a - b) / max(abs(a), abs(b), 1e-300)


def delt_diff(ts_a, ts_b):
    """Largest relative difference of the step sizes both codes took (steps both report)."""
    common = sorted(set(ts_a) & set(ts_b))
    worst = None
    for n0, n1 in zip(common, common[1:]):
        if n1 == n0 + 1:
            d = rel(ts_a[n1] - ts_a[n0], ts_b[n1] - ts_b[n0])
            worst = d if worst is None else max(worst, d)
    return worst


def press_diff(p_uda, s_uda):
    """Largest relative difference of press_CC's min and max (material 0) at sus's last output."""
    from framework.archiver import DataArchive
    from framework.uintah_uda import UintahArchive
    p, s = DataArchive(p_uda), UintahArchive(s_uda)
    sp, _ = s.read("press_CC", 0, -1)
    pp, _ = p.read("press_CC", 0, -1)
    return max(rel(sp.min(), pp.min()), rel(sp.max(), pp.max()))


def dat_diff(p_uda, s_uda):
    """Largest relative difference over the rows both .dat files hold (per file), as 'name:diff'."""
    import numpy as np
    worst = None
    for name in sorted(os.listdir(s_uda)):
        pf = os.path.join(p_uda, name)
        if not name.endswith(".dat") or not os.path.exists(pf):
            continue
        a = np.atleast_2d(np.loadtxt(os.path.join(s_uda, name), converters=None, ndmin=2))
        b = np.atleast_2d(np.loadtxt(pf, ndmin=2))
        n = min(len(a), len(b))
        if n == 0 or a.shape[1] != b.shape[1]:
            continue
        d = float(np.max(np.abs(a[:n, 1:] - b[:n, 1:]) / np.maximum(np.maximum(abs(a[:n, 1:]), abs(b[:n, 1:])), 1e-300)))
        if worst is None or d > worst[1]:
            worst = (name[:-4], d)
    return worst


def fmt(x):
    return "-" if x is None else f"{x:.1e}"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("src", help="Uintah's src/ folder")
    ap.add_argument("--sus", help="Uintah's sus executable: also run it and compare")
    ap.add_argument("--steps", type=int, default=5)
    ap.add_argument("--lists", default="ICE")
    ap.add_argument("--np", default="1", help="ranks for pysus: a number, or 'listed' (the list's count)")
    ap.add_argument("--timeout", type=float, default=300.0, help="seconds per run")
    ap.add_argument("--only", help="comma-separated test names")
    ap.add_argument("--keep", help="keep the run folders under this folder")
    args = ap.parse_args(argv)
    pysus = [sys.executable, "-m", "framework"]     # this checkout's pysus (PYTHONPATH below)
    only = set(args.only.split(",")) if args.only else None
    rows, summary = [], {}
    work = args.keep or tempfile.mkdtemp(prefix="uintah_decks_")
    for name in args.lists.split(","):
        counts = summary.setdefault(name, {})
        for test, deck, ranks, flags in read_list(args.src, name):
            if only and test not in only:
                continue
            label = os.path.basename(deck.filename if isinstance(deck, ModDeck) else deck)
            np_ = ranks if args.np == "listed" else int(args.np)
            row = {"list": name, "test": test, "deck": label, "np": np_, "wall": None}
            try:
                text, root, path = deck_text(deck, args.steps, bool(args.sus))
            except (OSError, etree.XMLSyntaxError) as e:
                row.update(status="skipped", detail=f"deck unreadable: {e}")
                rows.append(row); counts["skipped"] = counts.get("skipped", 0) + 1
                print_row(row, args.sus); continue
            why = out_of_scope(root, flags)
            if why:
                row.update(status="skipped", detail=why)
                rows.append(row); counts["skipped"] = counts.get("skipped", 0) + 1
                print_row(row, args.sus); continue
            folder = os.path.join(work, f"{name}_{test}")
            shutil.rmtree(folder, ignore_errors=True)
            for sub in ("pysus", "sus"):
                os.makedirs(os.path.join(folder, sub))
                os.symlink(os.path.join(args.src, "StandAlone", "inputs"), os.path.join(folder, sub, "inputs"))
                with open(os.path.join(folder, sub, label), "wb") as f:
                    f.write(text)
            cmd = pysus + ["--quiet"] + (["--np", str(np_)] if np_ > 1 else []) + [label]
            rc, out, wall = run(cmd, os.path.join(folder, "pysus"), args.timeout, {"PYTHONPATH": ROOT})
            row["wall"] = wall
            msg = first_line(out)
            if rc is None:
                row.update(status="timeout", detail=f"over {args.timeout:.0f} s")
            elif rc == 0:
                row.update(status="ran", detail="")
            elif rc == 2 and msg:
                row.update(status="refused", detail=msg)
            else:
                row.update(status="failed", detail=failure_line(out, rc))
            counts[row["status"]] = counts.get(row["status"], 0) + 1
            if args.sus and row["status"] == "ran":
                compare(row, folder, label, args)
            rows.append(row)
            print_row(row, args.sus)
            if not args.keep:
                shutil.rmtree(folder, ignore_errors=True)
    print()
    for name, counts in summary.items():
        print(f"{name}: " + ", ".join(f"{k} {v}" for k, v in sorted(counts.items())) + f" (of {sum(counts.values())})")
    if not args.keep:
        shutil.rmtree(work, ignore_errors=True)
    return 0


def compare(row, folder, label, args):
    """Runs sus on the same deck and adds the agreement columns to row."""
    root = etree.parse(os.path.join(folder, "sus", label)).getroot()
    if needs_hypre(root):
        row["sus"] = "no hypre"
        return
    rc, out, wall = run([args.sus, label], os.path.join(folder, "sus"), args.timeout, SUS_ENV)
    row["sus_wall"] = wall
    if rc != 0:
        row["sus"] = "sus " + ("timeout" if rc is None else failure_line(out, rc))
        return
    p_uda, s_uda = find_uda(os.path.join(folder, "pysus")), find_uda(os.path.join(folder, "sus"))
    try:
        s_times, p_times = sus_times(s_uda), pysus_times(p_uda)
        if 0 not in s_times and 0 in p_times:    # sus saves no t00000 here: both start at initTime
            s_times[0] = p_times[0]
        row["delT"] = delt_diff(s_times, p_times)
        row["press"] = press_diff(p_uda, s_uda)
        row["dat"] = dat_diff(p_uda, s_uda)
        row["sus"] = "ok"
    except Exception as e:  # a comparison that cannot be made is reported, not fatal
        row["sus"] = f"compare: {type(e).__name__}: {e}"


def print_row(row, with_sus):
    wall = "-" if row["wall"] is None else f"{row['wall']:.0f}"
    line = f"{row['list']:7s} {row['test']:26s} {row['deck'][:34]:34s} {row['np']:3d} {row['status']:8s} {wall:>5s}"
    if with_sus and row["status"] == "ran":
        dat = row.get("dat")
        line += (f"  sus:{row.get('sus', '-')} delT {fmt(row.get('delT'))} press {fmt(row.get('press'))}"
                 f" dat {dat[0] + ' ' + fmt(dat[1]) if dat else '-'}")
    if row.get("detail"):
        line += f"  {row['detail'][:160]}"
    print(line, flush=True)


if __name__ == "__main__":
    sys.exit(main())
