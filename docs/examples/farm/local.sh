#!/bin/sh
# local.sh SCENE STRIPS OUTDIR IMAGE: the farm on one machine, the same commands through
# xargs -P instead of Slurm: every strip (JOBS at a time), then the merge.
# A scene rt cannot read fails once, before any strip starts. Strips of an earlier run with
# the same STRIPS are overwritten, others are left alone (they are named -of-STRIPS).
set -eu
scene=$1 strips=$2 outdir=$3 image=$4
here=$(cd "$(dirname "$0")" && pwd)
rt=${RT:-$(command -v rt || echo "$here/../../../build/rt")}
rtimg=${RTIMG:-$(command -v rtimg || echo "$here/../../../build/rtimg")}
export RT="$rt"
"$rt" -r -q ${RTFLAGS:-} "$scene" >/dev/null
mkdir -p "$outdir"
i=0
while [ "$i" -lt "$strips" ]; do echo "$i"; i=$((i + 1)); done |
    xargs -P "${JOBS:-4}" -I '{}' "$here/strip.sh" "$scene" "$strips" '{}' "$outdir"
exec "$rtimg" merge "$outdir"/strip-*-of-"$strips".png -o "$image"
