#pragma once
// The script's "water" operation (issue 40): water over the terrain as it stands for a while,
// from rain, nozzles and evaporation, draining through open sides (engine/water); with
// "erode", carrying sand; and the sand it wets taking a moisture, so that the relaxation
// afterwards lets wet sand stand at its steeper angle. "rain" is a "water" operation whose
// source is rain (its fields at the top), "flow" one without a source: the water already on
// the terrain runs for some seconds, or until it is dry or at rest.
//
// The water's depth is kept between operations in the terrain (Tin::set_water_depth, so it is
// saved with the session, exported and undone); its velocity is not: each operation starts
// the water from rest. What the water still carries at the end of an operation settles there.
// The moisture spreads into dry sand and dries (water/moisture_diffusion.hpp): over the
// seconds a water operation ran, after the wetting, and over a "dry" operation's, where time
// passes with no water.

#include <cstdint>

#include <nlohmann/json.hpp>

#include "tin/tin.hpp"
#include "util/json_fields.hpp"
#include "water/moisture_diffusion.hpp"
#include "water/water_borders.hpp"
#include "water/water_sources.hpp"

namespace sandtin {

/// Which water scheme a "water" operation runs (engine/water).
enum class WaterScheme : std::uint8_t {
    /// Virtual pipes (virtual_pipes.hpp): fast, but without momentum its fronts move at the
    /// linear wave speed (a dam break's front 25 % short of Ritter's).
    Pipes,
    /// Finite volumes with momentum (shallow_water.hpp): SWASHES's dam breaks and Thacker's
    /// lake within 0.3-4 %, at about 100x the pipes' CPU time per simulated second on the
    /// 4 cm dam break (728 against 7 ms, `sandtin bench water`).
    ShallowWater,
};

/// What ends a water operation besides its seconds (which then bound it).
enum class WaterStop : std::uint8_t {
    Seconds,  ///< the seconds run out
    /// No vertex holds rest_depth or more; what is left (films thinner than that) is taken as
    /// evaporated, so the terrain is dry.
    Dry,
    /// No depth changes faster than rest_rate: the water stands, or flows steadily.
    Rest,
};

/// Which operation a WaterOp was written as; only the parsing differs.
enum class WaterOpKind : std::uint8_t { Water, Rain, Flow };

struct WaterOp {
    double seconds = 0.0;  ///< s of water, > 0: the duration, or the longest with `until`
    WaterStop until = WaterStop::Seconds;
    double rest_rate = 1e-5;   ///< m/s: the fastest depth change that counts as at rest
    double rest_depth = 1e-6;  ///< m: shallower than this counts as dry
    WaterSources sources;
    OpenSides open;
    WaterScheme scheme = WaterScheme::Pipes;
    double friction = VirtualPipeOptions{}.friction;  ///< 1/s, the pipes' linear friction
    /// Manning's n (s/m^(1/3)) of the shallow-water scheme: a sand bed's.
    double manning = 0.025;
    /// Sand the water reached at least wet_depth deep takes at least this moisture, in [0, 1].
    double wet_moisture = 1.0;
    double wet_depth = 1e-3;  ///< m
    /// The water carries sand (water/sediment_transport.hpp): it cuts where it runs fast and
    /// drops the sand where it slows; what is still suspended at the end settles where it is.
    bool erode = false;
    /// m: with erode, a vertex the water built up by at least this much takes the material
    /// of the sand it laid there (water/sediment_transport.hpp): gravel washed onto sand
    /// shows, and slides, as gravel. A vertex has one material; a thinner film leaves it.
    double label_depth = 1e-3;
    /// m, >= 0 (0: off): edges under the water (at least kFilmDepth at both ends) longer than
    /// this are split as the water runs (water/wet_edge_split.hpp), so water on a coarse
    /// terrain gets the triangles it flows through. Each refinement rebuilds the water on the
    /// new triangles from rest, what it carried settled first. The ground it left dry is
    /// simplified after the operation, as after any edit.
    double detail = 0.0;
    /// How the moisture spreads and dries over the same seconds, after the wetting: the sand
    /// the water reached is wetted with what it reached by the end, then that moisture (and
    /// any already in the sand) spreads and dries for `seconds`. (Sand wetted late in the
    /// operation spreads and dries a little more than it would have; early, a little less.)
    MoistureSettings moisture;
};

/// Time passes with no water: the moisture in the sand spreads into drier sand and dries.
struct DryOp {
    double seconds = 0.0;  ///< s, > 0
    MoistureSettings moisture;
};

/// Parses the fields of a "water" operation (rain, nozzles, evaporation_mm_per_hour,
/// open_sides, seconds, until, scheme, friction (pipes) or manning (shallow_water),
/// wet_moisture, wet_depth, erode, diffusivity, drying_half_life); of a "rain" operation
/// (the same, with one rain's mm_per_hour, centre and radius in place of rain and nozzles); or
/// of a "flow" operation (the same without sources). Throws JsonInputError naming the field.
WaterOp parse_water_op(JsonFields& f, WaterOpKind kind = WaterOpKind::Water);

/// Runs `op` on `tin`, starting from the water the terrain holds, and leaves the water where
/// it is at the end in the terrain. Reports what the water did (m³ on the terrain at the
/// start, added, evaporated, left through the open sides and on the terrain at the end; the
/// seconds run and why it stopped; the wetted vertices; the deepest water), and under
/// "moisture" what the moisture did afterwards (as run_dry_op reports it).
/// `reached`, when given, receives the live vertices the water covered at some time in the
/// operation (those the detail added included), for the simplifier.
nlohmann::json run_water_op(const WaterOp& op, Tin& tin, std::vector<VertexId>* reached = nullptr);

/// Parses the fields of a "dry" operation (seconds, required; diffusivity, drying_half_life).
/// Throws JsonInputError naming the field.
DryOp parse_dry_op(JsonFields& f);

/// Runs `op` on `tin`. Reports the seconds, the sub-steps, the vertices computed, changed and
/// slowed (water/moisture_diffusion.hpp), the moisture sum A m (m²) before and after, and the
/// wettest vertex afterwards ({"vertex", "at", "moisture"}, or null when all is dry).
nlohmann::json run_dry_op(const DryOp& op, Tin& tin);

}  // namespace sandtin
