#!/bin/bash
# Example batch job for a cluster with Slurm and the system MPI.
# Submit:  sbatch scripts/batch/slurm_example.sh inputs/examples/quickstart.ups
# On a cluster, build mpi4py against the system MPI instead of the mpich wheel:
#   module load mpi; python3 -m venv .venv; .venv/bin/pip install -e . ; (no [mpich] extra)
#SBATCH --job-name=pysus
#SBATCH --nodes=2
#SBATCH --ntasks-per-node=32
#SBATCH --time=02:00:00
#SBATCH --output=pysus-%j.log
set -euo pipefail
DECK=${1:?usage: sbatch slurm_example.sh DECK.ups [restart.uda]}
export NUMBA_NUM_THREADS=1 OMP_NUM_THREADS=1
if [ -n "${2:-}" ]; then
  srun .venv/bin/pysus -q -restart "$2"          # continue from the newest checkpoint
else
  srun .venv/bin/pysus -q "$DECK"
fi
