// The fuzz cases of every input surface besides rt's scene reader (fuzz_one.h): rtpp's
// compiler, NFF, PLY and OBJ, image decoding with a re-encode, and inflate with a round trip.
// Each is shared by its libFuzzer target (fuzz_*.cpp) and by ctest (test_fuzz_surfaces.cpp),
// which runs the seeds and every regression input through it. A case returns the problem it
// found, or "" for none: an input may be refused, but only with the error type its surface
// promises and a message that names its place; a re-encode must read back as it was.
#pragma once

#include <sstream>
#include <string>
#include <string_view>

#include "image/deflate.h"
#include "rt/error.h"
#include "rt/image_file.h"
#include "rt/image_io.h"
#include "rtpp/compiler.h"
#include "rtpp/nff.h"
#include "scene/mesh_file.h"

namespace rt_fuzz {

// rtpp: compile the bytes, with small limits so that each case takes milliseconds. Includes
// are looked for in a directory that does not exist. Any error must be a CompileError naming
// the source ("fuzz.rts:" first).
inline std::string rtpp_case(std::string_view bytes) {
    rtpp::CompileOptions options;
    options.limits.loop_iterations = 20'000;
    options.limits.objects = 20'000;
    options.limits.list_items = 20'000;
    try {
        rtpp::compile(std::string(bytes), "fuzz.rts", "/nonexistent/rt-fuzz", options);
    } catch (const rtpp::CompileError& e) {
        const std::string_view message = e.what();
        if (message.substr(0, 9) != "fuzz.rts:")
            return std::string("error without its place: ") + e.what();
    }
    return "";
}

// NFF through rtpp: errors are CompileErrors naming the input.
inline std::string nff_case(std::string_view bytes) {
    std::istringstream in{std::string(bytes)};
    std::ostringstream out;
    rtpp::NffOptions options;
    options.max_line_length = 1u << 16;
    options.max_polygon_vertices = 1u << 12;
    options.max_mesh_vertices = 1u << 12;
    options.max_lights = 1u << 8;
    try {
        rtpp::translate_nff(in, "fuzz.nff", out, options);
    } catch (const rtpp::CompileError& e) {
        const std::string_view message = e.what();
        if (message.substr(0, 9) != "fuzz.nff:")
            return std::string("error without its place: ") + e.what();
    }
    return "";
}

// PLY or OBJ (told from the bytes): errors are rt::Errors.
inline std::string mesh_case(std::string_view bytes) {
    try {
        rt::read_mesh_file(bytes, "fuzz.mesh");
    } catch (const rt::Error&) {
    }
    return "";
}

// An image: decoded, then written again as PNG (any channels), as PPM (grey or RGB) and as
// PFM, each read back: the samples and metadata must be what was decoded. An encoder may
// refuse metadata its format cannot hold (an rt::Error), never change it.
inline std::string image_case(std::string_view bytes) {
    rt::ImageFile image;
    try {
        image = rt::decode_image(bytes);
    } catch (const rt::Error&) {
        return "";
    }
    if (image.format == rt::ImageFormat::pfm) {
        const std::string again = rt::encode_pfm(rt::to_raster(image));
        const rt::ImageFile back = rt::decode_pfm(again);
        for (std::size_t i = 0; i < image.floats.size(); ++i) {
            const float a = image.floats[i], b = back.floats[i];
            if (!(a == b || (a != a && b != b))) return "PFM round trip changed a value";
        }
        return "";
    }
    try {
        const rt::DecodedImage png = rt::decode_png(rt::encode_png(image.samples, image.metadata));
        if (png.image.bytes != image.samples.bytes) return "PNG round trip changed the samples";
        if (png.metadata.entries != image.metadata.entries)
            return "PNG round trip changed the metadata";
    } catch (const rt::Error&) {
    }
    if (image.channels() == 1 || image.channels() == 3) {
        try {
            const rt::ImageFile ppm = rt::decode_ppm(rt::encode_ppm(image.samples, image.metadata));
            if (ppm.samples.bytes != image.samples.bytes)
                return "PPM round trip changed the samples";
            if (ppm.metadata.entries.size() != image.metadata.entries.size())
                return "PPM round trip lost or added metadata";
        } catch (const rt::Error&) {
        }
    }
    return "";
}

// Inflate: a stream that decodes must survive our deflate and back; and any bytes must
// survive deflate and inflate.
inline std::string inflate_case(std::string_view bytes) {
    try {
        const std::string data = rt::inflate(bytes, std::size_t{1} << 22);
        if (rt::zlib_decompress(rt::zlib_compress(data), data.size()) != data)
            return "inflated data did not survive a round trip";
    } catch (const rt::Error&) {
    }
    if (rt::inflate(rt::deflate(bytes), bytes.size()) != bytes)
        return "the input did not survive deflate and inflate";
    return "";
}

}  // namespace rt_fuzz
