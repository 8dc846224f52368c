#!/bin/bash
# Example batch job for a cluster with Slurm and the system MPI; submit from any directory:
#   sbatch /path/to/pysus/scripts/batch/slurm_example.sh DECK.ups          a new run
#   sbatch /path/to/pysus/scripts/batch/slurm_example.sh RUN.uda           continue from its newest checkpoint
#   sbatch /path/to/pysus/scripts/batch/slurm_example.sh RUN.uda --maxTime 2.0 -copy   (more pysus options)
# A new run's output (filebase of the deck) is written relative to the directory the job was submitted
# from; a restart writes beside the uda it continues (RUN.uda.000, ...).
# PYSUS selects the pysus command (default: `pysus` on the PATH, else this checkout's .venv/bin/pysus
# when the script is run where it lies rather than as sbatch's copy).
# On a cluster, build mpi4py against the system MPI instead of the mpich wheel:
#   module load mpi; python3 -m venv ~/pysus-env; ~/pysus-env/bin/pip install /path/to/pysus  (no [mpich] extra)
# One process compiles the numba kernels into a per-user cache before srun starts the ranks, which
# then load them instead of all compiling the same kernels at once.
#SBATCH --job-name=pysus
#SBATCH --nodes=2
#SBATCH --ntasks-per-node=32
#SBATCH --time=02:00:00
#SBATCH --output=pysus-%j.log
set -euo pipefail
INPUT=${1:?usage: sbatch slurm_example.sh DECK.ups | RUN.uda [pysus options]}
shift
HERE=$(cd "$(dirname "$0")" && pwd)
cd "${SLURM_SUBMIT_DIR:-$PWD}"

# sbatch runs a copy of this script, so it cannot find the repository from its own path
if [ -z "${PYSUS:-}" ]; then
  PYSUS=pysus
  command -v pysus >/dev/null || [ ! -x "$HERE/../../.venv/bin/pysus" ] || PYSUS="$HERE/../../.venv/bin/pysus"
fi
command -v "$PYSUS" >/dev/null || { echo "slurm_example.sh: no '$PYSUS' command; set PYSUS=/path/to/bin/pysus" >&2; exit 2; }
[ -e "$INPUT" ] || { echo "slurm_example.sh: no $INPUT in $PWD" >&2; exit 2; }

export NUMBA_NUM_THREADS=1 OMP_NUM_THREADS=1
export NUMBA_CACHE_DIR=${NUMBA_CACHE_DIR:-${XDG_CACHE_HOME:-$HOME/.cache}/pysus/numba}
mkdir -p "$NUMBA_CACHE_DIR"

if [ -d "$INPUT" ]; then
  "$PYSUS" -q --warm -restart "$INPUT"           # compile once, on this node, before the ranks start
  srun "$PYSUS" -q -restart "$INPUT" "$@"        # continue from the newest checkpoint
else
  "$PYSUS" -q --warm "$INPUT"
  srun "$PYSUS" -q "$INPUT" "$@"
fi
