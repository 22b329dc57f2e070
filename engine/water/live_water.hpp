#pragma once
// Water that runs with the editor (issue 40, items 2 and 7): the virtual pipes
// (virtual_pipes.hpp) kept beside a Tin that the artist edits while the water flows. The water
// lives in the terrain (VertexArrays::water_depth), so undo, saving and exporting see it; this
// class only moves it, a frame at a time:
//  - it reads the terrain's change journal through a reader of its own: a re-triangulation
//    (a stamp, a simplification) rebuilds the pipes from the terrain, and changed heights or
//    depths (the erosion, a brush, an undo) are taken over vertex by vertex;
//  - each frame it applies the sources (the Water tool's nozzle, rain, evaporation) and steps
//    the water for the frame's seconds under the CFL step, within a time budget, then writes
//    the depths that changed back into the terrain (journaled);
//  - a dry terrain with no source costs nothing but reading the vertices the journal names:
//    no pipes are built and no step runs; nor does water at rest (no depth changing faster
//    than kRestRate, and no source) until the terrain under it changes: an edit of a vertex
//    under the water or beside it, or a side opened. Edits elsewhere (the erosion sliding,
//    a stamp away from the pond) are only noted, so they stay local.
// Units: metres, seconds, m³; rates in mm/h and L/s as in water_sources.hpp.

#include <cstddef>
#include <optional>
#include <span>
#include <vector>

#include "tin/change_reader.hpp"
#include "tin/tin.hpp"
#include "water/sediment_transport.hpp"
#include "water/virtual_pipes.hpp"
#include "water/water_borders.hpp"
#include "water/water_sources.hpp"
#include "water/water_summary.hpp"

namespace sandtin {

/// m/s: water whose depths change more slowly than this, with no source, is at rest and stops
/// stepping (0.36 mm an hour; the pipes' friction would take minutes more to still it fully).
inline constexpr double kRestRate = 1e-7;

/// m: water shallower than this is a film when its speed is estimated (speeds()): 0.1 mm, the
/// depth the glTF export also leaves out (io/export_water_mesh.hpp).
inline constexpr double kFilmDepth = 1e-4;
/// Edges LiveWaterSettings::detail splits in one frame at most: an elevation model's lake
/// refines over a few frames instead of stalling one.
inline constexpr std::size_t kMaxWaterSplits = 2000;

struct LiveWaterSettings {
    bool flowing = true;                   ///< false: the water stands still (sources still add)
    double rain_mm_per_hour = 0.0;         ///< on the whole terrain, >= 0
    double evaporation_mm_per_hour = 0.0;  ///< >= 0
    OpenSides open;                        ///< the others are walls
    double friction = VirtualPipeOptions{}.friction;  ///< 1/s
    /// Sand under at least wet_depth of water takes at least wet_moisture (in [0, 1]), as a
    /// script's water operation wets it: the relaxation then holds it at its wetter angle.
    double wet_depth = 1e-3;  ///< m, > 0
    float wet_moisture = 1.0f;
    /// The flowing water carries sand (sediment_transport.hpp, its default law): it picks
    /// sand up where it runs fast and steep and drops it where it slows, and the terrain's
    /// heights follow. Sand plus what the water holds is conserved; the rock is never eroded.
    bool erode = false;
    /// m: a vertex the water built up by at least this much takes the material most of that
    /// sand was (gravel washed onto sand is gravel), as the script's water operation does.
    double label_depth = 1e-3;
    /// m, >= 0 (0: off): r_S for the water. After a frame, every edge longer than this with
    /// water at both ends (kFilmDepth or more) is split at its midpoint, so the water gets the
    /// detail it flows through (an imported elevation model's flats are metres across). The
    /// sand's volume is kept by the split, the water's by adding what the new triangulation
    /// changed to the new vertices. The simplifier leaves wet vertices alone and takes them
    /// once the ground is dry and planar again.
    double detail = 0.0;
};

/// What one frame of water did.
struct LiveWaterFrame {
    bool ran = false;      ///< the water stepped, or a source added some
    bool rebuilt = false;  ///< the pipes were built again from the terrain
    double seconds = 0.0;  ///< the flow stepped this frame (less than asked when out of budget)
    /// Seconds the flow fell behind for want of budget; the sources still gave the water of
    /// all the seconds asked.
    double behind = 0.0;
    std::size_t steps = 0;
    double added = 0.0, evaporated = 0.0, left = 0.0;  ///< m³ this frame
    std::size_t written = 0;                           ///< depths written back into the terrain
    std::size_t wetted = 0;                            ///< vertices whose moisture the water raised
    std::size_t eroded = 0;   ///< vertices whose height the sand the water moved changed
    std::size_t refined = 0;  ///< vertices the detail setting added under the water
    double ms = 0.0;
};

class LiveWater {
  public:
    /// `tin` must outlive this and stay where it is (a journal reader holds its address).
    explicit LiveWater(Tin& tin);

    /// Water enters at `nozzle` during the next advance() only (the Water tool, held there).
    void add_nozzle(const Nozzle& nozzle) { nozzles_.push_back(nozzle); }
    /// Rain falls on `shower`'s disc during the next advance() only (the Rain tool, held
    /// there), besides the settings' rain on the whole terrain. Throws std::invalid_argument
    /// for a negative or non-finite rate or radius, or a radius of 0 (the whole terrain is
    /// LiveWaterSettings::rain_mm_per_hour's).
    void add_shower(const Rain& shower);
    /// Advances the water by up to `seconds` (>= 0), stopping early once `budget_ms` of CPU
    /// time is spent. Throws std::invalid_argument for negative or non-finite arguments or
    /// settings.
    LiveWaterFrame advance(double seconds, const LiveWaterSettings& settings, double budget_ms);
    /// Whether advance() would do nothing, as of the last advance() (an edit since is seen by
    /// the next one): no source, and the terrain dry, or its water at rest or not flowing with
    /// no evaporation.
    bool idle(const LiveWaterSettings& settings) const;
    /// The water has come to rest (and stays so until a source or an edit disturbs it).
    bool resting() const { return resting_; }
    /// Takes every drop off the terrain (journaled, so one undo level can bring it back).
    /// Returns the m³ taken.
    double clear();
    /// O(vertices): the water the terrain holds now.
    WaterSummary measure() const;
    /// Flow speed per vertex id (m/s, virtual_pipes.hpp pipe_flow_speed) as the last frame
    /// that ran left it: 0 where dry, and everywhere while the water stands still. For the
    /// editor's Speed overlay; shorter than the terrain's arrays before any water ran.
    std::span<const float> speeds() const { return speed_; }
    /// Sand the water carries per vertex id, as a share of the water's volume (m³/m³, films
    /// counted kFilmDepth deep), as the last frame left it; empty without erosion. For the
    /// editor's Sediment overlay.
    std::span<const float> sediment() const { return sediment_share_; }
    /// m³ of sand the water holds now (0 without erosion): the terrain's volume plus this is
    /// what erosion by water conserves.
    double suspended() const { return sediment_ ? sediment_->suspended() : 0.0; }
    /// The vertices the water left since the last call (held water, now dry): for the
    /// simplifier, which leaves wet ground alone, so that the detail added under the water
    /// goes once the ground is dry and planar again.
    std::vector<VertexId> take_dried();

  private:
    /// Takes the journal's changes: notes a re-triangulation, water that appeared, and hands
    /// the pipes changed heights and depths. Returns whether a change touched the water: a
    /// vertex that holds water now, or held it or bordered it when the water came to rest.
    bool follow_terrain();
    /// Marks the vertices under the water and their neighbours (near_water_).
    void mark_near_water();
    void rebuild(const LiveWaterSettings& settings);
    /// speed_ from the pipes' fluxes (all 0 when the water does not flow), and the sediment's
    /// share of the water.
    void measure_speeds(bool flowing);
    /// Starts or stops the sediment to match `settings.erode`; stopping drops what it holds.
    void follow_erode_setting(const LiveWaterSettings& settings);
    /// Drops every grain the water holds where it is and writes the beds into the terrain.
    void settle_sediment();
    /// Writes the beds the sediment moved into the terrain's heights, and relabels the vertices
    /// built up by label_depth with the material laid on them. Returns the vertices written.
    std::size_t write_beds();
    /// Splits the wet edges longer than `max_length` (at most kMaxWaterSplits a frame) and
    /// keeps the water's volume; returns the vertices added.
    std::size_t refine_wet_edges(double max_length);
    /// Writes the depths that changed, and the moisture of the sand they wet, into the
    /// terrain; `fastest` becomes the largest depth change (m).
    void write_back(const LiveWaterSettings& settings, LiveWaterFrame& frame, double& fastest);

    Tin& tin_;
    ChangeReader reader_;
    std::optional<VirtualPipes> pipes_;
    double pipes_friction_ = -1.0;
    OpenSides pipes_open_;
    bool stale_ = true;  ///< the pipes no longer match the triangulation
    bool wet_ = false;   ///< some vertex may hold water
    bool resting_ = false;
    /// Per vertex, as the water came to rest: 1 under it or sharing a pipe with a vertex that
    /// is. An edit elsewhere cannot start it flowing.
    std::vector<std::uint8_t> near_water_;
    std::vector<Nozzle> nozzles_;
    std::vector<Rain> showers_;
    std::vector<float> speed_;                   ///< per vertex id, m/s
    std::optional<SedimentTransport> sediment_;  ///< while eroding, on pipes_'s mesh
    std::vector<float> sediment_share_;          ///< per vertex id, m³ of sand per m³ of water
    std::vector<std::uint8_t> relabelled_;       ///< per vertex id: took a laid material
    std::vector<VertexId> dried_;                ///< since the last take_dried()
    double label_depth_ = LiveWaterSettings{}.label_depth;  ///< the last advance()'s
};

}  // namespace sandtin
