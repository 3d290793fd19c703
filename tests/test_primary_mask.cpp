// The primary mask (render/primary_mask.h), which spares the hierarchy's walk to primary rays
// that no bounded object can lie along. A pixel it leaves unmarked must have no ray (the
// original's through its corner, or any of its grid's within half a pixel) that comes near one
// of its boxes: checked on seeded random cameras, skewed and not, and boxes small and large,
// ahead of the eye, straddling its plane, behind it and around it, at coordinates up to 1e12.
// It must also spare what it should (a small box ahead leaves the rest of the picture), and
// the renders it speeds up must be the linear scan's to the bit.
#include <algorithm>
#include <bit>
#include <cmath>
#include <string>
#include <vector>

#include "accel/object_index.h"
#include "check.h"
#include "render/primary_mask.h"
#include "rt/render.h"
#include "rt/trace.h"
#include "scene_util.h"

using namespace rt;
using namespace rt_test;

namespace {

// Whether the ray meets the box, widened by a millionth of its size and of the distances
// along the ray (far more than the walk's float test widens it), at t >= 0.
bool comes_near(const Ray& ray, const Bounds& box) {
    double t0 = 0, t1 = kInfinity;
    for (int k = 0; k < 3; ++k) {
        const double o = ray.origin[k], d = ray.direction[k];
        const double pad =
            1e-6 * (box.max[k] - box.min[k]) +
            1e-9 * (1 + std::fabs(box.min[k]) + std::fabs(box.max[k]) + std::fabs(o));
        const double lo = box.min[k] - pad, hi = box.max[k] + pad;
        if (d == 0) {
            if (o < lo || o > hi) return false;
            continue;
        }
        double a = (lo - o) / d, b = (hi - o) / d;
        if (a > b) std::swap(a, b);
        t0 = std::max(t0, a);
        t1 = std::min(t1, b);
    }
    return t0 <= t1 + 1e-6 * std::fabs(t1);
}

// A camera at `scale` from the origin looking somewhere near it, its vectors of any length and
// sometimes skewed, its image up to 48 pixels a side.
Viewer random_viewer(Random& random, double scale) {
    Viewer v;
    v.eye = random.in_box(scale);
    v.look_at = v.eye + random.unit_vector() * random.uniform(0.1, 10) * scale;
    if (random.next() % 2 == 0) v.look_at = random.in_box(scale * 0.2);
    const Vec3 view = normalized(v.look_at - v.eye);
    Vec3 side = cross(view, random.unit_vector());
    if (length(side) < 1e-3) side = cross(view, {0.3, 0.5, 0.7});
    side = normalized(side);
    const Vec3 up = cross(side, view);
    const double width = random.uniform(0.05, 3);
    v.x = side * width;
    v.y = up * width * random.uniform(0.3, 2);
    if (random.next() % 4 == 0) v.x += view * random.uniform(-1, 1);  // not across the view
    if (random.next() % 4 == 0) v.y += side * random.uniform(-0.5, 0.5);
    v.xres = 1 + static_cast<int>(random.next() % 48);
    v.yres = 1 + static_cast<int>(random.next() % 48);
    return v;
}

// Boxes about the view: small ones ahead, large ones, ones around or behind the eye.
std::vector<Bounds> random_boxes(Random& random, const Viewer& v, double scale) {
    std::vector<Bounds> boxes;
    const auto count = 1 + random.next() % 6;
    const Vec3 view = normalized(v.look_at - v.eye);
    for (std::uint64_t i = 0; i < count; ++i) {
        Vec3 centre;
        switch (random.next() % 4) {
            case 0:  // ahead, near the line of sight
                centre = v.eye + view * random.uniform(0.2, 5) * scale + random.in_box(0.5 * scale);
                break;
            case 1:  // behind the eye
                centre = v.eye - view * random.uniform(0.2, 5) * scale + random.in_box(0.5 * scale);
                break;
            case 2:  // near the eye, perhaps around it
                centre = v.eye + random.in_box(0.05 * scale);
                break;
            default:
                centre = random.in_box(scale);
        }
        const double size = scale * std::pow(10.0, random.uniform(-4, 0.5));
        const Vec3 half{random.uniform(0, size), random.uniform(0, size), random.uniform(0, size)};
        boxes.push_back({centre - half, centre + half});
    }
    return boxes;
}

// The rays of pixel (x, y) as the tracer makes them: the original's through its corner, and
// others within half a pixel of it.
std::vector<Ray> pixel_rays(Random& random, const Viewer& v, int x, int y) {
    std::vector<Ray> rays;
    const Vec3 centre = v.plane_centre();
    const double near_half = 0.5 - 1e-9;
    for (const double u : {0.0, -near_half, near_half, random.uniform(-0.5, 0.5)})
        for (const double w : {0.0, -near_half, near_half, random.uniform(-0.5, 0.5)})
            rays.push_back(v.primary_ray(x + u, y + w, centre));
    return rays;
}

TEST(no_ray_of_an_unmarked_pixel_comes_near_a_box) {
    Random random(20261205);
    int cameras_sparing = 0, cameras = 0;
    for (const double scale : {1.0, 1e-3, 1e4, 1e12}) {
        for (int trial = 0; trial < 250; ++trial) {
            const Viewer v = random_viewer(random, scale);
            const std::vector<Bounds> boxes = random_boxes(random, v, scale);
            const PrimaryMask mask(v, boxes);
            ++cameras;
            if (mask.pixels_spared() > 0) ++cameras_sparing;
            std::size_t unmarked = 0;
            for (int y = 0; y < v.yres; ++y)
                for (int x = 0; x < v.xres; ++x) {
                    if (mask.may_hit(x, y)) continue;
                    ++unmarked;
                    for (const Ray& ray : pixel_rays(random, v, x, y))
                        for (const Bounds& box : boxes)
                            if (comes_near(ray, box)) {
                                record_failure(__FILE__, __LINE__,
                                               "scale " + std::to_string(scale) + " trial " +
                                                   std::to_string(trial) + ": pixel " +
                                                   std::to_string(x) + "," + std::to_string(y) +
                                                   " unmarked, but a ray of it meets a box");
                                return;
                            }
                }
            CHECK_EQ(unmarked, mask.pixels_spared());
            // A mask of part of the image (a region's): as sound within it, every pixel
            // outside it marked.
            const int x0 = static_cast<int>(random.next() % static_cast<std::uint64_t>(v.xres));
            const int y0 = static_cast<int>(random.next() % static_cast<std::uint64_t>(v.yres));
            const PixelRect area{
                x0, y0,
                x0 + 1 + static_cast<int>(random.next() % static_cast<std::uint64_t>(v.xres - x0)),
                y0 + 1 + static_cast<int>(random.next() % static_cast<std::uint64_t>(v.yres - y0))};
            const PrimaryMask part(v, boxes, area);
            std::size_t unmarked_in_area = 0;
            for (int y = 0; y < v.yres; ++y)
                for (int x = 0; x < v.xres; ++x) {
                    const bool inside = x >= area.x0 && x < area.x1 && y >= area.y0 && y < area.y1;
                    if (part.may_hit(x, y)) continue;
                    CHECK(inside);
                    ++unmarked_in_area;
                    for (const Ray& ray : pixel_rays(random, v, x, y))
                        for (const Bounds& box : boxes) CHECK(!comes_near(ray, box));
                }
            CHECK_EQ(unmarked_in_area, part.pixels_spared());
        }
    }
    // Not vacuous: most cameras leave pixels out.
    CHECK(cameras_sparing > cameras / 2);
}

// A 64 x 64 image from (0, 0, 5) towards the origin, the image plane one unit away and
// spanning [-1, 1] both ways.
Viewer straight_viewer() {
    Viewer v;
    v.eye = {0, 0, 5};
    v.look_at = {0, 0, 0};
    v.x = {1, 0, 0};
    v.y = {0, 1, 0};
    v.xres = v.yres = 64;
    return v;
}

TEST(a_small_box_ahead_leaves_the_rest_of_the_picture) {
    // The box [-0.1, 0.1]^3 at the origin projects to alpha, beta within +-0.1 / 4.9, raster
    // positions 32 +- 0.65; two pixels' widening and 4 x 4 tiles mark columns and rows 28-35.
    const Viewer v = straight_viewer();
    const std::vector<Bounds> boxes{{{-0.1, -0.1, -0.1}, {0.1, 0.1, 0.1}}};
    const PrimaryMask mask(v, boxes);
    CHECK(!mask.everywhere());
    CHECK_EQ(mask.pixels_spared(), std::size_t{64 * 64 - 8 * 8});
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x)
            CHECK_EQ(mask.may_hit(x, y), x >= 28 && x <= 35 && y >= 28 && y <= 35);
}

TEST(a_box_behind_the_eye_leaves_every_pixel_and_one_around_it_none) {
    const Viewer v = straight_viewer();
    const std::vector<Bounds> behind{{{-1, -1, 6}, {1, 1, 8}}};
    CHECK_EQ(PrimaryMask(v, behind).pixels_spared(), std::size_t{64 * 64});
    const std::vector<Bounds> around{{{-0.1, -0.1, 4.9}, {0.1, 0.1, 5.1}}};
    CHECK_EQ(PrimaryMask(v, around).pixels_spared(), std::size_t{0});
    // A floor under the eye reaching behind it: only rays above its horizon miss it. Its far
    // edge (z = -100, y = -1) projects to beta = -1 / 105, raster row 32.3: widened by two
    // rows, from tile row 7 (rows 28-31) down.
    const std::vector<Bounds> floor{{{-100, -1.01, -100}, {100, -1, 100}}};
    const PrimaryMask below(v, floor);
    CHECK(!below.everywhere());
    CHECK_EQ(below.pixels_spared(), std::size_t{64 * 28});
    CHECK(!below.may_hit(32, 27));
    CHECK(below.may_hit(32, 28));
    // No box at all (a scene of planes): every pixel is spared.
    CHECK_EQ(PrimaryMask(v, {}).pixels_spared(), std::size_t{64 * 64});
}

TEST(a_camera_without_an_image_plane_marks_every_pixel) {
    Viewer v = straight_viewer();
    v.y = v.x * 2;  // no plane spanned
    const std::vector<Bounds> boxes{{{-0.1, -0.1, -0.1}, {0.1, 0.1, 0.1}}};
    CHECK(PrimaryMask(v, boxes).everywhere());
    const Viewer far = [] {
        Viewer w = straight_viewer();
        w.eye = {0, 0, 1e300};
        return w;
    }();
    CHECK(PrimaryMask(far, boxes).everywhere());
    CHECK(PrimaryMask().everywhere());
    CHECK(PrimaryMask().may_hit(5, 7));
}

// A random scene about the origin: spheres, triangles, boxes, cylinders, a mesh, with planes
// or without, looked at from a random camera (sometimes from among the objects).
std::string random_scene(Random& random, bool lone_mesh) {
    std::string text;
    const Vec3 eye = random.next() % 3 == 0 ? random.in_box(2) : random.in_box(12);
    const Vec3 look = random.in_box(1.5);
    const Vec3 view = normalized(look - eye);
    Vec3 side = normalized(cross(view, random.unit_vector()));
    const Vec3 up = cross(side, view) * random.uniform(0.3, 1);
    side = side * random.uniform(0.3, 1);
    const auto v3 = [](const Vec3& p) {
        return std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + " ";
    };
    text += "102 " + v3(eye) + v3(look) + v3(side) + v3(up) + "24 20\n";
    text += "104 4 9 7 1 1 1\n115 0.2 0.3 0.4\n";
    const std::string surface = " 100 0.7 0.5 0.2 0.3 20 0.7 0 1\n";
    if (random.next() % 2 == 0) text += "2 -2 0.1 1 0.05" + surface;
    if (lone_mesh) {
        // A strip of triangles with a few apart.
        const int n = 40;
        text += "14 " + std::to_string(2 * n) + " " + std::to_string(2 * n - 2) + "\n";
        for (int i = 0; i < n; ++i)
            for (const double z : {-0.5, 0.5})
                text += v3(Vec3(std::cos(i * 0.3) * (1 + 0.01 * i), std::sin(i * 0.3), z));
        for (int i = 0; i + 1 < n; ++i)
            text += std::to_string(2 * i) + " " + std::to_string(2 * i + 1) + " " +
                    std::to_string(2 * i + 2) + " " + std::to_string(2 * i + 1) + " " +
                    std::to_string(2 * i + 3) + " " + std::to_string(2 * i + 2) + "\n";
        return text + surface;
    }
    const auto count = 5 + random.next() % 60;
    for (std::uint64_t i = 0; i < count; ++i) {
        const Vec3 c = random.in_box(3);
        switch (random.next() % 4) {
            case 0:
                text += "1 " + std::to_string(random.uniform(0.05, 0.6)) + " " + v3(c) + surface;
                break;
            case 1:
                text +=
                    "5 " + v3(c) + v3(c + random.in_box(1)) + v3(c + random.in_box(1)) + surface;
                break;
            case 2:
                text += "12 " + v3(c) +
                        v3(c + Vec3(random.uniform(0.1, 1), random.uniform(0.1, 1),
                                    random.uniform(0.1, 1))) +
                        surface;
                break;
            default:
                text += "9 0.2 -0.5 0.5 " + v3(c) + v3(random.unit_vector()) + surface;
        }
    }
    return text;
}

TEST(renders_with_the_mask_are_the_linear_scans) {
    Random random(77);
    int sparing = 0;
    for (int trial = 0; trial < 24; ++trial) {
        const Scene scene = parse_scene(random_scene(random, trial % 4 == 3));
        const std::size_t pixels = static_cast<std::size_t>(scene.viewer.xres) *
                                   static_cast<std::size_t>(scene.viewer.yres);
        if (PrimaryMask(scene.viewer, scene.index->outline(pixels)).pixels_spared() > 0) ++sparing;
        RenderOptions options;
        RenderOptions linear;
        linear.accelerate = false;
        CHECK(identical(render(scene, options), render(scene, linear)));
        options.samples = linear.samples = 2;
        options.threads = 3;
        CHECK(identical(render(scene, options), render(scene, linear)));
        options.adaptive_threshold = linear.adaptive_threshold = 0.05;
        CHECK(identical(render(scene, options), render(scene, linear)));
        options = linear = {};
        linear.accelerate = false;
        options.mode = linear.mode = RenderMode::normal;
        CHECK(identical(render(scene, options), render(scene, linear)));
        // Pixels that meet nothing are not traced at all (Tracer::row_rays, pixel), in every
        // mode, and still counted as the primary rays they stand for.
        options.mode = linear.mode = RenderMode::depth;
        options.samples = linear.samples = 3;
        RenderStats masked_stats, linear_stats;
        CHECK(identical(render(scene, options, &masked_stats),
                        render(scene, linear, &linear_stats)));
        CHECK_EQ(masked_stats.primary_rays, linear_stats.primary_rays);
        options.mode = linear.mode = RenderMode::trace;
        options.samples = linear.samples = 1;
        masked_stats = linear_stats = {};
        CHECK(identical(render(scene, options, &masked_stats),
                        render(scene, linear, &linear_stats)));
        CHECK_EQ(masked_stats.primary_rays, linear_stats.primary_rays);
        CHECK_EQ(masked_stats.shadow_rays, linear_stats.shadow_rays);
    }
    CHECK(sparing > 12);
}

TEST(a_region_rendered_alone_is_the_whole_renders_crop) {
    // Its tracers' mask covers the region (and -a's margin) alone, its tiles counted from the
    // region's corner rather than the image's.
    Random random(78);
    for (int trial = 0; trial < 8; ++trial) {
        const Scene scene = parse_scene(random_scene(random, trial % 4 == 3));
        const PixelRect region{3, 5, 3 + 7 + trial, 5 + 6 + trial};
        for (const bool adaptive : {false, true}) {
            RenderOptions options;
            options.samples = 2;
            if (adaptive) options.adaptive_threshold = 0.05;
            const Raster whole = render(scene, options);
            const Raster part = render_region(scene, options, region);
            for (int y = region.y0; y < region.y1; ++y)
                for (int x = region.x0; x < region.x1; ++x)
                    for (std::size_t i = 0; i < kSpectrumComponents; ++i)
                        CHECK_EQ(
                            std::bit_cast<std::uint64_t>(part.at(x - region.x0, y - region.y0)[i]),
                            std::bit_cast<std::uint64_t>(whole.at(x, y)[i]));
        }
    }
}

}  // namespace
