#pragma once
// The vertices the relaxation still has to look at (seed 000 §7.2, list L_E): a vertex is
// active while it or a neighbour changed within the last `quiet_limit` iterations. A terrain at
// rest has an empty set and costs nothing.
//
// Membership is a bitmap (one bit per vertex id), so the Jacobi schedule can rebuild the list
// in vertex-id order by scanning 64 ids per word in parallel (TalusSolver); the list itself
// keeps the order of activation otherwise (the sequential schedule's Gauss-Seidel order).

#include <cstdint>
#include <span>
#include <vector>

namespace sandtin {

class TalusSolver;

class ActiveSet {
  public:
    /// Makes v active with a fresh quiet count.
    void activate(std::uint32_t v) {
        ensure(v);
        quiet_[v] = 0;
        const std::uint64_t bit = std::uint64_t{1} << (v & 63u);
        std::uint64_t& word = bits_[v >> 6];
        if ((word & bit) == 0) {
            word |= bit;
            list_.push_back(v);
        }
    }
    void activate(std::span<const std::uint32_t> vs) {
        for (std::uint32_t v : vs)
            activate(v);
    }
    bool contains(std::uint32_t v) const {
        return (v >> 6) < bits_.size() && ((bits_[v >> 6] >> (v & 63u)) & 1u) != 0;
    }
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
                bits_[v >> 6] &= ~(std::uint64_t{1} << (v & 63u));
                continue;
            }
            list_[out++] = v;
        }
        list_.resize(out);
    }
    /// Drops ids (their vertices died), keeping the order of the rest; ids that are not
    /// members are ignored. One pass over the list for the whole batch: a stamp removes
    /// hundreds of vertices from a groove that is still settling, and erasing them one by one
    /// was O(removed x active) (at 10^6 points a third of each relaxation step).
    void remove(std::span<const std::uint32_t> vs) {
        bool any = false;
        for (std::uint32_t v : vs) {
            if (!contains(v)) continue;
            bits_[v >> 6] &= ~(std::uint64_t{1} << (v & 63u));
            any = true;
        }
        if (any) std::erase_if(list_, [this](std::uint32_t v) { return !contains(v); });
    }
    /// Renames every member v to new_id[v] (ids must be in range and distinct), keeping the
    /// list order and the quiet counts: the relaxation continues exactly as before in the new
    /// numbering. Members whose new id is `drop` leave.
    void renumber(std::span<const std::uint32_t> new_id, std::uint32_t drop) {
        std::vector<std::uint32_t> list;
        std::vector<std::uint8_t> quiet;
        list.reserve(list_.size());
        for (std::uint32_t v : list_) {
            bits_[v >> 6] = 0;
            const std::uint32_t w = new_id[v];
            if (w == drop) continue;
            list.push_back(w);
            quiet.push_back(quiet_[v]);
        }
        list_.clear();
        for (std::size_t k = 0; k < list.size(); ++k) {
            activate(list[k]);
            quiet_[list[k]] = quiet[k];
        }
    }
    /// Room for ids below n now (a physics being created), so that activating them later
    /// never grows the arrays in the middle of an edit.
    void reserve_ids(std::size_t n) {
        if (n > quiet_.size()) {
            quiet_.resize(n, 0);
            bits_.resize((n + 63) / 64, 0);
        }
    }
    void clear() {
        for (std::uint32_t v : list_)
            bits_[v >> 6] = 0;
        list_.clear();
    }

  private:
    // The Jacobi schedule ages and rebuilds the set word by word on several threads.
    friend class TalusSolver;

    void ensure(std::uint32_t v) {
        if (v >= quiet_.size()) reserve_ids(static_cast<std::size_t>(v) + 1 + quiet_.size() / 2);
    }
    std::vector<std::uint32_t> list_;
    std::vector<std::uint64_t> bits_;  ///< membership, bit v & 63 of word v >> 6
    std::vector<std::uint8_t> quiet_;  ///< quiet iterations so far, per vertex id
};

}  // namespace sandtin
