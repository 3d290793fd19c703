#!/usr/bin/env python3
"""Measures rt's PNG files against zlib level 6 on the same filtered rows.

A dev-time check (not a build or test dependency; Python's zlib is only the yardstick):
    build/rt scenes/showcase.in -o /tmp/showcase.png && docs/png_vs_zlib.py /tmp/showcase.png
For each file: the IDAT stream is inflated by zlib (so zlib accepts rt's deflate and every
chunk CRC is checked), compressed again by zlib at level 6, and the file is rebuilt with that
stream in the same 64 KiB IDAT chunks. Prints both sizes, the ratio, and zlib's time.
"""
import struct
import sys
import time
import zlib


def chunks(data):
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        sys.exit("not a PNG file")
    pos = 8
    while pos < len(data):
        (length,) = struct.unpack(">I", data[pos : pos + 4])
        kind = data[pos + 4 : pos + 8]
        body = data[pos + 8 : pos + 8 + length]
        (crc,) = struct.unpack(">I", data[pos + 8 + length : pos + 12 + length])
        if crc != zlib.crc32(kind + body):
            sys.exit(f"{kind.decode()} chunk has a wrong CRC")
        yield kind, body
        pos += 12 + length


def chunk(kind, body):
    return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))


def measure(path):
    data = open(path, "rb").read()
    parts = list(chunks(data))
    stream = b"".join(body for kind, body in parts if kind == b"IDAT")
    raw = zlib.decompress(stream)
    start = time.perf_counter()
    level6 = zlib.compress(raw, 6)
    seconds = time.perf_counter() - start
    rebuilt = b"\x89PNG\r\n\x1a\n"
    for kind, body in parts:
        if kind == b"IDAT":
            continue
        if kind == b"IEND":
            for at in range(0, len(level6), 65536):
                rebuilt += chunk(b"IDAT", level6[at : at + 65536])
        rebuilt += chunk(kind, body)
    width, height, bits = struct.unpack(">IIB", parts[0][1][:9])
    print(
        f"{path}: {width}x{height} {bits}-bit, filtered rows {len(raw)} bytes; "
        f"rt {len(data)} bytes, zlib level 6 {len(rebuilt)} bytes, "
        f"rt / zlib = {len(data) / len(rebuilt):.4f}; zlib took {seconds:.3f} s"
    )


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit("usage: png_vs_zlib.py FILE.png ...")
    for name in sys.argv[1:]:
        measure(name)
