"""Every deck in inputs/EFEM/ runs two timesteps (output included)."""
import pytest

from tests.decks.runner import decks, run_two_steps

DECKS, IDS = decks("EFEM")


@pytest.mark.parametrize("deck", DECKS, ids=IDS)
def test_deck_runs_two_steps(deck, tmp_path):
    run_two_steps(deck, tmp_path)
