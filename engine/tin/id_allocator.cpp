#include "tin/id_allocator.hpp"

#include <iterator>

namespace sandtin {

std::uint32_t IdAllocator::allocate() {
    if (!free_.empty()) {
        const std::uint32_t id = free_.back();
        free_.pop_back();
        return id;
    }
    return capacity_++;
}

void IdAllocator::release(std::uint32_t id) {
    if (deferred_) {
        pending_.push_back(id);
    } else {
        free_.push_back(id);
    }
}

void IdAllocator::flush_deferred() {
    // Hand out the lowest ids first: keeps the arrays dense at the front.
    free_.insert(free_.end(), pending_.rbegin(), pending_.rend());
    pending_.clear();
}

void IdAllocator::flush_deferred(std::size_t count) {
    if (count >= pending_.size()) {
        flush_deferred();
        return;
    }
    const auto end = pending_.begin() + static_cast<std::ptrdiff_t>(count);
    free_.insert(free_.end(), std::make_reverse_iterator(end), pending_.rend());
    pending_.erase(pending_.begin(), end);
}

void IdAllocator::restore(std::uint32_t capacity, std::vector<std::uint32_t> free_list) {
    capacity_ = capacity;
    free_ = std::move(free_list);
    pending_.clear();
}

void IdAllocator::clear() {
    capacity_ = 0;
    free_.clear();
    pending_.clear();
}

}  // namespace sandtin
