// Checker (107), image-mapped (108) and affine (111) surfaces, the texture reader behind 108,
// and the affine light (112), at points whose answers are known by hand.
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "rt/image_file.h"
#include "rt/image_io.h"
#include "rt/render.h"
#include "rt/trace.h"
#include "scene/texture.h"
#include "scene_util.h"

using namespace rt;
using namespace rt_test;

namespace {

const std::filesystem::path kWorkDir = RT_TEST_WORK_DIR;

// Surfaces with easily told colours and a distinctive ks, so tests can see which one answered.
const std::string kRed = "100 1 0 0  0.125 1 1 0 1";
const std::string kBlue = "100 0 0 1  0.25 1 1 0 1";
const Spectrum kRedColour(1.0, 0.0, 0.0), kBlueColour(0.0, 0.0, 1.0);

SurfacePtr parse_surface(const std::string& text, const std::filesystem::path& base_dir = {}) {
    std::istringstream in(text);
    SceneReader reader(in, "test.in", base_dir);
    return reader.surface();
}

std::string surface_error(const std::string& text, const std::filesystem::path& base_dir = {}) {
    try {
        parse_surface(text, base_dir);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

// Writes a file into the test's work directory and returns its full path.
std::string write_work_file(const std::string& name, const std::string& bytes) {
    const std::filesystem::path path = kWorkDir / name;
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << bytes;
    return path.string();
}

// A 4 x 2 texture, rows from the top: every pixel a different colour, with comments in the
// header. Pixel (x, y) has colour (x / 15, y / 15, 15 / 15) scaled by maxval 15.
const std::string kTexture4x2 =
    "P3\n# a comment\n4 # width\n2\n# maxval next\n15\n"
    "0 0 15  1 0 15  2 0 15  3 0 15\n"
    "0 1 15  1 1 15  2 1 15  3 1 15\n";

Spectrum texel(int x, int y) { return {x / 15.0, y / 15.0, 1.0}; }

// An image-mapped surface on the texture at `path`, with O at the origin, U along x and V
// along y, over a base surface with ks 0.5 and kt 0.
std::string image_surface(const std::string& path, const std::string& frame = "0 0 0 1 0 0 0 1 0") {
    return "108 " + frame + " \"" + path + "\" 100 0.3 0.3 0.3 0.5 7 0.75 0 1";
}

std::string texture_error(const std::string& name, const std::string& bytes) {
    const std::string path = write_work_file(name, bytes);
    return surface_error(image_surface(path));
}

// The start of every texture error for a scene "108 ... "path"": line 1, the column of the
// opening quote.
std::string texture_error_prefix(const std::string& path) {
    const std::string text = image_surface(path);
    return join("test.in:1:", text.find('"') + 1, ": cannot read texture '", path, "': ");
}

LightSample sample_light(const std::string& text, const Vec3& point) {
    const Scene scene = parse_scene(std::string(kTestViewer) + text);
    CHECK_EQ(scene.lights.size(), std::size_t{1});
    CHECK_EQ(scene.lights.at(0).sample_count(), 1);
    return scene.lights.at(0).sample(point, 0);
}

}  // namespace

// ---- Checker (107) ----

TEST(checker_cells_at_known_points) {
    const SurfacePtr s = parse_surface("107 1 " + kRed + " " + kBlue);
    struct Case {
        Vec3 point;
        bool red;
    };
    const Case cases[] = {
        {{0.5, 0.5, 0.5}, true},      // cell (0, 0, 0)
        {{1.5, 0.5, 0.5}, false},     // (1, 0, 0)
        {{1.5, 1.5, 0.5}, true},      // (1, 1, 0)
        {{1.5, 1.5, 1.5}, false},     // (1, 1, 1)
        {{-0.5, 0.5, 0.5}, false},    // (-1, 0, 0)
        {{-0.5, -0.5, 0.5}, true},    // (-1, -1, 0)
        {{-0.5, -0.5, -0.5}, false},  // (-1, -1, -1)
        {{-2.5, 0.5, 0.5}, false},    // (-3, 0, 0)
        // Cell boundaries belong to the cell above them (floor), and so do points within a
        // millionth of a cell below them: a surface lying on a boundary, with its points
        // rounded to either side, takes one cell rather than speckling.
        {{0, 0, 0}, true},
        {{1, 0, 0}, false},
        {{-1e-12, 0, 0}, true},
        {{0, -1e-9, 0}, true},
        {{-1e-5, 0, 0}, false},
        {{1 - 1e-12, 0, 0}, false},
        {{1 - 1e-5, 0, 0}, true},
        {{-1, 0, 0}, false},
        {{-1, -1, 0}, true},
        {{-1, -1 - 1e-12, 0}, true},
        {{1e15 + 1, 0.5, 0.5}, false},
    };
    for (const Case& c : cases) {
        const Material m = s->at(c.point);
        CHECK_NEAR(m.colour, c.red ? kRedColour : kBlueColour, 0);
        CHECK_EQ(m.ks, c.red ? 0.125 : 0.25);  // the whole sub-surface, not just its colour
    }
    // Far out, huge or non-finite coordinates give some cell rather than undefined behaviour.
    const double huge = 1e300, nan = std::numeric_limits<double>::quiet_NaN();
    CHECK(s->at({huge, -huge, huge}).ks > 0);
    CHECK(s->at({nan, 0, 0}).ks > 0);
    CHECK(s->at({kInfinity, 0, 0}).ks > 0);
}

TEST(checker_matches_parity_on_random_points) {
    Random random(17);
    const double size = 0.7;
    const SurfacePtr s = parse_surface("107 0.7 " + kRed + " " + kBlue);
    int red = 0;
    for (int i = 0; i < 5000; ++i) {
        const Vec3 p = random.in_box(10);
        long sum = 0;
        for (int axis = 0; axis < 3; ++axis) sum += static_cast<long>(std::floor(p[axis] / size));
        const bool even = ((sum % 2) + 2) % 2 == 0;
        if (even) ++red;
        CHECK_NEAR(s->at(p).colour, even ? kRedColour : kBlueColour, 0);
    }
    CHECK(red > 2000 && red < 3000);
}

TEST(checker_cell_size_scales_cells) {
    const SurfacePtr s = parse_surface("107 2 " + kRed + " " + kBlue);
    CHECK_NEAR(s->at({1.9, 0, 0}).colour, kRedColour, 0);
    CHECK_NEAR(s->at({2, 0, 0}).colour, kBlueColour, 0);
    CHECK_NEAR(s->at({-0.1, 0, 0}).colour, kBlueColour, 0);
    CHECK_NEAR(s->at({-2.1, 0, 0}).colour, kRedColour, 0);
    // The nudge is relative to the cell: 1e-7 below a boundary of 2-unit cells is within it.
    CHECK_NEAR(s->at({2 - 1e-7, 0, 0}).colour, kBlueColour, 0);
    CHECK_NEAR(s->at({2 - 1e-5, 0, 0}).colour, kRedColour, 0);
}

TEST(checker_floor_on_a_boundary_does_not_speckle) {
    // The plane y = 0, seen from above: every hit point, whatever its rounding, is in the
    // row of cells above y = 0, so the colour depends on x and z only.
    const Scene scene =
        parse_scene(std::string(kTestViewer) + "2 0 0 1 0  107 1 " + kRed + " " + kBlue);
    const Object& floor = scene.objects.at(0);
    Random random(29);
    int checked = 0;
    for (int i = 0; i < 5000; ++i) {
        const Vec3 eye{random.uniform(-3, 3), random.uniform(0.5, 5), random.uniform(-3, 3)};
        const Vec3 target{random.uniform(-20, 20), 0, random.uniform(-20, 20)};
        const Ray ray{eye, normalized(target - eye)};
        Hit hit;
        if (!floor.shape.intersect(ray, {1e-9, kInfinity}, hit)) continue;
        ++checked;
        const Vec3 p = ray.at(hit.t);
        const bool even = static_cast<long>(std::floor(p.x) + std::floor(p.z)) % 2 == 0;
        // Skip the x and z boundaries, where rounding legitimately decides.
        if (std::fabs(p.x - std::round(p.x)) < 1e-6 || std::fabs(p.z - std::round(p.z)) < 1e-6)
            continue;
        CHECK_NEAR(floor.surface->at(p).colour, even ? kRedColour : kBlueColour, 0);
    }
    CHECK(checked > 4000);
}

TEST(checker_of_checkers_and_default_surfaces) {
    // A fine checker inside the even cells of a coarse one.
    const SurfacePtr s = parse_surface("107 2  107 1 " + kRed + " " + kBlue + "  " + kBlue);
    CHECK_NEAR(s->at({0.5, 0.5, 0.5}).colour, kRedColour, 0);
    CHECK_NEAR(s->at({1.5, 0.5, 0.5}).colour, kBlueColour, 0);
    CHECK_NEAR(s->at({2.5, 0.5, 0.5}).colour, kBlueColour, 0);
    const Scene scene =
        parse_scene(std::string(kTestViewer) + "105 " + kRed + "\n1 1 0 0 0  107 1 106 " + kBlue);
    CHECK_NEAR(scene.objects.at(0).surface->at({0.5, 0.5, 0.5}).colour, kRedColour, 0);
    CHECK_NEAR(scene.objects.at(0).surface->at({1.5, 0.5, 0.5}).colour, kBlueColour, 0);
}

TEST(checker_errors) {
    CHECK_CONTAINS(surface_error("107 0 " + kRed + " " + kBlue),
                   "test.in:1:5: checker cell size must be > 0, got 0");
    CHECK_CONTAINS(surface_error("107 -1 " + kRed + " " + kBlue),
                   "checker cell size must be > 0, got -1");
    CHECK_CONTAINS(surface_error("107 1 " + kRed), "unexpected end of file: expected surface ID");
    CHECK_CONTAINS(surface_error("107 1 " + kRed + " 1 1 0 0 0"),
                   "expected a surface ID (one of 100, 106, 107, 108, 111, 114), got 1 (sphere)");
    CHECK_CONTAINS(surface_error("107 1 106 " + kBlue), "test.in:1:7: 106 (use default surface)");
}

// ---- The texture reader behind 108 ----

TEST(ppm_reads_p3_with_comments) {
    const Image image = read_texture(write_work_file("p3.ppm", kTexture4x2));
    CHECK_EQ(image.width, 4);
    CHECK_EQ(image.height, 2);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 4; ++x) CHECK_NEAR(image.at(x, y), texel(x, y), 1e-7);
}

TEST(ppm_reads_p6_8_and_16_bit) {
    std::string p6 = "P6\n# binary\n2 1\n255\n";
    p6 += std::string{'\xff', '\x00', '\x80', '\x00', '\x33', '\x01'};
    const Image a = read_texture(write_work_file("p6.ppm", p6));
    CHECK_NEAR(a.at(0, 0), Spectrum(1.0, 0.0, 128 / 255.0), 1e-7);
    CHECK_NEAR(a.at(1, 0), Spectrum(0.0, 51 / 255.0, 1 / 255.0), 1e-7);
    // 16-bit samples are big-endian.
    std::string p16 = "P6 1 1 65535\n";
    p16 += std::string{'\x80', '\x00', '\x00', '\x01', '\xff', '\xff'};
    const Image b = read_texture(write_work_file("p16.ppm", p16));
    CHECK_NEAR(b.at(0, 0), Spectrum(32768 / 65535.0, 1 / 65535.0, 1.0), 1e-7);
    // 16-bit text samples too.
    const Image c = read_texture(write_work_file("p3_16.ppm", "P3 1 1 1000 1000 500 0"));
    CHECK_NEAR(c.at(0, 0), Spectrum(1.0, 0.5, 0.0), 1e-7);
    // A binary sample that looks like whitespace right after the header is data, not space.
    std::string spaces = "P6 1 1 255\n";
    spaces += std::string{' ', '\n', '#'};
    const Image d = read_texture(write_work_file("spaces.ppm", spaces));
    CHECK_NEAR(d.at(0, 0), Spectrum(32 / 255.0, 10 / 255.0, 35 / 255.0), 1e-7);
}

TEST(texture_reads_grey_ppm_and_keeps_values_above_one_in_pfm) {
    // P5 (grey) stands for all three colours.
    const Image grey = read_texture(write_work_file("grey.pgm", "P5 2 1 255\n\x33\xff"));
    CHECK_NEAR(grey.at(0, 0), Spectrum(51 / 255.0), 1e-7);
    CHECK_NEAR(grey.at(1, 0), Spectrum(1.0), 0);
    // PFM values are used as they are, above 1 too; rows are stored bottom first.
    Raster r(1, 2);
    r.set(0, 0, {2.5, 0.25, 0});
    r.set(0, 1, {0, 1, 1e6});
    const Image pfm = read_texture(write_work_file("bright.pfm", encode_pfm(r)));
    CHECK_NEAR(pfm.at(0, 0), Spectrum(2.5, 0.25, 0.0), 0);
    CHECK_NEAR(pfm.at(0, 1), Spectrum(0.0, 1.0, 1e6), 0);
}

// Renders a 12 x 9 view of a parallelogram wearing the texture at `path`, lit only by ambient
// light, so that every pixel shows the texture's colour.
Raster render_textured(const std::string& path) {
    return render(parse_scene("102 0 0 5  0 0 0  1 0 0  0 1 0  12 9\n"
                              "103 1 1 1\n"
                              "6 -1.5 -1 0  3 0 0  0 2 0\n"
                              "108 -1.5 -1 0  3 0 0  0 2 0  \"" +
                              path + "\"  100 1 1 1  0 1 1 0 1\n"),
                  {});
}

bool same_pixels(const Raster& a, const Raster& b) {
    if (a.width() != b.width() || a.height() != b.height()) return false;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x)
            for (std::size_t c = 0; c < 3; ++c)
                if (!(a.at(x, y)[c] == b.at(x, y)[c])) return false;
    return true;
}

TEST(png_and_pfm_textures_render_as_the_ppm_they_were_made_from) {
    // A 5 x 3 texture, every sample different; 8 and 16 bits, RGB and grey.
    for (const int bits : {8, 16})
        for (const int channels : {3, 1}) {
            SampleImage samples{5, 3, channels, bits, {}};
            samples.bytes.resize(samples.row_bytes() * 3);
            for (std::size_t i = 0; i < samples.bytes.size(); ++i)
                samples.bytes[i] = static_cast<std::uint8_t>(37 + 53 * i);
            const std::string name = join("t", bits, "_", channels);
            const Raster ppm =
                render_textured(write_work_file(name + ".ppm", encode_ppm(samples, {})));
            const Raster png =
                render_textured(write_work_file(name + ".png", encode_png(samples, {})));
            CHECK(same_pixels(ppm, png));
            // The content decides the format, not the name.
            const Raster misnamed =
                render_textured(write_work_file(name + "-png.ppm", encode_png(samples, {})));
            CHECK(same_pixels(ppm, misnamed));
            // A PFM holding exactly the PPM's values (each sample divided by the maximum, as a
            // float) renders the same pixels too.
            Raster values(5, 3);
            const double max = samples.max_value();
            for (int y = 0; y < 3; ++y)
                for (int x = 0; x < 5; ++x) {
                    Spectrum s;
                    for (int c = 0; c < 3; ++c)
                        s[static_cast<std::size_t>(c)] = static_cast<float>(
                            samples.sample(x, y, channels == 1 ? 0 : c) * (1.0 / max));
                    values.set(x, y, s);
                }
            const Raster pfm = render_textured(write_work_file(name + ".pfm", encode_pfm(values)));
            CHECK(same_pixels(ppm, pfm));
            // And the texture shows: the middle row crosses several of its pixels.
            std::vector<double> reds;
            for (int x = 0; x < 12; ++x) reds.push_back(ppm.at(x, 4)[0]);
            std::sort(reds.begin(), reds.end());
            CHECK(std::unique(reds.begin(), reds.end()) - reds.begin() >= 4);
        }
}

TEST(a_texture_that_is_a_fifo_or_a_directory_is_refused_whatever_its_name) {
    const std::filesystem::path fifo = kWorkDir / "fifo.png";
    std::filesystem::remove(fifo);
    CHECK_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    ::alarm(60);  // a texture open that blocks would otherwise hang the test for ever
    CHECK_CONTAINS(surface_error(image_surface(fifo.string())),
                   texture_error_prefix(fifo.string()) + "it is not a regular file (a FIFO)");
    ::alarm(0);
    const std::filesystem::path dir = kWorkDir / "dir.pfm";
    std::filesystem::create_directories(dir);
    CHECK_CONTAINS(surface_error(image_surface(dir.string())),
                   texture_error_prefix(dir.string()) + "it is a directory");
}

// ---- Image-mapped surface (108) ----

TEST(image_lookup_at_known_uv) {
    const std::string path = write_work_file("lookup.ppm", kTexture4x2);
    const SurfacePtr s = parse_surface(image_surface(path));
    struct Case {
        double u, v;
        int x, y;  // the expected pixel, rows from the top
    };
    const Case cases[] = {
        {0.1, 0.1, 0, 1},               // v = 0 is the bottom row
        {0, 0, 0, 1},                   // the bottom-left corner
        {0.25, 0.5, 1, 0},              // pixel edges belong to the pixel above them
        {0.74, 0.49, 2, 1},             // just below the edges
        {0.99, 0.99, 3, 0},             // the top-right pixel
        {1, 1, 0, 1},                   // exactly 1 wraps to 0
        {-0.1, 0.2, 3, 1},              // negative coordinates wrap
        {-1e-20, -1e-20, 3, 0},         // wrap to just below 1: the last pixel, never out of range
        {-3.3, 7.6, 2, 0},              // several periods away
        {1e6 + 0.3, -1e6 - 0.3, 1, 0},  // a million periods away
    };
    for (const Case& c : cases) {
        const Material m = s->at({c.u, c.v, 5});  // z is along neither U nor V
        CHECK_NEAR(m.colour, texel(c.x, c.y), 1e-7);
        // Everything but the colour comes from the base surface.
        CHECK_EQ(m.ks, 0.5);
        CHECK_EQ(m.ke, 7.0);
        CHECK_EQ(m.kd, 0.75);
    }
    // Non-finite points still land on some pixel.
    const double nan = std::numeric_limits<double>::quiet_NaN();
    CHECK(s->at({nan, nan, 0}).colour[2] == 1.0);
    CHECK(s->at({kInfinity, -kInfinity, 0}).colour[2] == 1.0);
}

TEST(image_frame_scales_and_moves_the_mapping) {
    const std::string path = write_work_file("frame.ppm", kTexture4x2);
    // O (1, 1, 0); U (2, 0, 0): u = (x - 1) / 2; V (0, 0, 4): v = z / 4.
    const SurfacePtr s = parse_surface(image_surface(path, "1 1 0  2 0 0  0 0 4"));
    CHECK_NEAR(s->at({1, 9, 0}).colour, texel(0, 1), 1e-7);
    CHECK_NEAR(s->at({2, 0, 0}).colour, texel(2, 1), 1e-7);     // u = 0.5
    CHECK_NEAR(s->at({2.6, 0, 2}).colour, texel(3, 0), 1e-7);   // u = 0.8, v = 0.5
    CHECK_NEAR(s->at({0.6, 0, -1}).colour, texel(3, 0), 1e-7);  // u = -0.2, v = -0.25
    // U and V need not be perpendicular: each coordinate is its own projection.
    const SurfacePtr skew = parse_surface(image_surface(path, "0 0 0  1 0 0  1 1 0"));
    // u = 0.3; v = (0.3 + 0.2) / |V|^2 = 0.25, the bottom row.
    CHECK_NEAR(skew->at({0.3, 0.2, 0}).colour, texel(1, 1), 1e-7);
    CHECK_NEAR(skew->at({0.3, 0.8, 0}).colour, texel(1, 0), 1e-7);  // v = 0.55
}

TEST(image_path_resolves_against_the_scene_directory) {
    write_work_file("relative.ppm", kTexture4x2);
    const SurfacePtr s = parse_surface(image_surface("relative.ppm"), kWorkDir);
    CHECK_NEAR(s->at({0.3, 0.6, 0}).colour, texel(1, 0), 1e-7);
    // A quoted path may hold spaces.
    write_work_file("with space.ppm", kTexture4x2);
    const SurfacePtr q = parse_surface(image_surface("with space.ppm"), kWorkDir);
    CHECK_NEAR(q->at({0.9, 0.1, 0}).colour, texel(3, 1), 1e-7);
    // Not found relative to the scene: the message says where it looked.
    const std::string message = surface_error(image_surface("nowhere.ppm"), kWorkDir);
    CHECK_CONTAINS(message, "test.in:1:23: cannot read texture 'nowhere.ppm': cannot open it: ");
    CHECK_CONTAINS(message, (kWorkDir / "nowhere.ppm").string());
}

TEST(texture_errors_name_the_path_token) {
    struct Case {
        const char* name;
        std::string bytes;
        const char* reason;
    };
    const Case cases[] = {
        {"empty.ppm", "", "not an image rt reads (PPM, PGM, PNG or PFM)"},
        {"magic.ppm", "P7 1 1 255\n\x01", "not a PPM or PGM file (expected P6, P5, P3 or P2)"},
        {"magic2.ppm", "P612 1 255\n", "not a PPM or PGM file (expected P6, P5, P3 or P2)"},
        {"width.ppm", "P3 x 1 255", "expected width in the PPM file"},
        {"height.ppm", "P3 1", "expected height in the PPM file"},
        {"nopixels.ppm", "P3 0 1 255", "PPM image has no pixels"},
        {"huge.ppm", "P6 100000 100000 255\n", "PPM image 100000x100000 is larger than"},
        {"toolarge.ppm", "P6 99999999999 1 255\n", "width too large in the PPM file"},
        {"maxval0.ppm", "P3 1 1 0 0 0 0", "PPM maximum value must be 1 to 65535"},
        {"maxval.ppm", "P3 1 1 70000 0 0 0", "PPM maximum value must be 1 to 65535"},
        {"above.ppm", "P3 1 1 15 0 16 0", "PPM pixel value above the maximum value"},
        {"negative.ppm", "P3 1 1 15 0 -1 0", "expected pixel value in the PPM file"},
        {"short3.ppm", "P3 2 1 15 0 0 0 1 1", "expected pixel value in the PPM file"},
        {"short6.ppm", "P6 2 1 255\n\x01\x02\x03\x04\x05", "PPM pixel data ends early"},
        {"short16.ppm", "P6 1 1 65535\n\x01\x02\x03\x04\x05", "PPM pixel data ends early"},
        // Claims 8000 x 8000 pixels but holds none: refused by size before any allocation.
        {"claims.ppm", "P6 8000 8000 255\n\x01", "PPM pixel data ends early"},
        {"nospace.ppm", "P6 1 1 255#\x01\x02\x03", "expected one whitespace character after"},
        // PNG and PFM are read by the image library's decoders, with their reasons.
        {"broken.png", "\x89PNG\r\n\x1a\n", "PNG file ends before its IEND chunk"},
        {"short.pfm", "PF 2 2 -1.0\n\x01\x02", "PFM pixel data ends early"},
        {"negative.pfm", "Pf 1 1 -1.0\n" + std::string{'\x00', '\x00', '\x80', '\xbf'},
         "PFM value -1 at column 0, row 0 from the top is no colour (each must be finite and "
         ">= 0)"},
        {"infinite.pfm",
         "Pf 2 1 -1.0\n" + std::string(4, '\0') + std::string{'\x00', '\x00', '\x80', '\x7f'},
         "PFM value inf at column 1, row 0 from the top is no colour"},
    };
    for (const Case& c : cases) {
        const std::string path = (kWorkDir / c.name).string();
        const std::string message = texture_error(c.name, c.bytes);
        CHECK_CONTAINS(message, texture_error_prefix(path) + c.reason);
    }
    const std::string missing = (kWorkDir / "missing.ppm").string();
    std::filesystem::remove(missing);
    CHECK_CONTAINS(surface_error(image_surface(missing)),
                   texture_error_prefix(missing) + "cannot open it: No such file or directory");
    CHECK_CONTAINS(surface_error(image_surface(kWorkDir.string())),
                   texture_error_prefix(kWorkDir.string()) + "it is a directory");
}

TEST(image_surface_field_errors) {
    CHECK_CONTAINS(surface_error("108 0 0 0  0 0 0  0 1 0 \"x.ppm\" " + kRed),
                   "test.in:1:12: image-mapped surface U vector must have a non-zero");
    CHECK_CONTAINS(surface_error("108 0 0 0  1 0 0  0 0 0 \"x.ppm\" " + kRed),
                   "test.in:1:19: image-mapped surface V vector must have a non-zero");
    CHECK_CONTAINS(surface_error("108 0 0 0  1 0 0  0 1 0 \"\" " + kRed),
                   "test.in:1:25: texture file path must not be empty");
    CHECK_CONTAINS(surface_error("108 0 0 0  1 0 0  0 1 0"),
                   "unexpected end of file: expected texture file path");
    const std::string path = write_work_file("nobase.ppm", kTexture4x2);
    CHECK_CONTAINS(surface_error("108 0 0 0 1 0 0 0 1 0 \"" + path + "\""),
                   "unexpected end of file: expected surface ID");
}

// ---- Affine surface (111) ----

TEST(affine_surface_takes_points_into_the_frame) {
    // X = (4, 0, 0): cells four units long in x, one in y and z.
    const SurfacePtr stretched =
        parse_surface("111 0 0 0  4 0 0  0 1 0  0 0 1  107 1 " + kRed + " " + kBlue);
    CHECK_NEAR(stretched->at({3.9, 0.5, 0.5}).colour, kRedColour, 0);
    CHECK_NEAR(stretched->at({4.1, 0.5, 0.5}).colour, kBlueColour, 0);
    CHECK_NEAR(stretched->at({0.5, 1.5, 0.5}).colour, kBlueColour, 0);
    CHECK_NEAR(stretched->at({-0.1, 0.5, 0.5}).colour, kBlueColour, 0);
    // The origin moves the pattern: O = (0.5, 0, 0) makes world x = 0.4 local x < 0.
    const SurfacePtr moved =
        parse_surface("111 0.5 0 0  1 0 0  0 1 0  0 0 1  107 1 " + kRed + " " + kBlue);
    CHECK_NEAR(moved->at({0.4, 0.5, 0.5}).colour, kBlueColour, 0);
    CHECK_NEAR(moved->at({0.6, 0.5, 0.5}).colour, kRedColour, 0);
    // A quarter turn about z: X = (0, 1, 0), Y = (-1, 0, 0), so local (x, y) = (y, -x).
    // With cell size 2, the world point (1, 5, 0) is local (5, -1): cells (2, -1, 0), odd.
    const SurfacePtr turned =
        parse_surface("111 0 0 0  0 1 0  -1 0 0  0 0 1  107 2 " + kRed + " " + kBlue);
    CHECK_NEAR(turned->at({1, 5, 0}).colour, kBlueColour, 0);
    CHECK_NEAR(turned->at({-1, 5, 0}).colour, kRedColour, 0);   // local (5, 1): (2, 0, 0)
    CHECK_NEAR(turned->at({-1, 3, 0}).colour, kBlueColour, 0);  // local (3, 1): (1, 0, 0)
    // An image through an affine surface: X = (0, 0, 2) maps local x (and so u) to world z / 2.
    const std::string path = write_work_file("affine.ppm", kTexture4x2);
    const SurfacePtr mapped =
        parse_surface("111 0 0 0  0 0 2  0 1 0  1 0 0  " + image_surface(path));
    CHECK_NEAR(mapped->at({0, 0.1, 1.1}).colour, texel(2, 1), 1e-7);
    CHECK_EQ(mapped->at({0, 0.1, 1.1}).ks, 0.5);
}

TEST(affine_surface_errors) {
    CHECK_CONTAINS(surface_error("111 0 0 0  1 0 0  1 0 0  0 0 1 " + kRed),
                   "test.in:1:12: affine surface frame is singular");
    CHECK_CONTAINS(surface_error("111 0 0 0  1 0 0  0 1 0  0 0 1 1 1 0 0 0"),
                   "test.in:1:32: expected a surface ID");
    CHECK_CONTAINS(surface_error("111 0 0 0  1 0 0  0 1 0"),
                   "unexpected end of file: expected affine surface axis Z");
    // Nesting counts: kMaxNesting affine surfaces hold one surface too many.
    std::string deep;
    for (int i = 0; i < kMaxNesting; ++i) deep += "111 0 0 0 1 0 0 0 1 0 0 0 1\n";
    CHECK_CONTAINS(surface_error(deep + kRed),
                   join("test.in:", kMaxNesting + 1, ":1: objects nested more than"));
    std::string deeper;
    for (int i = 0; i < 10000; ++i) deeper += "107 1 ";
    CHECK_CONTAINS(surface_error(deeper), "objects nested more than");
}

// ---- Affine light (112) ----

TEST(affine_light_under_uniform_scale) {
    // O (1, 2, 3), F = 2 I; a 1/r^2 light at local (0, 1, 0), world (1, 4, 3). Lit at the
    // world point O, which is local (0, 0, 0): one local unit away, two world units.
    const LightSample s =
        sample_light("112 1 2 3  2 0 0  0 2 0  0 0 2  101 0 1 0  1 2 3", {1, 2, 3});
    CHECK_NEAR(s.direction, Vec3(0, 1, 0), 1e-15);
    CHECK_NEAR(s.distance, 2, 1e-15);
    CHECK_NEAR(s.intensity, Spectrum(1.0, 2.0, 3.0), 1e-15);  // falloff in local units: 1/1^2
    const LightSample far = sample_light("112 1 2 3  2 0 0  0 2 0  0 0 2  101 0 1 0  1 2 3",
                                         {1, 2, -5});  // local (0, 0, -4)
    CHECK_NEAR(far.direction, normalized(Vec3(0, 2, 8)), 1e-15);
    CHECK_NEAR(far.distance, std::sqrt(68.0), 1e-14);
    CHECK_NEAR(far.intensity, Spectrum(1.0, 2.0, 3.0) * (1 / 17.0), 1e-15);
}

TEST(affine_light_under_a_stretch) {
    // Y = (0, 3, 0): the light at local (0, 1, 0) is at world (0, 3, 0). The lit point
    // (2, 0, 0) is local (2, 0, 0), sqrt(5) local units from it: intensity 4 / 5. In the
    // world the light is along (-2, 3, 0), sqrt(13) away.
    const LightSample s =
        sample_light("112 0 0 0  1 0 0  0 3 0  0 0 1  101 0 1 0  4 4 4", {2, 0, 0});
    CHECK_NEAR(s.direction, normalized(Vec3(-2, 3, 0)), 1e-15);
    CHECK_NEAR(s.distance, std::sqrt(13.0), 1e-14);
    CHECK_NEAR(s.intensity, Spectrum(0.8), 1e-15);
    // Without falloff the intensity passes unchanged.
    const LightSample flat =
        sample_light("112 0 0 0  1 0 0  0 3 0  0 0 1  104 0 1 0  4 4 4", {2, 0, 0});
    CHECK_NEAR(flat.direction, normalized(Vec3(-2, 3, 0)), 1e-15);
    CHECK_NEAR(flat.intensity, Spectrum(4.0), 0);
}

TEST(affine_light_positions_on_random_frames) {
    // Wherever the lit point is, the sample points at O + F p, the light's world position.
    Random random(23);
    for (int i = 0; i < 1000; ++i) {
        Vec3 axes[3];
        for (Vec3& a : axes) a = random.in_box(2);
        if (std::fabs(dot(axes[0], cross(axes[1], axes[2]))) < 0.3) continue;
        const Vec3 o = random.in_box(3), p = random.in_box(2), x = random.in_box(5);
        const std::string text =
            object_text(112, {o.x, o.y, o.z, axes[0].x, axes[0].y, axes[0].z, axes[1].x, axes[1].y,
                              axes[1].z, axes[2].x, axes[2].y, axes[2].z}) +
            " " + object_text(104, {p.x, p.y, p.z, 1, 1, 1});
        const Vec3 light = o + p.x * axes[0] + p.y * axes[1] + p.z * axes[2];
        const LightSample s = sample_light(text, x);
        CHECK_NEAR(x + s.direction * s.distance, light, 1e-12);
        CHECK_NEAR(length(s.direction), 1, 1e-15);
        CHECK_NEAR(s.distance, length(light - x), 1e-12);
    }
}

TEST(nested_affine_lights_compose) {
    // Outer: O (1, 0, 0), F = diag(2, 1, 1). Inner: O (0, 1, 0), F = diag(1, 1, 3). The light
    // at innermost (1, 1, 1) is at middle (1, 2, 3), world (3, 2, 3).
    const LightSample s = sample_light(
        "112 1 0 0  2 0 0  0 1 0  0 0 1  112 0 1 0  1 0 0  0 1 0  0 0 3  104 1 1 1  1 1 1",
        {3, 2, 0});
    CHECK_NEAR(s.direction, Vec3(0, 0, 1), 1e-15);
    CHECK_NEAR(s.distance, 3, 1e-15);
}

TEST(point_on_an_affine_light_receives_nothing) {
    const LightSample s =
        sample_light("112 0 0 0  2 0 0  0 2 0  0 0 2  101 1 1 1  1 1 1", {2, 2, 2});
    CHECK(s.intensity.is_black());
    CHECK(std::isfinite(s.direction.x) && std::isfinite(s.distance));
}

TEST(affine_light_renders_as_the_light_written_directly) {
    // A frame that turns a quarter about y and doubles (scenes/affine-light.in): the light
    // at local (1, 1, 0) is at world (0, 5, -2), and local distances are half the world's,
    // so the 1/r^2 light of intensity 10 matches a direct one of intensity 40, pixel for pixel.
    const std::string objects =
        "102  0 2.5 6  0 0.6 0  0.5 0 0  0 0.5 0  24 24\n"
        "2 0 0 1 0  100 0.8 0.8 0.8 0 1 0.8 0 1\n"
        "1 0.6 0 0.6 0  100 0.2 0.8 0.3 0.2 30 0.8 0 1\n";
    const Scene framed =
        parse_scene(objects + "112 0 3 0  0 0 -2  0 2 0  2 0 0  101 1 1 0  10 10 10");
    const Scene direct = parse_scene(objects + "101 0 5 -2  40 40 40");
    RenderOptions options;
    options.threads = 1;
    const Raster a = render(framed, options), b = render(direct, options);
    double brightest = 0;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) {
            CHECK_NEAR(a.at(x, y), b.at(x, y), 1e-9);
            brightest = std::max(brightest, a.at(x, y)[0]);
        }
    CHECK(brightest > 0.5);  // the light does reach the scene
}

TEST(affine_light_errors) {
    const std::string v = kTestViewer;
    CHECK_CONTAINS(scene_error(v + "112 0 0 0  1 0 0  0 1 0  0 0 0  101 0 0 0 1 1 1"),
                   "test.in:2:12: affine light frame is singular");
    CHECK_CONTAINS(scene_error(v + "112 0 0 0  1 0 0  0 1 0  0 0 1  103 1 1 1"),
                   "test.in:2:33: expected affine inner light ID (a light with a position), got "
                   "103 (ambient light)");
    CHECK_CONTAINS(scene_error(v + "112 0 0 0  1 0 0  0 1 0  0 0 1  1 1 0 0 0"), "got 1 (sphere)");
    CHECK_CONTAINS(scene_error(v + "112 0 0 0  1 0 0  0 1 0  0 0 1"),
                   "unexpected end of file: expected affine inner light ID");
}

TEST(every_surface_can_be_the_default) {
    // 105 takes any surface, and 106 hands the same one to each primitive that asks.
    const std::string path = write_work_file("default.ppm", kTexture4x2);
    const std::string defaults[] = {
        "107 1 " + kRed + " " + kBlue,
        image_surface(path),
        "111  0 0 0  2 0 0  0 2 0  0 0 2  107 1 " + kRed + " " + kBlue,
    };
    for (const std::string& surface : defaults) {
        const Scene scene = parse_scene(std::string(kTestViewer) + "105 " + surface +
                                        "\n1 1 0 0 0 106\n1 1 5 0 0 106\n");
        CHECK(scene.objects.at(0).surface == scene.objects.at(1).surface);
        const SurfacePtr direct = parse_surface(surface);
        for (const Vec3& p : {Vec3(0.5, 0.5, 0.5), Vec3(1.5, 0.2, 0.7), Vec3(-0.3, 2.5, 1.1)})
            CHECK_NEAR(scene.objects.at(1).surface->at(p).colour, direct->at(p).colour, 0);
    }
    // The affine surface's frame doubles the cells: (1.5, 0.2, 0.7) is in local cell (0,0,0).
    const SurfacePtr affine = parse_surface(defaults[2]);
    CHECK_NEAR(affine->at({1.5, 0.2, 0.7}).colour, kRedColour, 0);
    CHECK_NEAR(affine->at({2.5, 0.2, 0.7}).colour, kBlueColour, 0);
}

TEST(a_texture_is_loaded_once_per_scene) {
    const std::string path = write_work_file("shared.ppm", kTexture4x2);
    std::istringstream in(path + " " + path + " \"" + path + "\"");
    SceneReader reader(in, "test.in", {});
    const auto first = reader.texture("texture file path");
    const auto second = reader.texture("texture file path");
    const auto third = reader.texture("texture file path");
    CHECK(first == second);
    CHECK(first == third);
    CHECK_EQ(first->width, 4);
}
