# Sourced by ./pysus and scripts/test: create .venv on first use (or when
# pyproject.toml changed) with the project, mpi4py, the mpich wheel (for mpiexec) and
# matplotlib (the plot extra, for `pysus plot`).
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
VENV="$ROOT/.venv"
STAMP="$VENV/.pysus-installed"
if [ ! -x "$VENV/bin/python" ] || [ ! -f "$STAMP" ] || [ "$ROOT/pyproject.toml" -nt "$STAMP" ]; then
  echo "pysus: setting up $VENV (first use; about a minute)" >&2
  PY="${PYTHON:-python3}"
  [ -x "$VENV/bin/python" ] || "$PY" -m venv "$VENV" || { echo "pysus: could not create $VENV with $PY" >&2; exit 1; }
  "$VENV/bin/python" -m pip install -q --upgrade pip >&2 || exit 1
  "$VENV/bin/python" -m pip install -q -e "$ROOT[mpich,plot]" >&2 || { echo "pysus: pip install failed" >&2; exit 1; }
  touch "$STAMP"
fi
export PATH="$VENV/bin:$PATH"
