#include "editor_command.hpp"

#include <algorithm>
#include <system_error>

namespace sandtin::cli {

namespace fs = std::filesystem;

fs::path path_for_display(const fs::path& path) {
    std::error_code ec;
    const fs::path absolute = fs::weakly_canonical(fs::absolute(path, ec), ec);
    if (ec) return path;
    const fs::path relative = absolute.lexically_proximate(fs::current_path(ec));
    if (ec || relative.empty() || *relative.begin() == "..") return absolute;
    return relative;
}

std::string shell_quote(const std::string& word) {
    const bool safe = !word.empty() && std::all_of(word.begin(), word.end(), [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
               c == '_' || c == '-' || c == '.' || c == '/' || c == '+' || c == ',' || c == ':';
    });
    if (safe) return word;
    std::string quoted = "'";
    for (char c : word) {
        // A single quote ends the quoted run, is escaped, and starts a new one.
        if (c == '\'') {
            quoted += "'\\''";
        } else {
            quoted += c;
        }
    }
    return quoted + "'";
}

std::string editor_command(const fs::path& scene) {
    std::error_code ec;
    const fs::path self = fs::read_symlink("/proc/self/exe", ec);
    std::string editor = "sandtin-editor";
    if (!ec) {
        const fs::path built = self.parent_path().parent_path() / "app" / "sandtin-editor";
        if (fs::is_regular_file(built, ec)) {
            const fs::path shown = path_for_display(built);
            // A bare name would be looked up on PATH, not in the current directory.
            editor = shown.has_parent_path() ? shown.string() : "./" + shown.string();
        }
    }
    return shell_quote(editor) + " " + shell_quote(path_for_display(scene).string());
}

}  // namespace sandtin::cli
