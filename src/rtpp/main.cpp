// rtpp: compiles rt's readable scene language to its numeric scene format.
#include <ostream>

#include "common/exit_status.h"
#include "common/interrupt.h"
#include "common/spool.h"
#include "rtpp/command_line.h"
#include "rtpp/compiler.h"
#include "rtpp/nff.h"

int main(int argc, char** argv) {
    return rt::run_guarded({"rtpp"}, [&] {
        const rtpp::CommandLine cl = rtpp::parse_command_line({argv + 1, argv + argc});
        if (cl.help) return rt::print_to_stdout("rtpp", rtpp::usage_text());
        if (cl.version) return rt::print_to_stdout("rtpp", "rtpp " RT_VERSION "\n");
        rt::interrupt::install_handlers("rtpp");  // a signal removes the temporary file
        rtpp::SceneOutput output(cl);
        if (cl.from == rtpp::InputFormat::nff) {
            // Spooled: written only once complete, in bounded memory (src/common/spool.h).
            rt::Spool spool;
            std::ostream out(&spool);
            rtpp::translate_nff_file(cl.input, out);
            return output.write(spool);
        }
        rtpp::CompileOptions options;
        for (const std::string& dir : cl.include_dirs) options.include_dirs.emplace_back(dir);
        options.defines = cl.defines;
        return output.write(rtpp::compile_file(cl.input, options));
    });
}
