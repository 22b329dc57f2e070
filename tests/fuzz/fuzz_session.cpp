// libFuzzer target: the session loader. Half of the inputs are taken as a whole file; the
// other half as a payload wrapped in a valid header with correct checksums, so the fuzzer
// reaches the chunk parser and the terrain rebuild instead of stopping at the CRC.
// Contract under test: decode_session either returns a session or throws std::runtime_error;
// it never crashes, leaks or trips a sanitizer.

#include <zlib.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <stdexcept>
#include <vector>

#include "io/session_file.hpp"

namespace {

void put_u32(std::vector<std::uint8_t>& out, std::uint32_t v) {
    for (int i = 0; i < 4; ++i)
        out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}

std::uint32_t crc_of(const std::uint8_t* data, std::size_t size) {
    return static_cast<std::uint32_t>(crc32(crc32(0L, Z_NULL, 0), data, static_cast<uInt>(size)));
}

/// The session header of format 2 (see engine/io/session_file.cpp) around `payload`.
std::vector<std::uint8_t> wrap(std::span<const std::uint8_t> payload) {
    std::vector<std::uint8_t> out = {'S', 'A', 'N', 'D', 'T', 'I', 'N', 0x1a};
    put_u32(out, sandtin::kSessionFormatVersion);
    put_u32(out, 0);
    const std::uint64_t length = payload.size();
    put_u32(out, static_cast<std::uint32_t>(length));
    put_u32(out, static_cast<std::uint32_t>(length >> 32));
    put_u32(out, crc_of(payload.data(), payload.size()));
    put_u32(out, crc_of(out.data(), out.size()));
    out.insert(out.end(), payload.begin(), payload.end());
    return out;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    const std::span<const std::uint8_t> rest(data + 1, size - 1);
    try {
        if (data[0] & 1u) {
            const std::vector<std::uint8_t> file = wrap(rest);
            sandtin::decode_session(file, "fuzz");
        } else {
            sandtin::decode_session(rest, "fuzz");
        }
    } catch (const std::runtime_error&) {
        // Rejected with a message: the expected outcome for most inputs.
    }
    return 0;
}
