#include "io/autosave.hpp"

#include <stdexcept>
#include <system_error>

namespace sandtin {

std::filesystem::path autosave_path(const std::filesystem::path& session_path) {
    std::filesystem::path p = session_path;
    p += ".autosave";
    return p;
}

void write_autosave(const std::filesystem::path& session_path, const Session& session,
                    const WriteInterruption& interruption) {
    save_session(autosave_path(session_path), session, interruption);
}

void save_session_clearing_autosave(const std::filesystem::path& session_path,
                                    const Session& session, const WriteInterruption& interruption) {
    save_session(session_path, session, interruption);
    discard_autosave(session_path);
}

std::optional<AutosaveInfo> find_autosave(const std::filesystem::path& session_path) {
    std::error_code ec;
    const std::filesystem::path autosave = autosave_path(session_path);
    if (!std::filesystem::is_regular_file(autosave, ec)) return std::nullopt;
    AutosaveInfo info;
    info.path = autosave;
    info.scene_exists = std::filesystem::is_regular_file(session_path, ec);
    const auto autosave_time = std::filesystem::last_write_time(autosave, ec);
    if (ec) {
        info.problem = "cannot read its time: " + ec.message();
        return info;
    }
    if (info.scene_exists) {
        const auto scene_time = std::filesystem::last_write_time(session_path, ec);
        info.newer_than_scene = !ec && autosave_time >= scene_time;
    } else {
        info.newer_than_scene = true;
    }
    try {
        (void)load_session(autosave);
    } catch (const std::exception& e) {
        info.problem = e.what();
    }
    return info;
}

Session recover_autosave(const std::filesystem::path& session_path) {
    return load_session(autosave_path(session_path));
}

bool discard_autosave(const std::filesystem::path& session_path) {
    std::error_code ec;
    const bool removed = std::filesystem::remove(autosave_path(session_path), ec);
    if (ec) {
        throw std::runtime_error("cannot delete the autosave '" +
                                 autosave_path(session_path).string() + "': " + ec.message());
    }
    return removed;
}

}  // namespace sandtin
