#!/usr/bin/env python3
"""Writes the two models scenes/models.in renders, so that anyone can regenerate them:

  vase.ply  a vase (a surface of revolution with a wavy profile), binary little-endian PLY,
            float positions and no normals: rt computes smooth normals for it (15, mode 2).
  knot.obj  a (2,3) torus knot tube, Wavefront OBJ with a normal per vertex (vn) and quad
            faces written v//vn: rt shades it smooth with the file's normals (15, mode 0).

Run from anywhere: python3 scenes/models/make-models.py. The output is the same bytes on
every run (no randomness, fixed number formatting)."""
import math
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))


def vase(rings=40, slices=48):
    """Rings from the foot (y = 0) to the lip (y = 1.6), each a circle of `slices` points,
    closed at the bottom by a fan around a centre point; open at the top."""
    def radius(y):
        return 0.28 + 0.22 * math.sin(1.9 * y + 0.4) + 0.07 * math.sin(7.0 * y)

    points = [(0.0, 0.0, 0.0)]
    for i in range(rings + 1):
        y = 1.6 * i / rings
        r = radius(y)
        for j in range(slices):
            a = 2 * math.pi * j / slices
            points.append((r * math.cos(a), y, -r * math.sin(a)))
    faces = []
    for j in range(slices):  # the foot: outward normals face down
        faces.append((0, 1 + (j + 1) % slices, 1 + j))
    for i in range(rings):
        for j in range(slices):
            a = 1 + i * slices + j
            b = 1 + i * slices + (j + 1) % slices
            faces.append((a, b, b + slices, a + slices))  # quads, counter-clockwise outside
    header = (
        "ply\nformat binary_little_endian 1.0\ncomment made by scenes/models/make-models.py\n"
        f"element vertex {len(points)}\nproperty float x\nproperty float y\nproperty float z\n"
        f"element face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n"
    )
    body = bytearray(header.encode("ascii"))
    for p in points:
        body += struct.pack("<3f", *p)
    for f in faces:
        body += struct.pack("<B", len(f)) + struct.pack(f"<{len(f)}i", *f)
    with open(os.path.join(HERE, "vase.ply"), "wb") as out:
        out.write(body)


def knot(segments=120, sides=10, tube=0.16):
    """A (2,3) torus knot's centre line, with a tube around it in a frame that follows the
    curve; each vertex's normal is its direction from the centre line (exact for a tube)."""
    def centre(t):
        r = 0.6 + 0.25 * math.cos(3 * t)
        return (r * math.cos(2 * t), 0.25 * math.sin(3 * t), r * math.sin(2 * t))

    def sub(a, b):
        return tuple(x - y for x, y in zip(a, b))

    def cross(a, b):
        return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])

    def unit(a):
        n = math.sqrt(sum(x * x for x in a))
        return tuple(x / n for x in a)

    lines = ["# a (2,3) torus knot tube, made by scenes/models/make-models.py"]
    normals = []
    for i in range(segments):
        t = 2 * math.pi * i / segments
        c = centre(t)
        tangent = unit(sub(centre(t + 1e-4), centre(t - 1e-4)))
        side = unit(cross(tangent, (0.0, 1.0, 0.0)))
        up = cross(side, tangent)
        for k in range(sides):
            a = 2 * math.pi * k / sides
            n = tuple(math.cos(a) * s + math.sin(a) * u for s, u in zip(side, up))
            lines.append("v %.5f %.5f %.5f" % tuple(ci + tube * ni for ci, ni in zip(c, n)))
            normals.append(n)
    for n in normals:
        lines.append("vn %.4f %.4f %.4f" % n)
    for i in range(segments):
        for k in range(sides):
            a = i * sides + k + 1
            b = i * sides + (k + 1) % sides + 1
            c = ((i + 1) % segments) * sides + (k + 1) % sides + 1
            d = ((i + 1) % segments) * sides + k + 1
            lines.append(f"f {a}//{a} {d}//{d} {c}//{c} {b}//{b}")
    with open(os.path.join(HERE, "knot.obj"), "w", newline="\n") as out:
        out.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    vase()
    knot()
