#pragma once
// A non-blocking IPv4 UDP socket (POSIX), owned RAII-style. Only what the haptic protocol
// needs: bind on loopback (or any address), send a datagram, poll for one with a timeout.

#include <cstdint>
#include <optional>
#include <span>
#include <string>

namespace sandtin::haptics {

struct UdpEndpoint {
    std::uint32_t address = 0x7F000001u;  ///< IPv4, host order (default 127.0.0.1)
    std::uint16_t port = 0;
    friend bool operator==(const UdpEndpoint&, const UdpEndpoint&) = default;
};

/// Parses a dotted IPv4 address; throws std::invalid_argument naming it otherwise.
std::uint32_t parse_ipv4(const std::string& text);

class UdpSocket {
  public:
    /// Binds to `address:port` (port 0 = any free port). Throws std::runtime_error with the
    /// system's reason.
    static UdpSocket bind(std::uint16_t port, std::uint32_t address = 0x7F000001u);

    UdpSocket(UdpSocket&& other) noexcept;
    UdpSocket& operator=(UdpSocket&& other) noexcept;
    UdpSocket(const UdpSocket&) = delete;
    UdpSocket& operator=(const UdpSocket&) = delete;
    ~UdpSocket();

    std::uint16_t port() const { return port_; }
    /// False when the datagram could not be sent (e.g. the peer's port is closed); never throws.
    bool send_to(std::span<const std::uint8_t> bytes, const UdpEndpoint& to);
    /// Waits up to `timeout_ms` (0 = just poll) for a datagram and returns its real size, which
    /// exceeds buffer.size() when it did not fit (only the buffer's worth was stored), and the
    /// sender; nullopt when none arrived.
    std::optional<std::size_t> receive(std::span<std::uint8_t> buffer, UdpEndpoint* from,
                                       int timeout_ms = 0);

  private:
    explicit UdpSocket(int fd, std::uint16_t port) : fd_(fd), port_(port) {}
    int fd_ = -1;
    std::uint16_t port_ = 0;
};

}  // namespace sandtin::haptics
