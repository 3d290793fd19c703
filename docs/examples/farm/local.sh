#!/bin/sh
# local.sh SCENE STRIPS OUTDIR IMAGE: the farm on one machine, the same commands through
# xargs -P instead of Slurm: every strip (JOBS at a time), then the merge.
set -eu
scene=$1 strips=$2 outdir=$3 image=$4
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$outdir"
i=0
while [ "$i" -lt "$strips" ]; do echo "$i"; i=$((i + 1)); done |
    xargs -P "${JOBS:-4}" -I '{}' "$here/strip.sh" "$scene" "$strips" '{}' "$outdir"
exec "${RTIMG:-rtimg}" merge "$outdir"/strip-*.png -o "$image"
