#pragma once
// Strokes: a tool dragged along a path is a sequence of stamps spaced by arc length (metres),
// never per frame, so the terrain does not depend on how often the path was sampled.

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "tools/stamp.hpp"

namespace sandtin {

struct StrokeSample {
    Vec2 position;
    /// Unit tangent of the path there; none for the sample of a path that never moved (a
    /// click), whose stamp then has no motion: its ridge surrounds the tool (stamp()).
    std::optional<Vec2> direction;
    double arc_length = 0.0;  ///< metres from the start of the stroke
};

/// Emits points every `spacing` metres along a path that arrives piece by piece (mouse moves,
/// haptic samples). The first point of the path is always a sample; it is emitted once the
/// path's first direction is known, or by finish(), without a direction, for a single click.
class StrokeSampler {
  public:
    explicit StrokeSampler(double spacing);
    /// Extends the path to p and returns the samples passed on the way (possibly none).
    std::vector<StrokeSample> add_point(Vec2 p);
    /// Ends the path: emits the start sample if the path never moved.
    std::vector<StrokeSample> finish();
    double spacing() const { return spacing_; }
    double length() const { return travelled_; }

  private:
    double spacing_;
    std::optional<Vec2> last_;
    bool start_pending_ = false;
    double travelled_ = 0.0;
    std::uint64_t next_index_ = 1;  ///< the next sample lies at next_index_ * spacing_ metres
};

/// Densifies control points into a Catmull-Rom curve through them (centripetal
/// parametrisation, no loops or cusps), with segments of at most `max_step` metres.
std::vector<Vec2> catmull_rom(std::span<const Vec2> control, double max_step);

/// How the tool's height is set along a stroke.
enum class DepthMode : std::uint8_t {
    Absolute,  ///< depth is the height of the tool's lowest point (m)
    Relative,  ///< the tool's lowest point is `depth` metres below the terrain ahead of it
};

struct StrokeSettings {
    double spacing = 0.01;  ///< metres between stamps
    double depth = 0.0;     ///< see DepthMode
    DepthMode depth_mode = DepthMode::Relative;
    bool follow_path = true;  ///< tool heading = path tangent (else `angle`)
    double angle = 0.0;       ///< radians, when not following the path or before it moved
};

/// Stamp placement for a sample: heading and bottom height from the settings (a sample without
/// a direction keeps settings.angle). In relative mode the reference terrain is sampled at the
/// front of the tool, which the stroke has not dug yet (at its centre without a direction).
ToolPlacement placement_for(const Tin& tin, const Tool& tool, const StrokeSample& sample,
                            const StrokeSettings& settings, LocateHint* hint);

/// Stamps the tool along a polyline (already densified if it is a curve), each stamp moving
/// along the path; a path of one point (or of points that never part) is a click, stamped
/// without motion. `after_stamp` runs after each stamp (e.g. a few relaxation iterations, as in
/// the seeds' main loop).
StampReport apply_stroke(Tin& tin, const Tool& tool, std::span<const Vec2> path,
                         const StrokeSettings& settings, SculptContext& context,
                         std::vector<StampReport>* per_stamp = nullptr,
                         const std::function<void(const StampReport&)>& after_stamp = {});

}  // namespace sandtin
