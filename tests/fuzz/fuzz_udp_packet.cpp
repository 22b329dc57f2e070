// libFuzzer target: the haptic UDP packet decoder. Contract: a packet or a DecodeError; a
// decoded packet re-encodes to exactly the datagram it came from (the format has no slack).

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <span>
#include <vector>

#include "haptics/udp_protocol.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    sandtin::haptics::DecodeError error{};
    const auto packet = sandtin::haptics::decode_packet(std::span(data, size), &error);
    if (!packet) return 0;
    const std::vector<std::uint8_t> again = sandtin::haptics::encode_packet(*packet);
    if (again.size() != size || std::memcmp(again.data(), data, size) != 0) std::abort();
    return 0;
}
