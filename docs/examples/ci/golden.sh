#!/bin/sh
# golden.sh SCENE GOLDEN [OUTDIR]: renders SCENE and compares it with the golden image
# GOLDEN; on failure the render and a heat map stay in OUTDIR (default: a directory of its
# own under $TMPDIR or /tmp, so nothing lands in a source tree) and the message says where.
# Set UPDATE=1 to write GOLDEN from the render instead. RT and RTIMG name the programs
# (default: on the PATH, else in the build tree of the rt checkout this script is in).
#
# The tolerance: 2 levels (of 255) and 0.2 % of the pixels. The same rt built by g++ or
# clang gives the same bytes (rt builds with -ffp-contract=off), but another C library's
# pow, exp or trigonometry may round a last bit differently: that moves a pixel by a level
# at a rounding boundary, or flips an edge pixel between two objects. 0 and 0 catch every
# change but only on the machine that made the goldens; 2 levels and 0.002 catch every
# visible regression everywhere.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
rt=${RT:-$(command -v rt || echo "$here/../../../build/rt")}
rtimg=${RTIMG:-$(command -v rtimg || echo "$here/../../../build/rtimg")}
scene=$1 golden=$2
name=$(basename "$scene" .in)
if [ $# -ge 3 ]; then
    out=$3 own_out=0
else
    out=$(mktemp -d "${TMPDIR:-/tmp}/golden-$name.XXXXXX") own_out=1
fi
mkdir -p "$out"
"$rt" -q ${RTFLAGS:-} -o "$out/$name.png" "$scene"
if [ "${UPDATE:-0}" = 1 ]; then
    cp "$out/$name.png" "$golden"
    [ "$own_out" = 0 ] || rm -rf "$out"
    exit 0
fi
if ! "$rtimg" diff --tolerance "${TOLERANCE:-2}" --max-fraction "${FRACTION:-0.002}" \
    -o "$out/$name-diff.png" "$out/$name.png" "$golden"; then
    echo "golden.sh: $scene differs from $golden: see $out/$name.png and $out/$name-diff.png" >&2
    exit 1
fi
[ "$own_out" = 0 ] || rm -rf "$out"  # passed: a directory of our own is not needed
