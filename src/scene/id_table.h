// Shared helpers for the ID tables (primitives, surfaces, lights): each is a constexpr array
// of rows sorted by ID and searched by bisection, as the original's author wished his was.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>

namespace rt {

template <typename Row, std::size_t N>
constexpr bool strictly_sorted_by_id(const std::array<Row, N>& rows) {
    for (std::size_t i = 1; i < N; ++i)
        if (rows[i - 1].id >= rows[i].id) return false;
    return true;
}

template <typename Row, std::size_t N>
const Row* find_by_id(const std::array<Row, N>& rows, int id) {
    const auto* row = std::lower_bound(rows.begin(), rows.end(), id,
                                       [](const Row& r, int wanted) { return r.id < wanted; });
    return row != rows.end() && row->id == id ? row : nullptr;
}

}  // namespace rt
