#!/bin/sh
# strip.sh SCENE STRIPS INDEX OUTDIR: renders strip INDEX (0 to STRIPS-1) of SCENE, rows split
# as evenly as they go, to OUTDIR/strip-INDEX-of-STRIPS.png (so that the strips of a run with
# another STRIPS never mix with these). Every job of the farm runs this; extra rt options (the
# same for every strip) come from RTFLAGS, rt itself from RT (default: rt on the PATH, else
# the build tree of the rt checkout this example is in). The strip checkpoints to
# OUTDIR/strip-INDEX-of-STRIPS.ck while it renders, so a strip interrupted (preempted,
# requeued, killed) and run again resumes where it stopped; rt removes the checkpoint once
# the strip is written.
set -eu
scene=$1 strips=$2 index=$3 outdir=$4
here=$(cd "$(dirname "$0")" && pwd)
rt=${RT:-$(command -v rt || echo "$here/../../../build/rt")}
# The full size from rt -r's summary, "scene: 5 objects, 1 lights, 256x256" (after --size).
# rt -r runs on its own first: in a pipe its failure would be lost (sh has no pipefail).
summary=$("$rt" -r -q ${RTFLAGS:-} "$scene")
size=$(printf '%s\n' "$summary" | sed 's/.* \([0-9]*x[0-9]*\)[^x]*$/\1/')
width=${size%x*} height=${size#*x}
y0=$((height * index / strips))
y1=$((height * (index + 1) / strips))
name="$outdir/strip-$index-of-$strips"
exec "$rt" ${RTFLAGS:-} -j "${THREADS:-1}" --region "0,$width,$y0,$y1" \
    --checkpoint "$name.ck" --resume -o "$name.png" "$scene"
