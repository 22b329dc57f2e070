#include "heap_reuse.hpp"

#include <cstdlib>  // defines __GLIBC__ on glibc

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace sandtin::editor {

void keep_freed_heap_for_reuse() {
#if defined(__GLIBC__)
    // Free memory at the top of the heap is returned to the system only past 512 MiB, and each
    // growth takes 64 MiB more than asked, so a frame's buffers land on pages the last frame
    // already faulted in. (Setting either also stops glibc's dynamic mmap threshold, which is
    // what let the per-frame buffers bounce between the heap and fresh mappings.)
    constexpr int kMiB = 1024 * 1024;
    mallopt(M_TRIM_THRESHOLD, 512 * kMiB);
    mallopt(M_TOP_PAD, 64 * kMiB);
#endif
}

}  // namespace sandtin::editor
