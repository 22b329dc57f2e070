#include "tin/change_journal.hpp"

#include <algorithm>

namespace sandtin {

std::vector<IdRange> merge_into_ranges(std::vector<std::uint32_t> ids, std::uint32_t max_gap) {
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    std::vector<IdRange> ranges;
    for (std::uint32_t id : ids) {
        if (!ranges.empty() && static_cast<std::uint64_t>(id) <=
                                   static_cast<std::uint64_t>(ranges.back().end) + max_gap) {
            ranges.back().end = id + 1;
        } else {
            ranges.push_back({id, id + 1});
        }
    }
    return ranges;
}

std::uint64_t count_in_ranges(const std::vector<IdRange>& ranges) {
    std::uint64_t n = 0;
    for (const IdRange& r : ranges)
        n += r.size();
    return n;
}

}  // namespace sandtin
