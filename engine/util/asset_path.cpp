#include "util/asset_path.hpp"

#include <cstdlib>
#include <stdexcept>
#include <string>

namespace sandtin {

std::filesystem::path asset_directory() {
    if (const char* env = std::getenv("SANDTIN_ASSET_DIR"); env != nullptr && *env != '\0') {
        return env;
    }
    return SANDTIN_DEFAULT_ASSET_DIR;
}

std::filesystem::path find_asset(std::string_view relative) {
    const std::filesystem::path p = asset_directory() / std::filesystem::path(relative);
    std::error_code ec;
    if (!std::filesystem::exists(p, ec)) {
        throw std::runtime_error("asset '" + std::string(relative) + "' not found (looked for " +
                                 p.string() + "; set SANDTIN_ASSET_DIR to the assets folder)");
    }
    return p;
}

}  // namespace sandtin
