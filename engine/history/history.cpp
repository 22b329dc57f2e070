#include "history/history.hpp"

#include <utility>

namespace sandtin {

History::History(Tin& tin, HistoryLimits limits) : tin_(tin), limits_(limits), recorder_(tin) {
    if (limits_.max_levels == 0) limits_.max_levels = 1;
}

bool History::record(const std::string& label) {
    TinDelta delta = recorder_.take();
    if (delta.empty()) return false;
    for (const Level& l : redo_)
        bytes_ -= l.bytes;
    redo_.clear();
    Level level{label, std::move(delta), 0};
    level.bytes = level.delta.bytes() + label.capacity();
    bytes_ += level.bytes;
    undo_.push_back(std::move(level));
    enforce_limits();
    return true;
}

void History::forget_pending() {
    recorder_.take();
}

void History::enforce_limits() {
    // The newest level always stays, even when it alone exceeds the byte budget.
    while (undo_.size() > 1 && (undo_.size() > limits_.max_levels || bytes_ > limits_.max_bytes)) {
        bytes_ -= undo_.front().bytes;
        undo_.pop_front();
        ++dropped_;
    }
}

HistoryStep History::undo() {
    record("edit");
    HistoryStep step;
    if (undo_.empty()) return step;
    Level level = std::move(undo_.back());
    undo_.pop_back();
    step.done = true;
    step.label = level.label;
    step.report = apply_delta(tin_, level.delta, DeltaSide::Before);
    recorder_.take();  // the undo itself is not a new level
    redo_.push_back(std::move(level));
    return step;
}

HistoryStep History::redo() {
    // Edits made after an undo fork the history: record() has cleared the redo levels then.
    record("edit");
    HistoryStep step;
    if (redo_.empty()) return step;
    Level level = std::move(redo_.back());
    redo_.pop_back();
    step.done = true;
    step.label = level.label;
    step.report = apply_delta(tin_, level.delta, DeltaSide::After);
    recorder_.take();
    undo_.push_back(std::move(level));
    enforce_limits();
    return step;
}

std::string History::next_undo_label() const {
    return undo_.empty() ? std::string{} : undo_.back().label;
}

std::string History::next_redo_label() const {
    return redo_.empty() ? std::string{} : redo_.back().label;
}

}  // namespace sandtin
