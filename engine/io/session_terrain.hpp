#pragma once
// The terrain of a loaded session, with the file named in any error: a session whose bytes and
// checksums are intact can still describe an invalid triangulation (Tin::from_snapshot refuses
// it), and the user must learn which file that is.

#include <filesystem>

#include "io/session_file.hpp"
#include "tin/tin.hpp"

namespace sandtin {

/// Tin::from_snapshot(session.terrain, options), its errors prefixed with "'<file>': ". Moves
/// the session's terrain into the TIN rather than copying it (about 50 MB at 10^6 vertices):
/// session.terrain is left empty, the rest of the session as it was.
Tin take_session_terrain(Session& session, const std::filesystem::path& file,
                         TinOptions options = {});

}  // namespace sandtin
