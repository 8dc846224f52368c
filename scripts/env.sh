# Sourced by ./pysus and scripts/test: create .venv on first use (or when
# pyproject.toml changed) with the project, mpi4py and the mpich wheel (for mpiexec),
# and the extras for the tests (pytest, pytest-xdist) and the plotting scripts (matplotlib);
# then compile the numba kernels of the shipped decks once, in parallel (scripts/warm_kernels),
# so that no later run, test worker or MPI rank waits for numba. PYSUS_WARM=0 skips that step.
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
VENV="$ROOT/.venv"
STAMP="$VENV/.pysus-installed"
if [ ! -x "$VENV/bin/python" ] || [ ! -f "$STAMP" ] || [ "$ROOT/pyproject.toml" -nt "$STAMP" ]; then
  echo "pysus: setting up $VENV (first use; about a minute)" >&2
  PY="${PYTHON:-python3}"
  [ -x "$VENV/bin/python" ] || "$PY" -m venv "$VENV" || { echo "pysus: could not create $VENV with $PY" >&2; exit 1; }
  "$VENV/bin/python" -m pip install -q --upgrade pip >&2 || exit 1
  "$VENV/bin/python" -m pip install -q -e "$ROOT[mpich,test,plot]" >&2 || { echo "pysus: pip install failed" >&2; exit 1; }
  touch "$STAMP"
  rm -f "$VENV/.pysus-warmed"
fi
if [ ! -f "$VENV/.pysus-warmed" ] && [ "${PYSUS_WARM:-1}" != 0 ]; then
  echo "pysus: compiling the numba kernels once (a few minutes; PYSUS_WARM=0 skips)" >&2
  "$ROOT/scripts/warm_kernels" >&2
  touch "$VENV/.pysus-warmed"
fi
export PATH="$VENV/bin:$PATH"
