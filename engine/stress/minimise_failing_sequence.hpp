#pragma once
// Delta debugging (Zeller's ddmin): the smallest subsequence of a failing sequence that still
// fails, found by removing chunks of halving size. The stress runner uses it to turn a failing
// random session into a short reproducing script.

#include <chrono>
#include <cstddef>
#include <functional>
#include <vector>

namespace sandtin {

/// `fails(indices)` replays the elements at those indices (increasing) and says whether the
/// failure reproduces. Starting from all of 0..n-1 (which must fail), returns a subsequence that
/// fails and from which no single chunk at the finest granularity can be removed, or the best
/// found when `budget` runs out. Calls `fails` O(k² log n) times in the worst case for a
/// result of k elements.
std::vector<std::size_t> minimise_failing_sequence(
    std::size_t n, const std::function<bool(const std::vector<std::size_t>&)>& fails,
    std::chrono::steady_clock::duration budget = std::chrono::seconds(120));

}  // namespace sandtin
