// rtimg merge: checks that region files tile their full image, then copies their rows in.
#include <algorithm>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <utility>
#include <vector>

#include "rt/error.h"
#include "rt/image_merge.h"
#include "rt/limits.h"

namespace rt {

namespace {

// Whole numbers separated by `separator`, exactly `count` of them, or nothing.
std::optional<std::vector<int>> numbers(std::string_view text, char separator, int count) {
    std::vector<int> values;
    const char* p = text.data();
    const char* end = p + text.size();
    for (int i = 0; i < count; ++i) {
        if (i > 0 && (p == end || *p++ != separator)) return std::nullopt;
        int v = 0;
        const auto [ptr, ec] = std::from_chars(p, end, v);
        if (ec != std::errc() || v < 0) return std::nullopt;
        values.push_back(v);
        p = ptr;
    }
    if (p != end) return std::nullopt;
    return values;
}

std::string describe(const PixelRect& r) {
    return "columns " + std::to_string(r.x0) + "-" + std::to_string(r.x1 - 1) + ", rows " +
           std::to_string(r.y0) + "-" + std::to_string(r.y1 - 1);
}

// The metadata that says what made an image, without where its region lies.
ImageMetadata without_region(const ImageMetadata& metadata) {
    ImageMetadata out;
    for (const auto& [key, value] : metadata.entries)
        if (key != kRegionKey && key != kFullSizeKey) out.entries.emplace_back(key, value);
    return out;
}

std::string bits_text(const ImageFile& f) {
    return std::string(format_name(f.format)) + ", " + std::to_string(f.bits()) + " bits, " +
           std::to_string(f.channels()) + " channels";
}

// The pieces agree on everything but their region.
void check_alike(const std::vector<ImagePiece>& pieces,
                 const std::vector<RecordedRegion>& regions) {
    const ImagePiece& first = pieces[0];
    const ImageMetadata made = without_region(first.image.metadata);
    for (std::size_t i = 0; i < pieces.size(); ++i) {
        const ImagePiece& p = pieces[i];
        const RecordedRegion& r = regions[i];
        if (r.full_width != regions[0].full_width || r.full_height != regions[0].full_height)
            throw Error(p.name + " is a region of a " + std::to_string(r.full_width) + "x" +
                        std::to_string(r.full_height) + " image, but " + first.name + " of a " +
                        std::to_string(regions[0].full_width) + "x" +
                        std::to_string(regions[0].full_height) + " one");
        if (p.image.format != first.image.format || p.image.bits() != first.image.bits() ||
            p.image.channels() != first.image.channels())
            throw Error(p.name + " is " + bits_text(p.image) + ", but " + first.name + " is " +
                        bits_text(first.image));
        if (p.image.format == ImageFormat::pfm)
            throw Error(p.name + ": PFM pieces cannot be merged (PFM records no region)");
        const ImageMetadata other = without_region(p.image.metadata);
        if (other.entries != made.entries) {
            std::string why;
            for (const auto& [key, value] : made.entries) {
                const std::string* v = other.find(key);
                if (v == nullptr || *v != value) {
                    why = key + " '" + value + "' against '" + (v ? *v : "") + "'";
                    break;
                }
            }
            if (why.empty()) why = "it records more about what made it";
            throw Error(p.name + " was not made like " + first.name + " (" + why +
                        "): pieces must come from one scene rendered with the same options");
        }
        if (p.image.width() != r.rect.width() || p.image.height() != r.rect.height())
            throw Error(p.name + " is " + std::to_string(p.image.width()) + "x" +
                        std::to_string(p.image.height()) + " pixels, but its region (" +
                        describe(r.rect) + ") is " + std::to_string(r.rect.width()) + "x" +
                        std::to_string(r.rect.height()));
    }
}

void check_no_overlap(const std::vector<ImagePiece>& pieces,
                      const std::vector<RecordedRegion>& regions) {
    for (std::size_t i = 0; i < regions.size(); ++i)
        for (std::size_t j = i + 1; j < regions.size(); ++j) {
            const PixelRect& a = regions[i].rect;
            const PixelRect& b = regions[j].rect;
            const PixelRect both{std::max(a.x0, b.x0), std::max(a.y0, b.y0), std::min(a.x1, b.x1),
                                 std::min(a.y1, b.y1)};
            if (!both.empty())
                throw Error("pieces overlap: " + describe(both) + " are in both " + pieces[i].name +
                            " and " + pieces[j].name);
        }
}

// The pieces lie inside the full image and do not overlap (checked before this), so they
// cover it exactly when their areas add up to its area. Only a gap's description needs more,
// and it is found on the grid that the pieces' edges cut the image into, each of whose
// cells lies wholly in one piece or in none: the work grows with the number of pieces, not
// with the recorded full size (which a piece may claim far larger than all the pieces).
void check_no_gap(const std::vector<RecordedRegion>& regions) {
    const RecordedRegion& full = regions[0];
    const auto area = static_cast<std::uint64_t>(full.full_width) *
                      static_cast<std::uint64_t>(full.full_height);
    std::uint64_t covered = 0;
    for (const RecordedRegion& r : regions)
        covered += static_cast<std::uint64_t>(r.rect.width()) *
                   static_cast<std::uint64_t>(r.rect.height());
    if (covered == area) return;
    std::vector<int> rows{0, full.full_height};
    for (const RecordedRegion& r : regions) {
        rows.push_back(r.rect.y0);
        rows.push_back(r.rect.y1);
    }
    std::sort(rows.begin(), rows.end());
    rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
    PixelRect box{full.full_width, full.full_height, 0, 0};
    const auto add_gap = [&](int x0, int x1, int y0, int y1) {
        box = {std::min(box.x0, x0), std::min(box.y0, y0), std::max(box.x1, x1),
               std::max(box.y1, y1)};
    };
    std::vector<std::pair<int, int>> spans;  // the columns of the pieces across one band
    for (std::size_t band = 0; band + 1 < rows.size(); ++band) {
        const int y0 = rows[band], y1 = rows[band + 1];
        spans.clear();
        for (const RecordedRegion& r : regions)
            if (r.rect.y0 <= y0 && r.rect.y1 >= y1) spans.emplace_back(r.rect.x0, r.rect.x1);
        std::sort(spans.begin(), spans.end());
        int x = 0;  // the band is covered up to here
        for (const auto& [x0, x1] : spans) {
            if (x0 > x) add_gap(x, x0, y0, y1);
            x = x1;
        }
        if (x < full.full_width) add_gap(x, full.full_width, y0, y1);
    }
    const std::uint64_t missing = area - covered;
    throw Error("the pieces leave a gap: " + std::to_string(missing) +
                (missing == 1 ? " pixel" : " pixels") + " within " + describe(box) + " of the " +
                std::to_string(full.full_width) + "x" + std::to_string(full.full_height) +
                " image are in no piece");
}

}  // namespace

std::optional<RecordedRegion> recorded_region(const ImageFile& image) {
    const std::string* region = image.metadata.find(kRegionKey);
    const std::string* size = image.metadata.find(kFullSizeKey);
    if (region == nullptr && size == nullptr) return std::nullopt;
    if (region == nullptr || size == nullptr)
        throw Error("records only one of Region and Full-Size");
    const auto r = numbers(*region, ',', 4);
    const auto s = numbers(*size, 'x', 2);
    if (!r || !s) throw Error("has a malformed Region or Full-Size record");
    // The full image is allocated from this record, so it is held to the size any image read
    // may have before anything else is done with it.
    if (static_cast<long long>((*s)[0]) * (*s)[1] > kMaxImagePixels)
        throw Error("records a full size (" + *size + ") larger than " +
                    std::to_string(kMaxImagePixels) + " pixels");
    RecordedRegion out{{(*r)[0], (*r)[2], (*r)[1], (*r)[3]}, (*s)[0], (*s)[1]};
    if (out.rect.empty() || !PixelRect{0, 0, out.full_width, out.full_height}.contains(out.rect))
        throw Error("records a region (" + *region + ") outside its full image (" + *size + ")");
    return out;
}

ImageFile merge_pieces(const std::vector<ImagePiece>& pieces) {
    if (pieces.empty()) throw Error("no pieces to merge");
    std::vector<RecordedRegion> regions;
    for (const ImagePiece& p : pieces) {
        std::optional<RecordedRegion> r;
        try {
            r = recorded_region(p.image);
        } catch (const Error& e) {
            throw Error(p.name + " " + e.what());
        }
        if (!r) throw Error(p.name + " records no region: render pieces with rt --region");
        regions.push_back(*r);
    }
    check_alike(pieces, regions);
    check_no_overlap(pieces, regions);
    check_no_gap(regions);

    ImageFile full;
    const ImageFile& first = pieces[0].image;
    full.format = first.format;
    full.variant = first.variant;
    full.metadata = without_region(first.metadata);
    SampleImage& out = full.samples;
    out = {regions[0].full_width, regions[0].full_height, first.channels(), first.bits(), {}};
    out.bytes.resize(out.row_bytes() * static_cast<std::size_t>(out.height));
    for (std::size_t i = 0; i < pieces.size(); ++i) {
        const SampleImage& in = pieces[i].image.samples;
        const PixelRect& r = regions[i].rect;
        for (int y = 0; y < in.height; ++y)
            std::memcpy(&out.bytes[static_cast<std::size_t>(r.y0 + y) * out.row_bytes() +
                                   static_cast<std::size_t>(r.x0) * out.bytes_per_pixel()],
                        &in.bytes[static_cast<std::size_t>(y) * in.row_bytes()], in.row_bytes());
    }
    return full;
}

}  // namespace rt
