#include "io/session_terrain.hpp"

#include <stdexcept>
#include <string>

namespace sandtin {

Tin session_terrain(const Session& session, const std::filesystem::path& file, TinOptions options) {
    try {
        return Tin::from_snapshot(session.terrain, options);
    } catch (const std::invalid_argument& e) {
        throw std::invalid_argument("'" + file.string() + "': " + e.what());
    } catch (const std::runtime_error& e) {
        throw std::runtime_error("'" + file.string() + "': " + e.what());
    }
}

}  // namespace sandtin
