#include "io/session_terrain.hpp"

#include <stdexcept>
#include <string>
#include <utility>

namespace sandtin {

namespace {

Tin restore_naming_the_file(TinSnapshot terrain, const std::filesystem::path& file,
                            TinOptions options) {
    try {
        return Tin::from_snapshot(std::move(terrain), options);
    } catch (const std::invalid_argument& e) {
        throw std::invalid_argument("'" + file.string() + "': " + e.what());
    } catch (const std::runtime_error& e) {
        throw std::runtime_error("'" + file.string() + "': " + e.what());
    }
}

}  // namespace

Tin session_terrain(const Session& session, const std::filesystem::path& file, TinOptions options) {
    return restore_naming_the_file(session.terrain, file, options);
}

Tin take_session_terrain(Session& session, const std::filesystem::path& file, TinOptions options) {
    TinSnapshot terrain = std::move(session.terrain);
    session.terrain = {};
    return restore_naming_the_file(std::move(terrain), file, options);
}

}  // namespace sandtin
