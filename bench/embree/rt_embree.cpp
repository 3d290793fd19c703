// rt_embree: rt's ray tree with Intel Embree 3 answering the ray queries, as a measuring
// stick for rt's own. The tracer, the camera, the shading and the depth and weight cut-offs
// are rt's (rt::render with RenderOptions::queries set); only the two queries, the nearest hit
// and whether a shadow ray is blocked, go to Embree's single-ray API (rtcIntersect1,
// rtcOccluded1).
//   rt_embree [--threads 1,2] [--runs N] [--depth D] [--size N] [--robust] [--check] scene.in ...
// Per scene it renders with rt's own queries and with Embree's alternately, --runs times per
// thread count, and prints the rays of one render, how far Embree's ray count is from rt's,
// the median Mrays/s of each and their ratio (rt/Embree: below 1, rt's queries are slower).
// --check instead renders once asking both for every query (and going on with rt's answer)
// and counts the queries where they disagree.
//
// What Embree holds (one geometry per kind, built with RTC_BUILD_QUALITY_HIGH):
// - every mesh (IDs 14, 15, 16) as native triangles, in float;
// - every sphere (ID 1) as a native sphere (RTC_GEOMETRY_TYPE_SPHERE_POINT), in float;
// - every polygon (11) and triangle (5) as native triangles, a fan from its first corner
//   (which covers it, concave or not: primitives/flat_corners.h);
// - every other bounded object as user geometry whose callbacks are rt's own intersect
//   functions on the double-precision ray;
// and unbounded objects (planes, affines of them) are tested by rt after Embree, as rt does.
// A native candidate that Embree finds is confirmed by rt's own test of that one mesh
// triangle, sphere, polygon or triangle (a filter function), which also gives the Hit the shading needs; so every answer is
// one of rt's, and they differ from rt's only where Embree's float tests miss a primitive rt
// hits (or order two candidates differently by less than float precision).
#include <embree3/rtcore.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include "accel/object_index.h"
#include "primitives/flat_corners.h"
#include "primitives/mesh_core.h"
#include "rt/error.h"
#include "rt/reader.h"
#include "rt/render.h"
#include "rt/trace.h"

namespace {

using namespace rt;
using Clock = std::chrono::steady_clock;

constexpr std::uint32_t kNone = 0xffffffff;
constexpr float kFloatInfinity = std::numeric_limits<float>::infinity();

// Floats on either side of a double, so that Embree's float tests lose no hit of rt's.
float float_below(double v) {
    const auto f = static_cast<float>(v);
    return static_cast<double>(f) > v ? std::nextafter(f, -kFloatInfinity) : f;
}
float float_above(double v) {
    const auto f = static_cast<float>(v);
    return static_cast<double>(f) < v ? std::nextafter(f, kFloatInfinity) : f;
}

// What one query carries through Embree into the callbacks: the exact ray and range, and the
// nearest hit rt's own tests have confirmed so far.
struct Query {
    RTCIntersectContext context;  // first: callbacks get a pointer to it
    const Ray* ray;
    Interval range;
    std::uint32_t object = kNone;
    Hit hit;

    // The range in which a hit can still win: up to the best so far, that distance included
    // (of objects at the same distance, the earliest in the file wins, as in rt).
    Interval open() const {
        return {range.t_min, object == kNone ? range.t_max : std::nextafter(hit.t, kInfinity)};
    }
    // Keeps a hit of rt's if it beats the best so far.
    bool offer(std::uint32_t candidate, const Hit& candidate_hit) {
        if (object != kNone &&
            !(candidate_hit.t < hit.t || (candidate_hit.t == hit.t && candidate < object)))
            return false;
        object = candidate;
        hit = candidate_hit;
        return true;
    }
};

enum class Kind { mesh, spheres, flat, others };

// One Embree geometry: a mesh, or all the scene's spheres, or all its polygons and triangles
// (as fans of triangles), or all its other bounded objects.
struct Geometry {
    Kind kind;
    const Scene* scene;
    std::vector<std::uint32_t> objects;  // by primID (a mesh: its one object)
    const mesh_core::Core* core = nullptr;
    std::vector<Vec3> corners;                      // flat: the fans' corners
    std::vector<std::array<unsigned, 3>> triangles;  // flat: by primID, indices into corners

    const Object& object(unsigned prim) const { return scene->objects[objects[prim]]; }

    // rt's own test of one primitive in the query's open range.
    bool exact(unsigned prim, const Ray& ray, Interval range, std::uint32_t& object_index,
               Hit& hit) const {
        if (kind == Kind::mesh) {
            const mesh_core::PackedTriangle& p = core->packed[prim];
            double t = 0;
            if (!TriangleRay(ray).crosses(p.vertex[0], p.vertex[1], p.vertex[2], t) ||
                !range.contains(t))
                return false;
            object_index = objects[0];
            hit = {t, static_cast<int>(prim)};
            return true;
        }
        object_index = objects[prim];
        return object(prim).shape.intersect(ray, range, hit);
    }
};

// The mesh core behind an object, or nullptr. The mesh (14) keeps a mesh_core::Core, the
// smooth mesh (16) and the mesh from a file (15) a mesh_core::ShadedMesh (their intersect
// function is shaded::intersect).
const mesh_core::Core* mesh_core_of(const Object& object) {
    if (object.shape.type->id == 14) return static_cast<const mesh_core::Core*>(object.shape.data.get());
    if (object.shape.functions->intersect == &mesh_core::shaded::intersect)
        return &static_cast<const mesh_core::ShadedMesh*>(object.shape.data.get())->core;
    return nullptr;
}

// Native candidates: kept only when rt's own test of that primitive confirms them.
void filter_nearest(const RTCFilterFunctionNArguments* args) {
    auto& q = *reinterpret_cast<Query*>(args->context);
    const auto& g = *static_cast<const Geometry*>(args->geometryUserPtr);
    const unsigned prim = RTCHitN_primID(args->hit, args->N, 0);
    std::uint32_t object = kNone;
    Hit hit;
    if (!g.exact(prim, *q.ray, q.open(), object, hit) || !q.offer(object, hit)) args->valid[0] = 0;
}

void filter_any(const RTCFilterFunctionNArguments* args) {
    const auto& q = *reinterpret_cast<const Query*>(args->context);
    const auto& g = *static_cast<const Geometry*>(args->geometryUserPtr);
    const unsigned prim = RTCHitN_primID(args->hit, args->N, 0);
    std::uint32_t object = kNone;
    Hit hit;
    const bool blocks = g.kind == Kind::mesh ? g.exact(prim, *q.ray, q.range, object, hit)
                                             : g.object(prim).shape.intersect_any(*q.ray, q.range);
    if (!blocks) args->valid[0] = 0;
}

// User geometry: rt's own functions on the exact ray.
void user_bounds(const RTCBoundsFunctionArguments* args) {
    const auto& g = *static_cast<const Geometry*>(args->geometryUserPtr);
    const Bounds b = g.object(args->primID).shape.bounds();
    *args->bounds_o = {float_below(b.min.x), float_below(b.min.y), float_below(b.min.z), 0,
                       float_above(b.max.x), float_above(b.max.y), float_above(b.max.z), 0};
}

void user_nearest(const RTCIntersectFunctionNArguments* args) {
    if (args->valid[0] == 0) return;
    auto& q = *reinterpret_cast<Query*>(args->context);
    const auto& g = *static_cast<const Geometry*>(args->geometryUserPtr);
    Hit hit;
    if (!g.object(args->primID).shape.intersect(*q.ray, q.open(), hit) ||
        !q.offer(g.objects[args->primID], hit))
        return;
    auto* rayhit = reinterpret_cast<RTCRayHit*>(args->rayhit);
    rayhit->ray.tfar = std::min(rayhit->ray.tfar, float_above(hit.t));
    rayhit->hit.geomID = args->geomID;
    rayhit->hit.primID = args->primID;
}

void user_any(const RTCOccludedFunctionNArguments* args) {
    if (args->valid[0] == 0) return;
    const auto& q = *reinterpret_cast<const Query*>(args->context);
    const auto& g = *static_cast<const Geometry*>(args->geometryUserPtr);
    if (g.object(args->primID).shape.intersect_any(*q.ray, q.range))
        reinterpret_cast<RTCRay*>(args->ray)->tfar = -kFloatInfinity;  // Embree's "occluded"
}

void report_error(void*, RTCError code, const char* message) {
    std::cerr << "embree error " << static_cast<int>(code) << ": " << message << "\n";
    std::exit(1);
}

class EmbreeQueries : public RayQueries {
  public:
    EmbreeQueries(const Scene& scene, RTCDevice device, bool robust) : scene_(scene) {
        Geometry spheres{Kind::spheres, &scene, {}, nullptr, {}, {}};
        Geometry others{Kind::others, &scene, {}, nullptr, {}, {}};
        Geometry flat{Kind::flat, &scene, {}, nullptr, {}, {}};
        for (std::uint32_t i = 0; i < scene.objects.size(); ++i) {
            const Object& o = scene.objects[i];
            const Bounds b = o.shape.bounds();
            const bool bounded = std::isfinite(b.min.x) && std::isfinite(b.min.y) &&
                                 std::isfinite(b.min.z) && std::isfinite(b.max.x) &&
                                 std::isfinite(b.max.y) && std::isfinite(b.max.z);
            if (!bounded) {
                unbounded_.push_back(i);
            } else if (const mesh_core::Core* core = mesh_core_of(o)) {
                if (!core->triangles.empty())
                    geometries_.push_back(std::make_unique<Geometry>(
                        Geometry{Kind::mesh, &scene, {i}, core, {}, {}}));
            } else if (o.shape.type->id == 1) {
                spheres.objects.push_back(i);
            } else if (const std::vector<Vec3> corners = flat_corners(o.shape); !corners.empty()) {
                const auto first = static_cast<unsigned>(flat.corners.size());
                flat.corners.insert(flat.corners.end(), corners.begin(), corners.end());
                for (unsigned k = 1; k + 1 < corners.size(); ++k) {
                    flat.triangles.push_back({first, first + k, first + k + 1});
                    flat.objects.push_back(i);
                }
            } else {
                others.objects.push_back(i);
            }
        }
        for (Geometry* g : {&spheres, &flat, &others})
            if (!g->objects.empty()) geometries_.push_back(std::make_unique<Geometry>(*g));

        rtc_ = rtcNewScene(device);
        rtcSetSceneBuildQuality(rtc_, RTC_BUILD_QUALITY_HIGH);
        if (robust) rtcSetSceneFlags(rtc_, RTC_SCENE_FLAG_ROBUST);
        for (std::size_t id = 0; id < geometries_.size(); ++id) {
            Geometry& g = *geometries_[id];
            RTCGeometry geometry = make_geometry(device, g);
            rtcSetGeometryBuildQuality(geometry, RTC_BUILD_QUALITY_HIGH);
            rtcSetGeometryUserData(geometry, &g);
            rtcCommitGeometry(geometry);
            rtcAttachGeometryByID(rtc_, geometry, static_cast<unsigned>(id));
            rtcReleaseGeometry(geometry);
        }
        rtcCommitScene(rtc_);
    }
    ~EmbreeQueries() override { rtcReleaseScene(rtc_); }
    EmbreeQueries(const EmbreeQueries&) = delete;
    EmbreeQueries& operator=(const EmbreeQueries&) = delete;

    bool closest(const Ray& ray, Interval range, SceneHit& found) const override {
        Query q;
        rtcInitIntersectContext(&q.context);
        q.ray = &ray;
        q.range = range;
        alignas(16) RTCRayHit rayhit;
        rayhit.ray = embree_ray(ray, range);
        rayhit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(rtc_, &q.context, &rayhit);
        // q holds the winner: every candidate Embree kept was offered to it on the way.
        for (const std::uint32_t i : unbounded_) {
            Hit hit;
            if (scene_.objects[i].shape.intersect(ray, q.open(), hit)) q.offer(i, hit);
        }
        if (q.object == kNone) return false;
        found = {&scene_.objects[q.object], q.hit};
        return true;
    }

    bool any(const Ray& ray, Interval range) const override {
        Query q;
        rtcInitIntersectContext(&q.context);
        q.ray = &ray;
        q.range = range;
        alignas(16) RTCRay r = embree_ray(ray, range);
        rtcOccluded1(rtc_, &q.context, &r);
        if (r.tfar == -kFloatInfinity) return true;
        return std::any_of(unbounded_.begin(), unbounded_.end(), [&](std::uint32_t i) {
            return scene_.objects[i].shape.intersect_any(ray, range);
        });
    }

    std::size_t geometry_count() const { return geometries_.size(); }

  private:
    static RTCRay embree_ray(const Ray& ray, Interval range) {
        RTCRay r{};
        r.org_x = static_cast<float>(ray.origin.x);
        r.org_y = static_cast<float>(ray.origin.y);
        r.org_z = static_cast<float>(ray.origin.z);
        r.dir_x = static_cast<float>(ray.direction.x);
        r.dir_y = static_cast<float>(ray.direction.y);
        r.dir_z = static_cast<float>(ray.direction.z);
        r.tnear = float_below(range.t_min);
        r.tfar = float_above(range.t_max);
        r.mask = 0xffffffff;
        return r;
    }

    static void fill_vertices(RTCGeometry geometry, std::span<const Vec3> vertices) {
        auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0,
                                                              RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                              vertices.size()));
        for (std::size_t i = 0; i < vertices.size(); ++i) {
            v[3 * i] = static_cast<float>(vertices[i].x);
            v[3 * i + 1] = static_cast<float>(vertices[i].y);
            v[3 * i + 2] = static_cast<float>(vertices[i].z);
        }
    }

    static RTCGeometry make_geometry(RTCDevice device, const Geometry& g) {
        const auto count = static_cast<unsigned>(g.objects.size());
        if (g.kind == Kind::mesh) {
            RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
            fill_vertices(geometry, g.core->vertices);
            // primID is the triangle's place in the core's leaf order: Hit::part.
            const auto& triangles = g.core->triangles;
            auto* index = static_cast<unsigned*>(
                rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                        3 * sizeof(unsigned), triangles.size()));
            for (std::size_t i = 0; i < triangles.size(); ++i)
                for (std::size_t k = 0; k < 3; ++k) index[3 * i + k] = triangles[i].vertex[k];
            rtcSetGeometryIntersectFilterFunction(geometry, filter_nearest);
            rtcSetGeometryOccludedFilterFunction(geometry, filter_any);
            return geometry;
        }
        if (g.kind == Kind::flat) {
            RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
            fill_vertices(geometry, g.corners);
            auto* index = static_cast<unsigned*>(
                rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                        3 * sizeof(unsigned), g.triangles.size()));
            for (std::size_t i = 0; i < g.triangles.size(); ++i)
                for (std::size_t k = 0; k < 3; ++k) index[3 * i + k] = g.triangles[i][k];
            rtcSetGeometryIntersectFilterFunction(geometry, filter_nearest);
            rtcSetGeometryOccludedFilterFunction(geometry, filter_any);
            return geometry;
        }
        if (g.kind == Kind::spheres) {
            RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_SPHERE_POINT);
            auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
                geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), count));
            for (unsigned i = 0; i < count; ++i) {
                // A sphere's bounds are its centre plus and minus its radius.
                const Bounds b = g.object(i).shape.bounds();
                v[4 * i] = static_cast<float>((b.min.x + b.max.x) / 2);
                v[4 * i + 1] = static_cast<float>((b.min.y + b.max.y) / 2);
                v[4 * i + 2] = static_cast<float>((b.min.z + b.max.z) / 2);
                v[4 * i + 3] = static_cast<float>((b.max.x - b.min.x) / 2);
            }
            rtcSetGeometryIntersectFilterFunction(geometry, filter_nearest);
            rtcSetGeometryOccludedFilterFunction(geometry, filter_any);
            return geometry;
        }
        RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
        rtcSetGeometryUserPrimitiveCount(geometry, count);
        rtcSetGeometryBoundsFunction(geometry, user_bounds, nullptr);
        rtcSetGeometryIntersectFunction(geometry, user_nearest);
        rtcSetGeometryOccludedFunction(geometry, user_any);
        return geometry;
    }

    const Scene& scene_;
    std::vector<std::unique_ptr<Geometry>> geometries_;  // by geomID; callbacks point into it
    std::vector<std::uint32_t> unbounded_;
    RTCScene rtc_ = nullptr;
};

// Asks Embree and rt's own hierarchy every query, counts where they differ, and answers
// with rt's (so that every query is compared on rt's own ray tree).
class CheckedQueries : public RayQueries {
  public:
    CheckedQueries(const RayQueries& embree, const ObjectIndex& index)
        : embree_(embree), index_(index) {}

    bool closest(const Ray& ray, Interval range, SceneHit& found) const override {
        SceneHit theirs{};
        const bool they_hit = embree_.closest(ray, range, theirs);
        ObjectIndex::Found ours{};
        const bool we_hit = index_.closest(ray, range, ours);
        nearest_queries.fetch_add(1, std::memory_order_relaxed);
        if (they_hit != we_hit) {
            nearest_differ.fetch_add(1, std::memory_order_relaxed);
        } else if (we_hit && (theirs.object != &objects()[ours.object] ||
                              theirs.hit.t != ours.hit.t || theirs.hit.part != ours.hit.part)) {
            nearest_differ.fetch_add(1, std::memory_order_relaxed);
        }
        if (we_hit) found = {&objects()[ours.object], ours.hit};
        return we_hit;
    }
    bool any(const Ray& ray, Interval range) const override {
        const bool theirs = embree_.any(ray, range);
        const bool ours = index_.any(ray, range);
        any_queries.fetch_add(1, std::memory_order_relaxed);
        if (theirs != ours) any_differ.fetch_add(1, std::memory_order_relaxed);
        return ours;
    }

    const Object* objects_ = nullptr;
    mutable std::atomic<std::uint64_t> nearest_queries{0}, nearest_differ{0};
    mutable std::atomic<std::uint64_t> any_queries{0}, any_differ{0};

  private:
    const Object* objects() const { return objects_; }
    const RayQueries& embree_;
    const ObjectIndex& index_;
};

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    return n % 2 == 1 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2;
}

double render_seconds(const Scene& scene, const RenderOptions& options, RenderStats& stats) {
    stats = {};
    const auto start = Clock::now();
    render(scene, options, &stats);
    return std::chrono::duration<double>(Clock::now() - start).count();
}

struct Settings {
    std::vector<int> threads{1, 2};
    int runs = 5;
    int depth = -1;  // -1: the scene's first line ("Render with: rt -d D"), else rt's default
    int size = 0;  // the image's width and height; 0: the viewer's resolution
    bool robust = false;
    bool check = false;
};

// The depth a bench scene asks for on its first line, or rt's default.
int depth_of(const std::string& file, int fallback) {
    std::ifstream in(file);
    std::string line;
    std::getline(in, line);
    const std::size_t at = line.find("rt -d ");
    return at == std::string::npos ? fallback : std::atoi(line.c_str() + at + 6);
}

// Measures one scene; adds each thread count's ratio's logarithm to log_ratios.
void measure(const std::string& file, const Settings& settings, RTCDevice device,
             std::vector<double>& log_ratios) {
    const int most_threads = *std::max_element(settings.threads.begin(), settings.threads.end());
    Scene scene = read_scene_file(file, most_threads);
    if (settings.size > 0) scene.viewer.xres = scene.viewer.yres = settings.size;  // rt --size NxN
    auto start = Clock::now();
    const EmbreeQueries embree(scene, device, settings.robust);
    const double build_s = std::chrono::duration<double>(Clock::now() - start).count();
    RenderOptions options;
    options.max_depth = settings.depth >= 0 ? settings.depth : depth_of(file, options.max_depth);
    const std::string name = std::filesystem::path(file).stem().string();

    if (settings.check) {
        CheckedQueries checked(embree, *scene.index);
        checked.objects_ = scene.objects.data();
        options.queries = &checked;
        options.threads = most_threads;
        render(scene, options);
        const auto share = [](std::uint64_t part, std::uint64_t whole) {
            return whole == 0 ? 0.0 : 100.0 * static_cast<double>(part) / static_cast<double>(whole);
        };
        std::printf("%-16s nearest %llu of %llu differ (%.4f %%), shadow %llu of %llu (%.4f %%)\n",
                    name.c_str(), static_cast<unsigned long long>(checked.nearest_differ.load()),
                    static_cast<unsigned long long>(checked.nearest_queries.load()),
                    share(checked.nearest_differ, checked.nearest_queries),
                    static_cast<unsigned long long>(checked.any_differ.load()),
                    static_cast<unsigned long long>(checked.any_queries.load()),
                    share(checked.any_differ, checked.any_queries));
        return;
    }

    std::string row;
    RenderStats ours, theirs;
    for (std::size_t k = 0; k < settings.threads.size(); ++k) {
        const int threads = settings.threads[k];
        options.threads = threads;
        std::vector<double> rt_s, embree_s;
        for (int run = 0; run < settings.runs; ++run) {  // alternately, so both see the same load
            options.queries = nullptr;
            rt_s.push_back(render_seconds(scene, options, ours));
            options.queries = &embree;
            embree_s.push_back(render_seconds(scene, options, theirs));
        }
        const double rt_rate = static_cast<double>(ours.total()) / median(rt_s) / 1e6;
        const double embree_rate = static_cast<double>(theirs.total()) / median(embree_s) / 1e6;
        char cell[96];
        std::snprintf(cell, sizeof cell, " %8.2f %8.2f %7.2f", rt_rate, embree_rate,
                      rt_rate / embree_rate);
        row += cell;
        log_ratios[k] += std::log(rt_rate / embree_rate);
    }
    const double diff_ppm = 1e6 *
                            (static_cast<double>(theirs.total()) - static_cast<double>(ours.total())) /
                            static_cast<double>(std::max<std::uint64_t>(1, ours.total()));
    std::printf("%-16s %8zu %8.3f %9.3f %+9.1f%s\n", name.c_str(), scene.objects.size(), build_s,
                static_cast<double>(ours.total()) / 1e6, diff_ppm, row.c_str());
    std::fflush(stdout);
}

int usage() {
    std::cerr << "usage: rt_embree [--threads 1,2] [--runs N] [--depth D] [--size N] [--robust] [--check] "
                 "scene.in ...\n";
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    Settings settings;
    std::vector<std::string> files;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        const bool has_value = i + 1 < argc;
        if (arg == "--threads" && has_value) {
            settings.threads.clear();
            std::istringstream list(argv[++i]);
            for (std::string n; std::getline(list, n, ',');)
                settings.threads.push_back(std::max(1, std::atoi(n.c_str())));
            if (settings.threads.empty()) return usage();
        } else if (arg == "--runs" && has_value) {
            settings.runs = std::max(1, std::atoi(argv[++i]));
        } else if (arg == "--depth" && has_value) {
            settings.depth = std::max(0, std::atoi(argv[++i]));
        } else if (arg == "--size" && has_value) {
            settings.size = std::clamp(std::atoi(argv[++i]), 0, 1 << 14);
        } else if (arg == "--robust") {
            settings.robust = true;
        } else if (arg == "--check") {
            settings.check = true;
        } else if (arg.starts_with("-")) {
            return usage();
        } else {
            files.push_back(arg);
        }
    }
    if (files.empty()) return usage();
    const int most_threads = *std::max_element(settings.threads.begin(), settings.threads.end());
    const std::string config = "threads=" + std::to_string(most_threads) + ",set_affinity=0";
    RTCDevice device = rtcNewDevice(config.c_str());
    if (device == nullptr) return report_error(nullptr, rtcGetDeviceError(nullptr), "no device"), 1;
    rtcSetDeviceErrorFunction(device, report_error, nullptr);
    if (!settings.check) {
        std::printf("%-16s %8s %8s %9s %9s", "scene", "objects", "embree_s", "rays_M", "diff_ppm");
        for (const int t : settings.threads)
            std::printf(" %8s %8s %7s", ("rt_" + std::to_string(t) + "j").c_str(),
                        ("emb_" + std::to_string(t) + "j").c_str(),
                        ("ratio_" + std::to_string(t)).c_str());
        std::printf("\n");
    }
    int status = 0;
    std::vector<double> log_ratios(settings.threads.size(), 0.0);
    int measured = 0;
    for (const std::string& file : files) {
        try {
            measure(file, settings, device, log_ratios);
            ++measured;
        } catch (const std::exception& e) {
            std::cerr << file << ": " << e.what() << "\n";
            status = 1;
        }
    }
    if (!settings.check && measured > 1) {
        std::printf("geometric mean of the ratios over %d scenes:", measured);
        for (std::size_t k = 0; k < settings.threads.size(); ++k)
            std::printf(" %d thread%s %.2f", settings.threads[k], settings.threads[k] == 1 ? "" : "s",
                        std::exp(log_ratios[k] / measured));
        std::printf("\n");
    }
    rtcReleaseDevice(device);
    return status;
}
