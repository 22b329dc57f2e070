// libFuzzer target: the script parser (`sandtin run` scripts). Contract: a parsed script or
// JsonInputError/std::runtime_error with a message; parsing never touches the terrain.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string_view>

#include "io/script.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    try {
        sandtin::parse_script(text, "fuzz.json", std::filesystem::temp_directory_path());
    } catch (const std::runtime_error&) {
    } catch (const std::invalid_argument&) {
    }
    return 0;
}
