// Whether resident memory measures what rt allocates in this build: not under ASan, whose
// shadow memory and quarantine dwarf it. Tests that bound memory check only where it does.
// The sanitizer build compiles rt instrumented and the tests not (CMakeLists.txt's
// RT_SANITIZE), and tells them so with RT_TESTS_UNDER_ASAN.
#pragma once

#if defined(RT_TESTS_UNDER_ASAN) || defined(__SANITIZE_ADDRESS__)
#define RT_MEASURES_MEMORY 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define RT_MEASURES_MEMORY 0
#endif
#endif
#ifndef RT_MEASURES_MEMORY
#define RT_MEASURES_MEMORY 1
#endif
