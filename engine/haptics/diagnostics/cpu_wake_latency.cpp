#include "haptics/diagnostics/cpu_wake_latency.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace sandtin::haptics {

CpuWakeLatencyHold::CpuWakeLatencyHold(std::int32_t max_latency_us, const char* device) {
    if (max_latency_us < 0) {
        error_ = "cpu wake latency: the maximum must be >= 0 us";
        return;
    }
    const int fd = ::open(device, O_WRONLY | O_CLOEXEC);
    if (fd < 0) {
        error_ = std::string("cpu wake latency: ") + device + ": " + std::strerror(errno);
        return;
    }
    // The PM QoS device takes the value as a binary 32-bit integer.
    if (::write(fd, &max_latency_us, sizeof max_latency_us) !=
        static_cast<ssize_t>(sizeof max_latency_us)) {
        error_ = std::string("cpu wake latency: writing ") + device + ": " + std::strerror(errno);
        ::close(fd);
        return;
    }
    fd_ = fd;
}

CpuWakeLatencyHold::~CpuWakeLatencyHold() {
    if (fd_ >= 0) ::close(fd_);
}

}  // namespace sandtin::haptics
