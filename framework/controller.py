"""The time loop: read the deck, compile the graphs, step, output, checkpoint, restart.

delT for the next step is the minimum over patches of the component's stable timestep
(a `delT` reduction), times timestep_multiplier, limited by max_delt_increase,
delt_init (first step), delt_min/delt_max, and end_at_max_time_exactly, as Uintah's
simulation controller does.
"""
from __future__ import annotations

import math
import os
import re
import sys
import time

import numpy as np

from . import labels as L
from .analysis import read_analysis
from .archiver import Archiver, load_checkpoint, restore_dw
from .component import lookup
from .datawarehouse import DataWarehouse
from .gridspec import level_from_spec
from .errors import RunStopped
from .health import check_health
from .loadbalancer import LoadBalancer
from .memory import keep_freed_memory, physical_memory
from .problemspec import InputError, Param, ProblemSpec, deck_bytes
from .progress import Progress
from .scheduler.comm import Comm
from .scheduler.compile import GraphError
from .variables import VarType
from .scheduler.relocate import relocation_task
from .scheduler.scheduler import Scheduler

TIME = {
    "maxTime": Param("float"),
    "initTime": Param("float", 0.0, at_least=0.0),
    "delt_min": Param("float", 0.0, at_least=0.0),
    "delt_max": Param("float", math.inf, above=0.0),
    "delt_init": Param("float", math.inf, above=0.0),
    "max_initial_delt": Param("float", math.inf, above=0.0),
    "timestep_multiplier": Param("float", 1.0, above=0.0),
    "max_delt_increase": Param("float", 1e99, above=0.0),
    "max_Timesteps": Param("int", 2**62, at_least=0),
    "max_iterations": Param("int", 2**62, at_least=0),
    "end_at_max_time_exactly": Param("bool", False),
    "clamp_timesteps_to_output": Param("bool", False),
}

RECOMPUTE_FACTOR = 0.5    # delT scale for a recomputed timestep
MAX_RECOMPUTES = 10

ARCHIVER = {
    "filebase": Param("str", "pysus_output.uda"),
    "outputInterval": Param("float", 0.0, at_least=0.0),
    "outputTimestepInterval": Param("int", 0, at_least=0),
    "compression": Param("str", "none", choices=("none", "gzip"),
                         doc="Uintah's compression of its .uda files; read, pysus's HDF5 output is the same"),
}


def read_archiver(root):
    """The `<DataArchiver>` block as a dict (None when the deck has none)."""
    da = root.child("DataArchiver")
    if da is None:
        return None
    spec = da.read(ARCHIVER)
    if spec["outputInterval"] > 0 and spec["outputTimestepInterval"] > 0:
        raise da.error("give either <outputInterval> or <outputTimestepInterval>, not both")
    spec["save"] = []
    spec["save_nodes"] = {}
    for s in da.children("save"):
        name = s.attr("label")
        s.attr("material", default=None)
        s.attr("matl", default=None)
        s.attr("levels", "int", default=None, choices=(-1, 0))    # pysus's one level: the finest, level 0
        spec["save"].append(name)
        spec["save_nodes"][name] = s
    spec["checkpoint_interval"] = 0.0
    spec["checkpoint_timestepInterval"] = 0
    spec["checkpoint_cycle"] = 2
    cps = da.children("checkpoint")
    if len(cps) > 1:
        raise cps[1].error("only one <checkpoint> is accepted")
    if cps:
        c = cps[0]
        spec["checkpoint_interval"] = c.attr("interval", "float", 0.0, at_least=0.0)
        spec["checkpoint_timestepInterval"] = c.attr("timestepInterval", "int", 0, at_least=0)
        spec["checkpoint_cycle"] = c.attr("cycle", "int", 2, at_least=0)
        c.attr("walltimeStart", "float", None, at_least=0.0)
        c.attr("walltimeInterval", "float", None, at_least=0.0)
        if spec["checkpoint_interval"] <= 0 and spec["checkpoint_timestepInterval"] <= 0:
            raise c.error('<checkpoint> needs interval="..." (time) or timestepInterval="..." (steps)')
    spec["filebase_node"] = da.child("filebase")
    # as Uintah: <outputInitTimestep/> (a presence flag) writes the initial state,
    # <outputLastTimestep>true</outputLastTimestep> the final step, even when no output is due then
    spec["outputInitTimestep"] = da.child("outputInitTimestep") is not None
    spec["outputLastTimestep"] = da.get("outputLastTimestep", "bool", False)
    return spec


def check_output_dir(path, node=None, filename=None):
    """Refuse an output directory that cannot be made: a file in its way, or no write permission."""
    where = node.error if node is not None else (lambda m: InputError(m, filename))
    parent = os.path.abspath(path)
    while not os.path.exists(parent):
        parent = os.path.dirname(parent)
    if os.path.exists(path) and not os.path.isdir(path) and parent == os.path.abspath(path):
        return  # an existing file of that name: the archiver picks base.uda.000 beside it
    if not os.path.isdir(parent):
        raise where(f"output directory {path} lies under {parent}, which is a file; "
                    "accepted: a path under directories (or none yet)")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise where(f"output directory {path} cannot be made: {parent} is not writable; "
                    "accepted: a path under a writable directory")


HEALTH_CELLS = 2000          # grids this large are checked every step; smaller ones less often


def _health_interval(ncells) -> int:
    """Steps between state checks: PYSUS_CHECK_STATE=N (0: off), else every step on a grid of
    HEALTH_CELLS cells or more and every ceil(HEALTH_CELLS / cells) steps (at most 10) on a
    smaller one, whose steps are so short that the check's fixed cost would be a large share of
    them. Fixed by the deck, never by measured times: a run stops at the same step on any
    machine, loaded or not, and on any number of ranks."""
    text = os.environ.get("PYSUS_CHECK_STATE", "").strip()
    if not text:
        return max(1, min(10, math.ceil(HEALTH_CELLS / max(1, math.prod(ncells)))))
    try:
        every = int(text)
    except ValueError:
        every = -1
    if every < 0:
        raise InputError(f"PYSUS_CHECK_STATE={text!r}: expected 0 (off), 1 (every step) or N (every N steps)")
    return every


class Controller:
    """Sets up a run from a deck (or a checkpoint) and runs the time loop."""

    def __init__(self, deck=None, comm: Comm | None = None, restart=None, restart_index=-1,
                 quiet=False, filebase=None, max_timesteps=None, deck_text=None, max_time=None,
                 restart_mode="nocopy"):
        keep_freed_memory()
        self.comm = comm or Comm(None)
        self.quiet = quiet
        self.restart = restart
        self.restart_mode = restart_mode    # what the new uda takes of the old: archiver.RESTART_MODES
        self.restart_info = None
        if restart is not None:
            notices = []
            cdir, info, deck_text = load_checkpoint(restart, restart_index, notices)
            if self.comm.rank == 0:
                for line in notices:
                    print(f"pysus: notice: {line}", file=sys.stderr)
            self.restart_info = (cdir, info)
            deck = os.path.join(cdir, "input.ups")
        if deck_text is not None and restart is None:
            self.deck_text = deck_bytes(deck_text, deck or "<string>")
            self.root = ProblemSpec.from_string(self.deck_text, deck or "<string>")
        else:
            self.root = ProblemSpec.load(deck)
            # the bytes, not decoded text: the copy in the uda stays in the deck's own encoding
            with open(self.root.filename, "rb") as f:
                self.deck_text = f.read()
            if self.root.has_includes:   # the uda keeps the deck with its includes resolved, for restarts
                self.deck_text = self.root.resolved_bytes()
        self._read_deck()
        if filebase is None and restart is not None:
            # beside the uda restarted from (run.uda -> run.uda.000, run.uda.000 -> run.uda.001), as
            # Uintah run from the deck's directory; not the deck's filebase relative to wherever the
            # restart is started (a batch job's directory), nor lost when the run used --filebase
            filebase = re.sub(r"\.\d{3}$", "", os.path.normpath(restart))
        if filebase is not None and self.archive_spec is not None:
            self.archive_spec["filebase"] = filebase
            self.archive_spec["filebase_node"] = None
        if self.archive_spec is not None:
            check_output_dir(self.archive_spec["filebase"], self.archive_spec["filebase_node"], self.root.filename)
        if max_timesteps is not None:
            self.time["max_Timesteps"] = max_timesteps
        if max_time is not None:
            if not (math.isfinite(max_time) and max_time >= self.time["initTime"]):
                raise InputError(f"--maxTime {max_time!r}; accepted: a finite number >= initTime "
                                 f"{self.time['initTime']:g}")
            self.time["maxTime"] = max_time
        self._check_restart_has_work()
        self._build()

    def _check_restart_has_work(self):
        """A restart from a checkpoint at or past maxTime / max_Timesteps would write an empty uda:
        say so, and how to go on (--maxTime, --max-timesteps)."""
        if self.restart_info is None:
            return
        st = self.restart_info[1]["state"]
        tm = self.time
        if st["time"] >= tm["maxTime"] * (1 - 1e-14):
            reached = f"maxTime {tm['maxTime']:g} s"
        elif st["timestep"] >= tm["max_Timesteps"]:
            reached = f"max_Timesteps {tm['max_Timesteps']}"
        else:
            return
        raise InputError(f"{self.restart}: the checkpoint (timestep {st['timestep']}, t = {st['time']:.6g} s) "
                         f"already reached {reached}; nothing to run. Accepted: raise it with "
                         "pysus -restart UDA --maxTime T (or --max-timesteps N)")

    # -- set-up ----------------------------------------------------------------------
    def _read_deck(self):
        root = self.root
        if root.tag != "Uintah_specification":
            raise root.error("the root element is not <Uintah_specification>; accepted: a Uintah deck "
                             "(<Uintah_specification> ... </Uintah_specification>)")
        meta = root.child("Meta")
        if meta is not None:
            meta.mark_used()
        sc = root.child("SimulationComponent", required=True)
        self.component_name = sc.attr("type")
        cls = lookup(self.component_name, sc)
        t = root.child("Time", required=True)
        self.time = t.read(TIME)
        self.time["delt_init"] = min(self.time["delt_init"], self.time["max_initial_delt"])
        self.time["max_Timesteps"] = min(self.time["max_Timesteps"], self.time["max_iterations"])
        if self.time["maxTime"] < self.time["initTime"]:
            raise t.child("maxTime").error(f"maxTime {self.time['maxTime']:g} is before initTime "
                                           f"{self.time['initTime']:g}; accepted: maxTime >= initTime")
        if self.time["delt_min"] > self.time["delt_max"]:
            raise t.child("delt_min").error("delt_min exceeds delt_max")
        self.level = level_from_spec(root)
        if self.level.holes and not cls.holes_ok:
            raise root.child("Grid").child("Level").error(
                f"the <Box>es of this level do not fill one rectangular box (an L-shaped level), which "
                f'component "{self.component_name}" does not support; accepted: such a level with <SimulationComponent '
                'type="mpm" or "ice">, or boxes that tile one rectangular box')
        lbn = root.child("LoadBalancer")
        self.lb_interval = 0
        if lbn is not None:
            lbn.attr("type", default="SFC", choices=("SFC", "DLB", "Simple", "SimpleLoadBalancer"))
            self.lb_interval = lbn.get("timestepInterval", "int", 0, at_least=0)
            lbn.get("hasParticles", "bool", False)     # Uintah's DLB: weigh patches by particles; read
        self.archive_spec = read_archiver(root)
        self.component = cls()
        self.component.problem_setup(root, self.level)
        self.analysis = read_analysis(root, self.component, self.level)
        root.check_all_used()

    def _build(self):
        comm, level = self.comm, self.level
        try:
            self.lb = LoadBalancer(level, comm.size, comm.rank, self.lb_interval)
        except ValueError as e:
            raise InputError(str(e), self.root.filename) from None
        self.sched = Scheduler(level, self.lb, comm)
        self.recomputes = 0
        self.recompute_reason = None
        self.outputs = set(self.archive_spec["save"]) if self.archive_spec else set()
        self._apply_save_aliases()
        self.sched.output_labels = set(self.outputs)
        self.compile()
        self._check_memory()
        # a component that may ask to redo a step needs the old warehouse intact until the end
        self.sched.scrub_old = not getattr(self.component, "may_recompute", False)
        self.archiver = None
        if self.archive_spec is not None:
            base = self.archive_spec["filebase"]
            self.archive_spec["filebase"] = Archiver.unique_dir(base, comm)
            self.archiver = Archiver(self.archive_spec, level, comm, self.deck_text, self.component_name,
                                     self.component.material_names())
            for module in self.analysis:          # modules that write files of their own in the uda
                if hasattr(module, "uda"):
                    module.uda = self.archiver.dir

    def _apply_save_aliases(self):
        """A component's save_aliases {Uintah's name: the label holding it here}: a <save> of
        such a name writes that label (ArenaSoil's plastic strain tensor), with a note."""
        aliases = getattr(self.component, "save_aliases", {})
        for name in sorted(self.outputs & set(aliases)):
            held = aliases[name]
            self.outputs = (self.outputs - {name}) | {held}
            self.archive_spec["save"] = [held if n == name else n for n in self.archive_spec["save"]]
            self.archive_spec["save_nodes"][held] = self.archive_spec["save_nodes"][name]
            if self.comm.rank == 0:
                print(f'pysus: note: <save label="{name}"> writes {held} (this deck\'s {name} is a tensor, '
                      f"held under that name)", file=sys.stderr)

    def compile(self):
        """Compile the initialization and timestep graphs and check they fit together."""
        sched, comp, level = self.sched, self.component, self.level
        provided = {L.delT.name, L.simTime.name}
        sched.begin_graph("timestep")
        comp.schedule_time_advance(level, sched)
        for module in self.analysis:
            module.schedule(sched)
        comp.schedule_compute_stable_timestep(level, sched)
        step_tasks, step_reloc = list(sched.tasks), list(sched.relocation)
        probe = sched.compile({L.delT.name} | self.outputs | self._old_requires(step_tasks),
                              old_available=_Anything(), build_patch_graph=False)
        carried = probe.carried - provided

        sched.begin_graph("initialize")
        comp.schedule_initialize(level, sched)
        for module in self.analysis:          # modules whose values are carried from step to step
            if hasattr(module, "schedule_initialize"):
                module.schedule_initialize(sched)
        comp.schedule_compute_stable_timestep(level, sched)
        init_tasks = list(sched.tasks)
        all_computed = set()
        for t in init_tasks + step_tasks:
            all_computed |= {d.label.name for d in t.computes_}
        if step_reloc:
            all_computed |= {d.label.name for d in relocation_task(step_reloc).computes_}
        for name in sorted(self.outputs):
            if name not in all_computed:
                node = self.archive_spec["save_nodes"][name]
                raise node.error(f'<save label="{name}"> names a variable this deck does not compute; '
                                 f"computed: {', '.join(sorted(all_computed - provided))}")
        init_needed = {L.delT.name} | carried | (self.outputs & all_computed)
        self.init_graph = sched.compile(init_needed, old_available=None)
        missing = carried - self.init_graph.computed
        if missing:
            name = sorted(missing)[0]
            user = next(t.name for t in step_tasks if any(d.label.name == name for d in t.requires_))
            raise GraphError(f"task {user} requires {name} from the old warehouse, but initialization "
                             "does not compute it")

        sched.begin_graph("timestep")
        sched.tasks, sched.relocation = step_tasks, step_reloc
        self.carried = carried
        available = self.init_graph.computed | carried | provided
        analysed = set().union(*(m.needed for m in self.analysis))   # every step, as Uintah's modules
        # saved reductions (TotalMass.dat ...) get a line every timestep, as in Uintah
        self.saved_reductions = {n for n in self.outputs
                                 if (lab := L.find(n)) is not None and lab.vartype == VarType.REDUCTION}
        analysed |= self.saved_reductions
        self.step_graph = sched.compile({L.delT.name} | carried | self.outputs | analysed, old_available=available,
                                        protect={L.delT.name} | carried | analysed)
        # steps that write no output skip the tasks that only feed output
        self.quiet_step_graph = self.step_graph
        if self.outputs - carried - {L.delT.name} - analysed:
            self.quiet_step_graph = sched.compile({L.delT.name} | carried | analysed, old_available=available,
                                                  protect={L.delT.name} | carried | analysed,
                                                  build_patch_graph=False)
        sched.set_halo([self.init_graph, self.step_graph, self.quiet_step_graph])

    def grid_bytes_needed(self) -> int:
        """A lower bound of this rank's memory for grid variables: the carried ones twice (old
        and new warehouse) plus the largest single task's grid computes, on its local patches."""
        from .variables import GRID_TYPES
        patches = self.lb.local_patches()

        def nbytes(deps):
            seen, total = set(), 0
            for d in deps:
                if d.label.vartype not in GRID_TYPES:
                    continue
                per = np.dtype(d.label.dtype).itemsize * math.prod(d.label.shape)
                for m in d.matls or (-1,):
                    if (d.label.name, m) not in seen:
                        seen.add((d.label.name, m))
                        total += per * sum(math.prod(p.alloc_shape(d.label.vartype)) for p in patches)
            return total

        tasks = self.step_graph.tasks + self.init_graph.tasks
        carried = nbytes(d for t in tasks for d in t.computes_ if d.label.name in self.carried)
        largest = max((nbytes(t.computes_) for t in tasks), default=0)
        return 2 * carried + largest

    def _check_memory(self):
        """Refuse a grid whose arrays cannot fit in this computer's memory, before allocating any."""
        need, have = self.grid_bytes_needed(), physical_memory()
        if have and need > have:
            box = self.root.child("Grid").child("Level").child("Box")
            raise box.error(f"{self.level.ncells[0]} x {self.level.ncells[1]} x {self.level.ncells[2]} cells need at "
                            f"least {need / 2**30:.3g} GiB for grid variables on rank {self.comm.rank}, more than "
                            f"the {have / 2**30:.3g} GiB of memory here; accepted: a resolution (or more ranks) "
                            "whose arrays fit in memory")

    @staticmethod
    def _old_requires(tasks):
        return {d.label.name for t in tasks for d in t.requires_ if d.dw == "old"}

    # -- delT ---------------------------------------------------------------------------
    def next_delt(self, raw, t, prev, first):
        tm = self.time
        delt = raw * tm["timestep_multiplier"]
        if first:
            delt = min(delt, tm["delt_init"])
        if prev is not None and delt > (1.0 + tm["max_delt_increase"]) * prev:
            delt = (1.0 + tm["max_delt_increase"]) * prev
        if delt < tm["delt_min"]:
            if self.comm.rank == 0 and not self.quiet:
                print(f"pysus: warning: delT {delt:.3e} below delt_min, using delt_min {tm['delt_min']:.3e}",
                      file=sys.stderr)
            delt = tm["delt_min"]
        delt = min(delt, tm["delt_max"])
        if tm["clamp_timesteps_to_output"] and self.archiver is not None:
            nxt = self.archiver.next_event_time()
            if nxt is not None and t < nxt < t + delt:
                delt = nxt - t
        if tm["end_at_max_time_exactly"] and t + delt > tm["maxTime"]:
            delt = tm["maxTime"] - t
        return delt

    # -- the loop ------------------------------------------------------------------------
    def initialize(self):
        """Run the initialization graph (or load the checkpoint); returns the warehouse."""
        dw = DataWarehouse(0)
        if self.restart_info is not None:
            cdir, info = self.restart_info
            restore_dw(dw, cdir, info, self.level, self.sched.local_patches)
            st = info["state"]
            self.t, self.timestep, self.prev_delt = st["time"], st["timestep"], st["prev_delt"]
            if self.archiver is not None:
                self.archiver.setup(self.t, restart_from=self.restart, restart_timestep=self.timestep,
                                    restart_mode=self.restart_mode)
                self.archiver.next_output_time = st.get("next_output_time")
                self.archiver.next_checkpoint_time = st.get("next_checkpoint_time")
            return dw
        self.t, self.timestep, self.prev_delt = self.time["initTime"], 0, None
        self.sched.execute(self.init_graph, None, dw, keep=self.outputs)
        if self.archiver is not None:
            self.archiver.setup(self.t)
            if self.archiver.output_due(0, self.t) or self.archiver.spec["outputInitTimestep"]:
                self.archiver.output(dw, 0, self.t, 0.0, self.sched.local_patches)
        return dw

    def run(self):
        """Initialize and step to maxTime or max_Timesteps; returns the final warehouse."""
        progress = Progress(enabled=not self.quiet and self.comm.rank == 0, max_time=self.time["maxTime"],
                            max_timesteps=self.time["max_Timesteps"])
        # on a terminal, until the first step is drawn: a first run compiles for a minute or more
        progress.note("setting up (a deck's first run compiles its kernels: a minute or more)")
        try:
            return self._run(progress)
        finally:        # the line ends before any error message, which would otherwise join it
            progress.close()

    def _run(self, progress):
        wall0 = time.perf_counter()
        dw = self.initialize()
        self.output_wall = 0.0
        self.init_wall = time.perf_counter() - wall0
        # set-up beyond its tasks (those have their rows in the scheduler's table)
        self.init_other_wall = self.init_wall - sum(t for _, t, _, _ in self.sched.timing_table())
        tm = self.time
        progress.begin(self.timestep, self.t, self.init_wall)
        first = self.restart_info is None
        self._health_every = _health_interval(self.level.ncells)
        self._next_health_check, self._last_healthy = self.timestep + 1, self.timestep
        step_wall = []
        while self.t < tm["maxTime"] * (1 - 1e-14) and self.timestep < tm["max_Timesteps"]:
            raw = self.sched.reduce_delT(dw)
            delt = self.next_delt(raw, self.t, self.prev_delt, first)
            if not (delt > 0.0) or not math.isfinite(delt):
                raise RuntimeError(f"timestep {self.timestep}: delT = {delt} (stable timestep {raw}); "
                                   "the solution has probably blown up")
            first = False
            if self.lb.due(self.timestep):
                self._rebalance(dw)
            old = dw
            retries = 0
            while True:
                dw = DataWarehouse(self.timestep + 1)
                old.set_reduction(L.delT, delt)
                old.set_reduction(L.simTime, self.t)
                writes = self.archiver is not None and (
                    self.archiver.output_due(self.timestep + 1, self.t + delt)
                    or (self.archiver.spec["outputLastTimestep"] and self._last_step(delt)))
                graph = self.step_graph if writes else self.quiet_step_graph
                s0 = time.perf_counter()
                try:
                    self._inject_fault()
                    self.sched.execute(graph, old, dw, keep=self.outputs if writes else frozenset())
                except Exception as e:
                    e.pysus_when = f"timestep {self.timestep + 1} (t = {self.t:.6g} s, delT = {delt:.4g} s)"
                    raise
                step_wall.append(time.perf_counter() - s0)
                if not self._recompute_requested():
                    break
                retries += 1
                delt *= RECOMPUTE_FACTOR
                if retries > MAX_RECOMPUTES or delt < self.time["delt_min"]:
                    raise RuntimeError(f"timestep {self.timestep + 1}: recomputed {retries - 1} times and still "
                                       f"asked to recompute ({self.recompute_reason})")
                if self.comm.rank == 0 and not self.quiet:
                    print(f"pysus: timestep {self.timestep + 1} recomputed with delT {delt:.4e} "
                          f"({self.recompute_reason})", file=sys.stderr)
                self.recomputes += 1
            del old
            self.t += delt
            self.timestep += 1
            self.prev_delt = delt
            self._check_state(dw, delt)
            if self.analysis and self.comm.rank == 0:
                uda = self.archiver.dir if self.archiver is not None else None
                for module in self.analysis:
                    module.after_step(dw, self.timestep, self.t, uda)
            if self.archiver is not None:
                o0 = time.perf_counter()
                if writes:
                    self.archiver.output(dw, self.timestep, self.t, delt, self.sched.local_patches)
                elif self.saved_reductions:
                    self.archiver.write_reductions(dw, self.t, self.saved_reductions)
                if self.archiver.checkpoint_due(self.timestep, self.t):
                    self.archiver.checkpoint(dw, self.carried | {L.delT.name}, self.timestep, self.t,
                                             self._state(), self.sched.local_patches)
                self.output_wall += time.perf_counter() - o0
            progress.update(self.timestep, self.t, delt, time.perf_counter() - wall0)
        self.wall = time.perf_counter() - wall0
        self.step_times = step_wall
        return dw

    def _last_step(self, delt) -> bool:
        """True when the step about to be taken with delt ends the run (the loop's own test)."""
        tm = self.time
        return self.timestep + 1 >= tm["max_Timesteps"] or self.t + delt >= tm["maxTime"] * (1 - 1e-14)

    def _check_state(self, dw, delt):
        """Stop at the first non-finite or negative-mass/density/temperature value of the carried
        state; the bad step is written as an output timestep so a viewer shows where it went
        wrong, and no checkpoint is written from it.

        The check runs on a schedule the deck fixes (_health_interval: every step on grids of
        HEALTH_CELLS cells or more; PYSUS_CHECK_STATE=N every N steps, 0 off), and always before
        an output or a checkpoint is written, so whether a run stops never depends on the
        machine's load."""
        every = self._health_every
        if every == 0:
            return
        a = self.archiver
        due = self.timestep >= self._next_health_check or (
            a is not None and (a.output_due(self.timestep, self.t) or a.checkpoint_due(self.timestep, self.t)))
        if not due:
            return
        try:
            check_health(dw, self.carried, self.level, self.sched.local_patches, L, self.comm, self.timestep)
        except RunStopped as e:
            since = "" if self._last_healthy == self.timestep - 1 else \
                f" (healthy at timestep {self._last_healthy}, checked every {every} steps)"
            if a is None:
                raise RunStopped(f"{e}{since}") from None
            a.output(dw, self.timestep, self.t, delt, self.sched.local_patches)
            raise RunStopped(f"{e}{since}; that state is output timestep {a.dir}/t{self.timestep:05d}") from None
        self._last_healthy = self.timestep
        self._next_health_check = self.timestep + every

    def timing_table(self):
        """(name, seconds, calls) rows that add up to the run's wall time: set-up, each task, ghost
        exchange, relocation, output, and the rest (delT reduction, load balancing, scheduling)."""
        rows = [("set-up outside tasks (grid, first output)", self.init_other_wall, 1)]
        rows += [(name, t, calls) for name, t, calls, _ in self.sched.timing_table()]
        rows.append(("output and checkpoints", self.output_wall, 0))
        rows.append(("other (delT, load balance, scheduling)", self.wall - sum(r[1] for r in rows), 0))
        return rows

    def _recompute_requested(self) -> bool:
        """True on every rank when any rank's component asked to redo the step."""
        local = self.sched.recompute_reason
        if not getattr(self.component, "may_recompute", False):
            if local:
                raise RuntimeError(f"component asked to recompute a timestep ({local}) without declaring "
                                   "may_recompute = True")
            return False
        flag = self.comm.allreduce(1.0 if local else 0.0, "max")
        if flag:
            self.recompute_reason = local or "requested on another rank"
        self.sched.recompute_reason = None
        return bool(flag)

    def _inject_fault(self):
        """PYSUS_FAULT=rank:timestep raises on that rank before that step (to test failure handling)."""
        spec = os.environ.get("PYSUS_FAULT")
        if spec:
            rank, step = (int(x) for x in spec.split(":"))
            if rank == self.comm.rank and step == self.timestep:
                raise RuntimeError(f"fault injected by PYSUS_FAULT on rank {rank} at timestep {step}")

    def _state(self):
        a = self.archiver
        return {"time": self.t, "timestep": self.timestep, "prev_delt": self.prev_delt,
                "next_output_time": a.next_output_time if a else None,
                "next_checkpoint_time": a.next_checkpoint_time if a else None}

    def _rebalance(self, dw):
        costs = self.sched.patch_costs(dw)
        old_map = list(self.lb.rank_of)
        if self.lb.rebalance(costs):
            from .migrate import migrate
            migrate(dw, self.level, old_map, self.lb.rank_of, self.comm)


class _Anything:
    """old_available stand-in that accepts every label (first compile pass)."""

    def __contains__(self, item):
        return True
