#include "tin/detail/half_edge_twins.hpp"

#include <algorithm>

#include "util/prepare_for_writing.hpp"

namespace sandtin::detail {

TwinProblem pair_half_edges(std::span<const std::array<std::uint32_t, 3>> triangles,
                            std::uint32_t vertex_count, std::vector<std::uint32_t>& twin) {
    const std::size_t half_edges = 3 * triangles.size();
    auto from = [&](std::size_t k) { return triangles[k / 3][(k % 3 + 1) % 3]; };
    auto to = [&](std::size_t k) { return triangles[k / 3][(k % 3 + 2) % 3]; };

    // Rows of half-edges by the vertex they leave, each entry (reached vertex << 32 | half-edge)
    // so that sorting a row orders it by the vertex reached.
    std::vector<std::uint32_t> row(static_cast<std::size_t>(vertex_count) + 1, 0);
    for (std::size_t k = 0; k < half_edges; ++k) {
        if (from(k) >= vertex_count) return TwinProblem::CornerOutOfRange;
        ++row[from(k) + 1];
    }
    for (std::size_t v = 0; v < vertex_count; ++v)
        row[v + 1] += row[v];
    std::vector<std::uint64_t> leaving;
    reserve_for_writing(leaving, half_edges);
    leaving.resize(half_edges);
    {
        std::vector<std::uint32_t> next(row.begin(), row.end() - 1);
        for (std::size_t k = 0; k < half_edges; ++k)
            leaving[next[from(k)]++] = (std::uint64_t{to(k)} << 32) | k;
    }
    for (std::size_t v = 0; v < vertex_count; ++v) {
        const auto begin = leaving.begin() + row[v];
        const auto end = leaving.begin() + row[v + 1];
        std::sort(begin, end);
        // (adjacent_find, not `it + 1 < end`: on an empty soup begin is a null pointer, and
        // adding 1 to it is undefined; clang's UBSan says so.)
        const auto same_target = [](std::uint64_t a, std::uint64_t b) {
            return a >> 32 == b >> 32;
        };
        if (std::adjacent_find(begin, end, same_target) != end)
            return TwinProblem::RepeatedHalfEdge;
    }

    reserve_for_writing(twin, half_edges);
    twin.resize(half_edges);
    for (std::size_t k = 0; k < half_edges; ++k) {
        // The twin leaves to(k) and reaches from(k).
        const std::uint32_t v = to(k);
        const std::uint64_t key = std::uint64_t{from(k)} << 32;
        const auto end = leaving.begin() + row[v + 1];
        const auto it = std::lower_bound(leaving.begin() + row[v], end, key);
        if (it == end || (*it >> 32) != from(k)) return TwinProblem::MissingTwin;
        twin[k] = static_cast<std::uint32_t>(*it);
    }
    return TwinProblem::None;
}

}  // namespace sandtin::detail
