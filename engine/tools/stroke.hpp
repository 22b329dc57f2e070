#pragma once
// Strokes: a tool dragged along a path is a sequence of stamps spaced by arc length (metres),
// never per frame, so the terrain does not depend on how often the path was sampled.

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <unordered_map>
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
    /// The tool's lowest point is `depth` metres below the terrain under its centre: along a
    /// Stroke (and apply_stroke) the terrain as the stroke found it (StrokeGround), not the
    /// sand its own stamps dug out or heaped up.
    Relative,
};

struct StrokeSettings {
    /// Metres between stamps; a Stroke (and apply_stroke) keeps to the tool's
    /// max_stroke_spacing() too, so that its tips leave continuous furrows.
    double spacing = 0.01;
    double depth = 0.0;  ///< see DepthMode
    DepthMode depth_mode = DepthMode::Relative;
    bool follow_path = true;  ///< tool heading = path tangent (else `angle`)
    double angle = 0.0;       ///< radians, when not following the path or before it moved
};

/// The terrain as a stroke found it, where its stamps reached: heights remembered on a square
/// lattice before the first stamp that could change them. Measured against the terrain as it
/// is, a relative depth rode up on the ridge the previous stamp had pushed ahead (a ball stroke
/// asked 15 mm deep dug 15 mm at its start and 11 mm after, 3 mm with the editor's erosion) or
/// sank into its dent.
class StrokeGround {
  public:
    /// `cell`: the lattice spacing (m).
    explicit StrokeGround(double cell);
    /// Before a stamp: remembers the terrain's height at the lattice points within `radius` m
    /// of `centre` that it does not hold yet.
    void remember(const Tin& tin, Vec2 centre, double radius, LocateHint* hint);
    /// The height at p (clamped into the domain) as the stroke found it: bilinear between the
    /// four lattice points around p, each as remembered or, where no stamp has reached yet, as
    /// the terrain is now. nullopt when the terrain has no height there.
    std::optional<double> height_at(const Tin& tin, Vec2 p, LocateHint* hint) const;
    double cell() const { return cell_; }

  private:
    std::optional<double> node_height(const Tin& tin, std::int64_t i, std::int64_t j,
                                      LocateHint* hint) const;
    double cell_;
    std::unordered_map<std::uint64_t, double> heights_;
};

/// Stamp placement for a sample: heading and bottom height from the settings (a sample without
/// a direction keeps settings.angle). In relative mode the reference is, with `ground`, the
/// terrain as the stroke found it under the tool's centre; without it, the terrain as it is now
/// at the tool's leading edge (radius ahead along the direction; the centre without one), which
/// a lone stamp may use but a stroke should not: there the previous stamp's ridge stands.
ToolPlacement placement_for(const Tin& tin, const Tool& tool, const StrokeSample& sample,
                            const StrokeSettings& settings, LocateHint* hint,
                            const StrokeGround* ground = nullptr);

/// Runs after each stamp of a stroke (e.g. a few relaxation iterations, as in the seeds' main
/// loop).
using AfterStamp = std::function<void(const StampReport&)>;

/// One stamp of a stroke: the sample, where the tool went and what the stamp did.
struct StrokeStamp {
    StrokeSample sample;
    ToolPlacement placement;
    StampReport report;
};

/// A stroke of a tool along a path that arrives piece by piece (the editor's mouse, a pen): it
/// samples the path every spacing (the settings', at most the tool's max_stroke_spacing()),
/// places each stamp, a relative depth below the terrain as the
/// stroke found it (StrokeGround, kept in relative mode only), and stamps it moving along the
/// path, or without motion for a click (its ridge all around). Refers to the tool, which must
/// outlive it.
class Stroke {
  public:
    Stroke(const Tool& tool, const StrokeSettings& settings);
    /// Extends the path to p and stamps the samples passed on the way (possibly none).
    std::vector<StrokeStamp> add_point(Tin& tin, Vec2 p, SculptContext& context,
                                       const AfterStamp& after_stamp = {});
    /// Ends the path: stamps its start if it never moved.
    std::vector<StrokeStamp> finish(Tin& tin, SculptContext& context,
                                    const AfterStamp& after_stamp = {});
    double spacing() const { return sampler_.spacing(); }
    const StrokeSettings& settings() const { return settings_; }

  private:
    std::vector<StrokeStamp> stamp_all(Tin& tin, const std::vector<StrokeSample>& samples,
                                       SculptContext& context, const AfterStamp& after_stamp);
    const Tool* tool_;
    StrokeSettings settings_;
    StrokeSampler sampler_;
    StrokeGround ground_;
    double reach_;  ///< m around a stamp's centre that it may change
};

/// A whole stroke along a polyline (already densified if it is a curve): a Stroke fed every
/// point, then finished. A path of one point (or of points that never part) is a click.
StampReport apply_stroke(Tin& tin, const Tool& tool, std::span<const Vec2> path,
                         const StrokeSettings& settings, SculptContext& context,
                         std::vector<StampReport>* per_stamp = nullptr,
                         const AfterStamp& after_stamp = {});

}  // namespace sandtin
