#include "io/session_name.hpp"

#include <algorithm>
#include <array>

#include "util/lower_extension.hpp"

namespace sandtin {

std::optional<std::string> session_name_problem(const std::filesystem::path& path) {
    const std::string ext = lower_extension(path);
    // What export writes and import reads: never a session's name.
    constexpr std::array<const char*, 12> kOtherFormats{".obj",  ".ply", ".stl",  ".gltf",
                                                        ".glb",  ".png", ".exr",  ".tif",
                                                        ".tiff", ".asc", ".json", ".mtl"};
    if (std::find(kOtherFormats.begin(), kOtherFormats.end(), ext) == kOtherFormats.end())
        return std::nullopt;
    return "a session is written in sandtin's own format, not as " + ext + "; name it .sandtin";
}

}  // namespace sandtin
