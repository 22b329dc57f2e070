#pragma once
// Where a held Pour or Remove puts its dabs, so that the sand moved depends on the gesture
// and never on how many mouse events or frames delivered it: one dab where the button goes
// down, one every `spacing` metres along the drag (as the script's pour path spaces its
// points), and one every kPourHoldSeconds while the cursor stays (hold to keep pouring).

#include <optional>
#include <vector>

#include "geom/vec2.hpp"
#include "tools/stroke.hpp"

namespace sandtin::editor {

/// Seconds between the dabs of a pour held still: four dabs a second.
inline constexpr double kPourHoldSeconds = 0.25;

class PourFlow {
  public:
    /// `spacing`: metres between the dabs along a drag (> 0).
    explicit PourFlow(double spacing) : sampler_(spacing) {}
    /// The button went down at `p`: the first dab.
    std::vector<Vec2> press(Vec2 p);
    /// The cursor moved to `p`: the dabs passed on the way (possibly none).
    std::vector<Vec2> move(Vec2 p);
    /// `seconds` more of holding: the dabs due at the cursor. Time counts from the last dab,
    /// so a drag that keeps dabbing is not given extra ones.
    std::vector<Vec2> hold(double seconds);

  private:
    StrokeSampler sampler_;
    std::optional<Vec2> cursor_;
    double since_dab_ = 0.0;  ///< seconds since the last dab
};

}  // namespace sandtin::editor
