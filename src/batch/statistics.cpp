#include "batch/statistics.h"

#include <sys/resource.h>

#include <cstdio>

namespace rt {

std::uint64_t peak_memory_bytes() {
    rusage usage{};
    if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;
    return static_cast<std::uint64_t>(usage.ru_maxrss) * 1024;  // Linux reports kilobytes
}

namespace {

std::string line(const char* format, auto... values) {
    char text[256];
    std::snprintf(text, sizeof text, format, values...);
    return std::string("rt: stats: ") + text + "\n";
}

unsigned long long count(std::uint64_t n) { return static_cast<unsigned long long>(n); }

std::string counted(std::size_t n, const char* thing) {
    return std::to_string(n) + " " + thing + (n == 1 ? "" : "s");
}

}  // namespace

std::string format_statistics(const RunStatistics& s) {
    const RenderStats& r = s.rays;
    const double per_second =
        s.times.render > 0 ? static_cast<double>(r.total()) / s.times.render : 0;
    const double tests_per_ray =
        r.total() > 0 ? static_cast<double>(r.object_tests) / static_cast<double>(r.total()) : 0;
    return line("time: read %.3f s, build %.3f s, render %.3f s, write %.3f s", s.times.read,
                s.times.build, s.times.render, s.times.write) +
           line(
               "rays: %llu primary, %llu reflected, %llu refracted, %llu shadow; %llu in all, "
               "%.2f M/s",
               count(r.primary_rays), count(r.reflected_rays), count(r.refracted_rays),
               count(r.shadow_rays), count(r.total()), per_second / 1e6) +
           line("tests: %llu object intersection tests, %.2f per ray", count(r.object_tests),
                tests_per_ray) +
           line("scene: %s, %s; %s; peak memory %.1f MiB", counted(s.objects, "object").c_str(),
                counted(s.lights, "light").c_str(),
                counted(static_cast<std::size_t>(s.threads), "thread").c_str(),
                static_cast<double>(s.peak_memory_bytes) / (1024 * 1024)) +
           (s.checkpoint
                ? line("checkpoint: %llu of %llu rows resumed, %llu rendered",
                       count(s.rows_resumed), count(s.rows), count(s.rows - s.rows_resumed))
                : std::string());
}

}  // namespace rt
