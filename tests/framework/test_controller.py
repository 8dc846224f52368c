"""The time loop's delT rules and the progress display."""
import io
import math

import pytest

from tests.conftest import run_deck
from tests.framework import decks


class FakeTTY(io.StringIO):
    def isatty(self):
        return True


@pytest.fixture
def ctl(tmp_path):
    return run_deck(decks.heat(n=8, maxTime=0.01), tmp_path)


def test_delt_rules(ctl):
    ctl.time.update(timestep_multiplier=0.5, delt_init=1e-3, max_delt_increase=0.1, delt_min=1e-6,
                    delt_max=0.1, end_at_max_time_exactly=True, maxTime=1.0)
    assert ctl.next_delt(1.0, 0.0, None, first=True) == 1e-3            # delt_init caps the first step
    assert ctl.next_delt(1.0, 0.0, 0.01, first=False) == pytest.approx(0.011)  # max_delt_increase
    assert ctl.next_delt(1e-9, 0.0, None, first=False) == 1e-6          # delt_min
    assert ctl.next_delt(10.0, 0.0, 1.0, first=False) == 0.1            # delt_max
    assert ctl.next_delt(0.2, 0.95, 0.1, first=False) == pytest.approx(0.05)   # lands on maxTime


def test_max_timesteps_and_end_exactly(tmp_path):
    text = decks.heat(n=8, maxTime=5.0).replace("<initTime>0</initTime>",
                                                   "<initTime>0</initTime><max_Timesteps>3</max_Timesteps>")
    c = run_deck(text, tmp_path, name="m")
    assert c.timestep == 3 and c.t < 5.0
    c = run_deck(decks.heat(n=8, maxTime=0.05), tmp_path, name="e")
    assert c.t == 0.05


def test_progress_draws_on_a_terminal_only():
    from framework.progress import Progress
    tty, pipe = FakeTTY(), io.StringIO()
    for stream in (tty, pipe):
        p = Progress(stream=stream, interval=0.0)
        p.update(12, 0.5, 1e-3, 2.0)
        p.close()
    assert "step      12" in tty.getvalue() and "ms/step" in tty.getvalue()
    assert pipe.getvalue() == ""
    q = FakeTTY()
    p = Progress(enabled=False, stream=q)
    p.update(1, 0, 1, 1)
    assert q.getvalue() == ""


def test_output_last_timestep(tmp_path):
    """Uintah's <outputLastTimestep>true</...>: the final step is written though no output is due
    (every 10th step here, 3 steps run); without it only the initial state is."""
    def run(flag):
        text = decks.heat(n=8, maxTime=5.0, out=10).replace(
            "<initTime>0</initTime>", "<initTime>0</initTime><max_Timesteps>3</max_Timesteps>")
        text = text.replace("</DataArchiver>", f"{flag}</DataArchiver>")
        c = run_deck(text, tmp_path, name=f"r{len(flag)}")
        return sorted(p.name for p in (tmp_path / f"r{len(flag)}.uda").glob("t0*"))
    assert run("") == ["t00000"]
    assert run("<outputLastTimestep> true </outputLastTimestep><outputInitTimestep/>") == ["t00000", "t00003"]
