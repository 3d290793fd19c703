// rt: reads a scene, traces it and writes a PPM, PNG or PFM image (section 1.10.3 of the
// original). main() parses the command line and hands over to rt's job (batch/job.h);
// run_guarded turns whatever goes wrong into a message and an exit status.
#include <optional>

#include "batch/cli.h"
#include "batch/job.h"
#include "batch/jobserver.h"
#include "common/exit_status.h"
#include "common/interrupt.h"

int main(int argc, char** argv) {
    // Declared before anything that can fail, so its tokens go back on every exit path (after
    // the message saying why).
    std::optional<rt::JobserverClient> jobs;
    return rt::run_guarded({"rt"}, [&] {
        const rt::CommandLine cl = rt::parse_command_line({argv + 1, argv + argc});
        if (cl.help) return rt::print_to_stdout("rt", rt::usage_text());
        if (cl.version) return rt::print_to_stdout("rt", "rt " RT_VERSION "\n");
        // The jobserver is read before rt opens any file (see JobserverClient).
        const rt::JobserverAuth auth = rt::jobserver_from_environment();
        if (auth.dry_run) return rt::kExitOk;  // make -n, -q and -t run '+' lines too
        rt::interrupt::install_handlers();
        return rt::run_job(cl, rt::choose_threads(cl, auth, jobs));
    });
}
