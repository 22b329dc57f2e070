#include "io/session_terrain.hpp"

#include <stdexcept>
#include <string>
#include <utility>

namespace sandtin {

Tin take_session_terrain(Session& session, const std::filesystem::path& file, TinOptions options) {
    TinSnapshot terrain = std::move(session.terrain);
    session.terrain = {};
    try {
        return Tin::from_snapshot(std::move(terrain), options);
    } catch (const std::invalid_argument& e) {
        throw std::invalid_argument("'" + file.string() + "': " + e.what());
    } catch (const std::runtime_error& e) {
        throw std::runtime_error("'" + file.string() + "': " + e.what());
    }
}

}  // namespace sandtin
