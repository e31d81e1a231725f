#!/bin/bash
# A crane-cosim sweep study as a Slurm array job: one array task per case, every task writing
# its case file into one output folder on a file system shared by the compute nodes.
#
# Submit with the array covering the study's cases (indices 0 to N-1), then collect once every
# task has ended:
#
#   n=$(crane-cosim sweep plan study.json | tail -n +2 | wc -l)
#   job=$(sbatch --parsable --array=0-$((n - 1)) docs/jobs/slurm-array.sh study.json out/study)
#   sbatch --dependency=afterany:"$job" --wrap "crane-cosim sweep collect out/study"
#
# `--array=0-$((n - 1))%50` runs at most 50 cases at a time. Slurm's MaxArraySize (1001 by
# default) bounds N; for larger studies give each task a shard instead (`--shard` below). A case
# already done is skipped, so submitting the array again after failures re-runs only the failed
# and unfinished cases.
#
#SBATCH --job-name=crane-sweep
#SBATCH --cpus-per-task=1
#SBATCH --mem=1G
#SBATCH --time=00:15:00
#SBATCH --output=crane-sweep-%A_%a.out
set -euo pipefail

study=${1:?usage: sbatch --array=0-N-1 slurm-array.sh STUDY OUT}
out=${2:?usage: sbatch --array=0-N-1 slurm-array.sh STUDY OUT}

# No --case-index: crane-cosim takes the case from SLURM_ARRAY_TASK_ID, which Slurm sets to this
# task's index. With more cases than array tasks, run a shard per task instead:
#   crane-cosim sweep run "$study" -o "$out" --jobs 1 --shard "$SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT"
exec crane-cosim sweep run "$study" -o "$out" --jobs 1 --quiet
