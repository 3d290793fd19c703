// Times the build of a scene's object hierarchy (Scene::build_index, as rt runs it after
// reading) on each scene file, for each thread count, --repeat times (5 by default), and
// prints the medians: wall-clock seconds, processor seconds, and millions of primitives per
// second of each (the second is the rate per core).
//   rt_bench_build [--threads 1,2,...] [--repeat N] scene.in ...

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "rt/error.h"
#include "rt/reader.h"

namespace {

double wall_seconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

// Every thread's processor time: the build's helpers are threads of this process.
double processor_seconds() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) * 1e-9;
}

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    return n % 2 == 1 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2;
}

int run(int argc, char** argv) {
    int repeat = 5;
    std::vector<int> thread_counts = {1};
    std::vector<std::string> files;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--repeat" && i + 1 < argc) {
            repeat = std::max(1, std::atoi(argv[++i]));
        } else if (arg == "--threads" && i + 1 < argc) {
            thread_counts.clear();
            std::stringstream list(argv[++i]);
            for (std::string item; std::getline(list, item, ',');)
                thread_counts.push_back(std::max(1, std::atoi(item.c_str())));
        } else if (!arg.empty() && arg[0] == '-') {
            std::cerr << "usage: rt_bench_build [--threads 1,2,...] [--repeat N] scene.in ...\n";
            return 2;
        } else {
            files.push_back(arg);
        }
    }
    std::printf("%-24s %10s %8s %9s %9s %10s %14s\n", "scene", "objects", "threads", "wall_s",
                "cpu_s", "Mprims/s", "Mprims/s/core");
    for (const std::string& file : files) {
        std::ifstream in(file, std::ios::binary);
        if (!in) throw rt::Error(file + ": cannot open");
        rt::Scene scene =
            rt::SceneReader(in, file, std::filesystem::path(file).parent_path()).read_scene();
        const auto objects = static_cast<double>(scene.objects.size());
        for (const int threads : thread_counts) {
            std::vector<double> wall, cpu;
            for (int r = 0; r < repeat; ++r) {
                const double wall_start = wall_seconds();
                const double cpu_start = processor_seconds();
                scene.build_index(threads);
                cpu.push_back(processor_seconds() - cpu_start);
                wall.push_back(wall_seconds() - wall_start);
            }
            std::printf("%-24s %10.0f %8d %9.3f %9.3f %10.2f %14.2f\n",
                        std::filesystem::path(file).filename().c_str(), objects, threads,
                        median(wall), median(cpu), objects / median(wall) / 1e6,
                        objects / median(cpu) / 1e6);
        }
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const rt::Error& e) {
        std::cerr << "rt_bench_build: " << e.what() << "\n";
        return 1;
    }
}
