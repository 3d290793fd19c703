// rtpp's NFF front end: Eric Haines's Neutral File Format (version 3.9, the SPD's format) in,
// rt's numeric scene out, one line at a time. docs/nff.md describes the translation.
#pragma once

#include <cstddef>
#include <istream>
#include <ostream>
#include <string>

#include "rt/vec.h"
#include "rtpp/source.h"  // CompileError

namespace rtpp {

struct NffOptions {
    // Longest line read; past it the input is refused (a file without newlines must not fill
    // memory).
    std::size_t max_line_length = 1u << 20;
    // Vertices in one p or pp.
    std::size_t max_polygon_vertices = 1u << 20;
    // Vertices gathered into one smooth mesh (ID 16): past this the mesh is written and a new
    // one started, so memory stays bounded however long a run of pp patches is.
    std::size_t max_mesh_vertices = 1u << 20;
    // Lights are held until the end (their intensity depends on how many there are).
    std::size_t max_lights = 1u << 16;
};

// Reads NFF from `in`, named `name` in messages and line markers, and writes the numeric
// scene to `out` as it goes. Throws CompileError ("name:line:col: message") at the first
// problem; `out` then holds a partial scene, so a caller writing a file writes it elsewhere
// first and renames it on success.
void translate_nff(std::istream& in, const std::string& name, std::ostream& out,
                   const NffOptions& options = {});

// Translates a file ("-" for standard input, named <stdin>) to `out` (rtpp gives it a
// rt::Spool, so that nothing is written unless the translation completes, in bounded memory
// however large the file), or returns the whole numeric scene.
void translate_nff_file(const std::string& path, std::ostream& out, const NffOptions& options = {});
std::string translate_nff_file(const std::string& path, const NffOptions& options = {});

// The pieces of the translation with numbers worth testing on their own. Both throw
// std::invalid_argument on degenerate input.

// NFF's view: the angle (degrees) spans the centres of the first and last pixels along the
// image's longer side, and rays pass through pixel centres.
struct NffView {
    rt::Vec3 from, at, up;
    double angle = 0;
    int xres = 0, yres = 0;
};
// rt's viewer (102) whose rays are NFF's: the ray rt traces for pixel (X, Y), through the
// raster position (X, Y) that would be the pixel's corner, is NFF's ray through its centre.
struct NffViewer {
    rt::Vec3 eye, look_at, x, y;
};
NffViewer nff_viewer(const NffView& view);

// NFF's truncated cone (base point and radius, apex point and radius, radii different and
// not both zero) as rt's cone (ID 8): the double cone with apex `apex` and axis `axis`, kept
// for start <= (x - apex).axis / |axis|^2 <= finish. The axis is scaled so that start and
// finish are the two radii.
struct NffCone {
    double alpha = 0;  // cos(half-angle)
    double start = 0, finish = 0;
    rt::Vec3 apex, axis;
};
NffCone nff_cone(const rt::Vec3& base, double base_radius, const rt::Vec3& apex,
                 double apex_radius);

}  // namespace rtpp
