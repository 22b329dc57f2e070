#pragma once
// A file's extension in lower case, as the commands that pick a format by name compare it.

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>

namespace sandtin {

/// ".PNG" and ".png" both give ".png"; no extension gives "".
inline std::string lower_extension(const std::filesystem::path& p) {
    std::string ext = p.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

}  // namespace sandtin
