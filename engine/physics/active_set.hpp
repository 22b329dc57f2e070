#pragma once
// The vertices the relaxation still has to look at (seed 000 §7.2, list L_E): a vertex is
// active while it or a neighbour changed within the last `quiet_limit` iterations. A terrain at
// rest has an empty set and costs nothing.

#include <cstdint>
#include <span>
#include <vector>

namespace sandtin {

class ActiveSet {
  public:
    /// Makes v active with a fresh quiet count.
    void activate(std::uint32_t v) {
        ensure(v);
        quiet_[v] = 0;
        if (!flag_[v]) {
            flag_[v] = 1;
            list_.push_back(v);
        }
    }
    void activate(std::span<const std::uint32_t> vs) {
        for (std::uint32_t v : vs)
            activate(v);
    }
    bool contains(std::uint32_t v) const { return v < flag_.size() && flag_[v]; }
    const std::vector<std::uint32_t>& list() const { return list_; }
    std::size_t size() const { return list_.size(); }
    bool empty() const { return list_.empty(); }

    /// After an iteration: vertices that did not change count one more quiet iteration and
    /// leave after `quiet_limit` of them; the order of the rest is kept.
    void age(std::span<const std::uint8_t> changed, int quiet_limit) {
        std::size_t out = 0;
        for (std::uint32_t v : list_) {
            const bool moved = v < changed.size() && changed[v];
            if (moved) {
                quiet_[v] = 0;
            } else if (++quiet_[v] >= quiet_limit) {
                flag_[v] = 0;
                continue;
            }
            list_[out++] = v;
        }
        list_.resize(out);
    }
    /// Drops an id (the vertex died).
    void remove(std::uint32_t v) {
        if (!contains(v)) return;
        flag_[v] = 0;
        std::erase(list_, v);
    }
    void clear() {
        for (std::uint32_t v : list_)
            flag_[v] = 0;
        list_.clear();
    }

  private:
    void ensure(std::uint32_t v) {
        if (v >= flag_.size()) {
            flag_.resize(static_cast<std::size_t>(v) + 1 + flag_.size() / 2, 0);
            quiet_.resize(flag_.size(), 0);
        }
    }
    std::vector<std::uint32_t> list_;
    std::vector<std::uint8_t> flag_;
    std::vector<std::uint8_t> quiet_;
};

}  // namespace sandtin
