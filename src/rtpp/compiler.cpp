#include "rtpp/compiler.h"

#include <cctype>
#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>

#include "rtpp/emitter.h"
#include "rtpp/evaluator.h"
#include "rtpp/parser.h"

namespace rtpp {

namespace {
// A name as the language writes one: a letter or '_', then letters, digits and '_'.
bool is_valid_name(const std::string& name) {
    if (name.empty() || !(std::isalpha(static_cast<unsigned char>(name[0])) != 0 || name[0] == '_'))
        return false;
    for (const char c : name)
        if (!(std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_')) return false;
    return true;
}
}  // namespace

std::string compile(const std::string& text, const std::string& name,
                    const std::filesystem::path& dir, const CompileOptions& options) {
    SourceFiles files;
    std::string out = "# Written by rtpp from " + name + "; edit that, not this.\n";
    try {
        const Block program =
            parse_program(text, name, dir, files, {options.include_dirs, options.limits});
        Emitter emitter(files, options.limits, out);
        Evaluator evaluator(options.limits, emitter);
        // Each definition is read as a one-line program of its own, named after the option,
        // so that its errors say where they are: "-D frame=x:1:13: unknown name 'x'".
        std::vector<Block> definitions;
        for (const auto& [define_name, value] : options.defines) {
            const std::string label = "-D " + define_name + "=" + value;
            if (!is_valid_name(define_name))
                throw CompileError(label + ": '" + define_name +
                                   "' is not a name (a letter or '_', then letters, digits, '_')");
            if (is_reserved_word(define_name))
                throw CompileError(label + ": '" + define_name + "' is a reserved word");
            definitions.push_back(parse_program("let " + define_name + " = " + value, label, dir,
                                                files, {{}, options.limits}));
            if (definitions.back().size() != 1)
                throw CompileError(label + ": the value must be one expression");
            evaluator.define(definitions.back().front());
        }
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
