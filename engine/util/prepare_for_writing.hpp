#pragma once
// Large arrays about to be filled whole, with the kernel told first.
//
// Fresh memory costs a page fault per 4 KiB page on first write. On a virtual machine each
// fault also traps to the hypervisor: on the 2-core reference machine, filling 112 MB of fresh
// memory took 440 ms one page at a time and 18-23 ms after these hints, and a 10^6-vertex
// session touches about 400 MB while it opens. On bare metal the saving is smaller, never a
// loss.

#include <algorithm>
#include <cstddef>
#include <iterator>
#include <vector>

namespace sandtin {

/// Hints that the `bytes` at `data` are about to be written whole: on Linux, backs them with
/// transparent huge pages where the system allows (MADV_HUGEPAGE) and maps them in one call
/// (MADV_POPULATE_WRITE, Linux 5.14) instead of one fault per page. Regions under 2 MiB are
/// left alone (a syscall would cost more than it saves). Only a hint: on other systems, older
/// kernels or memory that is not the process's own mapping it changes nothing but speed, and
/// the bytes' values are never changed.
void prepare_for_writing(void* data, std::size_t bytes);

/// Room for n elements in v, the first n prepared for writing; then fill it (assign, resize,
/// push_back). Grows at least twofold, as push_back does, so that growing a vector one step at a
/// time through it stays amortised O(1); an empty vector gets exactly n. Capacity past n is
/// left to be mapped when it is used: a terrain one vertex past its arrays' capacity would
/// otherwise map twice its size at once.
/// The elements v holds move into the prepared storage: preparing after reserve() would come
/// too late for them (growing a 27 MB pool took 74 ms that way, the copy faulting page by page).
template <class T>
void reserve_for_writing(std::vector<T>& v, std::size_t n) {
    if (v.capacity() >= n) return;
    std::vector<T> grown;
    grown.reserve(std::max(n, 2 * v.capacity()));
    prepare_for_writing(grown.data(), n * sizeof(T));
    grown.insert(grown.end(), std::make_move_iterator(v.begin()), std::make_move_iterator(v.end()));
    v.swap(grown);
}

/// Grows v to n value-initialised (zero) elements in prepared storage; never shrinks. For the
/// per-vertex and per-slot scratch arrays of the walks and edits, which are sized to the whole
/// terrain once and then only read and written where the work is: zeroed page by page, they
/// made the first stamp on a fresh 10^6-point terrain take 159-177 ms instead of 115 ms (about
/// 21 500 page faults).
template <class T>
void grow_zero_filled(std::vector<T>& v, std::size_t n) {
    if (v.size() >= n) return;
    reserve_for_writing(v, n);
    v.resize(n);
}

}  // namespace sandtin
