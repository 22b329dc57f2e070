#include "water/live_water.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "tin/vertex_arrays.hpp"
#include "util/elapsed_ms.hpp"
#include "water/tin_water_mesh.hpp"
#include "water/wet_edge_split.hpp"

namespace sandtin {

namespace {

void check(bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("live water: ") + what);
}

bool same_sides(const OpenSides& a, const OpenSides& b) {
    return a.west == b.west && a.east == b.east && a.south == b.south && a.north == b.north;
}

}  // namespace

LiveWater::LiveWater(Tin& tin) : tin_(tin), reader_(tin) {
    // The first take reports every vertex: follow_terrain() finds any water already there.
    follow_terrain();
}

bool LiveWater::follow_terrain() {
    const ChangeSet changes = reader_.take();
    if (!changes.triangles.empty()) stale_ = true;
    const VertexArrays& va = tin_.vertices();
    const bool follow_pipes = pipes_ && !stale_ && va.size() <= pipes_->vertex_count();
    if (pipes_ && va.size() > pipes_->vertex_count()) stale_ = true;  // new ids: rebuild
    bool touched = false;
    for (const IdRange r : changes.vertices) {
        const std::uint32_t end =
            std::min<std::uint32_t>(r.end, static_cast<std::uint32_t>(va.size()));
        for (std::uint32_t v = r.begin; v < end; ++v) {
            if (v < near_water_.size() && near_water_[v]) touched = true;  // alive or not
            if (!va.alive[v]) continue;
            if (va.water_depth[v] > 0.0) wet_ = touched = true;
            if (!follow_pipes) continue;
            // Heights the erosion or a brush moved, depths an undo brought back.
            if (pipes_->mesh().bed[v] != va.height[v]) pipes_->set_bed(v, va.height[v]);
            if (pipes_->depth(v) != va.water_depth[v]) pipes_->set_depth(v, va.water_depth[v]);
        }
    }
    return touched;
}

std::vector<VertexId> LiveWater::take_dried() {
    std::vector<VertexId> out;
    out.swap(dried_);
    return out;
}

void LiveWater::add_shower(const Rain& shower) {
    check(std::isfinite(shower.mm_per_hour) && shower.mm_per_hour >= 0.0,
          "a shower's rate must be finite and >= 0");
    check(std::isfinite(shower.radius) && shower.radius > 0.0 && std::isfinite(shower.centre.x) &&
              std::isfinite(shower.centre.y),
          "a shower needs a finite centre and a radius > 0");
    showers_.push_back(shower);
}

void LiveWater::mark_near_water() {
    near_water_.assign(pipes_->vertex_count(), 0);
    for (const VirtualPipes::Pipe& p : pipes_->pipes()) {
        if (pipes_->depth(p.a) > 0.0 || pipes_->depth(p.b) > 0.0)
            near_water_[p.a] = near_water_[p.b] = 1;
    }
    for (std::size_t v = 0; v < near_water_.size(); ++v)
        if (pipes_->depth(v) > 0.0) near_water_[v] = 1;
}

void LiveWater::rebuild(const LiveWaterSettings& settings) {
    VirtualPipeOptions options;
    options.friction = settings.friction;
    pipes_.emplace(water_mesh_of(tin_), options);
    load_water_depths(*pipes_, tin_);
    open_borders(*pipes_, tin_.domain(), settings.open);
    pipes_friction_ = settings.friction;
    pipes_open_ = settings.open;
    stale_ = false;
}

bool LiveWater::idle(const LiveWaterSettings& settings) const {
    // Evaporation takes water at rest or standing still too (and a terrain it dried is dry).
    const bool still = (resting_ || !settings.flowing) && settings.evaporation_mm_per_hour == 0.0;
    return (!wet_ || still) && nozzles_.empty() && showers_.empty() &&
           settings.rain_mm_per_hour == 0.0;
}

LiveWaterFrame LiveWater::advance(double seconds, const LiveWaterSettings& settings,
                                  double budget_ms) {
    check(std::isfinite(seconds) && seconds >= 0.0, "seconds must be finite and >= 0");
    check(std::isfinite(budget_ms) && budget_ms >= 0.0, "the budget must be finite and >= 0");
    check(std::isfinite(settings.rain_mm_per_hour) && settings.rain_mm_per_hour >= 0.0 &&
              std::isfinite(settings.evaporation_mm_per_hour) &&
              settings.evaporation_mm_per_hour >= 0.0,
          "rain and evaporation must be finite rates >= 0");
    check(std::isfinite(settings.friction) && settings.friction >= 0.0,
          "friction must be finite and >= 0");
    check(std::isfinite(settings.wet_depth) && settings.wet_depth > 0.0 &&
              settings.wet_moisture >= 0.0f && settings.wet_moisture <= 1.0f,
          "the wetting depth must be > 0 and its moisture in [0, 1]");
    const auto start = std::chrono::steady_clock::now();
    LiveWaterFrame frame;
    // An edit under or beside the water, or a side opened, may start it flowing again.
    if (follow_terrain() || (pipes_ && !same_sides(pipes_open_, settings.open))) resting_ = false;
    if (!settings.erode) settle_sediment();  // Erode off: what the water carried drops at once
    if (idle(settings) || seconds == 0.0) {
        nozzles_.clear();
        showers_.clear();
        return frame;
    }
    check(std::isfinite(settings.label_depth) && settings.label_depth > 0.0,
          "the labelling depth must be finite and > 0");
    check(std::isfinite(settings.detail) && settings.detail >= 0.0,
          "the water's detail length must be finite and >= 0");
    label_depth_ = settings.label_depth;
    // Phase 1: pipes that match the terrain and the settings (the sand the water holds drops
    // where it is before the pipes are built again: their vertices may be gone).
    if (!pipes_ || stale_ || pipes_friction_ != settings.friction) {
        settle_sediment();
        rebuild(settings);
        frame.rebuilt = true;
    } else if (!same_sides(pipes_open_, settings.open)) {
        open_borders(*pipes_, tin_.domain(), settings.open);
        pipes_open_ = settings.open;
    }
    follow_erode_setting(settings);
    // Phase 2: sources and steps within the budget.
    WaterSources sources;
    sources.nozzles = std::move(nozzles_);
    nozzles_.clear();
    sources.rain = std::move(showers_);
    showers_.clear();
    if (settings.rain_mm_per_hour > 0.0)
        sources.rain.push_back({settings.rain_mm_per_hour, {}, 0.0});
    sources.evaporation_mm_per_hour = settings.evaporation_mm_per_hour;
    const double left_before = pipes_->volume_left();
    const auto spent_ms = [&] { return elapsed_ms(start); };
    while (frame.seconds < seconds && (frame.steps == 0 || spent_ms() < budget_ms)) {
        const double dt =
            std::min({settings.flowing ? pipes_->stable_time_step() : kLongestSourceStep,
                      kLongestSourceStep, seconds - frame.seconds});
        const SourceReport r = apply_sources(*pipes_, sources, dt);
        frame.added += r.added;
        frame.evaporated += r.evaporated;
        if (settings.flowing) pipes_->step(dt);
        if (settings.flowing && sediment_) sediment_->step(*pipes_, dt);
        frame.seconds += dt;
        ++frame.steps;
    }
    // Out of budget: the flow falls behind, but the sources give the whole frame's water (a
    // nozzle's litres per second do not depend on the machine's speed).
    if (frame.seconds < seconds) {
        const SourceReport r = apply_sources(*pipes_, sources, seconds - frame.seconds);
        frame.added += r.added;
        frame.evaporated += r.evaporated;
        frame.behind = seconds - frame.seconds;
    }
    frame.left = pipes_->volume_left() - left_before;
    frame.ran = true;
    measure_speeds(settings.flowing);
    // Phase 3: the depths into the terrain; at rest once they barely move with no source.
    double fastest = 0.0;
    write_back(settings, frame, fastest);
    wet_ = pipes_->volume() > 0.0;
    const bool was_resting = resting_;
    resting_ = sources.nozzles.empty() && sources.rain.empty() && settings.flowing &&
               fastest < kRestRate * frame.seconds;
    // Phase 4: detail where the water is (the pipes are built again next frame).
    if (settings.detail > 0.0 && settings.flowing)
        frame.refined = refine_wet_edges(settings.detail);
    if (resting_ && !was_resting) {
        // Still water carries nothing: what it held lies where it stopped.
        settle_sediment();
        mark_near_water();
    }
    frame.ms = spent_ms();
    return frame;
}

void LiveWater::follow_erode_setting(const LiveWaterSettings& settings) {
    if (settings.erode && !sediment_) {
        std::vector<double> rock = tin_.vertices().bedrock;
        rock.resize(pipes_->vertex_count(), kNoBedrock);
        for (double& z : rock) {
            if (!(z > 0.5 * kNoBedrock)) z = -std::numeric_limits<double>::infinity();
        }
        std::vector<std::uint16_t> material = tin_.vertices().material;
        material.resize(pipes_->vertex_count(), 0);
        sediment_.emplace(pipes_->mesh(), std::move(rock), SedimentOptions{}, std::move(material));
        relabelled_.assign(pipes_->vertex_count(), 0);
    } else if (!settings.erode && sediment_) {
        settle_sediment();
    }
}

void LiveWater::settle_sediment() {
    if (!sediment_ || !pipes_) return;
    sediment_->settle_all(*pipes_);
    write_beds();
    sediment_.reset();
    sediment_share_.clear();
    follow_terrain();  // its own writes come back through the journal
}

std::size_t LiveWater::write_beds() {
    const VertexArrays& va = tin_.vertices();
    const WaterMesh& m = pipes_->mesh();
    const std::size_t n = std::min(va.size(), pipes_->vertex_count());
    std::vector<VertexId> moved;
    std::vector<double> heights;
    for (std::size_t v = 0; v < n; ++v) {
        if (!va.alive[v] || m.bed[v] == va.height[v]) continue;
        moved.push_back(VertexId{static_cast<std::uint32_t>(v)});
        heights.push_back(m.bed[v]);
    }
    tin_.set_heights(moved, heights);
    // Sand laid down label_depth thick is of the material it came from.
    for (const VertexId id : moved) {
        const std::size_t v = id.index();
        if (relabelled_[v] || !(m.area[v] > 0.0)) continue;
        if (sediment_->dropped(v) / m.area[v] < label_depth_) continue;
        const std::uint16_t laid = sediment_->deposited_material(v);
        if (laid != va.material[v]) tin_.set_material(id, laid);
        relabelled_[v] = 1;
    }
    return moved.size();
}

std::size_t LiveWater::refine_wet_edges(double max_length) {
    // The terrain holds the pipes' depths: write_back ran just before.
    const std::vector<VertexId> born =
        split_wet_edges(tin_, max_length, kMaxWaterSplits, kFilmDepth);
    if (!born.empty()) stale_ = true;  // the pipes are built again from the refined terrain
    return born.size();
}

void LiveWater::measure_speeds(bool flowing) {
    speed_.assign(pipes_->vertex_count(), 0.0f);
    if (sediment_) {
        sediment_share_.assign(pipes_->vertex_count(), 0.0f);
        const WaterMesh& m = pipes_->mesh();
        for (std::size_t v = 0; v < sediment_share_.size(); ++v) {
            const double water = std::max(pipes_->depth(v), kFilmDepth) * m.area[v];
            if (pipes_->depth(v) > 0.0 && water > 0.0)
                sediment_share_[v] = static_cast<float>(sediment_->suspended(v) / water);
        }
    }
    if (!flowing) return;
    // The flow vector, not the sum of |flux|: the pipes' fluxes slosh back and forth in a
    // pond being filled (metres a second by |flux|, where the water spreads at centimetres),
    // and those cancel. A flow through a vertex counts twice in it (in and out), hence half.
    // A film at the wet front divides a trickle by almost no depth (metres a second on a
    // pond at rest): films count as kFilmDepth deep, as the glTF export leaves them out.
    const std::vector<Vec2> flow = pipes_->flow_vectors();
    const WaterMesh& m = pipes_->mesh();
    for (std::size_t v = 0; v < speed_.size(); ++v) {
        const double depth = pipes_->depth(v);
        if (depth > 0.0)
            speed_[v] = static_cast<float>(
                pipe_flow_speed(0.5 * length(flow[v]), std::max(depth, kFilmDepth), m.area[v]));
    }
}

void LiveWater::write_back(const LiveWaterSettings& settings, LiveWaterFrame& frame,
                           double& fastest) {
    if (sediment_) frame.eroded = write_beds();
    const VertexArrays& va = tin_.vertices();
    const std::size_t n = std::min(va.size(), pipes_->vertex_count());
    for (std::size_t v = 0; v < n; ++v) {
        if (!va.alive[v]) continue;
        const VertexId id{static_cast<std::uint32_t>(v)};
        const double depth = pipes_->depth(v);
        if (depth >= settings.wet_depth && va.moisture[v] < settings.wet_moisture) {
            tin_.set_moisture(id, settings.wet_moisture);
            ++frame.wetted;
        }
        if (va.water_depth[v] == depth) continue;
        if (depth == 0.0) dried_.push_back(id);
        fastest = std::max(fastest, std::abs(va.water_depth[v] - depth));
        tin_.set_water_depth(id, depth);
        ++frame.written;
    }
    // Its own writes come back through the journal; the pipes already hold them.
    follow_terrain();
}

double LiveWater::clear() {
    settle_sediment();  // the sand the water held stays on the terrain
    const VertexArrays& va = tin_.vertices();
    double volume = 0.0;
    for (std::size_t v = 0; v < va.size(); ++v) {
        if (!va.alive[v] || va.water_depth[v] == 0.0) continue;
        volume += va.lumped_area[v] * va.water_depth[v];
        tin_.set_water_depth(VertexId{static_cast<std::uint32_t>(v)}, 0.0);
        dried_.push_back(VertexId{static_cast<std::uint32_t>(v)});
    }
    follow_terrain();
    if (pipes_) {
        for (std::size_t v = 0; v < pipes_->vertex_count(); ++v)
            if (pipes_->depth(v) > 0.0) pipes_->set_depth(v, 0.0);
    }
    std::fill(speed_.begin(), speed_.end(), 0.0f);
    wet_ = false;
    resting_ = false;
    return volume;
}

WaterSummary LiveWater::measure() const {
    return measure_water(tin_);
}

}  // namespace sandtin
