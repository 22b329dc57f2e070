#pragma once
// Crash-safe file replacement: the data goes to a temporary file in the same directory, is
// flushed to disk, and then renamed over the target. A crash at any point leaves either the
// old file or the new one, never a mixture.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace sandtin {

/// Test hook: called after this many bytes of the temporary file were written; returning
/// false aborts the save as if the process had died there (the temporary is left behind, the
/// target is untouched).
using WriteInterruption = std::function<bool(std::size_t bytes_written)>;

/// Writes `data` to `path` atomically. Throws std::runtime_error naming the path and the
/// system error on failure; the previous file (if any) is then unchanged. A symbolic link at
/// `path` is followed: the file it leads to is replaced, the link stays. A replaced file keeps
/// its permission bits; a new one gets 0666 less the umask.
void write_file_atomically(const std::filesystem::path& path, std::span<const std::uint8_t> data,
                           const WriteInterruption& interruption = {});

struct FileToWrite {
    std::filesystem::path path;
    std::span<const std::uint8_t> data;
};

/// Writes several files that belong together (a mesh and its material and textures) as one
/// save: each goes to its temporary first, and only when all of them were written are they
/// renamed into place. When writing any of them fails (a full disk), no target has changed
/// and no temporary is left. Links, devices and permissions as for write_file_atomically.
/// (The renames are not one atomic step: a crash between two leaves some replaced.)
void write_files_atomically(std::span<const FileToWrite> files);

/// Throws std::runtime_error naming the problem when write_file_atomically could not write
/// `path` now: its folder does not exist, is not a folder, or is not writable. For commands to
/// ask before long work whose result they then save.
void check_writable(const std::filesystem::path& path);

/// Throws std::runtime_error when `output` is the same file as `input` (the same path, or
/// another name for it: a link, a relative path), which a command reads as its `role` (for
/// example "the script being run") and a save to `output` would destroy. Nothing is thrown
/// when either does not exist.
void check_not_overwriting(const std::filesystem::path& output, const std::filesystem::path& input,
                           const std::string& role);

/// Reads a whole file. Throws std::runtime_error naming the path when it cannot be read or is
/// larger than `max_bytes`.
std::vector<std::uint8_t> read_file(const std::filesystem::path& path,
                                    std::uint64_t max_bytes = 1ull << 34);

}  // namespace sandtin
