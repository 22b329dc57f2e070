#include "haptics/recording_replay.hpp"

#include <cmath>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "tools/tool_json.hpp"

namespace sandtin::haptics {

nlohmann::json replay_recording(const HapticRecording& r, Tin& tin, SculptContext& context,
                                const std::filesystem::path& base_dir) {
    if (r.start) {
        const TerrainSummary now = summarise(tin);
        const double tolerance = 1e-9 * std::max(1.0, std::abs(r.start->volume));
        if (now.vertices != r.start->vertices ||
            std::abs(now.volume - r.start->volume) > tolerance) {
            throw std::runtime_error(
                "haptic replay: the terrain is not the one the recording started from (" +
                std::to_string(now.vertices) + " vertices, volume " + std::to_string(now.volume) +
                " m^3; the recording expects " + std::to_string(r.start->vertices) +
                " vertices, volume " + std::to_string(r.start->volume) + " m^3)");
        }
    }
    auto tool = std::make_shared<const Tool>(
        Tool::build(parse_tool_spec(r.tool, base_dir, "haptic recording: tool")));
    context.set_next_generation(r.next_generation);
    const double volume_before = tin.volume();
    LiveEditor editor(tin, tool, context, r.edit);
    std::size_t stamps = 0;
    std::size_t skipped = 0;
    for (const EditInput& e : r.edits) {
        const EditResult er = editor.apply(e);
        stamps += er.stamps;
        skipped += er.skipped;
    }
    double max_force = 0.0;
    for (const RecordedTick& t : r.ticks)
        max_force = std::max(max_force, length(t.force));
    nlohmann::json j;
    j["edits"] = r.edits.size();
    j["stamps_applied"] = stamps;
    j["stamps_skipped_above_sand"] = skipped;
    j["ticks"] = r.ticks.size();
    j["seconds"] = static_cast<double>(r.ticks.size()) / r.rate_hz;
    j["max_recorded_force"] = max_force;
    j["volume_change"] = tin.volume() - volume_before;
    if (r.result) {
        const TerrainSummary after = summarise(tin);
        const bool matches =
            after.vertices == r.result->vertices && after.volume == r.result->volume;
        j["result_matches_recording"] = matches;
        if (!matches) {
            // The replay is still a valid edit; the artist should know it is not the recorded
            // one (the tools' code, or the recording's file, changed since).
            std::ostringstream w;
            w.precision(17);
            w << "the replay does not reproduce the recording: it ends with " << after.vertices
              << " vertices and " << after.volume << " m³, the recording with "
              << r.result->vertices << " and " << r.result->volume << " m³";
            j["warning"] = w.str();
        }
    }
    return j;
}

Script recording_script(std::string_view text, const std::string& name,
                        const std::filesystem::path& base_dir) {
    auto recording = std::make_shared<const HapticRecording>(parse_recording(text, name));
    // Check the tool now, so a bad recording fails before any terrain is touched.
    (void)Tool::build(parse_tool_spec(recording->tool, base_dir, name + ": tool"));
    Script script;
    script.name = name;
    script.terrain = recording->terrain;
    CustomOp op;
    op.name = "haptic_replay";
    op.run = [recording, base_dir](Tin& tin, SculptContext& context) {
        return replay_recording(*recording, tin, context, base_dir);
    };
    script.steps.push_back({op, "haptic_replay", 1});
    return script;
}

}  // namespace sandtin::haptics
