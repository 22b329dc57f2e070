#include "util/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>

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
    int get() const { return fd_; }
    int release() {
        const int fd = fd_;
        fd_ = -1;
        return fd;
    }

  private:
    int fd_;
};

}  // namespace

void write_file_atomically(const std::filesystem::path& path, std::span<const std::uint8_t> data,
                           const WriteInterruption& interruption) {
    const std::filesystem::path dir = path.has_parent_path() ? path.parent_path() : ".";
    std::string temp_template = (dir / ("." + path.filename().string() + ".tmp-XXXXXX")).string();
    FileDescriptor fd(::mkstemp(temp_template.data()));
    const std::filesystem::path temp = temp_template;
    if (fd.get() < 0) fail("cannot create a temporary file next to", path, errno);
    ::fchmod(fd.get(), 0644);

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
    if (::rename(temp.c_str(), path.c_str()) != 0) {
        const int error = errno;
        std::filesystem::remove(temp);
        fail("cannot replace", path, error);
    }
    // Make the rename itself durable.
    FileDescriptor dir_fd(::open(dir.c_str(), O_RDONLY | O_DIRECTORY));
    if (dir_fd.get() >= 0) ::fsync(dir_fd.get());
}

std::vector<std::uint8_t> read_file(const std::filesystem::path& path, std::uint64_t max_bytes) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) {
        throw std::runtime_error("cannot read '" + path.string() + "': no such file");
    }
    const auto size = std::filesystem::file_size(path, ec);
    if (ec) throw std::runtime_error("cannot read '" + path.string() + "': " + ec.message());
    if (size > max_bytes) {
        throw std::runtime_error("cannot read '" + path.string() + "': file is larger than " +
                                 std::to_string(max_bytes) + " bytes");
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error("cannot open '" + path.string() + "'");
    std::vector<std::uint8_t> bytes(size);
    if (size > 0 &&
        !in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size))) {
        throw std::runtime_error("cannot read '" + path.string() + "': read failed");
    }
    return bytes;
}

}  // namespace sandtin
