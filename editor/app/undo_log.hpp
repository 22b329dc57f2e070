#pragma once
// The editor's undo order over two kinds of level: terrain levels, which engine/history
// records and restores (strokes, brushes, pours, erosion runs), and material-table edits from
// the Materials panel, which are not terrain and which the editor restores itself. The log
// keeps them interleaved in the order the artist made them; a new level clears redo, as the
// History does for terrain levels.

#include <cstddef>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "physics/material.hpp"

namespace sandtin::editor {

class UndoLog {
  public:
    /// Oldest levels beyond this are forgotten (the History bounds its own levels too; a
    /// terrain entry whose History level was dropped undoes nothing).
    static constexpr std::size_t kMaxLevels = 4096;

    struct Entry {
        bool terrain = true;   ///< a History level; otherwise a material edit
        std::string label;     ///< what the status line says
        MaterialTable before;  ///< material edits: the table before...
        MaterialTable after;   ///< ...and after the edit
    };

    void push_terrain(std::string label);
    void push_materials(MaterialTable before, MaterialTable after);
    /// The level to undo (it moves onto the redo list), or nothing.
    std::optional<Entry> undo();
    /// The level to redo (it moves back onto the undo list), or nothing.
    std::optional<Entry> redo();
    bool can_undo() const { return !done_.empty(); }
    bool can_redo() const { return !undone_.empty(); }
    std::size_t levels() const { return done_.size(); }
    void clear();

  private:
    void push(Entry e);
    std::deque<Entry> done_;
    std::vector<Entry> undone_;
};

/// The File panel's readout of the undo levels and the memory their terrain levels hold:
/// "1 level, 0.1 MB", "3 levels, 2.5 MB".
std::string undo_levels_text(std::size_t levels, std::size_t bytes);

}  // namespace sandtin::editor
