#!/bin/sh
# submit.sh SCENE STRIPS OUTDIR IMAGE: the strips as a Slurm job array, and the merge as a job
# that starts only when every strip has succeeded (afterok). Prints the merge job's id. Give
# absolute paths: the jobs run in the directory sbatch was called from, on any node.
set -eu
scene=$1 strips=$2 outdir=$3 image=$4
FARM_DIR=$(cd "$(dirname "$0")" && pwd)
export FARM_DIR  # with RT, RTIMG and RTFLAGS: sbatch passes the environment on (--export=ALL)
mkdir -p "$outdir"
array=$(sbatch --parsable --array="0-$((strips - 1))" --output="$outdir/slurm-%A_%a.out" \
    "$FARM_DIR/render.sbatch" "$scene" "$strips" "$outdir")
sbatch --parsable --dependency="afterok:${array%%;*}" --output="$outdir/slurm-%j.out" \
    "$FARM_DIR/merge.sbatch" "$outdir" "$image" "$strips"
