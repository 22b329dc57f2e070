// The bookkeeping every edit ends with (EditFinisher), and the Tin::Impl helpers it shares with
// construction and restore: reading a face into its slot record, lumped areas, capacities.

#include "tin/detail/edit_finisher.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "tin/detail/impl_helpers.hpp"

namespace sandtin {

using detail::SlotRecord;
using Vh = Tin::Impl::Vh;

// ---- Tin::Impl helpers --------------------------------------------------------------------

SlotRecord Tin::Impl::read_face(const detail::Face& f) const {
    SlotRecord r;
    for (int i = 0; i < 3; ++i) {
        r.corners[static_cast<std::size_t>(i)] = corner_id(f.vertex(i));
        if (f.is_constrained(i)) r.constraint_mask |= static_cast<std::uint8_t>(1u << i);
    }
    if (!r.finite()) r.constraint_mask = 0;  // edges at infinity carry no meaning
    return r;
}

double Tin::Impl::recompute_lumped_area(std::uint32_t id, double snap2, bool* near_snapped) const {
    const Vh v = handle(id);
    const Vec2 p = va.position[id];
    auto fc = cdt.incident_faces(v);
    const auto done = fc;
    double area = 0.0;
    do {
        if (cdt.is_infinite(fc)) continue;
        const Vec2 a = va.position[fc->vertex(0)->id];
        const Vec2 b = va.position[fc->vertex(1)->id];
        const Vec2 c = va.position[fc->vertex(2)->id];
        area += detail::triangle_area(a, b, c);
        if (near_snapped != nullptr) {
            // Every finite neighbour is a corner of a finite face around v.
            for (const Vec2 q : {a, b, c}) {
                const double d2 = length_squared(q - p);
                if (d2 <= snap2 && d2 > 0.0) *near_snapped = true;
            }
        }
    } while (++fc != done);
    return area / 3.0;
}

void Tin::Impl::ensure_vertex_capacity() {
    const std::size_t n = events.vertex_ids.capacity();
    if (va.size() < n) va.resize(n);
    if (events.vertex_of_id.size() < n) events.vertex_of_id.resize(n, nullptr);
}

void Tin::Impl::ensure_slot_capacity() {
    const std::size_t n = events.slots.capacity();
    if (slot_cache.size() < n) slot_cache.resize(n);
    if (events.face_of_slot.size() < n) events.face_of_slot.resize(n, nullptr);
}

namespace detail {

thread_local DirtySet EditFinisher::affected_;
thread_local std::vector<std::uint32_t> EditFinisher::near_snapped_;
thread_local std::vector<std::uint8_t> EditFinisher::shift_floor_;

void EditFinisher::prepare_born() {
    impl_.ensure_vertex_capacity();
    const std::vector<std::uint32_t>& born = impl_.events.born_vertices;
    for (; prepared_born_ < born.size(); ++prepared_born_) {
        const std::uint32_t id = born[prepared_born_];
        if (impl_.events.vertex_of_id[id] == nullptr) continue;
        const Vh v = impl_.handle(id);
        VertexArrays& va = impl_.va;
        if (va.alive[id]) continue;  // already prepared
        va.position[id] = {v->point().x(), v->point().y()};
        va.height[id] = std::numeric_limits<double>::quiet_NaN();
        va.bedrock[id] = kNoBedrock;
        va.material[id] = 0;
        va.moisture[id] = 0.0f;
        va.slide[id] = {};
        va.water_depth[id] = 0.0;
        va.lumped_area[id] = 0.0;
        va.alive[id] = 1;
    }
}

void EditFinisher::inherit(std::uint32_t id, std::span<const std::uint32_t> sources,
                           std::span<const double> weights) {
    VertexArrays& va = impl_.va;
    double moisture = 0.0;
    double water_depth = 0.0;
    double bedrock = 0.0;
    bool has_bedrock = true;
    std::size_t heaviest = 0;
    for (std::size_t i = 0; i < sources.size(); ++i) {
        const std::uint32_t s = sources[i];
        moisture += weights[i] * static_cast<double>(va.moisture[s]);
        water_depth += weights[i] * va.water_depth[s];
        if (va.bedrock[s] <= kNoBedrock) has_bedrock = false;
        bedrock += weights[i] * va.bedrock[s];
        if (weights[i] > weights[heaviest]) heaviest = i;
    }
    va.moisture[id] = static_cast<float>(std::clamp(moisture, 0.0, 1.0));
    // The water's depth, like the moisture, as the corners had it (not its volume: an edit
    // that re-triangulates under water moves water as it moves sand, by interpolation).
    va.water_depth[id] = std::max(water_depth, 0.0);
    va.bedrock[id] = has_bedrock ? bedrock : kNoBedrock;
    if (!sources.empty()) {
        va.material[id] = va.material[sources[heaviest]];
        va.slide[id] = va.slide[sources[heaviest]];
    }
}

void EditFinisher::finish(VolumePolicy policy, std::span<const std::uint32_t> absorb,
                          EditReport* report) {
    Tin::Impl& m = impl_;
    m.ensure_vertex_capacity();
    m.ensure_slot_capacity();
    prepare_born();

    EditReport local;
    update_slots(local);
    CompensatedSum dv;
    retire_dead(dv, local);
    welcome_born(local);
    update_lumped_areas(policy, dv);
    local.volume_change = dv.value();
    double net_change = local.volume_change;

    if (policy == VolumePolicy::Conserve && local.volume_change != 0.0) {
        // The new vertices absorb the change when there are any, else all re-triangulated
        // ones; what the first cannot take (they lie on the bedrock) falls to the second.
        const double owed = shift_to_conserve(absorb, -local.volume_change, net_change);
        if (owed != 0.0) shift_to_conserve(affected_.ids(), owed, net_change);
    }
    for (std::uint32_t id : m.events.born_vertices) {
        if (m.va.alive[id]) level_slivers(id, true, policy, net_change);
    }
    if (policy == VolumePolicy::Conserve && local.volume_change != 0.0) {
        // Only vertices with a neighbour within the snap distance have a sliver to level
        // (found while their areas were summed, in the same order as affected_).
        for (std::uint32_t id : near_snapped_)
            level_slivers(id, false, policy, net_change);
    }
    m.volume_ledger.add(net_change);
    end_edit();
    if (report != nullptr) report->accumulate(local);
}

/// Slots: compares the cached content with CGAL's face now, and collects the corners of every
/// triangle that changed (before and after) in affected_.
void EditFinisher::update_slots(EditReport& local) {
    Tin::Impl& m = impl_;
    affected_.clear();
    for (std::uint32_t slot : m.events.op_slots.ids()) {
        const SlotRecord before = m.slot_cache[slot];
        const void* face = m.events.face_of_slot[slot];
        const SlotRecord after =
            face != nullptr ? m.read_face(*static_cast<const Face*>(face)) : SlotRecord{};
        if (before == after) continue;
        ++local.triangles_changed;
        m.journal.note_slot(slot);
        if (before.finite()) {
            --m.live_triangles;
            for (std::uint32_t c : before.corners)
                affected_.mark(c);
        }
        if (after.finite()) {
            ++m.live_triangles;
            for (std::uint32_t c : after.corners)
                affected_.mark(c);
        }
        m.slot_cache[slot] = after;
    }
    m.events.op_slots.clear();
}

/// The vertices that died take their volume with them.
void EditFinisher::retire_dead(CompensatedSum& dv, EditReport& local) {
    Tin::Impl& m = impl_;
    VertexArrays& va = m.va;
    for (std::uint32_t id : m.events.died_vertices) {
        dv.add(-va.lumped_area[id] * va.height[id]);
        va.alive[id] = 0;
        va.lumped_area[id] = 0.0;
        mark_vertex(id);
        m.note_topology(id);
        ++local.vertices_removed;
    }
}

/// The vertices that were born have a height by now (or get their neighbours').
void EditFinisher::welcome_born(EditReport& local) {
    Tin::Impl& m = impl_;
    VertexArrays& va = m.va;
    for (std::uint32_t id : m.events.born_vertices) {
        if (!va.alive[id]) continue;
        if (!std::isfinite(va.height[id])) resolve_height_from_neighbours(id);
        mark_vertex(id);
        ++local.vertices_created;
    }
}

/// The lumped areas of the re-triangulated vertices, and the volume their change moves.
void EditFinisher::update_lumped_areas(VolumePolicy policy, CompensatedSum& dv) {
    Tin::Impl& m = impl_;
    VertexArrays& va = m.va;
    const double snap2 = m.snap_distance * m.snap_distance;
    // Only a compensation shift (VolumePolicy::Conserve) levels the re-triangulated
    // vertices' slivers, so only then are their near neighbours looked for.
    const bool find_snapped = policy == VolumePolicy::Conserve;
    near_snapped_.clear();
    for (std::uint32_t id : affected_.ids()) {
        if (!va.alive[id]) continue;
        m.note_topology(id);
        bool near_snapped = false;
        const double a_new =
            m.recompute_lumped_area(id, snap2, find_snapped ? &near_snapped : nullptr);
        if (near_snapped) near_snapped_.push_back(id);
        const double a_old = va.lumped_area[id];
        if (a_new != a_old) {
            dv.add((a_new - a_old) * va.height[id]);
            va.lumped_area[id] = a_new;
            mark_vertex(id);
        }
    }
}

/// Vertices a rounding error apart (CGAL's crossings of nearly coincident constraints) cannot
/// be merged, so they must share one height, or the sliver between them is a vertical wall: a
/// new vertex takes its old neighbour's height (take_neighbour), and a compensation shift
/// carries over to such neighbours. Under VolumePolicy::Conserve the pair meets at its
/// area-weighted mean height instead, so levelling moves no volume: the physics moves the two
/// vertices independently, and a copy would leak what it moved between them.
void EditFinisher::level_slivers(std::uint32_t id, bool take_neighbour, VolumePolicy policy,
                                 double& net_change) {
    Tin::Impl& m = impl_;
    VertexArrays& va = m.va;
    const double snap2 = m.snap_distance * m.snap_distance;
    auto vc = m.cdt.incident_vertices(m.handle(id));
    const auto done = vc;
    do {
        if (m.cdt.is_infinite(vc) || vc->id == id) continue;
        const std::uint32_t w = vc->id;
        if (length_squared(va.position[w] - va.position[id]) > snap2) continue;
        const std::uint32_t from = take_neighbour ? w : id;
        const std::uint32_t to = take_neighbour ? id : w;
        if (va.height[to] == va.height[from]) continue;
        if (policy == VolumePolicy::Conserve) {
            const double a_from = va.lumped_area[from];
            const double a_to = va.lumped_area[to];
            const double mean =
                a_from + a_to > 0.0
                    ? (a_from * va.height[from] + a_to * va.height[to]) / (a_from + a_to)
                    : 0.5 * (va.height[from] + va.height[to]);
            net_change += a_from * (mean - va.height[from]) + a_to * (mean - va.height[to]);
            va.height[from] = mean;
            va.height[to] = mean;
            clamp_bedrock(from);
            mark_vertex(from);
        } else {
            net_change += va.lumped_area[to] * (va.height[from] - va.height[to]);
            va.height[to] = va.height[from];
        }
        clamp_bedrock(to);
        mark_vertex(to);
    } while (++vc != done);
}

/// Clears the events of the edit; with no range reader open, dead ids and slots are recycled
/// at once.
void EditFinisher::end_edit() {
    Tin::Impl& m = impl_;
    affected_.clear();
    m.events.born_vertices.clear();
    prepared_born_ = 0;
    m.events.died_vertices.clear();
    if (!m.journal.has_range_readers()) m.recycle_seen_deaths();
}

/// Adds `volume` m³ to the live vertices of `ids` by a uniform height shift. The bedrock is
/// not erodible: a vertex a negative shift would take below its bedrock stops on it, and
/// the others share what it could not give, round after round (a vertex without bedrock
/// takes any shift). Adds the volume moved to `net_change`; returns what is still owed.
double EditFinisher::shift_to_conserve(std::span<const std::uint32_t> ids, double volume,
                                       double& net_change) {
    VertexArrays& va = impl_.va;
    shift_floor_.assign(ids.size(), 0);
    for (int round = 0; round < 16 && volume != 0.0; ++round) {
        double area = 0.0;
        for (std::size_t k = 0; k < ids.size(); ++k) {
            if (va.alive[ids[k]] && !shift_floor_[k]) area += va.lumped_area[ids[k]];
        }
        if (!(area > 0.0)) break;
        const double dh = volume / area;
        bool floored = false;
        for (std::size_t k = 0; k < ids.size(); ++k) {
            const std::uint32_t id = ids[k];
            if (!va.alive[id] || shift_floor_[k]) continue;
            const double before = va.height[id];
            double after = before + dh;
            if (dh < 0.0 && after <= va.bedrock[id]) {
                after = std::min(before, va.bedrock[id]);
                shift_floor_[k] = 1;
                floored = true;
            }
            if (after == before) continue;  // below half an ulp, or on the bedrock already
            va.height[id] = after;
            mark_vertex(id);
            const double moved = va.lumped_area[id] * (after - before);
            net_change += moved;
            volume -= moved;
        }
        // Without a vertex stopped by its bedrock the shift was the uniform one, and what
        // is left is rounding.
        if (!floored) return 0.0;
    }
    return volume;
}

void EditFinisher::clamp_bedrock(std::uint32_t id) {
    VertexArrays& va = impl_.va;
    if (va.bedrock[id] > va.height[id]) va.bedrock[id] = va.height[id];
}

/// Last resort for a vertex CGAL created whose height no rule determined: the mean of its
/// neighbours with known heights. The edits resolve every case they create, so this only
/// guards against leaving NaN in the terrain.
void EditFinisher::resolve_height_from_neighbours(std::uint32_t id) {
    Tin::Impl& m = impl_;
    const Vh v = m.handle(id);
    double sum = 0.0;
    int n = 0;
    auto vc = m.cdt.incident_vertices(v);
    const auto done = vc;
    do {
        if (!m.cdt.is_infinite(vc) && std::isfinite(m.va.height[vc->id])) {
            sum += m.va.height[vc->id];
            ++n;
        }
    } while (++vc != done);
    m.va.height[id] = n > 0 ? sum / n : 0.0;
}

}  // namespace detail

}  // namespace sandtin
