#include "undo_log.hpp"

#include <utility>

namespace sandtin::editor {

void UndoLog::push(Entry e) {
    done_.push_back(std::move(e));
    if (done_.size() > kMaxLevels) done_.pop_front();
    undone_.clear();
}

void UndoLog::push_terrain(std::string label) {
    Entry e;
    e.label = std::move(label);
    push(std::move(e));
}

void UndoLog::push_materials(MaterialTable before, MaterialTable after) {
    Entry e;
    e.terrain = false;
    e.label = "material edit";
    e.before = std::move(before);
    e.after = std::move(after);
    push(std::move(e));
}

std::optional<UndoLog::Entry> UndoLog::undo() {
    if (done_.empty()) return std::nullopt;
    undone_.push_back(std::move(done_.back()));
    done_.pop_back();
    return undone_.back();
}

std::optional<UndoLog::Entry> UndoLog::redo() {
    if (undone_.empty()) return std::nullopt;
    done_.push_back(std::move(undone_.back()));
    undone_.pop_back();
    return done_.back();
}

void UndoLog::clear() {
    done_.clear();
    undone_.clear();
}

}  // namespace sandtin::editor
