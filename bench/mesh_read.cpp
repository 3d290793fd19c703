// Times the mesh-file readers (ID 15) on a tessellated sphere of about a million triangles,
// generated in memory as binary PLY (both byte orders), ASCII PLY and OBJ (without and with
// normals), and the angle-weighted normals computed for it. Each is run --repeat times (5 by
// default) and the medians shown: wall-clock and processor seconds, MB/s of file, triangles/s.
//   rt_bench_mesh_read [--slices N] [--repeat N]
// The sphere has 2 N (N / 2) triangles for N slices (default 1000: 1,000,000 triangles).

#include <algorithm>
#include <array>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include "rt/error.h"
#include "scene/mesh_file.h"

namespace {

using Clock = std::chrono::steady_clock;

struct Sphere {
    std::vector<std::array<float, 3>> points;  // unit sphere: the points are the normals too
    std::vector<std::array<std::uint32_t, 3>> triangles;
};

// Rings of `slices` points between the poles, `slices / 2` bands; the caps are fans.
Sphere make_sphere(int slices) {
    const int stacks = slices / 2;
    Sphere s;
    s.points.push_back({0, 0, 1});
    for (int i = 1; i < stacks; ++i) {
        const double theta = std::numbers::pi * i / stacks;
        for (int j = 0; j < slices; ++j) {
            const double phi = 2 * std::numbers::pi * j / slices;
            s.points.push_back({static_cast<float>(std::sin(theta) * std::cos(phi)),
                                static_cast<float>(std::sin(theta) * std::sin(phi)),
                                static_cast<float>(std::cos(theta))});
        }
    }
    s.points.push_back({0, 0, -1});
    const auto ring = [&](int i, int j) {
        return static_cast<std::uint32_t>(1 + (i - 1) * slices + (j % slices));
    };
    const auto last = static_cast<std::uint32_t>(s.points.size() - 1);
    for (int j = 0; j < slices; ++j) {
        s.triangles.push_back({0, ring(1, j), ring(1, j + 1)});
        for (int i = 1; i + 1 < stacks; ++i) {
            s.triangles.push_back({ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)});
            s.triangles.push_back({ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)});
        }
        s.triangles.push_back({ring(stacks - 1, j), last, ring(stacks - 1, j + 1)});
    }
    return s;
}

template <typename T>
void put(std::string& out, T v, bool big) {
    unsigned char raw[sizeof(T)];
    std::memcpy(raw, &v, sizeof(T));
    if (big) std::reverse(raw, raw + sizeof(T));  // bench hosts are little-endian
    out.append(reinterpret_cast<const char*>(raw), sizeof(T));
}

template <typename T>
void put_text(std::string& out, T v) {
    char buffer[32];
    const auto r = std::to_chars(buffer, buffer + sizeof buffer, v);
    out.append(buffer, r.ptr);
}

std::string ply_header(const Sphere& s, const char* format) {
    return "ply\nformat " + std::string(format) + " 1.0\ncomment rt_bench_mesh_read sphere\n" +
           "element vertex " + std::to_string(s.points.size()) +
           "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
           std::to_string(s.triangles.size()) +
           "\nproperty list uchar int vertex_indices\nend_header\n";
}

std::string binary_ply(const Sphere& s, bool big) {
    std::string out = ply_header(s, big ? "binary_big_endian" : "binary_little_endian");
    for (const auto& p : s.points)
        for (const float c : p) put(out, c, big);
    for (const auto& t : s.triangles) {
        put(out, std::uint8_t{3}, big);
        for (const std::uint32_t i : t) put(out, static_cast<std::int32_t>(i), big);
    }
    return out;
}

std::string ascii_ply(const Sphere& s) {
    std::string out = ply_header(s, "ascii");
    for (const auto& p : s.points) {
        for (int k = 0; k < 3; ++k) {
            put_text(out, p[static_cast<std::size_t>(k)]);
            out += k < 2 ? ' ' : '\n';
        }
    }
    for (const auto& t : s.triangles) {
        out += '3';
        for (const std::uint32_t i : t) {
            out += ' ';
            put_text(out, i);
        }
        out += '\n';
    }
    return out;
}

std::string obj(const Sphere& s, bool normals) {
    std::string out = "# rt_bench_mesh_read sphere\no sphere\n";
    for (const char* kind :
         normals ? std::vector<const char*>{"v ", "vn "} : std::vector<const char*>{"v "}) {
        for (const auto& p : s.points) {
            out += kind;
            for (int k = 0; k < 3; ++k) {
                put_text(out, p[static_cast<std::size_t>(k)]);
                out += k < 2 ? ' ' : '\n';
            }
        }
    }
    for (const auto& t : s.triangles) {
        out += 'f';
        for (const std::uint32_t i : t) {
            out += ' ';
            put_text(out, i + 1);
            if (normals) {
                out += "//";
                put_text(out, i + 1);
            }
        }
        out += '\n';
    }
    return out;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 == 1 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

struct Times {
    std::vector<double> wall;
    std::vector<double> cpu;
};

// Wall-clock and processor time of one run: on a shared machine the processor time shows
// what the reader costs when the wall clock also counts waiting for a core.
void time_once(Times& times, const std::function<void()>& f) {
    const Clock::time_point start = Clock::now();
    const std::clock_t cpu_start = std::clock();
    f();
    times.cpu.push_back(static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC);
    times.wall.push_back(std::chrono::duration<double>(Clock::now() - start).count());
}

int usage() {
    std::fprintf(stderr, "usage: rt_bench_mesh_read [--slices N] [--repeat N]\n");
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    int slices = 1000;
    int repeat = 5;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if ((arg == "--slices" || arg == "--repeat") && i + 1 < argc) {
            const int value = std::atoi(argv[++i]);
            if (value < 1 || (arg == "--slices" && value < 4)) return usage();
            (arg == "--slices" ? slices : repeat) = value;
        } else {
            return usage();
        }
    }
    const Sphere sphere = make_sphere(slices);
    std::printf("sphere: %zu vertices, %zu triangles; median of %d runs\n", sphere.points.size(),
                sphere.triangles.size(), repeat);
    std::printf("%-18s %7s %8s %7s %7s %8s %8s\n", "format", "MB", "wall_s", "MB/s", "Mtri/s",
                "cpu_s", "cpu_MB/s");
    struct Case {
        const char* name;
        std::string bytes;
    };
    const Case cases[] = {
        {"ply binary LE", binary_ply(sphere, false)},
        {"ply binary BE", binary_ply(sphere, true)},
        {"ply ascii", ascii_ply(sphere)},
        {"obj", obj(sphere, false)},
        {"obj with normals", obj(sphere, true)},
    };
    try {
        rt::MeshFile kept;
        for (const Case& c : cases) {
            Times times;
            for (int r = 0; r < repeat; ++r) {
                time_once(times, [&] { kept = rt::read_mesh_file(c.bytes, c.name); });
                if (kept.triangles.size() != sphere.triangles.size()) {
                    std::fprintf(stderr, "%s: read %zu triangles, expected %zu\n", c.name,
                                 kept.triangles.size(), sphere.triangles.size());
                    return 1;
                }
            }
            const double t = median(times.wall);
            const double cpu = median(times.cpu);
            const double mb = static_cast<double>(c.bytes.size()) / 1e6;
            std::printf("%-18s %7.1f %8.4f %7.0f %7.2f %8.4f %8.0f\n", c.name, mb, t, mb / t,
                        static_cast<double>(kept.triangles.size()) / t / 1e6, cpu, mb / cpu);
        }
        // Mode 2: normals for the last mesh read, as if the file had none.
        Times times;
        for (int r = 0; r < repeat; ++r)
            time_once(times, [&] {
                const auto n = rt::angle_weighted_normals(kept.positions, kept.triangles);
                if (n.size() != kept.positions.size()) std::abort();
            });
        const double t = median(times.wall);
        std::printf("%-18s %7s %8.4f %7s %7.2f %8.4f %8s\n", "normals (mode 2)", "-", t, "-",
                    static_cast<double>(kept.triangles.size()) / t / 1e6, median(times.cpu), "-");
    } catch (const rt::Error& e) {
        std::fprintf(stderr, "rt_bench_mesh_read: %s\n", e.what());
        return 1;
    }
    return 0;
}
