"""The wheel (`pip wheel .`) holds every shipped deck beside the packages, and from it, outside
the source tree, the scene modules find their decks and `pysus inputs/examples/quickstart.ups`
runs (skipped where pip cannot fetch the build backend)."""
import os
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SCENES = {"components.mpmice.scene_container": "DECK", "components.mpmice.scene_cylinder": "DECK",
          "components.mpmice.scene_piston": "DECK", "components.mpm.scene_accuracy": "INPUTS"}


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    """The built wheel, unpacked as pip would install it into site-packages."""
    tmp = tmp_path_factory.mktemp("wheel")
    src = tmp / "src"        # a copy: setuptools leaves build/ in the tree it builds
    for d in ("framework", "components", "inputs"):
        shutil.copytree(ROOT / d, src / d, ignore=shutil.ignore_patterns("__pycache__", "*.uda*"))
    shutil.copy(ROOT / "pyproject.toml", src)
    r = subprocess.run([sys.executable, "-m", "pip", "wheel", str(src), "--no-deps", "-q", "-w", str(tmp / "dist")],
                       capture_output=True, text=True, timeout=600)
    if r.returncode != 0 and any(s in r.stderr for s in ("No matching distribution", "NewConnectionError",
                                                         "Could not find a version")):
        pytest.skip("pip could not fetch the build backend: " + r.stderr.strip().splitlines()[-1])
    assert r.returncode == 0, r.stderr
    wheel, = (tmp / "dist").glob("pysus-*.whl")
    with zipfile.ZipFile(wheel) as z:
        z.extractall(tmp / "site")
        names = set(z.namelist())
    return tmp / "site", names


def test_wheel_holds_every_deck(site):
    _, names = site
    decks = {p.relative_to(ROOT).as_posix() for p in (ROOT / "inputs").rglob("*.ups")}
    assert "inputs/examples/quickstart.ups" in decks and len(decks) > 20
    assert decks <= names, sorted(decks - names)
    assert "inputs/README.md" in names


def test_installed_scenes_and_quickstart_find_their_decks(site, tmp_path):
    path, _ = site
    env = {**os.environ, "PYTHONPATH": str(path)}
    code = ("import importlib, os\n"
            + "".join(f"m = importlib.import_module({mod!r}); print(os.path.realpath(m.{attr}))\n"
                      for mod, attr in SCENES.items()))
    r = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, env=env, capture_output=True, text=True,
                       timeout=300)
    assert r.returncode == 0, r.stderr
    for line in r.stdout.split():
        assert line.startswith(str(path.resolve())) and os.path.exists(line), line    # inside the install
    r = subprocess.run([sys.executable, "-m", "framework.cli", "-validate", "inputs/examples/quickstart.ups"],
                       cwd=tmp_path, env=env, capture_output=True, text=True, timeout=300)
    assert r.returncode == 0 and "valid" in r.stdout, r.stdout + r.stderr
    r = subprocess.run([sys.executable, "-c", "import framework; print(framework.__file__)"],
                       cwd=tmp_path, env=env, capture_output=True, text=True, timeout=60)
    assert r.stdout.startswith(str(path)), r.stdout      # the installed copy ran, not the source tree
