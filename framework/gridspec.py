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
    """The single level of `<Grid><Level>`; boundary conditions are left to components.

    Several `<Box>`es (Uintah allows a level of any union of boxes) of cells of one size
    that tile one rectangular box, their patches lining up into one grid of patches, are
    that box with the same cells and patches (extraCells the largest of the boxes', as in
    Uintah). A union that is not one box (L-shaped, with gaps) is the box that holds it cut
    along every box's edges and patch boundaries; the slots outside the boxes are holes of
    the level (grid.Level, present), their faces domain boundaries.
    """
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
    spacing = lv.get("spacing", "vector", None, above=0.0)
    periodic = lv.get("periodic", "ivector", (0, 0, 0))
    if any(p not in (0, 1) for p in periodic):
        raise lv.child("periodic").error(f"periodic {periodic} is not accepted; accepted: 0 or 1 in every direction")
    read = [_read_box(lv, box, spacing) for box in boxes]
    extra = tuple(max(r[4][d] for r in read) for d in range(3))
    if any(e > 1 for e in extra):
        node = next(box for box, r in zip(boxes, read) if any(e > 1 for e in r[4]))
        raise node.child("extraCells").error(f"extraCells {extra} is not accepted; accepted: 0 or 1 in "
                                             "each direction (the components fill one layer of boundary cells)")
    per = tuple(bool(x) for x in periodic)
    if len(boxes) == 1:
        lower, upper, res, patches, _ = read[0]
        try:
            return Level(lower, upper, res, patches, extra, per)
        except ValueError as e:
            raise boxes[0].child("patches").error(str(e)) from None
    lower, upper, res, splits, present = _tile(lv, boxes, read)
    if present is not None and any(per):
        raise lv.child("periodic").error("a periodic direction on a level whose <Box>es do not fill one "
                                         "rectangular box is not supported; accepted: periodic 0 on such a level")
    return Level(lower, upper, res, extra=extra, periodic=per, splits=splits, present=present)


def _read_box(lv, box, spacing):
    """(lower, upper, resolution, patches, extraCells) of one <Box>, checked."""
    box.attr("label", default=None)
    b = box.read(BOX)
    lower, upper = np.array(b["lower"]), np.array(b["upper"])
    if np.any(upper <= lower):
        raise box.error(f"<upper> {_vec(upper)} must exceed <lower> {_vec(lower)} in every direction")
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
    return lower, upper, tuple(res), tuple(b["patches"]), tuple(b["extraCells"])


def _vec(v):
    """[x, y, z] as a deck writes it."""
    return "[" + ", ".join(f"{float(x):g}" for x in v) + "]"


def _tile(lv, boxes, read):
    """(lower, upper, resolution, patch splits) of the one box that several <Box>es tile."""
    dx = (read[0][1] - read[0][0]) / np.array(read[0][2], dtype=float)
    for box, (lo, hi, res, _, _) in zip(boxes[1:], read[1:]):
        other = (hi - lo) / np.array(res, dtype=float)
        if np.any(np.abs(other - dx) > 1e-10 * dx):
            raise box.error(f"cell size {_vec(other)} differs from the first <Box>'s {_vec(dx)}; accepted: the "
                            "same cell size in every <Box> of a level")
    lower = np.min([r[0] for r in read], axis=0)
    upper = np.max([r[1] for r in read], axis=0)
    cells = []                               # each box's [lo, hi) in cells from `lower`
    for box, (lo, hi, res, _, _) in zip(boxes, read):
        first = np.round((lo - lower) / dx).astype(int)
        if np.any(np.abs(first * dx - (lo - lower)) > 1e-8 * (upper - lower)):
            raise box.error(f"<lower> {_vec(lo)} is not on the cell faces of the level's first <Box>; accepted: "
                            "boxes whose corners lie on one grid of cells")
        cells.append((first, first + np.array(res)))
    total = np.round((upper - lower) / dx).astype(int)
    labels = [repr(b.element.get("label", str(i))) for i, b in enumerate(boxes)]
    names = ", ".join(labels)
    for i in range(len(cells)):
        for j in range(i + 1, len(cells)):
            if np.all(np.maximum(cells[i][0], cells[j][0]) < np.minimum(cells[i][1], cells[j][1])):
                raise boxes[j].error(f"this <Box> overlaps <Box> {labels[i]}; accepted: boxes that "
                                     "do not overlap")
    if sum(int(np.prod(h - l)) for l, h in cells) != int(np.prod(total)):
        return _with_holes(lower, upper, total, cells, read)
    splits = []
    for d in range(3):
        cuts = set()
        for (l, h), (_, _, res, patches, _) in zip(cells, read):
            cuts |= {int(l[d]) + res[d] * i // patches[d] for i in range(patches[d] + 1)}
        splits.append(sorted(cuts))
    if int(np.prod([len(s) - 1 for s in splits])) != sum(int(np.prod(r[3])) for r in read):
        raise lv.error(f"the patches of the {len(boxes)} <Box>es ({names}) do not line up into one grid of patches "
                       "across the level, which a pysus level is; accepted: <patches> whose boundaries continue "
                       "from box to box")
    return lower, upper, tuple(int(t) for t in total), splits, None


def _with_holes(lower, upper, total, cells, read):
    """_tile of boxes that do not fill the box holding them: the splits are every box's edges
    and patch boundaries, and `present` marks the slots inside a box."""
    splits = []
    for d in range(3):
        cuts = {0, int(total[d])}
        for (l, h), (_, _, res, patches, _) in zip(cells, read):
            cuts |= {int(l[d]) + res[d] * i // patches[d] for i in range(patches[d] + 1)}
        splits.append(sorted(cuts))
    present = np.zeros([len(s) - 1 for s in splits], dtype=bool)
    for l, h in cells:
        sel = [slice(splits[d].index(int(l[d])), splits[d].index(int(h[d]))) for d in range(3)]
        present[tuple(sel)] = True
    return lower, upper, tuple(int(t) for t in total), splits, present


SUB_FACES = ("circle", "rectangle", "annulus")
_NOT_SUPPORTED = ("ellipse", "rectangulus")


def _face_kind(face):
    """"side" or the sub-face attribute of a <Face>; other geometries are refused."""
    for key in ("side",) + SUB_FACES:
        if face.element.get(key) is not None:
            return key
    for key in _NOT_SUPPORTED:
        if face.element.get(key) is not None:
            raise face.error(f'<Face {key}="..."> is not supported; accepted: side, circle, rectangle, annulus')
    raise face.error('missing required attribute side="..." (or a sub-face: circle, rectangle or annulus="...")')


def boundary_faces(bcs, sides):
    """[(side, <Face> node)] of the `<Face side=...>`s of a `<BoundaryConditions>` block; a side
    given twice is an error (its conditions would otherwise be merged without a word). The
    sub-faces (circle, rectangle, annulus) are left to sub_faces()."""
    seen, out = {}, []
    for face in bcs.children("Face"):
        if _face_kind(face) != "side":
            continue
        side = face.attr("side", choices=sides)
        if side in seen:
            raise face.error(f'<Face side="{side}"> given twice (first at line {seen[side].line}); accepted: '
                             "one <Face> per side holding all its <BCType>s")
        seen[side] = face
        out.append((side, face))
    return out


def sub_faces(bcs, sides, level):
    """[(side, SubFace, <Face> node)] of the `<Face circle|rectangle|annulus=...>`s of a
    `<BoundaryConditions>` block, in deck order (Uintah's BoundCondReader)."""
    out = []
    for face in bcs.children("Face"):
        kind = _face_kind(face)
        if kind == "side":
            continue
        side = face.attr(kind, choices=sides)
        out.append((side, SubFace(face, kind, side, level), face))
    return out


class SubFace:
    """The part of a domain face that a `<Face circle|rectangle|annulus>` covers.

    As Uintah's CircleBCData, RectangleBCData and AnnulusBCData: a boundary cell (extra
    cell) belongs to the sub-face when the centre of its face on the domain boundary is
    inside the shape (|p - origin| <= radius; lower <= p <= upper; inner_radius <
    |p - origin| <= outer_radius); a grid node on the face, when its position is. The
    face's other cells keep the `<Face side>` conditions (Uintah's DifferenceBCData).
    """

    def __init__(self, face, kind, side, level):
        self.kind, self.side, self.node = kind, side, face
        self.d, self.s = "xyz".index(side[0]), int(side[1] == "+")
        plane = (level.upper if self.s else level.anchor)[self.d]
        span = float(np.max(level.upper - level.anchor))
        if kind == "rectangle":
            self.lower, self.upper = _point(face, "lower"), _point(face, "upper")
            pts = {"lower": self.lower, "upper": self.upper}
            if np.any(self.lower > self.upper) or np.all(self.lower == self.upper):
                raise face.error(f"rectangle lower {tuple(self.lower)} must not exceed upper {tuple(self.upper)} "
                                 "in any direction")
        else:
            self.origin = _point(face, "origin")
            pts = {"origin": self.origin}
            if kind == "circle":
                self.inner, self.outer = -1.0, face.attr("radius", "float", above=0.0)
            else:
                self.inner = face.attr("inner_radius", "float", above=0.0)
                self.outer = face.attr("outer_radius", "float", above=0.0)
                if self.outer < self.inner:
                    raise face.error(f"annulus outer_radius {self.outer:g} is smaller than inner_radius "
                                     f"{self.inner:g}")
        for name, p in pts.items():
            if abs(p[self.d] - plane) > 1e-12 * span:
                raise face.error(f'{name} {tuple(p)} is not on face {side} ({"xyz"[self.d]} = {plane:g}); '
                                 f"accepted: a point of the face's plane")
        face.attr("name", default=None)

    def inside(self, pts):
        """Which points (rows of pts, on the face's plane: their normal coordinate is not read)
        the sub-face covers."""
        t = [c for c in range(3) if c != self.d]
        pts = np.asarray(pts, dtype=np.float64)[..., t]
        if self.kind == "rectangle":
            return np.all((pts >= self.lower[t]) & (pts <= self.upper[t]), axis=-1)
        r = np.sqrt(np.sum((pts - self.origin[t]) ** 2, axis=-1))
        return (r <= self.outer) & (r > self.inner)

    def cells(self, level, low, shape):
        """inside() for the boundary cells of face (d, s) of an array whose entry [0, 0, 0] has
        global index `low`: a (shape[d1], shape[d2]) array over the two tangential directions
        (d1, d2) = (d+1, d+2) mod 3, the test point the centre of each cell's boundary face."""
        d = self.d
        d1, d2 = (d + 1) % 3, (d + 2) % 3
        a = level.anchor[d1] + (np.arange(shape[d1]) + low[d1] + 0.5) * level.dx[d1]
        b = level.anchor[d2] + (np.arange(shape[d2]) + low[d2] + 0.5) * level.dx[d2]
        pts = np.zeros((shape[d1], shape[d2], 3))
        pts[..., d] = (level.upper if self.s else level.anchor)[d]
        pts[..., d1], pts[..., d2] = a[:, None], b[None, :]
        return self.inside(pts)


def _point(face, name):
    """A point attribute as Uintah writes it: "x y z" or "x,y,z" (brackets accepted)."""
    raw = face.attr(name)
    parts = raw.replace("[", " ").replace("]", " ").replace(",", " ").split()
    try:
        p = np.array([float(x) for x in parts])
    except ValueError:
        p = np.zeros(0)
    if p.size != 3 or not np.all(np.isfinite(p)):
        raise face.error(f'attribute {name}="{raw}" is not a point; accepted: three numbers "x y z"')
    return p
