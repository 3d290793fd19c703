// Times the scene reader on each file, one thread, --repeat times (5 by default), and prints
// the medians in MB of file per second of processor time:
//   rt_bench_read [--repeat N] scene.in ...
// - tokens_MB/s: the lexer alone, every token of the file;
// - numbers_MB/s: every token read as a number by SceneReader::number (the path every read
//   function takes), for a file of numbers only (a scene without paths: "-" otherwise);
// - scene_MB/s: the whole scene read and checked (SceneReader::read_scene), objects made,
//   a mesh's own hierarchy built (one thread), as `rt -r -j 1` does: beside numbers_MB/s, what
//   the objects cost beyond their numbers.

#include <algorithm>
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
#include "scene/lexer.h"

namespace {

// Processor time, not wall-clock time: on a shared machine a reader that waits for a core
// has not spent that time reading. Everything here runs on one thread.
struct Clock {
    using time_point = double;
    static double now() {
        timespec t{};
        clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
        return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) * 1e-9;
    }
};

double seconds_since(Clock::time_point start) { return Clock::now() - start; }

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    return n % 2 == 1 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2;
}

struct Counts {
    long tokens = 0;
    bool numbers_only = true;
};

Counts lex(const std::string& file) {
    std::ifstream in(file, std::ios::binary);
    rt::Lexer lexer(in, file);
    Counts counts;
    for (;;) {
        const rt::Token& token = lexer.next();
        if (token.at_end()) return counts;
        ++counts.tokens;
        if (token.quoted) counts.numbers_only = false;
    }
}

// The sum of the numbers keeps the compiler from dropping the reads.
double read_numbers(const std::string& file, long count) {
    std::ifstream in(file, std::ios::binary);
    rt::SceneReader reader(in, file, {});
    double sum = 0;
    for (long i = 0; i < count; ++i) sum += reader.number("number");
    return sum;
}

void read_whole(const std::string& file) {
    std::ifstream in(file, std::ios::binary);
    rt::SceneReader(in, file, std::filesystem::path(file).parent_path(), 1).read_scene();
}

int run(int argc, char** argv) {
    int repeat = 5;
    std::vector<std::string> files;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--repeat" && i + 1 < argc) {
            repeat = std::max(1, std::atoi(argv[++i]));
        } else if (!arg.empty() && arg[0] == '-') {
            std::cerr << "usage: rt_bench_read [--repeat N] scene.in ...\n";
            return 2;
        } else {
            files.push_back(arg);
        }
    }
    std::printf("%-24s %9s %10s %12s %13s %11s\n", "scene", "MB", "tokens_M", "tokens_MB/s",
                "numbers_MB/s", "scene_MB/s");
    for (const std::string& file : files) {
        const double megabytes = static_cast<double>(std::filesystem::file_size(file)) / 1e6;
        Counts counts;
        std::vector<double> lex_s, number_s, scene_s;
        double sink = 0;
        for (int r = 0; r < repeat; ++r) {
            auto start = Clock::now();
            counts = lex(file);
            lex_s.push_back(seconds_since(start));
            if (counts.numbers_only) {
                start = Clock::now();
                sink += read_numbers(file, counts.tokens);
                number_s.push_back(seconds_since(start));
            }
            start = Clock::now();
            read_whole(file);
            scene_s.push_back(seconds_since(start));
        }
        char numbers[32] = "-";
        if (counts.numbers_only)
            std::snprintf(numbers, sizeof numbers, "%.0f", megabytes / median(number_s));
        std::printf("%-24s %9.2f %10.3f %12.0f %13s %11.0f\n",
                    std::filesystem::path(file).filename().c_str(), megabytes,
                    static_cast<double>(counts.tokens) / 1e6, megabytes / median(lex_s), numbers,
                    megabytes / median(scene_s));
        if (sink == 1.5) std::printf("\n");  // never: only keeps the sum alive
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const rt::Error& e) {
        std::cerr << "rt_bench_read: " << e.what() << "\n";
        return 1;
    }
}
