#include "util/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>
#include <utility>

#include "util/prepare_for_writing.hpp"

namespace sandtin {

namespace {

[[noreturn]] void fail(const std::string& what, const std::filesystem::path& path, int error) {
    throw std::runtime_error(what + " '" + path.string() + "': " + std::strerror(error));
}

class FileDescriptor {
  public:
    explicit FileDescriptor(int fd) : fd_(fd) {}
    ~FileDescriptor() {
        if (fd_ >= 0) ::close(fd_);
    }
    FileDescriptor(const FileDescriptor&) = delete;
    FileDescriptor& operator=(const FileDescriptor&) = delete;
    FileDescriptor(FileDescriptor&& other) noexcept : fd_(other.release()) {}
    FileDescriptor& operator=(FileDescriptor&&) = delete;
    int get() const { return fd_; }
    int release() {
        const int fd = fd_;
        fd_ = -1;
        return fd;
    }

  private:
    int fd_;
};

/// The file a save must replace: `path`, or the file a symbolic link at `path` leads to
/// (followed link by link, as open() would), so that saving through a link updates the file
/// it points to rather than replacing the link with a copy.
std::filesystem::path save_target(const std::filesystem::path& path) {
    std::filesystem::path target = path;
    for (int hops = 0; hops < 40; ++hops) {
        std::error_code ec;
        if (!std::filesystem::is_symlink(std::filesystem::symlink_status(target, ec))) {
            return target;
        }
        const std::filesystem::path next = std::filesystem::read_symlink(target, ec);
        if (ec) fail("cannot follow the link", target, ec.value());
        target = next.is_absolute() ? next : target.parent_path() / next;
    }
    fail("cannot follow the links at", path, ELOOP);
}

/// Throws when something other than a regular file stands at `target` (already resolved by
/// save_target): a save replaces the file by renaming over it, which would delete a folder's
/// place, a device (as root, -o /dev/null would replace the system's), a pipe or a socket.
void require_regular_or_absent(const std::filesystem::path& path,
                               const std::filesystem::path& target) {
    std::error_code ec;
    const std::filesystem::file_status st = std::filesystem::symlink_status(target, ec);
    if (!std::filesystem::exists(st) || std::filesystem::is_regular_file(st)) return;
    const std::string what = std::filesystem::is_directory(st)        ? "a folder"
                             : std::filesystem::is_character_file(st) ? "a character device"
                             : std::filesystem::is_block_file(st)     ? "a block device"
                             : std::filesystem::is_fifo(st)           ? "a named pipe"
                             : std::filesystem::is_socket(st)         ? "a socket"
                                                                      : "not a regular file";
    throw std::runtime_error("cannot write '" + path.string() +
                             "': " + (target == path ? "it" : "'" + target.string() + "'") +
                             " is " + what + ", and a save only replaces regular files");
}

/// A new, empty temporary file beside `target`, created with mode 0666 less the umask, as
/// any new file of the user's would be (mkstemp would force 0600). Its name starts with the
/// target's, cut short so that it stays a legal name (255 bytes) whatever the target's length.
std::pair<FileDescriptor, std::filesystem::path> create_temporary(
    const std::filesystem::path& dir, const std::filesystem::path& target) {
    static std::atomic<std::uint64_t> counter{0};
    for (int attempt = 0; attempt < 100; ++attempt) {
        constexpr std::size_t kNameKept = 160;
        const std::filesystem::path temp =
            dir / ("." + target.filename().string().substr(0, kNameKept) + ".tmp-" +
                   std::to_string(::getpid()) + "-" + std::to_string(counter.fetch_add(1)));
        const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd >= 0) return {FileDescriptor(fd), temp};
        if (errno != EEXIST) fail("cannot create a temporary file next to", target, errno);
    }
    fail("cannot create a temporary file next to", target, EEXIST);
}

/// Writes `data` to a new temporary beside `target` and flushes it to disk; returns the
/// temporary's path. On failure the temporary is removed and the error names it.
std::filesystem::path write_temporary(const std::filesystem::path& path,
                                      const std::filesystem::path& target,
                                      std::span<const std::uint8_t> data,
                                      const WriteInterruption& interruption) {
    const std::filesystem::path dir = target.has_parent_path() ? target.parent_path() : ".";
    auto [fd, temp] = create_temporary(dir, target);
    // Replacing a file keeps its permissions (a private scene stays private, a shared one
    // group-writable).
    struct stat old {};
    if (::stat(target.c_str(), &old) == 0 && S_ISREG(old.st_mode)) {
        if (::fchmod(fd.get(), old.st_mode & 07777) != 0) {
            const int error = errno;
            std::filesystem::remove(temp);
            fail("cannot set the permissions of", temp, error);
        }
    }

    std::size_t written = 0;
    const std::size_t chunk = 1u << 20;
    while (written < data.size()) {
        const std::size_t n = std::min(chunk, data.size() - written);
        const ssize_t w = ::write(fd.get(), data.data() + written, n);
        if (w < 0) {
            if (errno == EINTR) continue;
            const int error = errno;
            std::filesystem::remove(temp);
            fail("cannot write", temp, error);
        }
        written += static_cast<std::size_t>(w);
        if (interruption && !interruption(written)) {
            throw std::runtime_error("save of '" + path.string() + "' was interrupted after " +
                                     std::to_string(written) + " bytes");
        }
    }
    if (::fsync(fd.get()) != 0) {
        const int error = errno;
        std::filesystem::remove(temp);
        fail("cannot flush", temp, error);
    }
    if (::close(fd.release()) != 0) {
        const int error = errno;
        std::filesystem::remove(temp);
        fail("cannot close", temp, error);
    }
    return temp;
}

/// Renames the flushed temporary over `target` (removing the temporary when that fails).
void replace_with(const std::filesystem::path& temp, const std::filesystem::path& target) {
    if (::rename(temp.c_str(), target.c_str()) != 0) {
        const int error = errno;
        std::filesystem::remove(temp);
        fail("cannot replace", target, error);
    }
}

/// Makes the renames in the folder of `target` durable.
void sync_folder_of(const std::filesystem::path& target) {
    const std::filesystem::path dir = target.has_parent_path() ? target.parent_path() : ".";
    FileDescriptor dir_fd(::open(dir.c_str(), O_RDONLY | O_DIRECTORY));
    if (dir_fd.get() >= 0) ::fsync(dir_fd.get());
}

}  // namespace

void write_file_atomically(const std::filesystem::path& path, std::span<const std::uint8_t> data,
                           const WriteInterruption& interruption) {
    const std::filesystem::path target = save_target(path);
    require_regular_or_absent(path, target);
    replace_with(write_temporary(path, target, data, interruption), target);
    sync_folder_of(target);
}

void write_files_atomically(std::span<const FileToWrite> files) {
    std::vector<std::filesystem::path> targets;
    for (const FileToWrite& f : files) {
        targets.push_back(save_target(f.path));
        require_regular_or_absent(f.path, targets.back());
    }
    // Every temporary first: a full disk or a folder in the way then changes no target.
    std::vector<std::filesystem::path> temps;
    try {
        for (std::size_t i = 0; i < files.size(); ++i)
            temps.push_back(write_temporary(files[i].path, targets[i], files[i].data, {}));
    } catch (...) {
        for (const std::filesystem::path& t : temps) {
            std::error_code ec;
            std::filesystem::remove(t, ec);
        }
        throw;
    }
    for (std::size_t i = 0; i < files.size(); ++i) {
        try {
            replace_with(temps[i], targets[i]);
        } catch (...) {
            for (std::size_t j = i + 1; j < files.size(); ++j) {
                std::error_code ec;
                std::filesystem::remove(temps[j], ec);
            }
            throw;
        }
    }
    for (const std::filesystem::path& t : targets)
        sync_folder_of(t);
}

void check_writable(const std::filesystem::path& path) {
    const std::filesystem::path target = save_target(path);
    const std::filesystem::path dir = target.has_parent_path() ? target.parent_path() : ".";
    std::error_code ec;
    if (!std::filesystem::exists(dir, ec)) {
        throw std::runtime_error("cannot write '" + path.string() + "': the folder '" +
                                 dir.string() + "' does not exist");
    }
    if (!std::filesystem::is_directory(dir, ec)) {
        throw std::runtime_error("cannot write '" + path.string() + "': '" + dir.string() +
                                 "' is not a folder");
    }
    if (::access(dir.c_str(), W_OK | X_OK) != 0) fail("cannot write in the folder of", path, errno);
    require_regular_or_absent(path, target);
}

void check_not_overwriting(const std::filesystem::path& output, const std::filesystem::path& input,
                           const std::string& role) {
    std::error_code ec;
    if (!std::filesystem::equivalent(output, input, ec) || ec) return;
    throw std::runtime_error("cannot write '" + output.string() + "': it is " + role + " ('" +
                             input.string() +
                             "'), which the save would destroy; choose another "
                             "output");
}

std::vector<std::uint8_t> read_file(const std::filesystem::path& path, std::uint64_t max_bytes) {
    std::error_code ec;
    const std::filesystem::file_status st = std::filesystem::status(path, ec);
    if (!std::filesystem::is_regular_file(st)) {
        throw std::runtime_error("cannot read '" + path.string() + "': " +
                                 (std::filesystem::is_directory(st) ? "it is a folder, not a file"
                                  : std::filesystem::exists(st)
                                      ? "it is not a regular file (a device, pipe or socket)"
                                      : "no such file"));
    }
    const auto size = std::filesystem::file_size(path, ec);
    if (ec) throw std::runtime_error("cannot read '" + path.string() + "': " + ec.message());
    if (size > max_bytes) {
        throw std::runtime_error("cannot read '" + path.string() + "': file is larger than " +
                                 std::to_string(max_bytes) + " bytes");
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error("cannot open '" + path.string() + "'");
    std::vector<std::uint8_t> bytes;
    reserve_for_writing(bytes, size);
    bytes.resize(size);
    if (size > 0 &&
        !in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size))) {
        throw std::runtime_error("cannot read '" + path.string() + "': read failed");
    }
    return bytes;
}

}  // namespace sandtin
