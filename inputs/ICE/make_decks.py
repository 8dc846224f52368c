"""Writes the shock-tube decks of this folder (run once; the decks are committed).

    .venv/bin/python inputs/ICE/make_decks.py
The template lives in components/ice/scenes.py, shared with the tests and
scripts/accuracy_cost.py.
"""
import os

from components.ice.scenes import TORO, shock_tube_deck

RUNTIME = {"toro3": "3 s", "toro5": "3 s"}

if __name__ == "__main__":
    here = os.path.dirname(os.path.abspath(__file__))
    for name in TORO:
        with open(os.path.join(here, f"{name}.ups"), "w") as f:
            f.write(shock_tube_deck(name, runtime=RUNTIME.get(name, "2 s")))
        print("wrote", name)
