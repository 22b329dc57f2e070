#pragma once
// Live haptic editing: the tool follows the device, and while the button is held the device
// path is a stroke, stamped every `spacing` metres of travel (tools/stroke.hpp), with the
// tool's lowest point at the device's height (dig mode: the sand under it is pressed down to
// it, and nothing happens while the tool is above the sand).
//
// The editor only sees the device states it is given, in order: feeding it the same inputs
// gives the same terrain, which is what recordings and deterministic replay rely on.

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "geom/vec3.hpp"
#include "haptics/haptic_device.hpp"
#include "haptics/haptic_snapshot.hpp"
#include "physics/material.hpp"
#include "physics/talus_solver.hpp"
#include "tin/tin.hpp"
#include "tools/sculpt_context.hpp"
#include "tools/stroke.hpp"
#include "tools/tool.hpp"

namespace sandtin {
class SandPhysics;
}

namespace sandtin::haptics {

struct LiveEditSettings {
    double spacing = 0.005;  ///< m of device travel between stamps while the button is held
    /// Sand relaxation iterations after each stamp (0 = no physics), as a script stroke's
    /// "erode" does; the physics uses the sequential (deterministic) schedule.
    int erode_iterations = 0;
    TalusParameters physics;                  ///< relocation radius, damping, rest tolerance
    std::uint32_t button_mask = kMainButton;  ///< which button bits mean "apply the tool"
};

/// One device state the simulation consumed, in the order it consumed them.
struct EditInput {
    std::uint64_t tick = 0;  ///< loop tick of the device state (for the record; not used)
    Vec3 position;           ///< m: tool centre (x, y) and the height of its lowest point (z)
    std::uint32_t buttons = 0;
    friend bool operator==(const EditInput&, const EditInput&) = default;
};

struct EditResult {
    std::size_t stamps = 0;      ///< stamps applied for this input
    std::size_t skipped = 0;     ///< stroke samples where the tool was above the sand
    double volume_change = 0.0;  ///< m³ by the stamps (erosion conserves volume)
    int erosion_iterations = 0;
};

class LiveEditor {
  public:
    /// Throws std::invalid_argument for a non-positive spacing or negative erode_iterations.
    LiveEditor(Tin& tin, std::shared_ptr<const Tool> tool, SculptContext& context,
               LiveEditSettings settings, MaterialTable materials = MaterialTable::presets());
    ~LiveEditor();
    LiveEditor(const LiveEditor&) = delete;
    LiveEditor& operator=(const LiveEditor&) = delete;

    /// The tool moves to the input (off the terrain too: its snapshot then touches nothing);
    /// with the button held, the path since the last input, clamped into the domain, is
    /// stamped; on release the stroke ends (a click without motion stamps once).
    EditResult apply(const EditInput& input);

    /// The snapshot for the force loop at the tool's current placement.
    HapticSnapshot snapshot();

    const ToolPlacement& placement() const { return placement_; }
    bool stroking() const { return sampler_.has_value(); }
    std::size_t total_stamps() const { return total_stamps_; }
    const Tool& tool() const { return *tool_; }
    const LiveEditSettings& settings() const { return settings_; }

  private:
    void stamp_samples(const std::vector<StrokeSample>& samples, double bottom, EditResult& result);
    bool touches_sand(const ToolPlacement& at);

    Tin& tin_;
    std::shared_ptr<const Tool> tool_;
    SculptContext& context_;
    LiveEditSettings settings_;
    MaterialTable materials_;
    std::unique_ptr<SandPhysics> physics_;
    std::optional<StrokeSampler> sampler_;
    ToolPlacement placement_;
    LocateHint snapshot_hint_;
    LocateHint probe_hint_;
    std::vector<VertexId> eroded_;
    std::size_t total_stamps_ = 0;
};

}  // namespace sandtin::haptics
