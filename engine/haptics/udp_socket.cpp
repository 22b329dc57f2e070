#include "haptics/udp_socket.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <utility>

namespace sandtin::haptics {

namespace {
std::runtime_error system_error(const std::string& what) {
    return std::runtime_error(what + ": " + std::strerror(errno));
}
sockaddr_in to_sockaddr(const UdpEndpoint& e) {
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(e.port);
    a.sin_addr.s_addr = htonl(e.address);
    return a;
}
}  // namespace

std::uint32_t parse_ipv4(const std::string& text) {
    in_addr a{};
    if (inet_pton(AF_INET, text.c_str(), &a) != 1)
        throw std::invalid_argument("not an IPv4 address: '" + text + "'");
    return ntohl(a.s_addr);
}

UdpSocket UdpSocket::bind(std::uint16_t port, std::uint32_t address) {
    const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (fd < 0) throw system_error("udp: socket");
    UdpSocket s(fd, 0);
    const sockaddr_in a = to_sockaddr({address, port});
    if (::bind(fd, reinterpret_cast<const sockaddr*>(&a), sizeof a) != 0)
        throw system_error("udp: bind to port " + std::to_string(port));
    sockaddr_in bound{};
    socklen_t len = sizeof bound;
    if (::getsockname(fd, reinterpret_cast<sockaddr*>(&bound), &len) != 0)
        throw system_error("udp: getsockname");
    s.port_ = ntohs(bound.sin_port);
    return s;
}

UdpSocket::UdpSocket(UdpSocket&& o) noexcept
    : fd_(std::exchange(o.fd_, -1)), port_(std::exchange(o.port_, 0)) {}

UdpSocket& UdpSocket::operator=(UdpSocket&& o) noexcept {
    if (this != &o) {
        if (fd_ >= 0) ::close(fd_);
        fd_ = std::exchange(o.fd_, -1);
        port_ = std::exchange(o.port_, 0);
    }
    return *this;
}

UdpSocket::~UdpSocket() {
    if (fd_ >= 0) ::close(fd_);
}

bool UdpSocket::send_to(std::span<const std::uint8_t> bytes, const UdpEndpoint& to) {
    const sockaddr_in a = to_sockaddr(to);
    const ssize_t n = ::sendto(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL,
                               reinterpret_cast<const sockaddr*>(&a), sizeof a);
    return n == static_cast<ssize_t>(bytes.size());
}

std::optional<std::size_t> UdpSocket::receive(std::span<std::uint8_t> buffer, UdpEndpoint* from,
                                              int timeout_ms) {
    if (timeout_ms > 0) {
        pollfd p{fd_, POLLIN, 0};
        if (::poll(&p, 1, timeout_ms) <= 0) return std::nullopt;
    }
    sockaddr_in a{};
    socklen_t len = sizeof a;
    const ssize_t n = ::recvfrom(fd_, buffer.data(), buffer.size(), MSG_TRUNC,
                                 reinterpret_cast<sockaddr*>(&a), &len);
    if (n < 0) return std::nullopt;
    if (from != nullptr) *from = {ntohl(a.sin_addr.s_addr), ntohs(a.sin_port)};
    // With MSG_TRUNC, n is the datagram's real size: report oversized datagrams as such so the
    // decoder rejects them instead of parsing a truncated prefix.
    return static_cast<std::size_t>(n);
}

}  // namespace sandtin::haptics
