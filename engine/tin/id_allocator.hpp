#pragma once
// Dense integer ids with a free list. When deferred recycling is on, a freed id is only handed
// out again after flush_deferred(): the change journal calls it once its readers have seen the
// deaths, so a consumer never sees an id die and be reborn within one batch of changes.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace sandtin {

class IdAllocator {
  public:
    explicit IdAllocator(bool deferred_recycling = true) : deferred_(deferred_recycling) {}

    /// Returns a free id, growing capacity() when none is free.
    std::uint32_t allocate();
    void release(std::uint32_t id);
    /// Makes ids released since the last flush available again.
    void flush_deferred();
    /// Makes the `count` oldest of the ids released since the last flush available again (the
    /// journal recycles an id once every reader has seen it die).
    void flush_deferred(std::size_t count);

    /// One past the largest id ever handed out; arrays indexed by id have this size.
    std::uint32_t capacity() const { return capacity_; }
    std::uint32_t live() const {
        return capacity_ - static_cast<std::uint32_t>(free_.size() + pending_.size());
    }
    /// Free ids in the order they will be handed out (last first), for session files.
    const std::vector<std::uint32_t>& free_list() const { return free_; }
    const std::vector<std::uint32_t>& pending_list() const { return pending_; }
    /// Rebuilds the allocator state exactly (used when loading sessions).
    void restore(std::uint32_t capacity, std::vector<std::uint32_t> free_list);
    void clear();

  private:
    bool deferred_;
    std::uint32_t capacity_ = 0;
    std::vector<std::uint32_t> free_;
    std::vector<std::uint32_t> pending_;
};

}  // namespace sandtin
