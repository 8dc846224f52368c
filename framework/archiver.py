"""Output, checkpoints, restart, and the Python reader of a `.uda` directory.

Layout of `<filebase>`:
  input.ups                the deck as run
  index.json               labels, materials, grid, checkpoints (rank 0)
  timesteps.jsonl          one line per output: time, delT, directory, patch boxes (appended,
                           so an output costs the same at the end of a long run as at its start)
  t00012/rank0000.h5       one HDF5 file per rank per output timestep, group per patch
  t00012/t00012.xdmf       XDMF of that timestep; `output.xdmf` holds all of them
  checkpoints/t00012/      same per-rank files holding everything needed to continue
  KineticEnergy.dat ...    saved reductions, a "time value" line every timestep (as Uintah)

Grid arrays are stored in (z, y, x) order so that XDMF readers (ParaView, VisIt) see
x as the fastest index; the reader transposes back to [i, j, k]. Checkpoints are
written to a temporary directory and renamed, so a crash never leaves a broken
newest checkpoint and never touches the older ones.
"""
from __future__ import annotations

import hashlib
import json
import os
import re
import shutil

import h5py
import numpy as np

from . import labels as label_registry
from .grid import box_intersect
from .xdmf import CONNECTIVITY
from .variables import VarType

SCALAR, VECTOR, TENSOR = "Scalar", "Vector", "Tensor"


def _zyx(a, ncomp_shape):
    """[i,j,k,(c)] -> flat (n,) or (n, ncomp) with x fastest, as XDMF readers expect."""
    t = np.ascontiguousarray(a.transpose((2, 1, 0) + tuple(range(3, a.ndim))))
    ncomp = int(np.prod(ncomp_shape)) if ncomp_shape else 1
    return t.reshape(-1, ncomp) if ncomp > 1 else t.reshape(-1)


def _ijk(a, shape, box):
    """Inverse of _zyx for an index box."""
    n = [h - l for l, h in zip(box[0], box[1])]
    a = a.reshape((n[2], n[1], n[0]) + tuple(shape))
    return np.ascontiguousarray(a.transpose((2, 1, 0) + tuple(range(3, a.ndim))))


def _atype(shape):
    return {(): SCALAR, (3,): VECTOR, (3, 3): TENSOR}.get(tuple(shape), SCALAR)


def _link_create():
    """HDF5's link-creation property: the groups on a dataset's path are made with it."""
    lcpl = h5py.h5p.create(h5py.h5p.LINK_CREATE)
    lcpl.set_create_intermediate_group(True)
    return lcpl


_LCPL = _link_create()


def _put(group, name, arr, **attrs):
    """group[name] = arr (contiguous, with attributes) through HDF5's own calls: the same file
    as h5py's create_dataset and attrs, at 0.4x their cost per dataset (an output writes one per
    variable, material and patch, and that cost was most of writing it)."""
    arr = np.ascontiguousarray(arr)                 # at least 1-D
    ds = h5py.h5d.create(group.id, name.encode(), h5py.h5t.py_create(arr.dtype, logical=True),
                         h5py.h5s.create_simple(arr.shape), lcpl=_LCPL)
    if arr.size:
        ds.write(h5py.h5s.ALL, h5py.h5s.ALL, arr)
    for key, value in attrs.items():
        v = np.asarray(value)
        h5py.h5a.create(ds, key.encode(), h5py.h5t.py_create(v.dtype, logical=True),
                        h5py.h5s.create_simple(v.shape)).write(v)


def _get(h5, name):
    """h5[name][...] through HDF5's own calls (half of h5py's cost per dataset)."""
    ds = h5py.h5d.open(h5.id, name.encode())
    out = np.empty(ds.shape, dtype=ds.dtype)
    if out.size:
        ds.read(h5py.h5s.ALL, h5py.h5s.ALL, out)
    return out


def _write_dw(h5, dw, level, patches, names, region):
    """Write the named variables of `dw` for `patches` into an open HDF5 file.

    region 'interior' keeps the physical domain only (for viewers), 'owned' keeps extra
    cells too (for checkpoints). Returns per-patch metadata for the index and XDMF.
    """
    meta = {}
    for p in patches:
        g = h5.require_group(f"patch_{p.id}")
        pm = {"grid": {}, "particles": {}}
        for (name, m, pid), arr in dw.grid.items():
            if pid != p.id or name not in names:
                continue
            label = label_registry.find(name)
            vt = label.vartype
            box = p.owned(vt) if region == "owned" else p.interior_box(vt)
            if box is None:
                continue
            data = arr[p.slices(vt, box)]
            _put(g, f"{name}/{m}", _zyx(data, label.shape), low=box[0], high=box[1])
            pm["grid"].setdefault(name, {})[m] = (list(box[0]), list(box[1]))
        for (name, m, pid), arr in dw.particles.items():
            if pid != p.id or name not in names:
                continue
            _put(g, f"particles/{m}/{name}", arr)
            pm["particles"].setdefault(str(m), []).append(name)
        for (m, pid), n in dw.nparticles.items():
            if pid == p.id:
                g.require_group(f"particles/{m}").attrs["n"] = n
                if region == "interior" and n:      # XDMF Polyvertex connectivity (framework/xdmf.py)
                    _put(g, f"particles/{m}/{CONNECTIVITY}", np.arange(n, dtype=np.int32))
                pm.setdefault("np", {})[str(m)] = n
        meta[p.id] = pm
    return meta


TIMESTEPS_FILE = "timesteps.jsonl"
RESTART_MODES = ("nocopy", "copy", "move")    # sus's -nocopy (its default), -copy, -move


class Archiver:
    """Writes output and checkpoints as the `<DataArchiver>` block asks."""

    def __init__(self, spec, level, comm, deck_text: bytes, component_name: str, materials):
        self.spec = spec
        self.level = level
        self.comm = comm
        self.dir = spec["filebase"]
        self.deck_text = deck_text
        self.component = component_name
        self.materials = materials
        self.index = {"timesteps": [], "checkpoints": [], "labels": {}, "component": component_name,
                      "materials": materials, "nranks": comm.size,
                      "grid": {"anchor": level.anchor.tolist(), "upper": level.upper.tolist(),
                               "ncells": list(level.ncells), "patches": list(level.layout),
                               "extra": list(level.extra), "periodic": list(level.periodic)}}
        self.next_output_time = None
        self.next_checkpoint_time = None
        self._labels_written = -1
        from .xdmf import XdmfWriter
        self.xdmf = XdmfWriter(self.dir, level)

    # -- set-up ---------------------------------------------------------------------
    def setup(self, t0, restart_from=None, restart_timestep=None, restart_mode=RESTART_MODES[0]):
        """Make the uda. A restart (as Uintah's sus) writes a new uda; with restart_mode "copy"
        or "move" it starts with the old uda's outputs, checkpoints and reduction lines up to
        the restart's timestep, so that one uda (one output.xdmf) holds the whole history,
        and "move" then deletes the old uda."""
        if restart_mode != "nocopy":
            self.comm.barrier()             # every rank has read its checkpoint before any is moved
        if self.comm.rank == 0:
            os.makedirs(self.dir, exist_ok=True)
            with open(os.path.join(self.dir, "input.ups"), "wb") as f:
                f.write(self.deck_text)
            open(os.path.join(self.dir, TIMESTEPS_FILE), "w").close()
            if restart_from:
                self.index["restarted_from"] = restart_from
                if restart_mode != "nocopy":
                    self._take_history(restart_from, restart_timestep, t0, move=restart_mode == "move")
            self._write_index()
        self.comm.barrier()
        if self.spec["outputInterval"] > 0:
            self.next_output_time = t0
        if self.spec["checkpoint_interval"] > 0:
            self.next_checkpoint_time = t0 + self.spec["checkpoint_interval"]

    def _take_history(self, old, timestep, t, move):
        """Copy (or move) the old uda's outputs and checkpoints at or before `timestep`, and its
        reduction lines at or before time `t`, into this uda (Uintah's DataArchiver::restartSetup)."""
        take = shutil.move if move else shutil.copytree
        prev = DataArchive(old)
        self.index["restarts"] = prev.index.get("restarts", []) + [{"from": os.path.abspath(old),
                                                                    "timestep": timestep}]
        for name, info in prev.index["labels"].items():
            self.index["labels"].setdefault(name, info)
        taken = [e for e in prev.index["timesteps"] if e["timestep"] <= timestep]
        with open(os.path.join(self.dir, TIMESTEPS_FILE), "a") as f:
            for entry in taken:
                take(os.path.join(old, entry["dir"]), os.path.join(self.dir, entry["dir"]))
                f.write(json.dumps(entry, separators=(",", ":")) + "\n")
        self.index["timesteps"].extend(taken)
        if taken:
            self.xdmf.add(self.index, taken)
        os.makedirs(os.path.join(self.dir, "checkpoints"), exist_ok=True)
        for cp in prev.index["checkpoints"]:
            if cp["timestep"] <= timestep and os.path.isdir(os.path.join(old, cp["dir"])):
                take(os.path.join(old, cp["dir"]), os.path.join(self.dir, cp["dir"]))
                self.index["checkpoints"].append(cp)
        for fn in sorted(os.listdir(old)):
            if fn.endswith(".dat"):
                with open(os.path.join(old, fn)) as src, open(os.path.join(self.dir, fn), "w") as dst:
                    dst.writelines(line for line in src if _line_time(line) <= t * (1 + 1e-12))
        if move:
            shutil.rmtree(old)

    @staticmethod
    def unique_dir(base, rank_comm):
        """`base`, or base.000, base.001 ... if it exists (as Uintah), agreed on by all ranks."""
        name = None
        if rank_comm.rank == 0:
            name = base
            i = 0
            while os.path.exists(name):
                stem = base[:-4] if base.endswith(".uda") else base
                name = f"{stem}.uda.{i:03d}"
                i += 1
        return rank_comm.bcast(name)

    # -- when ----------------------------------------------------------------------
    def output_due(self, timestep, t) -> bool:
        s = self.spec
        if s["outputTimestepInterval"] > 0:
            return timestep % s["outputTimestepInterval"] == 0
        if self.next_output_time is not None and t >= self.next_output_time * (1 - 1e-12) - 1e-300:
            return True
        return False

    def checkpoint_due(self, timestep, t) -> bool:
        s = self.spec
        if timestep == 0:
            return False
        if s["checkpoint_timestepInterval"] > 0:
            return timestep % s["checkpoint_timestepInterval"] == 0
        if self.next_checkpoint_time is not None and t >= self.next_checkpoint_time * (1 - 1e-12):
            return True
        return False

    def next_event_time(self):
        times = [x for x in (self.next_output_time, self.next_checkpoint_time) if x is not None]
        return min(times) if times else None

    # -- output --------------------------------------------------------------------
    def output(self, dw, timestep, t, delt, local_patches):
        s = self.spec
        if s["outputInterval"] > 0:
            self.next_output_time = _next_time(self.next_output_time, s["outputInterval"], t)
        names = set(s["save"])
        tdir = os.path.join(self.dir, f"t{timestep:05d}")
        if self.comm.rank == 0:
            os.makedirs(tdir, exist_ok=True)
        self.comm.barrier()
        fname = os.path.join(tdir, f"rank{self.comm.rank:04d}.h5")
        with h5py.File(fname, "w") as h5:
            meta = _write_dw(h5, dw, self.level, local_patches, names, "interior")
        allmeta = self.comm.allgather((self.comm.rank, meta))
        reductions = {(n, m): v for (n, m), v in dw.reductions.items() if n in names}
        if self.comm.rank == 0:
            patches = {}
            for r, m in allmeta:
                for pid, pm in m.items():
                    pm["file"] = f"rank{r:04d}.h5"
                    patches[str(pid)] = pm
            for n in names:
                lab = label_registry.find(n)
                if lab is not None:
                    self.index["labels"][n] = {"type": lab.vartype.value, "shape": list(lab.shape)}
            entry = {"timestep": timestep, "time": t, "delT": delt, "dir": f"t{timestep:05d}", "patches": patches}
            self.index["timesteps"].append(entry)
            self._append_reductions(reductions, t)
            # one appended line per output: the cost of an output does not grow with the run
            with open(os.path.join(self.dir, TIMESTEPS_FILE), "a") as f:
                f.write(json.dumps(entry, separators=(",", ":")) + "\n")
            self.xdmf.add(self.index)
            if len(self.index["labels"]) != self._labels_written:
                self._write_index()

    def write_reductions(self, dw, t, names):
        """A line "time value" in each saved reduction's .dat file, on a step that writes no
        output timestep (Uintah writes reductions every timestep)."""
        if self.comm.rank == 0:
            self._append_reductions({(n, m): v for (n, m), v in dw.reductions.items() if n in names}, t)

    def _append_reductions(self, reductions, t):
        """One line per reduction {(name, material): value}: `name.dat`, or as Uintah's
        `name_<material>.dat` for one material's sum."""
        for (n, m), v in reductions.items():
            with open(os.path.join(self.dir, f"{n}.dat" if m < 0 else f"{n}_{m}.dat"), "a") as f:
                vals = " ".join(repr(float(x)) for x in np.atleast_1d(v))
                f.write(f"{t!r} {vals}\n")

    def _write_index(self):
        """index.json: everything but the timesteps, which are in timesteps.jsonl."""
        tmp = os.path.join(self.dir, "index.json.tmp")
        with open(tmp, "w") as f:
            json.dump({**{k: v for k, v in self.index.items() if k != "timesteps"},
                       "timesteps_file": TIMESTEPS_FILE}, f, indent=1)
        os.replace(tmp, os.path.join(self.dir, "index.json"))
        self._labels_written = len(self.index["labels"])

    # -- checkpoints ---------------------------------------------------------------
    def checkpoint(self, dw, carried, timestep, t, state, local_patches):
        """Write every carried variable and the controller state; atomic per checkpoint."""
        s = self.spec
        if s["checkpoint_interval"] > 0:
            self.next_checkpoint_time = _next_time(self.next_checkpoint_time, s["checkpoint_interval"], t)
        # the state taken before this call has the time of this checkpoint: a restart would write it again
        state = {**state, "next_checkpoint_time": self.next_checkpoint_time}
        cdir = os.path.join(self.dir, "checkpoints")
        final = os.path.join(cdir, f"t{timestep:05d}")
        tmp = final + ".tmp"
        if self.comm.rank == 0:
            os.makedirs(cdir, exist_ok=True)
            shutil.rmtree(tmp, ignore_errors=True)
            os.makedirs(tmp)
        self.comm.barrier()
        rank_file = f"rank{self.comm.rank:04d}.h5"
        with h5py.File(os.path.join(tmp, rank_file), "w") as h5:
            meta = _write_dw(h5, dw, self.level, local_patches, set(carried), "owned")
        digest = file_digest(os.path.join(tmp, rank_file))
        allmeta = self.comm.allgather((self.comm.rank, meta, rank_file, digest))
        if self.comm.rank == 0:
            patches, digests = {}, {}
            for r, m, fn, dg in allmeta:
                digests[fn] = dg
                for pid in m:
                    patches[str(pid)] = fn
            reds = {f"{n}|{m}": (np.asarray(v).tolist()) for (n, m), v in dw.reductions.items()}
            with open(os.path.join(tmp, "input.ups"), "wb") as f:
                f.write(self.deck_text)
            digests["input.ups"] = file_digest(os.path.join(tmp, "input.ups"))
            info = {"timestep": timestep, "time": t, "state": state, "patches": patches,
                    "carried": sorted(carried), "reductions": reds, "nranks": self.comm.size,
                    "sha256": digests}
            text = json.dumps(info, indent=1)
            with open(os.path.join(tmp, "checkpoint.json"), "w") as f:
                f.write(text)
            with open(os.path.join(tmp, "checkpoint.sha256"), "w") as f:
                f.write(hashlib.sha256(text.encode()).hexdigest() + "\n")
            for fn in os.listdir(tmp):
                fd = os.open(os.path.join(tmp, fn), os.O_RDONLY)
                os.fsync(fd)
                os.close(fd)
            _remove_dir(final)
            os.replace(tmp, final)
            self.index["checkpoints"].append({"timestep": timestep, "time": t, "dir": f"checkpoints/t{timestep:05d}"})
            keep = s["checkpoint_cycle"]
            if keep > 0:
                while len(self.index["checkpoints"]) > keep:
                    old = self.index["checkpoints"].pop(0)
                    _remove_dir(os.path.join(self.dir, old["dir"]))
            self._write_index()
        self.comm.barrier()


CHECKPOINT_NAME = re.compile(r"^t\d{5,}$")     # a complete checkpoint; .tmp / .old are not


def _line_time(line):
    """The time a reduction (.dat) line starts with; infinite for a line cut short by a crash."""
    try:
        return float(line.split()[0]) if line.endswith("\n") else float("inf")
    except (IndexError, ValueError):
        return float("inf")


def file_digest(path):
    """sha256 of a file, read in 1 MiB blocks."""
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def _remove_dir(path):
    """Delete a checkpoint directory so that a kill part-way never leaves an incomplete one
    under a checkpoint's name: it is renamed to NAME.old first, then removed."""
    if not os.path.isdir(path):
        return
    trash = path + ".old"
    shutil.rmtree(trash, ignore_errors=True)
    os.replace(path, trash)
    shutil.rmtree(trash, ignore_errors=True)


class DamagedCheckpoint(Exception):
    """A checkpoint whose files are missing, unreadable or differ from their recorded sha256."""


def verify_checkpoint(d):
    """(checkpoint.json content, deck bytes) of checkpoint directory d after checking every
    file against the sha256 recorded when it was written; DamagedCheckpoint says what is wrong.
    Checkpoints written without digests are read as they are."""
    name = os.path.basename(d)
    try:
        with open(os.path.join(d, "checkpoint.json"), "rb") as f:
            raw = f.read()
        info = json.loads(raw)
    except (OSError, ValueError) as e:
        raise DamagedCheckpoint(f"{name}/checkpoint.json is unreadable ({e})") from None
    digests = info.get("sha256") if isinstance(info, dict) else None
    if digests is not None:
        try:
            with open(os.path.join(d, "checkpoint.sha256")) as f:
                want = f.read().strip()
        except OSError:
            raise DamagedCheckpoint(f"{name}/checkpoint.sha256 is missing") from None
        if hashlib.sha256(raw).hexdigest() != want:
            raise DamagedCheckpoint(f"{name}/checkpoint.json differs from its checksum (edited or damaged)")
        for fn, want in digests.items():
            path = os.path.join(d, fn)
            if not os.path.isfile(path):
                raise DamagedCheckpoint(f"{name}/{fn} is missing")
            if file_digest(path) != want:
                raise DamagedCheckpoint(f"{name}/{fn} differs from its checksum (truncated or overwritten)")
    for key in ("timestep", "time", "state", "patches", "carried", "reductions"):
        if not isinstance(info, dict) or key not in info:
            raise DamagedCheckpoint(f"{name}/checkpoint.json has no '{key}'")
    try:
        with open(os.path.join(d, "input.ups"), "rb") as f:
            deck = f.read()
    except OSError as e:
        raise DamagedCheckpoint(f"{name}/input.ups is unreadable ({e})") from None
    return info, deck


def load_checkpoint(uda, index=-1, notices=None):
    """(checkpoint directory, its checkpoint.json content, deck bytes) of checkpoint `index`.

    Every file is checked against its recorded sha256. The newest checkpoint (index -1) falls
    back to the newest intact one, and each damaged one skipped is described in `notices`;
    an explicitly chosen checkpoint that is damaged is an error."""
    cdir = os.path.join(uda, "checkpoints")
    if not os.path.isdir(uda):
        raise FileNotFoundError(f"{uda}: no such .uda directory")
    if not os.path.isdir(cdir):
        raise FileNotFoundError(f"{uda} has no checkpoints/ directory (its run wrote none); accepted: a uda "
                                'whose deck has <DataArchiver><checkpoint interval="..." cycle="2"/> and that ran '
                                "past one, or one a restart made with -copy or -move (they take the old checkpoints)")
    cps = sorted(d for d in os.listdir(cdir) if CHECKPOINT_NAME.match(d))
    if not cps:
        raise FileNotFoundError(f"{uda}/checkpoints holds no complete checkpoint")
    if index != -1:
        try:
            name = cps[index]
        except IndexError:
            raise FileNotFoundError(f"{uda} has {len(cps)} checkpoints; -t {index} does not exist") from None
        try:
            info, deck = verify_checkpoint(os.path.join(cdir, name))
        except DamagedCheckpoint as e:
            raise FileNotFoundError(f"checkpoint -t {index} of {uda} is damaged: {e}") from None
        return os.path.join(cdir, name), info, deck
    damaged = []
    for name in reversed(cps):
        try:
            info, deck = verify_checkpoint(os.path.join(cdir, name))
        except DamagedCheckpoint as e:
            damaged.append(str(e))
            continue
        if damaged and notices is not None:
            notices.append(f"damaged checkpoint skipped: {'; '.join(damaged)}; restarting from {name}")
        return os.path.join(cdir, name), info, deck
    raise FileNotFoundError(f"{uda}: no intact checkpoint ({'; '.join(damaged)})")


def restore_dw(dw, cdir, info, level, local_patches):
    """Fill a warehouse with a checkpoint's variables for this rank's patches."""
    files = {}
    try:
        for p in local_patches:
            fn = info["patches"][str(p.id)]
            h5 = files.get(fn) or files.setdefault(fn, h5py.File(os.path.join(cdir, fn), "r"))
            g = h5[f"patch_{p.id}"]
            if "particles" in g:
                for m in g["particles"]:
                    pg = g["particles"][m]
                    dw.create_particles(int(m), p, int(pg.attrs["n"]))
                    for name in pg:
                        dw.put(label_registry.find(name), int(m), p, pg[name][...])
            for name in g:
                if name == "particles":
                    continue
                label = label_registry.find(name)
                if label is None:
                    raise KeyError(f"checkpoint holds {name}, which no component defines")
                for m in g[name]:
                    ds = g[name][m]
                    box = (tuple(ds.attrs["low"]), tuple(ds.attrs["high"]))
                    arr = np.zeros(p.alloc_shape(label.vartype) + label.shape, dtype=label.dtype)
                    arr[p.slices(label.vartype, box)] = _ijk(ds[...], label.shape, box)
                    dw.put(label, int(m), p, arr)
    finally:
        for h in files.values():
            h.close()
    for key, v in info["reductions"].items():
        n, m = key.split("|")
        dw.reductions[(n, int(m))] = v if np.ndim(v) == 0 else np.asarray(v)


class DataArchive:
    """Read a `.uda` back into numpy: times, labels, whole-level variables, particles."""

    def __init__(self, path):
        self.path = path
        with open(os.path.join(path, "index.json")) as f:
            self.index = json.load(f)
        if "timesteps_file" in self.index:
            self.index["timesteps"] = []
            with open(os.path.join(path, self.index["timesteps_file"])) as f:
                for line in f:
                    try:
                        self.index["timesteps"].append(json.loads(line))
                    except json.JSONDecodeError:     # a line cut short by a crash: the outputs before it
                        break
        g = self.index["grid"]
        self.anchor = np.array(g["anchor"])
        self.upper = np.array(g["upper"])
        self.ncells = tuple(g["ncells"])
        self.dx = (self.upper - self.anchor) / np.array(self.ncells)

    @property
    def times(self):
        return np.array([e["time"] for e in self.index["timesteps"]])

    @property
    def timesteps(self):
        return [e["timestep"] for e in self.index["timesteps"]]

    @property
    def labels(self):
        return sorted(self.index["labels"])

    @property
    def materials(self):
        return self.index["materials"]

    def _entry(self, timestep):
        return self.index["timesteps"][timestep]

    def read(self, label, material=0, timestep=-1):
        """(array over the level's interior, coordinates) of a grid variable.

        Coordinates are three 1D arrays: cell centres for CC, node/face positions
        along node-like directions. `timestep` indexes the output list (negative counts
        from the end).
        """
        e = self._entry(timestep)
        info = self.index["labels"].get(label)
        if info is None:
            raise KeyError(f"{label} was not saved; saved: {', '.join(self.labels)}")
        vt = VarType(info["type"])
        shape = tuple(info["shape"])
        glo, ghi = [None] * 3, [None] * 3
        pieces = []
        for pid, pm in e["patches"].items():
            boxes = pm["grid"].get(label, {})
            if str(material) not in boxes and material not in boxes:
                continue
            lo, hi = boxes.get(str(material), boxes.get(material))
            pieces.append((pm["file"], pid, lo, hi))
            for d in range(3):
                glo[d] = lo[d] if glo[d] is None else min(glo[d], lo[d])
                ghi[d] = hi[d] if ghi[d] is None else max(ghi[d], hi[d])
        if not pieces:
            raise KeyError(f"{label} material {material} not in timestep {e['timestep']}")
        out = np.zeros(tuple(h - l for l, h in zip(glo, ghi)) + shape)
        files = {}
        try:
            for fn, pid, lo, hi in pieces:
                h5 = files.get(fn) or files.setdefault(fn, h5py.File(os.path.join(self.path, e["dir"], fn), "r"))
                data = _ijk(_get(h5, f"patch_{pid}/{label}/{material}"), shape, (lo, hi))
                sl = tuple(slice(l - g0, h - g0) for l, h, g0 in zip(lo, hi, glo))
                out[sl] = data
        finally:
            for h in files.values():
                h.close()
        coords = []
        for d in range(3):
            idx = np.arange(glo[d], ghi[d])
            node = vt.node_like(d) and self.ncells[d] > 1
            coords.append(self.anchor[d] + (idx + (0.0 if node else 0.5)) * self.dx[d])
        return out, coords

    def particles(self, material=0, timestep=-1):
        """All particles of a material at an output timestep, as {label: array}."""
        e = self._entry(timestep)
        out = {}
        files = {}
        try:
            for pid in sorted(e["patches"], key=int):
                pm = e["patches"][pid]
                names = pm["particles"].get(str(material), [])
                if not names:
                    continue
                fn = pm["file"]
                h5 = files.get(fn) or files.setdefault(fn, h5py.File(os.path.join(self.path, e["dir"], fn), "r"))
                for n in names:
                    out.setdefault(n, []).append(_get(h5, f"patch_{pid}/particles/{material}/{n}"))
        finally:
            for h in files.values():
                h.close()
        return {k: np.concatenate(v) for k, v in out.items()}

    def label_info(self, label):
        """What a saved label is: {'centring': CC/NC/SFCX/SFCY/SFCZ/Particle/Reduction,
        'materials': [..], 'shape': per-entry shape, 'units': SI units or None}."""
        if label not in self.index["labels"]:
            raise KeyError(f"{label} was not saved; saved: {', '.join(self.labels)}")
        info = self.index["labels"][label]
        mats = set()
        for e in self.index["timesteps"]:
            for pm in e["patches"].values():
                mats.update(int(m) for m in pm["grid"].get(label, {}))
                mats.update(int(m) for m, names in pm["particles"].items() if label in names)
        return {"centring": VarType(info["type"]).value, "materials": sorted(mats),
                "shape": tuple(info["shape"]), "units": units_of(label)}

    def __repr__(self):
        t = self.times
        span = f"t = {t[0]:.6g} .. {t[-1]:.6g} s" if len(t) else "no output yet"
        lines = [f"DataArchive('{self.path}'): {len(t)} timesteps {self.timesteps[:1] + self.timesteps[-1:]}, {span}",
                 f"  grid {self.ncells[0]}x{self.ncells[1]}x{self.ncells[2]} cells, "
                 f"[{', '.join(f'{v:g}' for v in self.anchor)}] .. [{', '.join(f'{v:g}' for v in self.upper)}] m"]
        for name in self.labels:
            i = self.label_info(name)
            lines.append(f"  {name:24s} {i['centring']:9s} materials {i['materials']}"
                         + (f" [{i['units']}]" if i["units"] else ""))
        return "\n".join(lines)

    def to_xarray(self, label, material=0, timestep=-1):
        """A grid variable as an xarray.DataArray with x, y, z coordinates (needs xarray)."""
        xr = _optional("xarray")
        data, (x, y, z) = self.read(label, material, timestep)
        dims = ["x", "y", "z"] + [f"c{k}" for k in range(data.ndim - 3)]
        return xr.DataArray(data, coords={"x": x, "y": y, "z": z}, dims=dims, name=label,
                            attrs={"units": units_of(label) or "", "material": material,
                                   "time": float(self.times[timestep])})

    def particles_table(self, material=0, timestep=-1):
        """Particles as {column: 1D array}: vectors and tensors split into `label[k]` columns,
        so pandas.DataFrame(...) takes it directly."""
        cols = {}
        for name, arr in self.particles(material, timestep).items():
            flat = arr.reshape(len(arr), -1)
            if arr.ndim == 1:
                cols[name] = arr
            else:
                cols.update({f"{name}[{k}]": flat[:, k] for k in range(flat.shape[1])})
        return cols

    def to_dataframe(self, material=0, timestep=-1):
        """Particles of a material as a pandas.DataFrame (needs pandas)."""
        return _optional("pandas").DataFrame(self.particles_table(material, timestep))

    def reduction(self, label, material=-1):
        """(times, values) from `<label>.dat` (`<label>_<material>.dat`: one material's sum)."""
        fn = os.path.join(self.path, f"{label}.dat" if material < 0 else f"{label}_{material}.dat")
        data = np.loadtxt(fn, ndmin=2)
        return data[:, 0], data[:, 1:].squeeze()


def _next_time(due, interval, t, steps=1000):
    """The first of due, due + interval, ... after t (with t's 1e-12 slack), added one interval
    at a time as Uintah does; an interval far below the step (a deck's outputInterval 1e-12)
    jumps all but the last `steps` intervals at once instead of looping for minutes."""
    end = t * (1 + 1e-12)
    behind = (end - due) / interval
    if behind > 2 * steps:
        due += (np.floor(behind) - steps) * interval
    while due <= end:
        due += interval
    return due


# SI units by the physical quantity a label's stem names (press_CC, p.stress, vel_CC ...)
_UNITS = {"press": "Pa", "temp": "K", "rho": "kg/m^3", "vel": "m/s", "velocity": "m/s", "mass": "kg",
          "volume": "m^3", "vol": "m^3", "sp_vol": "m^3/kg", "x": "m", "stress": "Pa", "int_eng": "J",
          "KineticEnergy": "J", "TotalIntEng": "J", "StrainEnergy": "J", "AccStrainEnergy": "J",
          "TotalMass": "kg", "TotalMomentum": "kg m/s", "temperature": "K", "delP_Dilatate": "Pa", "speedSound": "m/s",
          "displacement": "m", "externalforce": "N", "size": "1", "vol_frac": "1", "heatRate": "W/m^3",
          "thermalCond": "W/(m K)", "viscosity": "Pa s", "f": "1", "deformationMeasure": "1"}


def units_of(label):
    """SI units of a label, from its stem (None where the stem is not a known quantity)."""
    stem = label[2:] if label.startswith(("p.", "g.")) else label
    for suffix in ("_CC", "_NC", "_FC", "_FCX", "_FCY", "_FCZ", "+"):
        stem = stem.removesuffix(suffix)
    return _UNITS.get(stem)


def _optional(module):
    """Import an optional package or say in one line how to get it."""
    import importlib
    try:
        return importlib.import_module(module)
    except ImportError:
        raise ImportError(f"{module} is not installed; pip install {module}") from None
