"""`pysus --graph`: the tasks a deck will run, in order, and a DOT file of the graph."""
from __future__ import annotations


def _deps(deps):
    out = []
    for d in deps:
        g = f" +{d.n}{d.ghost.value}" if d.n else ""
        m = "" if d.matls in ((), (-1,)) else f" m{','.join(map(str, d.matls))}"
        out.append(f"{d.label.name}({d.dw}{m}{g})")
    return ", ".join(out) or "-"


def describe(ctl) -> str:
    lines = [f"deck: {ctl.root.filename}", f"component: {ctl.component_name}",
             f"grid: {ctl.level.ncells} cells, {len(ctl.level.patches)} patches, halo "
             + ", ".join(f"{vt.value}={g}" for vt, g in ctl.level.halo.items() if g)]
    for cg in (ctl.init_graph, ctl.step_graph):
        lines.append(f"\n== {cg.name}: {len(cg.tasks)} tasks ==")
        for i, t in enumerate(cg.tasks, 1):
            lines.append(f"{i:3d}. {t.name}")
            lines.append(f"       requires: {_deps(t.requires_)}")
            if t.modifies_:
                lines.append(f"       modifies: {_deps(t.modifies_)}")
            lines.append(f"       computes: {_deps(t.computes_)}")
        if cg.pruned:
            lines.append(f"   pruned (outputs not needed): {', '.join(t.name for t in cg.pruned)}")
    quiet = {t.name for t in ctl.quiet_step_graph.tasks}
    only_output = [t.name for t in ctl.step_graph.tasks if t.name not in quiet]
    if only_output:
        lines.append(f"\nrun only on steps that write output: {', '.join(only_output)}")
    lines.append(f"\ncarried between timesteps: {', '.join(sorted(ctl.carried))}")
    return "\n".join(lines)


def write_dot(ctl, path):
    """Task-level DOT graph of both stages, edges labelled with the variable."""
    with open(path, "w") as f:
        f.write("digraph pysus {\n  rankdir=TB;\n")
        for cg in (ctl.init_graph, ctl.step_graph):
            f.write(f'  subgraph "cluster_{cg.name}" {{\n    label="{cg.name}";\n')
            writer = {}
            for t in cg.tasks:
                f.write(f'    "{cg.name}:{t.name}" [label="{t.name}", shape=box];\n')
                for d in t.requires_ + t.modifies_:
                    if d.dw == "new" and d.label.name in writer:
                        f.write(f'    "{cg.name}:{writer[d.label.name]}" -> "{cg.name}:{t.name}" '
                                f'[label="{d.label.name}"];\n')
                for d in t.writes():
                    writer[d.label.name] = t.name
            f.write("  }\n")
        f.write("}\n")
