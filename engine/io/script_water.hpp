#pragma once
// The script's "water" operation (issue 40): water over the terrain as it stands for a while,
// from rain, nozzles and evaporation, draining through open sides (engine/water); with
// "erode", carrying sand; and the sand it wets taking a moisture, so that the relaxation
// afterwards lets wet sand stand at its steeper angle. The water itself is not kept between
// operations: the terrain and its moisture are.

#include <nlohmann/json.hpp>

#include "tin/tin.hpp"
#include "util/json_fields.hpp"
#include "water/water_borders.hpp"
#include "water/water_sources.hpp"

namespace sandtin {

struct WaterOp {
    double seconds = 0.0;  ///< s of water, > 0
    WaterSources sources;
    OpenSides open;
    double friction = VirtualPipeOptions{}.friction;  ///< 1/s
    /// Sand the water reached at least wet_depth deep takes at least this moisture, in [0, 1].
    double wet_moisture = 1.0;
    double wet_depth = 1e-3;  ///< m
    /// The water carries sand (water/sediment_transport.hpp): it cuts where it runs fast and
    /// drops the sand where it slows; what is still suspended at the end settles where it is.
    bool erode = false;
};

/// Parses the fields of a "water" operation (rain, nozzles, evaporation_mm_per_hour,
/// open_sides, seconds, friction, wet_moisture, wet_depth). Throws JsonInputError naming the
/// field.
WaterOp parse_water_op(JsonFields& f);

/// Runs `op` on `tin` and reports what the water did (m³ added, evaporated, left through the
/// open sides and still on the terrain at the end; the wetted vertices; the deepest water).
nlohmann::json run_water_op(const WaterOp& op, Tin& tin);

}  // namespace sandtin
