"""XDMF (version 2) descriptions of a `.uda` so ParaView and VisIt open it directly.

Each output timestep is a spatial collection of one uniform grid per patch (a
3DCoRectMesh for grid variables) and a Polyvertex set per material for particles, with
explicit connectivity so the Xdmf3 readers make cells of them too; `output.xdmf` is the
temporal collection of all of them. A grid one cell thick in z is drawn as a plane: the
same 3DCoRectMesh with a z spacing of zero, lying at the domain's bottom face, so the
particles (at mid-cell) show above it. That is the one 2D form every ParaView XDMF reader
places right (ParaView 5.11): they put XDMF's 2DCoRectMesh in the y-z plane, and the legacy
reader drops the cell data of a 3DCoRectMesh one point thick.
HDF5 datasets are stored (z, y, x) so the XDMF dimensions are written slowest first.
Naming rule, grid and particles alike: arrays are `<label>_<material>` (temp_CC_0,
p.mass_1), blocks are `<cells|nodes|particles_m<material>>_patch<id>`.
"""
from __future__ import annotations

import os

import numpy as np

from .variables import VarType

CONNECTIVITY = "vertex_ids"   # per particle set: 0..n-1, the Polyvertex connectivity
_ATYPE = {1: "Scalar", 3: "Vector", 9: "Tensor"}


def _ncomp(shape):
    return int(np.prod(shape)) if shape else 1


def _dataitem(path, dims):
    d = " ".join(str(x) for x in dims)
    return f'<DataItem Dimensions="{d}" NumberType="Float" Precision="8" Format="HDF">{path}</DataItem>'


def _attribute(name, center, path, dims, ncomp):
    """An attribute stored flat: (n,) scalars or (n, ncomp) vectors/tensors."""
    atype = _ATYPE.get(ncomp, "Matrix")
    full = list(dims) + ([ncomp] if ncomp > 1 else [])
    return (f'<Attribute Name="{name}" AttributeType="{atype}" Center="{center}">'
            f'{_dataitem(path, full)}</Attribute>')


def timestep_grids(entry, index, level, prefix=""):
    """XML of one timestep: a spatial collection of patch grids and particle sets."""
    labels = index["labels"]
    out = [f'<Grid Name="t{entry["timestep"]}" GridType="Collection" CollectionType="Spatial">',
           f'<Time Value="{float(entry["time"])!r}"/>']
    for pid, pm in sorted(entry["patches"].items(), key=lambda kv: int(kv[0])):
        fn = f'{prefix}{pm["file"]}'
        by_kind = {}
        for name, boxes in pm["grid"].items():
            vt = VarType(labels[name]["type"])
            for m, (lo, hi) in boxes.items():
                key = "cells" if vt is VarType.CC else "nodes"
                if vt not in (VarType.CC, VarType.NC):
                    continue
                by_kind.setdefault((key, tuple(lo), tuple(hi)), []).append((name, m, labels[name]["shape"]))
        for (kind, lo, hi), items in sorted(by_kind.items()):
            dims = [h - l for l, h in zip(lo, hi)]
            if kind == "cells":
                origin = [level.anchor[d] + lo[d] * level.dx[d] for d in range(3)]
                npts = [n + 1 for n in dims]
                center = "Cell"
            else:
                origin = [level.anchor[d] + lo[d] * level.dx[d] for d in range(3)]
                npts = dims
                center = "Node"
            out.append(f'<Grid Name="{kind}_patch{pid}" GridType="Uniform">')
            spacing = list(level.dx)
            if level.ncells[2] == 1 and npts[2] == 2:     # one cell thick: a plane at the bottom face
                spacing[2] = 0.0
            out.append(f'<Topology TopologyType="3DCoRectMesh" Dimensions="{npts[2]} {npts[1]} {npts[0]}"/>')
            out.append('<Geometry GeometryType="ORIGIN_DXDYDZ">'
                       f'<DataItem Dimensions="3" NumberType="Float" Precision="8" Format="XML">'
                       f'{float(origin[2])!r} {float(origin[1])!r} {float(origin[0])!r}</DataItem>'
                       f'<DataItem Dimensions="3" NumberType="Float" Precision="8" Format="XML">'
                       f'{float(spacing[2])!r} {float(spacing[1])!r} {float(spacing[0])!r}</DataItem></Geometry>')
            adims = [dims[2], dims[1], dims[0]]
            for name, m, shape in items:
                out.append(_attribute(f"{name}_{m}", center, f"{fn}:/patch_{pid}/{name}/{m}",
                                      adims, _ncomp(shape)))
            out.append("</Grid>")
        for m, names in sorted(pm["particles"].items()):
            n = pm.get("np", {}).get(m, 0)
            if n == 0 or "p.x" not in names:
                continue
            out.append(f'<Grid Name="particles_m{m}_patch{pid}" GridType="Uniform">')
            out.append(f'<Topology TopologyType="Polyvertex" NumberOfElements="{n}" NodesPerElement="1">'
                       f'<DataItem Dimensions="{n}" NumberType="Int" Precision="4" Format="HDF">'
                       f'{fn}:/patch_{pid}/particles/{m}/{CONNECTIVITY}</DataItem></Topology>')
            out.append(f'<Geometry GeometryType="XYZ">{_dataitem(f"{fn}:/patch_{pid}/particles/{m}/p.x", [n, 3])}</Geometry>')
            for name in names:
                if name == "p.x":
                    continue
                lab = labels.get(name, {"shape": []})
                nc = _ncomp(lab["shape"])
                out.append(_attribute(f"{name}_{m}", "Node", f"{fn}:/patch_{pid}/particles/{m}/{name}", [n], nc))
            out.append("</Grid>")
    out.append("</Grid>")
    return "\n".join(out)


def _document(body):
    return ('<?xml version="1.0" ?>\n<!DOCTYPE Xdmf SYSTEM "Xdmf.dtd" []>\n'
            '<Xdmf Version="2.0">\n<Domain>\n' + body + "\n</Domain>\n</Xdmf>\n")


class XdmfWriter:
    """Writes each new timestep's XDMF and the temporal `output.xdmf`, rendering every
    timestep once (the whole-run file is re-joined from the cached pieces)."""

    def __init__(self, uda, level):
        self.uda, self.level, self.parts = uda, level, []

    def add(self, index, entries=None):
        """Describe the index's newest timestep (or each of `entries`), then rewrite output.xdmf."""
        for entry in entries if entries is not None else index["timesteps"][-1:]:
            with open(os.path.join(self.uda, entry["dir"], f'{entry["dir"]}.xdmf'), "w") as f:
                f.write(_document(timestep_grids(entry, index, self.level)))
            self.parts.append(timestep_grids(entry, index, self.level, prefix=f'{entry["dir"]}/'))
        body = ['<Grid Name="TimeSeries" GridType="Collection" CollectionType="Temporal">', *self.parts, "</Grid>"]
        tmp = os.path.join(self.uda, "output.xdmf.tmp")
        with open(tmp, "w") as f:
            f.write(_document("\n".join(body)))
        os.replace(tmp, os.path.join(self.uda, "output.xdmf"))
