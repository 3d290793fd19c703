#include "rtpp/command_line.h"

#include <filesystem>

#include "common/exit_status.h"
#include "common/message_text.h"

namespace rtpp {

const char* usage_text() {
    return R"(usage: rtpp [options] [scene.rts]

Compiles a scene in rt's readable scene language to rt's numeric scene
format. The scene is read from the file named, or from standard input when
it is '-' or absent:  rtpp scene.rts | rt -o scene.ppm

options:
  -o, --output FILE   write the numeric scene to FILE ('-', the default:
                      standard output); nothing is written on an error
  -I, --include DIR   look for included files in DIR after the including
                      file's own directory (repeatable, searched in order)
  -h, --help          print this help and exit
  -V, --version       print the version and exit

exit status: 0 success, 1 scene or input/output error, 2 usage error
)";
}

CommandLine parse_command_line(const std::vector<std::string>& args) {
    CommandLine cl;
    bool have_input = false;
    rt::OptionReader options(args, "oI");
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
        } else if (arg == "-I" || arg == "--include") {
            const std::string dir = take_value();
            if (dir.empty()) throw UsageError{"-I needs a directory"};
            cl.include_dirs.push_back(dir);
        } else if (arg == "-h" || arg == "--help") {
            options.no_value();
            cl.help = true;
        } else if (arg == "-V" || arg == "--version") {
            options.no_value();
            cl.version = true;
        } else {
            options.unknown();
        }
    }
    return cl;
}

SceneOutput::SceneOutput(const CommandLine& cl) {
    if (cl.output == "-") return;
    file_.emplace(cl.output, std::vector<std::filesystem::path>{cl.input == "-" ? "" : cl.input},
                  "the output file");
}

int SceneOutput::write(const std::string& text) {
    if (!file_) return rt::print_to_stdout("rtpp", text);
    file_->write_bytes(text);
    return rt::kExitOk;
}

}  // namespace rtpp
