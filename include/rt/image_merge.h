// Putting the regions of an image (rt --region) back together: rtimg merge.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "rt/image_file.h"

namespace rt {

struct ImagePiece {
    std::string name;  // the file, for messages
    ImageFile image;
};

// The region a file records ("Region" and "Full-Size" metadata, as rt --region writes), or
// nothing when it records none; throws rt::Error when the record is malformed.
struct RecordedRegion {
    PixelRect rect;
    int full_width = 0;
    int full_height = 0;
};
std::optional<RecordedRegion> recorded_region(const ImageFile& image);

// The full image the pieces tile, with the metadata a whole render writes (the pieces' own,
// less Region and Full-Size). Throws rt::Error, naming the files and the pixels, when a piece
// records no region, when the pieces disagree on the full size, format, bit depth, channels or
// what made them (the scene, the options), when a piece's size is not its region's, and when
// the pieces leave a gap or overlap.
ImageFile merge_pieces(const std::vector<ImagePiece>& pieces);

}  // namespace rt
