// The bounds rt, rtpp and the image library share. Each keeps some input, however wrong or
// hostile, from costing memory or stack without end; exceeding one is an error, reported
// before anything is allocated. docs/format.md documents each.
#pragma once

#include <cstddef>

namespace rt {

// The largest image rt renders, in pixels per side and in all: a viewer (or a --size, or
// rtpp's `size`) asking for more is an error before the raster is allocated.
inline constexpr long kMaxResolution = 16384;
inline constexpr long kMaxPixels = 64L * 1024 * 1024;

// The largest image the image library reads (a texture, or a file rtimg is given), in
// pixels: a header claiming more is refused before the pixels are allocated.
inline constexpr long kMaxImagePixels = 64L * 1024 * 1024;

// Affine primitives, surfaces and lights and checker and image-mapped surfaces hold other
// objects; input that nests them deeper than this is refused, so no input can overflow the
// stack.
inline constexpr int kMaxNesting = 32;

// The longest token a scene may hold (a path, say); a longer one is an error, so no input
// makes the lexer allocate without bound. rtpp holds its string literals to the same length,
// so that every string it writes is a token rt reads.
inline constexpr std::size_t kMaxTokenLength = 4096;

// The most light samples a scene may take in all (a point light takes one, a sphere light n):
// each is a shadow ray for every point lit, so this bounds the cost of lighting one point.
inline constexpr long kMaxLightSamples = 1L << 20;

}  // namespace rt
