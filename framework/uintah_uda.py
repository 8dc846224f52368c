"""Read the output of Uintah's sus (a .uda directory) with DataArchive's interface.

Enough for comparing a run of sus with pysus on the same deck (scripts/accuracy_cost.py
--uintah): one level, any number of patches, CCVariable<double> and CCVariable<Vector>
saved uncompressed as 64-bit little-endian (sus's default). `read` returns the interior
cells only, x fastest in the file (Uintah's layout), as an (nx, ny, nz[, 3]) array like
DataArchive.read, with the cell-centre coordinates. `particles` returns one particle variable
(double, long64, Point, Vector) of all patches; `particle_var` reads one from either archive,
so an error function takes a pysus run and a sus run alike.
"""
from __future__ import annotations

import glob
import os

import numpy as np
from lxml import etree


def _ints(text):
    return [int(v) for v in text.strip().strip("[]").split(",")]


def _floats(text):
    return [float(v) for v in text.strip().strip("[]").split(",")]


def _index(patch, tag):
    """A patch's index triple; sus leaves out interior{Low,High}Index where it equals {low,high}Index."""
    text = patch.findtext(tag)
    if text is None and tag.startswith("interior"):
        text = patch.findtext(tag[len("interior"):][0].lower() + tag[len("interior") + 1:])
    return _ints(text)


class UintahArchive:
    """The timesteps of a sus .uda: times, read(label, matl, timestep)."""

    def __init__(self, path):
        self.dir = os.path.realpath(path)
        self.steps = sorted(glob.glob(os.path.join(self.dir, "t[0-9]*")), key=lambda p: int(os.path.basename(p)[1:]))
        if not self.steps:
            raise FileNotFoundError(f"{path}: no timestep directories (t00000...)")
        self.times = [float(etree.parse(os.path.join(s, "timestep.xml")).findtext("Time/currentTime"))
                      for s in self.steps]

    def read(self, label, matl=0, timestep=-1):
        """(values over the interior cells, (x, y, z) cell centres) of one CC variable (double,
        Vector or Matrix3; an int variable, such as DDT1's BurningCriteria, read as float)."""
        step = self.steps[timestep]
        ts = etree.parse(os.path.join(step, "timestep.xml"))
        meta = ts.find("Meta")
        if meta.findtext("endianness", "little_endian").strip() != "little_endian" or \
                int(meta.findtext("nBits", "64")) != 64:
            raise ValueError(f"{step}: only 64-bit little-endian output is read")
        level = ts.find("Grid/Level")
        dx = np.array(_floats(level.findtext("cellspacing")))
        anchor = np.array(_floats(level.findtext("anchor")))
        patches = {int(p.findtext("id")): p for p in level.findall("Patch")}
        lo = np.min([_index(p, "interiorLowIndex") for p in patches.values()], axis=0)
        hi = np.max([_index(p, "interiorHighIndex") for p in patches.values()], axis=0)
        out = None
        for href in (d.get("href") for d in ts.findall("Data/Datafile")):
            for var in etree.parse(os.path.join(step, href)).findall("Variable"):
                if var.findtext("variable").strip() != label or int(var.findtext("index")) != matl:
                    continue
                p = patches[int(var.findtext("patch"))]
                elo, ehi, ilo, ihi = (np.array(_index(p, tag)) for tag in
                                      ("lowIndex", "highIndex", "interiorLowIndex", "interiorHighIndex"))
                ncomp = 9 if "Matrix3" in var.get("type") else (3 if "Vector" in var.get("type") else 1)
                start, end = int(var.findtext("start")), int(var.findtext("end"))
                with open(os.path.join(step, os.path.dirname(href), var.findtext("filename").strip()), "rb") as f:
                    f.seek(start)
                    raw = np.frombuffer(f.read(end - start), dtype="<i4" if "<int>" in var.get("type") else "<f8")
                n = ehi - elo
                a = raw.reshape(n[2], n[1], n[0], ncomp).transpose(2, 1, 0, 3)      # x fastest on disk
                a = a[tuple(slice(l - e, h - e) for l, h, e in zip(ilo, ihi, elo))]
                if out is None:
                    out = np.empty(tuple(hi - lo) + (ncomp,))
                out[tuple(slice(l - o, h - o) for l, h, o in zip(ilo, ihi, lo))] = a
        if out is None:
            raise KeyError(f"{step}: no {label} for material {matl}")
        xyz = tuple(anchor[d] + (np.arange(lo[d], hi[d]) + 0.5) * dx[d] for d in range(3))
        if out.shape[3] == 9:                               # Matrix3, row-major on disk
            return out.reshape(out.shape[:3] + (3, 3)), xyz
        return (out if out.shape[3] == 3 else out[..., 0]), xyz

    def particles(self, label, matl=0, timestep=-1):
        """One particle variable (double, int, long64, Point/Vector/IntVector, Matrix3) of every patch, in patch
        order: an (n,), (n, 3) or (n, 3, 3) array."""
        step = self.steps[timestep]
        ts = etree.parse(os.path.join(step, "timestep.xml"))
        parts = []
        for href in (d.get("href") for d in ts.findall("Data/Datafile")):
            for var in etree.parse(os.path.join(step, href)).findall("Variable"):
                if var.findtext("variable").strip() != label or int(var.findtext("index")) != matl:
                    continue
                kind = var.get("type")
                ncomp = 9 if "Matrix3" in kind else 3 if ("Point" in kind or "Vector" in kind) else 1
                dtype = "<i8" if "long64" in kind else "<i4" if ("<int>" in kind or "IntVector" in kind) else "<f8"
                start, end = int(var.findtext("start")), int(var.findtext("end"))
                with open(os.path.join(step, os.path.dirname(href), var.findtext("filename").strip()), "rb") as f:
                    f.seek(start)
                    raw = np.frombuffer(f.read(end - start), dtype=dtype)
                parts.append((int(var.findtext("patch")), raw.reshape(-1, ncomp) if ncomp > 1 else raw))
        if not parts:
            raise KeyError(f"{step}: no {label} for material {matl}")
        out = np.concatenate([a for _, a in sorted(parts, key=lambda it: it[0])])
        return out.reshape(-1, 3, 3) if out.ndim == 2 and out.shape[1] == 9 else out


def particle_var(da, label, matl=0, timestep=-1):
    """One particle variable of all patches from a pysus DataArchive or a sus UintahArchive."""
    if isinstance(da, UintahArchive):
        return da.particles(label, matl, timestep)
    return da.particles(matl, timestep)[label]
