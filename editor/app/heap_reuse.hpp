#pragma once
// The editor's heap keeps what it frees for the next frame.

namespace sandtin::editor {

/// Tells the C library's allocator to keep freed memory for reuse instead of handing it back to
/// the system at every free. A software Vulkan driver (lavapipe) allocates and frees tens of
/// megabytes of binning and vertex data every frame; with glibc's default trimming, the heap
/// shrinks after each frame and grows again in the next, and every page of it is faulted in
/// and cleared anew: 127-176 ms a frame on the default sandbox with the panels open, against
/// 29 ms (640 x 360) and 62 ms (1280 x 720) with the heap kept (2 cores, Xvfb). Peak memory is
/// unchanged: the same pages are reused rather than returned and taken again. Call once, before any
/// thread starts. Does nothing where the allocator is not glibc's.
void keep_freed_heap_for_reuse();

}  // namespace sandtin::editor
