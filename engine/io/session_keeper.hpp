#pragma once
// A copy of a TIN kept current from its change journal, for autosaves.
//
// Tin::snapshot() copies the whole terrain: 220 ms at 10^6 vertices, about half of it the
// first touch of fresh pages, which the editor's frame paid once a minute. The keeper copies
// the terrain once, when the document is built (on the thread that builds it), and then each
// frame only what the journal says changed. An autosave hands the writer thread a source that
// copies the kept terrain there: the frame pays for the edits, never for the terrain.
//
// Ownership: the kept copy is the frame's (follow(), hand_out()) except while a source handed
// out is being called on the writer's thread; meanwhile follow() only gathers the changes and
// applies them once the source let go. A second hand_out() while a source is still out falls
// back to a whole snapshot, so nothing ever waits for the writer.

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "io/session_file.hpp"
#include "tin/change_reader.hpp"
#include "tin/tin.hpp"

namespace sandtin {

namespace detail {
struct KeptTerrain;
}

class SessionKeeper {
  public:
    /// Copies `tin` whole: O(vertices). `tin` must outlive the keeper and stay where it is; the
    /// keeper's range reader is one of its journal's.
    explicit SessionKeeper(Tin& tin);
    ~SessionKeeper();
    SessionKeeper(const SessionKeeper&) = delete;
    SessionKeeper& operator=(const SessionKeeper&) = delete;

    /// Brings the kept copy up to the TIN: O(what changed since the last call). Call it once a
    /// frame, after the edits: each call takes from the journal, whose range readers hold back
    /// the recycling of dead ids until they take.
    void follow();
    /// The session as it is now, to be made by the thread that calls the source once
    /// (AutosaveWriter): the kept copy is brought up to date here and copied there, with
    /// `next_generation` and `metadata_json` as given. Not calling the source (dropping it)
    /// lets the copy go as well.
    SessionSource hand_out(Generation next_generation, std::string metadata_json);
    /// Whole snapshots hand_out() took because a source was still out (for tests).
    std::size_t whole_copies() const { return whole_copies_; }

  private:
    Tin& tin_;
    ChangeReader changes_;
    std::shared_ptr<detail::KeptTerrain> kept_;
    ChangeSet pending_;  ///< taken while a source was out, applied once it let go
    std::size_t whole_copies_ = 0;
};

}  // namespace sandtin
