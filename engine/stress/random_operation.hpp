#pragma once
// Random script operations for the stress runner (sandtin stress). Every operation is a plain
// script object ("op": "stamp", "stroke", ...), so a failing sequence prints as a script that
// `sandtin run` replays. The mix covers every contour and profile and the degenerate cases the
// engine must survive or reject cleanly: zero-radius and zero-depth tools, self-intersecting
// contours, tools partly or wholly outside the domain, strokes along existing constraints and
// across many old ones.

#include <cstdint>
#include <random>
#include <string>

#include <nlohmann/json.hpp>

#include "geom/rect.hpp"
#include "tin/tin.hpp"

namespace sandtin {

class RandomOperations {
  public:
    /// `domain` is the terrain's extent (m); `save_path` names the file "save" operations
    /// write (relative to the script's directory).
    RandomOperations(std::uint64_t seed, Rect domain, std::string save_path = "stress.sandtin");

    /// The next operation. Reads `tin` only to aim strokes along its existing constraints.
    nlohmann::json next(const Tin& tin);

  private:
    nlohmann::json random_tool();
    nlohmann::json stamp();
    nlohmann::json stroke(const Tin& tin);
    nlohmann::json pour();
    nlohmann::json brush();
    nlohmann::json erode();
    Vec2 point(double outside_margin);  ///< uniform over the domain grown by the margin (m)
    double uniform(double lo, double hi);
    bool chance(double p);

    std::mt19937_64 rng_;
    Rect domain_;
    std::string save_path_;
};

}  // namespace sandtin
