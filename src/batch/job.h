// rt's job once its command line is read, as the steps main() runs in order: choose the
// threads, then read the scene, claim the outputs, render, write and report.
#pragma once

#include <optional>

#include "batch/cli.h"
#include "batch/jobserver.h"

namespace rt {

// The thread count: -j N when given; else, under make's jobserver, one plus the tokens free
// now (no more than the hardware has), held in `jobs`; else one per hardware thread.
// RT_DEBUG=threads prints it.
int choose_threads(const CommandLine& cl, const JobserverAuth& auth,
                   std::optional<JobserverClient>& jobs);

// Reads the scene and, unless -r asks only for its summary, renders it into the claimed
// output files; returns the exit status. Throws rt::Error, and UsageError for a --region
// that the scene's image does not contain.
int run_job(const CommandLine& cl, int threads);

}  // namespace rt
