"""Build a Level from the deck's `<Grid>` block."""
from __future__ import annotations

import numpy as np

from .grid import Level
from .problemspec import Param


BOX = {
    "lower": Param("vector"),
    "upper": Param("vector"),
    "extraCells": Param("ivector", (0, 0, 0), at_least=0),
    "patches": Param("ivector", (1, 1, 1), at_least=1),
    "resolution": Param("ivector", None),
}


def level_from_spec(root):
    """The single level of `<Grid><Level>`; boundary conditions are left to components."""
    grid = root.child("Grid", required=True)
    levels = grid.children("Level")
    if not levels:
        raise grid.error("missing required tag <Level>")
    if len(levels) > 1:
        raise levels[1].error("only one <Level> is supported (no AMR in pysus)")
    lv = levels[0]
    boxes = lv.children("Box")
    if not boxes:
        raise lv.error("missing required tag <Box>")
    if len(boxes) > 1:
        raise boxes[1].error(f"a <Level> made of {len(boxes)} <Box>es is not supported (a pysus level is one "
                             "box of cells, split into patches); accepted: one <Box> per <Level>")
    box = boxes[0]
    box.attr("label", default=None)
    b = box.read(BOX)
    spacing = lv.get("spacing", "vector", None, above=0.0)
    periodic = lv.get("periodic", "ivector", (0, 0, 0))
    if any(p not in (0, 1) for p in periodic):
        raise lv.child("periodic").error(f"periodic {periodic} is not accepted; accepted: 0 or 1 in every direction")
    lower, upper = np.array(b["lower"]), np.array(b["upper"])
    if np.any(upper <= lower):
        raise box.error(f"<upper> {tuple(upper)} must exceed <lower> {tuple(lower)} in every direction")
    if b["resolution"] is not None and spacing is not None:
        raise lv.error("give either <Box><resolution> or <Level><spacing>, not both")
    if b["resolution"] is not None:
        res = b["resolution"]
    elif spacing is not None:
        res = tuple(int(round(x)) for x in (upper - lower) / np.array(spacing))
        if any(abs(r * s - (u - l)) > 1e-8 * (u - l) for r, s, u, l in zip(res, spacing, upper, lower)):
            raise lv.child("spacing").error("spacing does not divide the box into whole cells")
    else:
        raise box.error("missing <resolution> (or <Level><spacing>)")
    if any(r < 1 for r in res):
        raise box.error(f"resolution {res} must be at least 1 in every direction")
    for d, (r, n) in enumerate(zip(res, b["patches"])):
        if n > r:
            raise box.child("patches").error(f"{n} patches along {'xyz'[d]} but only {r} cells; accepted: "
                                             "1 to the number of cells in each direction")
    if any(e > 1 for e in b["extraCells"]):
        raise box.child("extraCells").error(f"extraCells {b['extraCells']} is not accepted; accepted: 0 or 1 in "
                                            "each direction (the components fill one layer of boundary cells)")
    try:
        return Level(lower, upper, res, b["patches"], b["extraCells"], tuple(bool(x) for x in periodic))
    except ValueError as e:
        raise box.child("patches").error(str(e)) from None


def boundary_faces(bcs, sides):
    """[(side, <Face> node)] of a `<BoundaryConditions>` block; a side given twice is an error
    (its conditions would otherwise be merged without a word)."""
    seen, out = {}, []
    for face in bcs.children("Face"):
        side = face.attr("side", choices=sides)
        if side in seen:
            raise face.error(f'<Face side="{side}"> given twice (first at line {seen[side].line}); accepted: '
                             "one <Face> per side holding all its <BCType>s")
        seen[side] = face
        out.append((side, face))
    return out
