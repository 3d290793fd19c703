// libFuzzer target: the scene reader plus a tiny render, under ASan and UBSan. Built with
// -DRT_FUZZ=ON by clang; see tests/fuzz/README.md for the campaign.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "fuzz_one.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto outcome =
        rt_fuzz::fuzz_one({reinterpret_cast<const char*>(data), size}, RT_SOURCE_DIR "/scenes");
    if (!outcome.placed) {
        std::fprintf(stderr, "error without a place: %s\n", outcome.error.c_str());
        std::abort();
    }
    return 0;
}
