#pragma once
// Locating shipped assets (tools, materials, scenes, textures).

#include <filesystem>
#include <string_view>

namespace sandtin {

/// The asset directory: $SANDTIN_ASSET_DIR when set, else the repository's assets/ folder
/// recorded at build time.
std::filesystem::path asset_directory();

/// `relative` inside the asset directory. Throws std::runtime_error naming the path when the
/// file does not exist.
std::filesystem::path find_asset(std::string_view relative);

}  // namespace sandtin
