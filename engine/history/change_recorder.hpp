#pragma once
// Turns the edits made to a TIN into TinDeltas. It keeps a mirror of the per-vertex records and
// the constraint polylines as they were at the last take(), and learns from a Tin change
// subscription which vertex ids changed since, so take() costs O(changed vertices + live
// constraints), never O(terrain).
//
// The mirror is one copy of the vertex attributes (like the GPU mirror); the deltas it produces
// hold only what changed.

#include <cstdint>
#include <map>
#include <vector>

#include "history/tin_delta.hpp"
#include "tin/tin.hpp"
#include "tin/vertex_change_feed.hpp"

namespace sandtin {

class ChangeRecorder {
  public:
    /// Subscribes to `tin`'s vertex changes; the TIN must outlive the recorder.
    explicit ChangeRecorder(Tin& tin);
    ~ChangeRecorder();
    ChangeRecorder(const ChangeRecorder&) = delete;
    ChangeRecorder& operator=(const ChangeRecorder&) = delete;

    /// Everything that changed since the previous take() (or construction), as a delta from
    /// the state then to the state now. The mirror moves to the current state.
    TinDelta take();
    /// True when vertices changed since the last take() (constraint-only changes are found by
    /// take() itself).
    bool has_vertex_changes();

  private:
    VertexRecord current(VertexId v) const;

    Tin& tin_;
    VertexChangeFeed changes_;
    std::vector<VertexRecord> records_;  ///< by VertexId, as of the last take()
    std::vector<std::uint8_t> alive_;
    std::map<std::uint32_t, ConstraintPolyline> constraints_;  ///< by ConstraintId
    std::vector<VertexId> pending_;  ///< reported by the subscription, not yet taken
};

}  // namespace sandtin
