"""framework.uintah_uda reads sus's .uda layout: extra cells dropped, x fastest on disk, Vectors
as three doubles per cell, several patches assembled (the layout sus writes; the reader also
reproduces sus's own fields in tests/ice/test_advection_limiters.py's 2D reference)."""
import numpy as np
import pytest

from framework.uintah_uda import UintahArchive

TIMESTEP = """<?xml version="1.0"?>
<Uintah_timestep>
  <Meta><endianness>little_endian</endianness><nBits>64</nBits></Meta>
  <Time><timestepNumber>5</timestepNumber><currentTime>0.5</currentTime></Time>
  <Grid><numLevels>1</numLevels><Level>
    <extraCells>[1, 1, 1]</extraCells><anchor>[0, 0, 0]</anchor><cellspacing>[0.5, 0.25, 1]</cellspacing>
{patches}
  </Level></Grid>
  <Data><Datafile href="l0/p00000.xml" proc="0"/></Data>
</Uintah_timestep>
"""
PATCH = """    <Patch><id>{id}</id><lowIndex>{elo}</lowIndex><highIndex>{ehi}</highIndex>
      <interiorLowIndex>{ilo}</interiorLowIndex><interiorHighIndex>{ihi}</interiorHighIndex></Patch>"""
VARIABLE = """  <Variable type="CCVariable&lt;{type}&gt;"><variable>{name}</variable><index>0</index>
    <patch>{patch}</patch><start>{start}</start><end>{end}</end><filename>p00000.data</filename></Variable>
"""


def value(i, j, k):
    return 100.0 * i + 10.0 * j + k


def write_uda(root):
    """Two patches along x of a 4 x 3 x 1 interior, one extra cell around the domain."""
    patches = [(0, (-1, -1, -1), (2, 4, 2), (0, 0, 0), (2, 3, 1)), (1, (2, -1, -1), (5, 4, 2), (2, 0, 0), (4, 3, 1))]
    step = root / "t00005"
    (step / "l0").mkdir(parents=True)
    vec = lambda v: "[" + ", ".join(map(str, v)) + "]"
    (step / "timestep.xml").write_text(TIMESTEP.format(patches="\n".join(
        PATCH.format(id=p, elo=vec(a), ehi=vec(b), ilo=vec(c), ihi=vec(d)) for p, a, b, c, d in patches)))
    data, variables = b"", ""
    for p, elo, ehi, _, _ in patches:
        i, j, k = (np.arange(lo, hi) for lo, hi in zip(elo, ehi))
        kk, jj, ii = np.meshgrid(k, j, i, indexing="ij")           # x fastest
        rho = value(ii, jj, kk)
        vel = np.stack([rho, -rho, 2 * rho], axis=-1)
        for name, type_, arr in (("rho_CC", "double", rho), ("vel_CC", "Vector", vel)):
            raw = np.ascontiguousarray(arr, dtype="<f8").tobytes()
            variables += VARIABLE.format(type=type_, name=name, patch=p, start=len(data), end=len(data) + len(raw))
            data += raw + b"\0" * 16                                # sus pads between variables
    (step / "l0" / "p00000.xml").write_text(f"<Uintah_Output>\n{variables}</Uintah_Output>\n")
    (step / "l0" / "p00000.data").write_bytes(data)


def test_reads_interior_cells_x_fastest_over_patches(tmp_path):
    write_uda(tmp_path)
    da = UintahArchive(tmp_path)
    assert da.times == [0.5]
    rho, (x, y, z) = da.read("rho_CC", 0, -1)
    i, j, k = np.meshgrid(np.arange(4), np.arange(3), np.arange(1), indexing="ij")
    assert rho.shape == (4, 3, 1) and np.array_equal(rho, value(i, j, k))
    assert x == pytest.approx([0.25, 0.75, 1.25, 1.75]) and y == pytest.approx([0.125, 0.375, 0.625])
    vel, _ = da.read("vel_CC", 0, -1)
    assert vel.shape == (4, 3, 1, 3) and np.array_equal(vel[..., 1], -value(i, j, k))
    with pytest.raises(KeyError):
        da.read("press_CC", 0, -1)


def test_interior_index_left_out_when_it_is_the_patch_index():
    """sus writes no <interiorHighIndex> for a patch whose high side touches no domain face (its
    interior ends where its cells do), as in the timestep.xml of hotBlob2mat8patch.ups's patch 0."""
    from lxml import etree
    from framework.uintah_uda import _index
    p = etree.fromstring("<Patch><lowIndex>[-1, -1, -1]</lowIndex><highIndex>[5, 5, 5]</highIndex>"
                         "<interiorLowIndex>[0, 0, 0]</interiorLowIndex></Patch>")
    assert _index(p, "interiorHighIndex") == [5, 5, 5]
    assert _index(p, "interiorLowIndex") == [0, 0, 0]
