#include "session_output.hpp"

#include <algorithm>
#include <array>
#include <string>

#include "arguments.hpp"
#include "util/atomic_file.hpp"
#include "util/lower_extension.hpp"

namespace sandtin::cli {

void check_session_output(const std::filesystem::path& path) {
    const std::string ext = lower_extension(path);
    // What export writes and import reads: never a session's name.
    constexpr std::array<const char*, 12> kOtherFormats{".obj",  ".ply", ".stl",  ".gltf",
                                                        ".glb",  ".png", ".exr",  ".tif",
                                                        ".tiff", ".asc", ".json", ".mtl"};
    if (std::find(kOtherFormats.begin(), kOtherFormats.end(), ext) != kOtherFormats.end()) {
        throw UsageError("-o '" + path.string() + "': a session is written in sandtin's own " +
                         "format, not as " + ext + "; name it .sandtin (sandtin export writes " +
                         "meshes and maps)");
    }
    check_writable(path);
}

}  // namespace sandtin::cli
