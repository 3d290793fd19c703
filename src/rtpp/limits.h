// The bounds that keep any input, however wrong or hostile, from running for ever or using
// memory without end. Each is documented in docs/language.md; exceeding one is an error that
// names the place where it happened.
#pragma once

#include <cstddef>

#include "rt/limits.h"

namespace rtpp {

struct Limits {
    // Loop iterations in all, over the whole run (a 1000 x 1000 grid is 1,001,000).
    long loop_iterations = 20'000'000;
    // Evaluation steps in all: each expression evaluated, each statement run and each field
    // copied from a named object counts one. Bounds the work of loops whose bodies are long,
    // which the iteration count alone does not.
    long steps = 1'000'000'000;
    // Top-level objects written (an object inside a group or CSG counts as its parts).
    long objects = 10'000'000;
    // Vertices and index triples in one mesh, polygon or triangle.
    long list_items = 10'000'000;
    // Files open at once through include.
    int include_depth = 32;
    // Nesting of blocks, parentheses and objects in the source, and of objects in one another
    // as they are evaluated: keeps the parser's and evaluator's recursion off the stack's end.
    int nesting = 200;
    // A string literal, and a name: no longer than a token rt reads.
    std::size_t string_length = rt::kMaxTokenLength;
    // One source file.
    std::size_t file_size = 256u << 20;
    // Source read in all, the top-level file's and every include's, a file included twice
    // counted twice; and the number of includes read: a file that includes another twice,
    // nested, would otherwise parse an exponential amount of text.
    std::size_t source_total = 512u << 20;
    long includes = 100'000;
    // The scene written, which is held until the end (nothing is written on an error).
    std::size_t output_size = std::size_t{2} << 30;
};

}  // namespace rtpp
