// The checkpoint file (for --checkpoint): what identifies a render, then the rows it
// has finished with the raster's exact values, each record with its own checksum, so that a
// resumed render can keep every complete record and lose only a damaged or truncated tail.
//
// Layout: the line "rt checkpoint 1\n", then records, each
//   "RTCK", a type byte, the payload's length (u32), the payload, CRC-32 of type, length
//   and payload (u32); integers little-endian.
// The first record is the header (type 'H'): lines "key: value\n" in a fixed order. Rows
// (type 'R'): the pass (u8: 0 the one-ray pass of -a, 1 the final values), the row y, its
// first column x0 and the number of values (u32 each), then the values' IEEE 754 bit
// patterns (u64 each), three per pixel.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rt/error.h"

namespace rt {

// Ordered key-value pairs: rt's version, the digests of the scene and of every file it
// reads, every option that changes pixels, the image size and region.
using CheckpointHeader = std::vector<std::pair<std::string, std::string>>;

struct CheckpointRow {
    std::uint8_t pass = 1;
    std::uint32_t y = 0;
    std::uint32_t x0 = 0;
    std::vector<double> values;  // three per pixel, from x0 on
};

inline constexpr std::string_view kCheckpointMagic = "rt checkpoint 1\n";
// A header larger than this is no header rt wrote: refused before anything is kept.
inline constexpr std::uint32_t kMaxCheckpointHeader = 1 << 20;

std::string encode_checkpoint_start(const CheckpointHeader& header);  // the line and the header
std::string encode_checkpoint_row(const CheckpointRow& row);

struct CheckpointContents {
    CheckpointHeader header;
    std::vector<CheckpointRow> rows;  // every complete record whose checksum holds, in order
    std::uint64_t kept_bytes = 0;     // where the good records end: the rest is the damaged tail
    bool damaged = false;             // whether anything followed them
};

// The file starts as a checkpoint does, but its header record is incomplete or damaged.
struct CheckpointHeaderDamaged : Error {
    using Error::Error;
};

// Reads a checkpoint's bytes. Throws rt::Error when they are not a checkpoint (no magic line),
// CheckpointHeaderDamaged when its header record is incomplete or damaged: nothing of such a
// file can be trusted.
CheckpointContents read_checkpoint(std::string_view bytes);

// What differs between the header a command would write and the one found, as "key: value
// here, value in the checkpoint" clauses joined by "; " (keys missing on one side say so);
// empty when they are the same.
std::string checkpoint_differences(const CheckpointHeader& wanted, const CheckpointHeader& found);

}  // namespace rt
