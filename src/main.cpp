// rt: reads a scene, traces it and writes a PPM image (section 1.10.3 of the original).
#include <exception>
#include <iostream>
#include <new>

#include "rt/cli.h"
#include "rt/error.h"
#include "rt/interrupt.h"
#include "rt/output_file.h"
#include "rt/reader.h"
#include "rt/trace.h"

namespace {

constexpr int kExitOk = 0;
constexpr int kExitError = 1;  // a scene, texture or input/output error
constexpr int kExitUsage = 2;  // the command line made no sense

int run(const rt::CommandLine& cl) {
    std::vector<std::filesystem::path> textures;
    const rt::Scene scene =
        rt::read_scene_file(cl.input, rt::worker_threads(cl.render.threads), &textures);
    if (cl.read_only) {
        const std::string name = cl.input == "-" ? "<stdin>" : cl.input;
        std::cout << name << ": " << scene.objects.size() << " objects, " << scene.lights.size()
                  << " lights, " << scene.viewer.xres << "x" << scene.viewer.yres;
        if (const std::size_t n = scene.skipped_triangles; n != 0)
            std::cout << ", " << n << " zero-area " << (n == 1 ? "triangle" : "triangles")
                      << " skipped";
        std::cout << "\n";
        return kExitOk;
    }
    // The output file is checked and claimed before rendering, so a bad path fails fast, and
    // is only replaced once the whole image has been written. The files the render reads are
    // never written over.
    std::vector<std::filesystem::path> inputs = textures;
    inputs.insert(inputs.begin(), cl.input == "-" ? std::string() : cl.input);  // scene first
    rt::OutputFile output(cl.output, inputs);
    output.write(rt::render(scene, cl.render));
    return kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
    rt::CommandLine cl;
    try {
        cl = rt::parse_command_line({argv + 1, argv + argc});
    } catch (const rt::UsageError& e) {
        std::cerr << "rt: " << e.message << "\nTry 'rt --help' for more information.\n";
        return kExitUsage;
    }
    if (cl.help) {
        std::cout << rt::usage_text();
        return kExitOk;
    }
    if (cl.version) {
        std::cout << "rt " RT_VERSION "\n";
        return kExitOk;
    }
    rt::interrupt::install_handlers();
    try {
        return run(cl);
    } catch (const rt::Error& e) {
        std::cerr << e.what() << "\n";
    } catch (const std::bad_alloc&) {
        std::cerr << "rt: out of memory\n";
    } catch (const std::exception& e) {
        std::cerr << "rt: " << e.what() << "\n";
    }
    return kExitError;
}
