#include "rtpp/compiler.h"

#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>

#include "rtpp/emitter.h"
#include "rtpp/evaluator.h"
#include "rtpp/parser.h"

namespace rtpp {

std::string compile(const std::string& text, const std::string& name,
                    const std::filesystem::path& dir, const CompileOptions& options) {
    SourceFiles files;
    std::string out = "# Written by rtpp from " + name + "; edit that, not this.\n";
    try {
        const Block program =
            parse_program(text, name, dir, files, {options.include_dirs, options.limits});
        Emitter emitter(files, options.limits, out);
        Evaluator evaluator(options.limits, emitter);
        evaluator.run(program);
        // The end of the top-level file: where a missing camera is reported.
        int line = 1, column = 1;
        for (const char c : text) {
            if (c == '\n') {
                ++line;
                column = 1;
            } else {
                ++column;
            }
        }
        emitter.finish({0, line, column});
    } catch (const SourceError& e) {
        std::string message = files.describe(e.pos, e.message);
        for (const auto& [pos, note] : e.notes)
            message += "\n" + files.describe(pos, "note: " + note);
        throw CompileError(message);
    } catch (const std::bad_alloc&) {
        throw CompileError(name + ": out of memory");
    }
    return out;
}

std::string compile_file(const std::string& path, const CompileOptions& options) {
    if (path == "-") {
        const std::string text{std::istreambuf_iterator<char>(std::cin), {}};
        return compile(text, "<stdin>", std::filesystem::current_path(), options);
    }
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw CompileError(path + ": is a directory, not a scene");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw CompileError(path + ": cannot open");
    const auto size = std::filesystem::file_size(path, ec);
    if (!ec && size > options.limits.file_size)
        throw CompileError(path + ": larger than " + std::to_string(options.limits.file_size) +
                           " bytes");
    std::ostringstream text;
    text << in.rdbuf();
    return compile(text.str(), path, std::filesystem::path(path).parent_path(), options);
}

}  // namespace rtpp
