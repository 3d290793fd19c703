// What the hierarchies' builds share for doing a loop on several threads without changing
// its result: the loop's range cut into parts that depend only on its length and the thread
// count, each written by one thread, into arrays whose elements are not zeroed first
// (UninitializedAllocator, rt/large_pages.h: the threads that fill them are the first to
// touch their pages, at the same time).
#pragma once

#include <algorithm>
#include <cstddef>
#include <exception>
#include <memory>
#include <new>
#include <thread>
#include <utility>
#include <vector>

#include "rt/large_pages.h"

namespace rt {

// Calls body(begin, end) on consecutive parts of [0, count), at most one per thread and none
// shorter than `minimum_part`, on this thread and up to threads - 1 others, and returns when
// all are done (rethrowing the first part's failure, if any). A body that writes only what
// belongs to its own part makes the same result on any number of threads.
template <class Body>
void parallel_parts(std::size_t count, int threads, std::size_t minimum_part, Body&& body) {
    const std::size_t parts =
        std::clamp<std::size_t>(count / std::max<std::size_t>(minimum_part, 1), 1,
                                static_cast<std::size_t>(std::max(threads, 1)));
    if (parts == 1) {
        body(std::size_t{0}, count);
        return;
    }
    const auto begin = [&](std::size_t part) { return count / parts * part; };
    const auto end = [&](std::size_t part) { return part + 1 == parts ? count : begin(part + 1); };
    std::vector<std::exception_ptr> failures(parts);
    {
        std::vector<std::jthread> helpers;
        helpers.reserve(parts - 1);
        for (std::size_t part = 1; part < parts; ++part)
            helpers.emplace_back([&, part] {
                try {
                    body(begin(part), end(part));
                } catch (...) {
                    failures[part] = std::current_exception();
                }
            });
        try {
            body(begin(0), end(0));
        } catch (...) {
            failures[0] = std::current_exception();
        }
    }  // the helpers join here
    for (const std::exception_ptr& failure : failures)
        if (failure) std::rethrow_exception(failure);
}

}  // namespace rt
