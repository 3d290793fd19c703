// The fewest object tests per primary ray that any hierarchy of boxes could make on a scene,
// beside the number rt's hierarchy makes. A hierarchy can leave an object untested only
// where none of its boxes lies on the ray before the nearest hit: any such box could hold a
// nearer hit. So the objects with a box on the ray before its hit (anywhere, for a ray that
// hits nothing) are a lower bound on the tests, whatever the tree, the leaf sizes or the
// order of the visits. With each object's box cut into a grid of G x G x G cells, and each
// cell narrowed to the part of the object in it, the same count is the floor for any
// hierarchy over those pieces (what spatial splits that cut each object that finely could
// reach); it falls as G grows, and shows what such splits could win and what they would cost
// (pieces per object). Spheres are narrowed to their surface in each cell; other bounded
// objects are cut as boxes; unbounded ones (planes) count one test each, as rt tests them.
//   rt_bench_box_bound [--grids 1,2,4,8] [--step N] scene.in
// --step N takes the ray through the centre of every Nth pixel in each direction (4).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "accel/object_index.h"
#include "rt/error.h"
#include "rt/reader.h"

namespace {

// Whether the ray enters the box at a distance in [0, t].
bool enters_by(const rt::Bounds& b, const rt::Ray& ray, double t) {
    double near = 0, far = rt::kInfinity;
    for (int k = 0; k < 3; ++k) {
        const double inverse = 1 / ray.direction[k];
        double a = (b.min[k] - ray.origin[k]) * inverse, c = (b.max[k] - ray.origin[k]) * inverse;
        if (a > c) std::swap(a, c);
        if (a > near) near = a;  // a NaN (a ray in the slab's plane) is ignored
        if (c < far) far = c;
    }
    return near <= far && near <= t;
}

// Narrows the cell to the sphere's surface in it; false where the cell holds none of it.
bool surface_in(const rt::SphereParameters& s, rt::Bounds& cell) {
    const double lo[3] = {cell.min.x, cell.min.y, cell.min.z};
    const double hi[3] = {cell.max.x, cell.max.y, cell.max.z};
    double gap[3], reach[3], out_lo[3], out_hi[3];
    for (int k = 0; k < 3; ++k) {
        gap[k] = std::max(0.0, std::max(lo[k] - s.centre[k], s.centre[k] - hi[k]));
        reach[k] = std::max(std::fabs(lo[k] - s.centre[k]), std::fabs(hi[k] - s.centre[k]));
    }
    const double gaps = gap[0] * gap[0] + gap[1] * gap[1] + gap[2] * gap[2];
    const double reaches = reach[0] * reach[0] + reach[1] * reach[1] + reach[2] * reach[2];
    if (gaps > s.radius_squared || reaches < s.radius_squared) return false;
    for (int k = 0; k < 3; ++k) {
        const double half = std::sqrt(std::max(0.0, s.radius_squared - (gaps - gap[k] * gap[k])));
        out_lo[k] = std::max(lo[k], s.centre[k] - half);
        out_hi[k] = std::min(hi[k], s.centre[k] + half);
    }
    cell = {{out_lo[0], out_lo[1], out_lo[2]}, {out_hi[0], out_hi[1], out_hi[2]}};
    return true;
}

// Each bounded object's pieces for a grid of `grid` cells a side.
struct Pieces {
    std::vector<rt::Bounds> whole;               // per bounded object, its box
    std::vector<std::vector<rt::Bounds>> parts;  // and its pieces
    std::size_t count = 0;
};

Pieces cut(const rt::Scene& scene, int grid) {
    Pieces p;
    for (const rt::Object& object : scene.objects) {
        const rt::Bounds box = object.shape.bounds();
        if (!(std::isfinite(box.min.x) && std::isfinite(box.max.x) && std::isfinite(box.min.y) &&
              std::isfinite(box.max.y) && std::isfinite(box.min.z) && std::isfinite(box.max.z)))
            continue;
        rt::SphereFn* const sphere = object.shape.functions->sphere;
        std::vector<rt::Bounds> parts;
        const rt::Vec3 size = (box.max - box.min) / grid;
        for (int i = 0; i < grid; ++i)
            for (int j = 0; j < grid; ++j)
                for (int k = 0; k < grid; ++k) {
                    const rt::Vec3 lo = box.min + rt::Vec3{i * size.x, j * size.y, k * size.z};
                    rt::Bounds cell{lo, lo + size};
                    if (sphere != nullptr && !surface_in(sphere(object.shape.data.get()), cell))
                        continue;
                    parts.push_back(cell);
                }
        p.count += parts.size();
        p.whole.push_back(box);
        p.parts.push_back(std::move(parts));
    }
    return p;
}

int run(int argc, char** argv) {
    std::vector<int> grids = {1, 2, 4, 8};
    int step = 4;
    std::string file;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--grids" && i + 1 < argc) {
            grids.clear();
            std::stringstream list(argv[++i]);
            for (std::string item; std::getline(list, item, ',');)
                grids.push_back(std::clamp(std::atoi(item.c_str()), 1, 64));
        } else if (arg == "--step" && i + 1 < argc) {
            step = std::max(1, std::atoi(argv[++i]));
        } else if (arg.empty() || arg[0] == '-' || !file.empty()) {
            std::cerr << "usage: rt_bench_box_bound [--grids 1,2,4,8] [--step N] scene.in\n";
            return 2;
        } else {
            file = arg;
        }
    }
    if (file.empty()) {
        std::cerr << "usage: rt_bench_box_bound [--grids 1,2,4,8] [--step N] scene.in\n";
        return 2;
    }
    const rt::Scene scene = rt::read_scene_file(file);
    const rt::ObjectIndex& index = *scene.index;
    std::vector<rt::Ray> rays;
    std::vector<double> hits;  // each ray's nearest hit, or infinity
    std::uint64_t tests = 0;
    for (int y = 0; y < scene.viewer.yres; y += step)
        for (int x = 0; x < scene.viewer.xres; x += step) {
            const rt::Ray ray = scene.viewer.primary_ray(x + 0.5, y + 0.5);
            rt::ObjectIndex::Found found{};
            rays.push_back(ray);
            hits.push_back(index.closest(ray, {}, found, &tests) ? found.hit.t : rt::kInfinity);
        }
    const double ray_count = static_cast<double>(rays.size());
    const auto unbounded = static_cast<double>(index.unbounded_count());
    std::printf("%s: %zu objects (%.0f unbounded), %zu primary rays\n", file.c_str(),
                scene.objects.size(), unbounded, rays.size());
    std::printf("rt's hierarchy: %.2f object tests per primary ray\n",
                static_cast<double>(tests) / ray_count);
    std::printf("%6s %18s %28s\n", "grid", "pieces/object", "least tests/primary ray");
    for (const int grid : grids) {
        const Pieces pieces = cut(scene, grid);
        std::uint64_t least = 0;
        for (std::size_t r = 0; r < rays.size(); ++r)
            for (std::size_t o = 0; o < pieces.whole.size(); ++o) {
                if (!enters_by(pieces.whole[o], rays[r], hits[r])) continue;
                const auto& parts = pieces.parts[o];
                least += std::any_of(parts.begin(), parts.end(), [&](const rt::Bounds& b) {
                    return enters_by(b, rays[r], hits[r]);
                });
            }
        const double floor = static_cast<double>(least) / ray_count + unbounded;
        std::printf("%6d %18.1f %28.2f\n", grid,
                    static_cast<double>(pieces.count) / static_cast<double>(pieces.whole.size()),
                    floor);
        // rt's hierarchy is one of the trees the whole-box floor bounds: below it, this tool
        // (or rt's count) is wrong.
        if (grid == 1 && static_cast<double>(tests) / ray_count + 1e-9 < floor) {
            std::fprintf(stderr, "rt_bench_box_bound: rt tested fewer objects than the floor\n");
            return 1;
        }
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const rt::Error& e) {
        std::cerr << "rt_bench_box_bound: " << e.what() << "\n";
        return 1;
    }
}
