#pragma once
// Undo and redo for a TIN. Every level is a TinDelta of the region an action touched (a stroke,
// a brush drag, a pour, an erosion run), so memory grows with what was edited, not with the
// terrain. Levels past the limits are forgotten oldest first.
//
// Usage: edit the TIN as usual, then record("stroke") when the action ends. undo() first records
// edits made since the last record(), so nothing is lost by forgetting to record.

#include <cstddef>
#include <deque>
#include <string>
#include <vector>

#include "history/change_recorder.hpp"
#include "history/tin_delta.hpp"

namespace sandtin {

struct HistoryLimits {
    std::size_t max_levels = 256;
    std::size_t max_bytes = std::size_t{512} << 20;  ///< deltas kept, summed (bytes)
};

struct HistoryStep {
    bool done = false;  ///< false when there was nothing to undo / redo
    std::string label;
    ApplyReport report;
};

class History {
  public:
    /// The TIN must outlive the history. Its current state is the oldest reachable state.
    explicit History(Tin& tin, HistoryLimits limits = {});

    /// Closes an action: the edits since the last record() become one undo level (none when
    /// nothing changed). Clears the redo levels. Returns whether a level was added.
    bool record(const std::string& label);
    /// Makes the edits since the last record() the new baseline without an undo level (e.g.
    /// after loading a terrain into the same TIN).
    void forget_pending();

    HistoryStep undo();
    HistoryStep redo();

    bool can_undo() const { return !undo_.empty(); }
    bool can_redo() const { return !redo_.empty(); }
    std::size_t undo_levels() const { return undo_.size(); }
    std::size_t redo_levels() const { return redo_.size(); }
    /// Label of the level undo() / redo() would apply ("" when none).
    std::string next_undo_label() const;
    std::string next_redo_label() const;
    std::size_t bytes() const { return bytes_; }
    const HistoryLimits& limits() const { return limits_; }
    /// Levels dropped so far because of the limits.
    std::size_t dropped_levels() const { return dropped_; }

  private:
    struct Level {
        std::string label;
        TinDelta delta;
        std::size_t bytes = 0;
    };
    void enforce_limits();

    Tin& tin_;
    HistoryLimits limits_;
    ChangeRecorder recorder_;
    std::deque<Level> undo_;
    std::vector<Level> redo_;
    std::size_t bytes_ = 0;
    std::size_t dropped_ = 0;
};

}  // namespace sandtin
