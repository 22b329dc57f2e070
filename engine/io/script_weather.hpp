#pragma once
// The script's "weather" operation (issue 40, item 5): curvature-driven weathering
// (physics/curvature_weathering.hpp) over the whole terrain or a disc, for a number of
// iterations. Crests wear, hollows fill, the volume is kept and the bedrock is never cut.
//
//   {"op": "weather", "iterations": 20, "strength": 1, "power": 1,
//    "centre": [x, y], "radius": r}        (centre and radius: both or neither; metres)

#include <optional>

#include <nlohmann/json.hpp>

#include "geom/vec2.hpp"
#include "physics/curvature_weathering.hpp"
#include "tin/tin.hpp"
#include "util/json_fields.hpp"

namespace sandtin {

struct WeatherOp {
    int iterations = 1;
    WeatheringSettings settings;
    std::optional<Vec2> centre;  ///< with radius: only the vertices in this disc wear
    double radius = 0.0;         ///< metres
};

/// Parses the fields of a "weather" operation. Throws JsonInputError naming the field.
WeatherOp parse_weather_op(JsonFields& f);

/// Runs `op` on `tin` and reports what it did: iterations run (it stops early once nothing
/// bends), vertices worn (summed over the iterations), m³ moved, the deepest wear of one
/// iteration, the largest curvature met (1/m) and the volume change (m³, rounding only).
nlohmann::json run_weather_op(const WeatherOp& op, Tin& tin);

}  // namespace sandtin
