#include "tin/change_journal.hpp"

#include <algorithm>

namespace sandtin {

namespace {

/// Joins ranges whose gap is at most `max_gap`; with `budget` > 0, also up to `budget` of the
/// gaps equal to max_gap + 1 (left to right), consuming the budget.
std::vector<IdRange> join_gaps(const std::vector<IdRange>& ranges, std::uint64_t max_gap,
                               std::size_t budget) {
    std::vector<IdRange> out;
    out.reserve(ranges.size());
    for (const IdRange& r : ranges) {
        if (!out.empty()) {
            const std::uint64_t gap = std::uint64_t{r.begin} - out.back().end;
            const bool tie = gap == max_gap + 1 && budget > 0;
            if (gap <= max_gap || tie) {
                if (tie) --budget;
                out.back().end = std::max(out.back().end, r.end);
                continue;
            }
        }
        out.push_back(r);
    }
    return out;
}

}  // namespace

std::vector<IdRange> merge_into_ranges(std::vector<std::uint32_t> ids, std::uint32_t max_gap) {
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    std::vector<IdRange> exact;
    for (std::uint32_t id : ids) {
        if (!exact.empty() && id == exact.back().end) {
            ++exact.back().end;
        } else {
            exact.push_back({id, id + 1});
        }
    }
    return max_gap == 0 ? exact : join_gaps(exact, max_gap, 0);
}

std::vector<IdRange> coalesce_ranges(const std::vector<IdRange>& ranges, std::uint32_t max_gap,
                                     std::size_t max_ranges) {
    std::vector<IdRange> out = join_gaps(ranges, max_gap, 0);
    if (out.size() <= max_ranges || max_ranges == 0) return out;
    // Join the (size - max_ranges) smallest gaps: every gap below the k-th smallest, and as
    // many gaps equal to it as are still needed.
    std::vector<std::uint64_t> gaps(out.size() - 1);
    for (std::size_t i = 1; i < out.size(); ++i)
        gaps[i - 1] = std::uint64_t{out[i].begin} - out[i - 1].end;
    const std::size_t joins = out.size() - max_ranges;
    std::nth_element(gaps.begin(), gaps.begin() + static_cast<std::ptrdiff_t>(joins - 1),
                     gaps.end());
    const std::uint64_t kth = gaps[joins - 1];
    const auto below = static_cast<std::size_t>(
        std::count_if(gaps.begin(), gaps.end(), [&](std::uint64_t g) { return g < kth; }));
    return join_gaps(out, kth - 1, joins - below);
}

std::uint64_t count_in_ranges(const std::vector<IdRange>& ranges) {
    std::uint64_t n = 0;
    for (const IdRange& r : ranges)
        n += r.size();
    return n;
}

}  // namespace sandtin
