#include "session_output.hpp"

#include <optional>
#include <string>

#include "arguments.hpp"
#include "io/session_name.hpp"
#include "util/atomic_file.hpp"

namespace sandtin::cli {

void check_session_output(const std::filesystem::path& path) {
    if (const std::optional<std::string> problem = session_name_problem(path)) {
        throw UsageError("-o '" + path.string() + "': " + *problem +
                         " (sandtin export writes meshes and maps)");
    }
    check_writable(path);
}

}  // namespace sandtin::cli
