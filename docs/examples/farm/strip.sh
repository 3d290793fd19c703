#!/bin/sh
# strip.sh SCENE STRIPS INDEX OUTDIR: renders strip INDEX (0 to STRIPS-1) of SCENE, rows split
# as evenly as they go, to OUTDIR/strip-INDEX.png. Every job of the farm runs this; extra rt
# options (the same for every strip) come from RTFLAGS, rt itself from RT.
set -eu
scene=$1 strips=$2 index=$3 outdir=$4
rt=${RT:-rt}
# The full size from rt -r's summary, "scene: 5 objects, 1 lights, 256x256" (after --size).
size=$("$rt" -r -q ${RTFLAGS:-} "$scene" | sed 's/.* \([0-9]*x[0-9]*\)[^x]*$/\1/')
width=${size%x*} height=${size#*x}
y0=$((height * index / strips))
y1=$((height * (index + 1) / strips))
exec "$rt" -q ${RTFLAGS:-} -j "${THREADS:-1}" --region "0,$width,$y0,$y1" \
    -o "$outdir/strip-$index.png" "$scene"
