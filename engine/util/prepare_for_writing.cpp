#include "util/prepare_for_writing.hpp"

#include <cstdint>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace sandtin {

void prepare_for_writing(void* data, std::size_t bytes) {
#if defined(__linux__)
    constexpr std::size_t kWorthIt = std::size_t{2} << 20;
    constexpr std::uintptr_t kPage = 4096;
    if (data == nullptr || bytes < kWorthIt) return;
    // madvise takes whole pages: the pages wholly inside the region.
    const auto begin = (reinterpret_cast<std::uintptr_t>(data) + kPage - 1) & ~(kPage - 1);
    const auto end = (reinterpret_cast<std::uintptr_t>(data) + bytes) & ~(kPage - 1);
    if (end <= begin) return;
    void* const first = reinterpret_cast<void*>(begin);
    const std::size_t length = end - begin;
#if defined(MADV_HUGEPAGE)
    (void)madvise(first, length, MADV_HUGEPAGE);
#endif
#if defined(MADV_POPULATE_WRITE)
    (void)madvise(first, length, MADV_POPULATE_WRITE);
#endif
#else
    (void)data;
    (void)bytes;
#endif
}

}  // namespace sandtin
