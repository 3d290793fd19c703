#!/bin/sh
# Writes frame I of N of a bouncing ball as an rt scene: frame.sh I N > frame-I.in
# (POSIX sh and awk only). The ball falls and bounces twice over the N frames, squashing a
# little where it touches the floor; the floor is textured with checker.ppm, so a changed
# texture re-renders every frame (through the rules rt -M writes).
set -eu
if [ $# -ne 2 ]; then
    echo "usage: frame.sh I N" >&2
    exit 2
fi
awk -v i="$1" -v n="$2" 'BEGIN {
    pi = 3.141592653589793
    t = (i + 0.5) / n                      # time in (0, 1)
    phase = t * 2 - int(t * 2)             # two bounces
    height = 2.2 * (1 - (2 * phase - 1) ^ 2)   # a parabola between bounces
    r = 0.5
    squash = height < 0.15 ? 0.8 : 1       # flattened on the floor
    y = r * squash + height
    x = -2.4 + 4.8 * t
    printf "# frame %d of %d: the ball at x = %.4f, y = %.4f\n", i, n, x, y
    print "102  0 1.6 7  0 0.9 0  0.8 0 0  0 0.6 0  320 240"
    print "103  0.2 0.2 0.22"
    print "101  -3 6 5  40 38 34"
    # the ball: a sphere, squashed by an affine frame when it touches the floor
    printf "7  %.4f %.4f 0  1.1 0 0  0 %.2f 0  0 0 1.1\n", x, y, squash
    printf "1 %.2f 0 0 0\n", r / 1.1
    print "100  0.9 0.25 0.15  0.4 40  0.7 0 1"
    # the floor, image-mapped with the checker texture (a 1 x 1 tile per unit)
    print "2 0  0 1 0"
    print "108  0 0 0  1 0 0  0 0 1  checker.ppm  100 1 1 1  0.1 10  0.8 0 1"
}'
