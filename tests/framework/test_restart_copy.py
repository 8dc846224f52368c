"""-restart with Uintah's -nocopy (default), -copy and -move: the new uda holds only the
restart's outputs, or starts with the old uda's outputs, checkpoints and reduction lines up to
the checkpoint (copied, or moved and the old uda deleted), so that its output.xdmf and
DataArchive list the whole history, as the uninterrupted run's do."""
import re
import shutil
from pathlib import Path

import numpy as np
import pytest

from framework.archiver import DataArchive
from framework.cli import main

ROOT = Path(__file__).resolve().parents[2]


def xdmf_times(uda):
    return [float(t) for t in re.findall(r'<Time Value="([^"]+)"/>', (Path(uda) / "output.xdmf").read_text())]


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """The quickstart deck (16 x 16 cells) to t = 0.2, outputs every 0.05, checkpoints at 0.1
    and 0.2: run twice, once to restart from (copy and move take the same one), once whole."""
    tmp = tmp_path_factory.mktemp("restart")
    deck = (ROOT / "inputs/examples/quickstart.ups").read_text(encoding="latin-1")
    deck = (deck.replace("0.5      </maxTime>", "0.2 </maxTime>").replace("[64, 64, 1]", "[16, 16, 1]")
            .replace('<checkpoint interval="0.25" cycle="2"/>', '<checkpoint interval="0.1" cycle="2"/>'))
    assert "0.2 </maxTime>" in deck and "[16, 16, 1]" in deck and 'interval="0.1"' in deck
    (tmp / "run.ups").write_text(deck.replace("quickstart.uda", str(tmp / "whole.uda")), encoding="latin-1")
    assert main(["-q", str(tmp / "run.ups")]) == 0
    return tmp


@pytest.mark.parametrize("flag", ["", "-nocopy", "-copy", "-move"])
def test_restart_flags_give_one_history(runs, flag, tmp_path):
    old = tmp_path / "whole.uda"
    shutil.copytree(runs / "whole.uda", old)
    whole = DataArchive(runs / "whole.uda")
    first_cp, last_cp = whole.index["checkpoints"]
    assert len(whole.timesteps) == 5 and whole.times[-1] == 0.2 and 0.1 <= first_cp["time"] < 0.15
    old_dat = (old / "TotalHeat.dat").read_text().splitlines()
    new = tmp_path / "cont.uda"
    assert main(["-q", "-restart", str(old), "-t", "0", "--filebase", str(new)] + ([flag] if flag else [])) == 0
    da = DataArchive(new)
    copies = flag in ("-copy", "-move")
    kept = [ts for ts in whole.timesteps if copies or ts > first_cp["timestep"]]
    assert 2 <= len(kept) <= 5
    assert da.timesteps == kept
    assert xdmf_times(new) == pytest.approx(list(whole.times)[-len(kept):])
    for k in range(len(kept)):          # same fields as the uninterrupted run at every listed output
        np.testing.assert_allclose(da.read("temp_CC", 0, k)[0], whole.read("temp_CC", 0, k - len(kept))[0],
                                   rtol=1e-12, atol=0)
    dat = (new / "TotalHeat.dat").read_text().splitlines()
    # one line per timestep (as Uintah): the restart's own from the checkpoint on, or the whole history
    after = [line for line in old_dat if float(line.split()[0]) > first_cp["time"] * (1 + 1e-12)]
    assert len(old_dat) > len(whole.timesteps) and 0 < len(after) < len(old_dat)
    assert dat == (old_dat if copies else after)
    assert da.index["checkpoints"] == ([first_cp, last_cp] if copies else [last_cp])
    assert (new / "checkpoints" / Path(da.index["checkpoints"][0]["dir"]).name).is_dir()
    assert old.exists() == (flag != "-move")
    if flag == "-copy":     # the old uda is left as it was
        assert DataArchive(old).timesteps == whole.timesteps
