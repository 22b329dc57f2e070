#pragma once
// Marks for the ids a walk has visited, emptied in O(1): each mark holds the number of the walk
// that set it, and starting a new walk only increments that number. For walks that only ask
// "seen already?" (DirtySet also keeps the list of ids, and empties it id by id).

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "util/prepare_for_writing.hpp"

namespace sandtin {

class VisitMarks {
  public:
    /// Forgets every mark. O(1), except once every 2^32 walks (the counter wraps).
    void clear() {
        if (++walk_ == 0) {
            std::fill(marks_.begin(), marks_.end(), 0u);
            walk_ = 1;
        }
    }
    bool contains(std::uint32_t id) const { return id < marks_.size() && marks_[id] == walk_; }
    void mark(std::uint32_t id) {
        if (id >= marks_.size()) [[unlikely]]
            grow(id);
        marks_[id] = walk_;
    }
    /// Room for ids below `count` at once (a walk that knows its id range calls this first,
    /// instead of growing step by step as it meets larger ids).
    void reserve_ids(std::size_t count) { grow_zero_filled(marks_, count); }
    /// Marks `id`; true when it was not marked yet.
    bool insert(std::uint32_t id) {
        if (contains(id)) return false;
        mark(id);
        return true;
    }

  private:
    [[gnu::noinline]] void grow(std::uint32_t id) {
        grow_zero_filled(marks_, static_cast<std::size_t>(id) + 1 + marks_.size() / 2);
    }

    std::vector<std::uint32_t> marks_;
    std::uint32_t walk_ = 1;
};

}  // namespace sandtin
