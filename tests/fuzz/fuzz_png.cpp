// libFuzzer target: rt_fuzz::png_case (fuzz_cases.h) under ASan and UBSan. Built with
// -DRT_FUZZ=ON by clang; see tests/fuzz/README.md for the campaign.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "fuzz_cases.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string problem = rt_fuzz::png_case({reinterpret_cast<const char*>(data), size});
    if (!problem.empty()) {
        std::fprintf(stderr, "finding: %s\n", problem.c_str());
        std::abort();
    }
    return 0;
}
