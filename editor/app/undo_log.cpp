#include "undo_log.hpp"

#include <cstdio>
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

std::string undo_levels_text(std::size_t levels, std::size_t bytes) {
    char text[64];
    std::snprintf(text, sizeof(text), "%zu level%s, %.1f MB", levels, levels == 1 ? "" : "s",
                  static_cast<double>(bytes) / 1048576.0);
    return text;
}

}  // namespace sandtin::editor
