#include "rtpp/command_line.h"

#include <filesystem>
#include <optional>

#include "common/exit_status.h"
#include "common/message_text.h"

namespace rtpp {

const char* usage_text() {
    return R"(usage: rtpp [options] [scene.rts | scene.nff]

Compiles a scene in rt's readable scene language, or translates one in NFF
(the Neutral File Format of the Standard Procedural Databases), to rt's
numeric scene format. The scene is read from the file named, or from
standard input when it is '-' or absent:  rtpp scene.rts | rt -o scene.ppm
A name ending in .nff is NFF:  rtpp balls.nff | rt -o balls.png

options:
  -o, --output FILE   write the numeric scene to FILE ('-', the default:
                      standard output); nothing is written on an error
      --from FORMAT   read the input as FORMAT, whatever its name: 'rts'
                      (the readable language, the default) or 'nff'
                      (for standard input: rtpp --from nff < balls.nff)
  -I, --include DIR   look for included files in DIR after the including
                      file's own directory (repeatable, searched in order)
  -D, --define NAME=VALUE
                      bind NAME to VALUE (an expression of the language)
                      before the scene runs; a top-level let of NAME in the
                      scene takes this value instead (repeatable):
                      rtpp -D frame=12 ball.rts
  -h, --help          print this help and exit
  -V, --version       print the version and exit

exit status: 0 success, 1 scene or input/output error, 2 usage error
)";
}

namespace {

bool ends_with_nff(const std::string& name) {
    if (name.size() < 4) return false;
    std::string tail = name.substr(name.size() - 4);
    for (char& c : tail) c = static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
    return tail == ".nff";
}

}  // namespace

CommandLine parse_command_line(const std::vector<std::string>& args) {
    CommandLine cl;
    bool have_input = false;
    std::optional<InputFormat> from;
    rt::OptionReader options(args, "oID");
    while (options.next()) {
        const std::string& arg = options.argument();
        if (!options.is_option()) {
            if (have_input)
                throw UsageError{"more than one scene given (" +
                                 rt::quote_token(cl.input, rt::kShowWhole) + " and " +
                                 rt::quote_token(arg, rt::kShowWhole) + ")"};
            cl.input = arg;
            have_input = true;
            continue;
        }
        const auto take_value = [&] { return options.value(); };
        if (arg == "-o" || arg == "--output") {
            cl.output = take_value();
            if (cl.output.empty()) throw UsageError{"-o needs a file name"};
        } else if (arg == "--from") {
            const std::string format = take_value();
            if (format == "rts")
                from = InputFormat::rts;
            else if (format == "nff")
                from = InputFormat::nff;
            else
                throw UsageError{"--from takes 'rts' or 'nff', got " +
                                 rt::quote_token(format, rt::kShowWhole)};
        } else if (arg == "-I" || arg == "--include") {
            const std::string dir = take_value();
            if (dir.empty()) throw UsageError{"-I needs a directory"};
            cl.include_dirs.push_back(dir);
        } else if (arg == "-D" || arg == "--define") {
            const std::string definition = take_value();
            const std::size_t eq = definition.find('=');
            if (eq == std::string::npos || eq == 0)
                throw UsageError{"-D expects NAME=VALUE (such as -D frame=12), got " +
                                 rt::quote_token(definition, rt::kShowWhole)};
            cl.defines.emplace_back(definition.substr(0, eq), definition.substr(eq + 1));
        } else if (arg == "-h" || arg == "--help") {
            options.no_value();
            cl.help = true;
        } else if (arg == "-V" || arg == "--version") {
            options.no_value();
            cl.version = true;
        } else {
            options.unknown(usage_text());
        }
    }
    cl.from = from.value_or(ends_with_nff(cl.input) ? InputFormat::nff : InputFormat::rts);
    return cl;
}

SceneOutput::SceneOutput(const CommandLine& cl) {
    if (cl.output == "-") return;
    file_.emplace(cl.output,
                  std::vector<rt::InputFile>{{cl.input == "-" ? "" : cl.input, "the scene file"}},
                  "the output file", "rtpp");
}

int SceneOutput::write(const std::string& text) {
    if (!file_) return rt::print_to_stdout("rtpp", text);
    file_->write_bytes(text);
    return rt::kExitOk;
}

int SceneOutput::write(rt::Spool& text) {
    if (!file_) {
        int status = rt::kExitOk;
        text.each_piece([&](std::string_view piece) {
            if (status == rt::kExitOk) status = rt::print_to_stdout("rtpp", piece);
        });
        return status;
    }
    text.each_piece([&](std::string_view piece) { file_->append(piece); });
    file_->commit();
    return rt::kExitOk;
}

}  // namespace rtpp
