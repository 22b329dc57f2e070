#include "stress/minimise_failing_sequence.hpp"

#include <algorithm>

namespace sandtin {

std::vector<std::size_t> minimise_failing_sequence(
    std::size_t n, const std::function<bool(const std::vector<std::size_t>&)>& fails,
    std::chrono::steady_clock::duration budget) {
    std::vector<std::size_t> current(n);
    for (std::size_t i = 0; i < n; ++i)
        current[i] = i;
    const auto deadline = std::chrono::steady_clock::now() + budget;
    std::size_t chunks = 2;
    while (current.size() >= 2) {
        if (std::chrono::steady_clock::now() > deadline) break;
        chunks = std::min(chunks, current.size());
        const std::size_t size = current.size();
        bool reduced = false;
        // Try each complement (the sequence without one chunk); keep the first that fails.
        for (std::size_t c = 0; c < chunks && !reduced; ++c) {
            const std::size_t begin = c * size / chunks;
            const std::size_t end = (c + 1) * size / chunks;
            std::vector<std::size_t> complement;
            complement.reserve(size - (end - begin));
            complement.insert(complement.end(), current.begin(),
                              current.begin() + static_cast<std::ptrdiff_t>(begin));
            complement.insert(complement.end(), current.begin() + static_cast<std::ptrdiff_t>(end),
                              current.end());
            if (!complement.empty() && fails(complement)) {
                current = std::move(complement);
                chunks = std::max<std::size_t>(chunks - 1, 2);
                reduced = true;
            }
            if (std::chrono::steady_clock::now() > deadline) break;
        }
        if (reduced) continue;
        if (chunks >= current.size()) break;  // single elements cannot be removed: 1-minimal
        chunks = std::min(current.size(), chunks * 2);
    }
    return current;
}

}  // namespace sandtin
