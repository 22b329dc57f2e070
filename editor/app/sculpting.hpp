#pragma once
// An artist's edit from the button going down to the sand it disturbed coming to rest: the
// stamps of a tool along the path (tools/stroke.hpp's Stroke), a brush's dabs, a pour's dabs
// along the drag and with time, then the erosion the edit set off, frame by frame within a
// time budget, and the undo level it all becomes. The level opens with the gesture's first
// edit and stays open while the sand settles, so one Ctrl+Z undoes a stroke with its settling,
// as a sculpting program undoes one stroke; anything else that changes the document first
// closes it (close_level).
//
// Holds no document: each call gets the one being edited. No window, GPU or ImGui either: the
// app feeds it points on the terrain and reads back what it says.

#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "document.hpp"
#include "editor_settings.hpp"
#include "pour_flow.hpp"
#include "tools/stroke.hpp"
#include "water/live_water.hpp"

namespace sandtin::editor {

/// The palette's current tool as the editor stamps it: the asset scaled to the terrain (the
/// assets are made for the 1 m sandbox), a round tool at the Size slider's radius, extrusion
/// as the panel says. Throws for parameters the tool refuses.
Tool build_tool(const EditorSettings& settings);

/// The Water panel's settings as the live water takes them; the open sides as ticked.
LiveWaterSettings water_settings(const EditorSettings& settings);

/// What one frame of erosion did.
struct ErosionFrame {
    bool ran = false;               ///< a relaxation step ran this frame
    std::vector<VertexId> changed;  ///< vertices it moved (sorted, unique): the active overlay
    std::size_t active = 0;         ///< vertices the solver still looks at
    double ms = 0.0;
};

class Sculpting {
  public:
    /// The button went down on the terrain at `point` (metres, z the surface there): the
    /// previous edit's level closes, settled or not, and the current tool starts.
    void press(Document& doc, Vec3 point, const EditorSettings& settings);
    /// The pointer moved on to `point` with the button down.
    void drag(Document& doc, Vec3 point, const EditorSettings& settings);
    /// `seconds` more of the button held (a pour keeps pouring).
    void hold(Document& doc, double seconds, const EditorSettings& settings);
    /// The button came up: the gesture ends. Its level stays open while `erosion_runs`
    /// (the sand it disturbed settles into it), and closes now otherwise.
    void release(Document& doc, bool erosion_runs);
    bool pressed() const { return pressed_; }

    /// The gesture (its last stamps, its pour) and the open level end now: before anything
    /// else changes the document (undo, save, a switch of tool or of solver, a new document).
    void close_level(Document& doc);
    /// A handler threw: what the gesture did so far stays, as its own level, and the
    /// gesture is dropped.
    void abandon(Document& doc);
    /// Forgets everything of the last document (a new one was installed).
    void reset();

    /// One frame of erosion: up to `steps` iterations within `budget_ms` (the GPU batches
    /// them), with the panel's relocation radius and settle margin, when something changed or
    /// the sand is not at rest. Sand the erosion moved joins the open level, or opens one of
    /// its own; once it rests, what it moved is simplified and the level closes.
    ErosionFrame erode(Document& doc, const EditorSettings& settings, double budget_ms);
    /// Something changed outside a gesture (undo, a material, a switch of solver, Run): the
    /// solver looks at the terrain on the next erode() even if it rested.
    void kick() { kick_ = true; }
    /// Whether erode() would step now.
    bool wants_to_erode(const Document& doc) const { return kick_ || !doc.solver().at_rest(); }

    /// One frame of water (`seconds` of it, within `budget_ms`): the Water tool's nozzle or
    /// the Rain tool's shower while held, the panel's rain and evaporation, and the flow. What the
    /// water changed joins the open level, or opens a "water" level, which closes once the water
    /// rests or dries; the sand it wets takes its moisture, and the erosion then looks at it.
    LiveWaterFrame flow_water(Document& doc, const EditorSettings& settings, double seconds,
                              double budget_ms);

    /// Sentences for the status line since the last call (lost extrusion, a short pour, a
    /// stamp that missed the terrain).
    std::vector<std::string> take_messages();
    /// Radians: the heading of the stroke's last stamp (the cursor's footprint follows it).
    double heading() const { return heading_; }
    bool stroking() const { return stroke_.has_value(); }
    /// Milliseconds the tools took since the last call.
    double take_tool_ms();
    /// The level being made ("stroke (Ball)", "erosion"), empty when none.
    const std::string& open_level() const { return open_level_; }

  private:
    void apply(Document& doc, Vec3 point, const EditorSettings& settings);
    void stamp_at(Document& doc, Vec2 xy, const EditorSettings& settings);
    void brush_at(Document& doc, Vec3 point, const EditorSettings& settings);
    void pour_at(Document& doc, Vec2 xy, const EditorSettings& settings);
    void pour_dab(Document& doc, Vec2 at, const EditorSettings& settings);
    void end_gesture(Document& doc);
    void end_pour();
    void note_stamps(const std::vector<StrokeStamp>& stamps);
    /// The erosion came to rest: simplify what it moved, let the sand settle that, and close
    /// the level.
    void settle(Document& doc);

    bool pressed_ = false;
    std::optional<Tool> tool_;      ///< the stroke's tool (the Stroke refers to it)
    std::optional<Stroke> stroke_;  ///< a stamp tool's stroke under way
    std::optional<Vec2> last_dab_;  ///< a brush stroke's last dab
    std::optional<Vec2> nozzle_;    ///< the Water tool's, while held
    std::optional<Vec2> shower_;    ///< the Rain tool's disc centre, while held
    double flatten_level_ = 0.0;    ///< metres: the Flatten brush's level for this stroke
    std::optional<PourFlow> pour_flow_;
    bool pour_removes_ = false;
    double pour_asked_ = 0.0, pour_moved_ = 0.0;  ///< m³ over the gesture (moved < 0: removed)
    double heading_ = 0.0;
    std::string open_level_;
    /// The erosion's simplification ran; the sand settles what it steepened.
    bool resettling_ = false;
    bool kick_ = true;  ///< something changed since the solver last stepped
    std::vector<std::string> messages_;
    double tool_ms_ = 0.0;
};

}  // namespace sandtin::editor
