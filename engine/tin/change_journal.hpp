#pragma once
// The change journal: which vertex ids and triangle slots changed since the last
// take_changes(). The GPU mirror uploads exactly these ranges.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "util/prepare_for_writing.hpp"

namespace sandtin {

/// Half-open range [begin, end) of ids or slots.
struct IdRange {
    std::uint32_t begin = 0;
    std::uint32_t end = 0;
    constexpr std::uint32_t size() const { return end - begin; }
    friend constexpr bool operator==(IdRange, IdRange) = default;
};

/// Sorts and de-duplicates `ids`, then merges consecutive ids into ranges. Ids closer than
/// `max_gap` + 1 are merged too (gap 0 = exact), which a GPU uploader can use to trade a few
/// clean bytes for fewer copy regions.
std::vector<IdRange> merge_into_ranges(std::vector<std::uint32_t> ids, std::uint32_t max_gap = 0);

/// Joins sorted, disjoint ranges whose gap is at most `max_gap` ids (the gap's ids are then
/// covered too), then, while more than `max_ranges` remain, the ranges across the smallest
/// remaining gaps: the fewest extra ids for at most `max_ranges` ranges. An uploader trades a
/// few clean ids for fewer copy regions: scattered edits give thousands of short ranges, and
/// each costs a copy region per buffer.
std::vector<IdRange> coalesce_ranges(const std::vector<IdRange>& ranges, std::uint32_t max_gap,
                                     std::size_t max_ranges = SIZE_MAX);

/// Total number of ids covered by the ranges.
std::uint64_t count_in_ranges(const std::vector<IdRange>& ranges);

/// A set of dirty ids with O(1) insertion and no duplicates.
class DirtySet {
  public:
    void mark(std::uint32_t id) {
        if (id >= flags_.size()) [[unlikely]]
            grow(id);
        if (!flags_[id]) {
            flags_[id] = 1;
            list_.push_back(id);
        }
    }
    bool contains(std::uint32_t id) const { return id < flags_.size() && flags_[id]; }
    const std::vector<std::uint32_t>& ids() const { return list_; }
    bool empty() const { return list_.empty(); }
    /// Returns the ids (unsorted) and clears the set in O(count).
    std::vector<std::uint32_t> take() {
        for (std::uint32_t id : list_)
            flags_[id] = 0;
        std::vector<std::uint32_t> out;
        out.swap(list_);
        return out;
    }
    /// Empties the set in O(count), keeping its buffers (the walks clear theirs on every call).
    void clear() {
        for (std::uint32_t id : list_)
            flags_[id] = 0;
        list_.clear();
    }

  private:
    /// Out of line, so that mark() stays small enough to inline in the walks.
    [[gnu::noinline]] void grow(std::uint32_t id) {
        grow_zero_filled(flags_, static_cast<std::size_t>(id) + 1 + flags_.size() / 2);
    }

    std::vector<std::uint8_t> flags_;
    std::vector<std::uint32_t> list_;
};

/// What changed since the previous take_changes().
struct ChangeSet {
    std::vector<IdRange> vertices;  ///< dirty VertexId ranges (born, died or any attribute changed)
    std::vector<IdRange>
        triangles;  ///< dirty TriangleSlot ranges (born, died, re-pointed or re-flagged)
    std::uint32_t vertex_capacity = 0;  ///< size of every per-vertex array
    std::uint32_t slot_capacity = 0;    ///< size of the triangle buffer
    std::uint32_t live_vertices = 0;
    std::uint32_t live_slots = 0;  ///< slots holding a finite triangle
    std::uint32_t dead_slots = 0;  ///< slot_capacity - live_slots: free or outside the domain
    bool empty() const { return vertices.empty() && triangles.empty(); }
};

}  // namespace sandtin
