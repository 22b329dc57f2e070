// Tin: attributes and the change journal. The attribute setters change vertices outside edits
// and record them; the range readers (take_changes) and the vertex feeds hand what changed to
// their consumers, each from a cursor of its own (detail/journal_readers.hpp).

#include <cmath>
#include <stdexcept>
#include <string>

#include "tin/detail/cgal_tin.hpp"
#include "tin/detail/impl_helpers.hpp"
#include "util/compensated_sum.hpp"

namespace sandtin {

using detail::require;

// ---- Attributes ---------------------------------------------------------------------------

namespace {

template <class T>
void set_attribute(Tin::Impl& m, VertexId v, std::vector<T>& array, T value, const char* what) {
    if (!m.alive(v)) {
        throw std::invalid_argument(std::string(what) + ": vertex id " + std::to_string(v.value) +
                                    " is not alive");
    }
    if (array[v.value] == value) return;
    array[v.value] = value;
    m.note_attribute(v.value);
}

}  // namespace

void Tin::set_height(VertexId v, double height) {
    require(std::isfinite(height), "set_height: height is not finite");
    Impl& m = *impl_;
    const double before = m.alive(v) ? m.va.height[v.value] : 0.0;
    set_attribute(m, v, m.va.height, height, "set_height");
    m.volume_ledger.add(m.va.lumped_area[v.value] * (height - before));
    if (m.va.bedrock[v.value] > height) set_attribute(m, v, m.va.bedrock, height, "set_height");
}

void Tin::set_bedrock(VertexId v, double bedrock) {
    require(std::isfinite(bedrock), "set_bedrock: bedrock is not finite");
    if (is_alive(v) && bedrock > impl_->va.height[v.value]) {
        throw std::invalid_argument("set_bedrock: bedrock " + std::to_string(bedrock) +
                                    " m would lie above the surface at " +
                                    std::to_string(impl_->va.height[v.value]) + " m");
    }
    set_attribute(*impl_, v, impl_->va.bedrock, bedrock, "set_bedrock");
}

void Tin::set_material(VertexId v, std::uint16_t material) {
    set_attribute(*impl_, v, impl_->va.material, material, "set_material");
}

void Tin::set_moisture(VertexId v, float moisture) {
    require(std::isfinite(moisture) && moisture >= 0.0f && moisture <= 1.0f,
            "set_moisture: moisture must lie in [0, 1]");
    set_attribute(*impl_, v, impl_->va.moisture, moisture, "set_moisture");
}

void Tin::set_water_depth(VertexId v, double depth) {
    require(std::isfinite(depth) && depth >= 0.0, "set_water_depth: depth must be finite and >= 0");
    set_attribute(*impl_, v, impl_->va.water_depth, depth, "set_water_depth");
}

void Tin::set_slide(VertexId v, Vec2f slide) {
    require(std::isfinite(slide.x) && std::isfinite(slide.y), "set_slide: offset is not finite");
    set_attribute(*impl_, v, impl_->va.slide, slide, "set_slide");
}

void Tin::set_heights(std::span<const VertexId> vertices, std::span<const double> heights) {
    Impl& m = *impl_;
    require(vertices.size() == heights.size(),
            "set_heights: vertices and heights differ in length");
    VertexArrays& va = m.va;
    CompensatedSum change;
    for (std::size_t i = 0; i < vertices.size(); ++i) {
        const std::uint32_t id = vertices[i].value;
        const double h = heights[i];
        if (!m.alive(vertices[i]) || !std::isfinite(h)) {
            throw std::invalid_argument("set_heights: dead vertex or non-finite height at entry " +
                                        std::to_string(i));
        }
        if (va.height[id] == h) continue;
        change.add(va.lumped_area[id] * (h - va.height[id]));
        va.height[id] = h;
        if (va.bedrock[id] > h) va.bedrock[id] = h;
        m.note_attribute(id);
    }
    m.volume_ledger.add(change.value());
}

// ---- Journal ------------------------------------------------------------------------------

namespace {

/// No ranges; the capacities and counts of now.
ChangeSet counts_only(const Tin::Impl& m) {
    ChangeSet cs;
    cs.vertex_capacity = m.events.vertex_ids.capacity();
    cs.slot_capacity = m.events.slots.capacity();
    cs.live_vertices = m.events.vertex_ids.live();
    cs.live_slots = m.live_triangles;
    cs.dead_slots = cs.slot_capacity - cs.live_slots;
    return cs;
}

ChangeSet take_reader(Tin::Impl& m, std::uint32_t reader) {
    ChangeSet cs = counts_only(m);
    detail::JournalReaders::Taken taken = m.journal.take(
        reader, m.events.vertex_ids.pending_list().size(), m.events.slots.pending_list().size());
    if (taken.everything) {
        if (cs.vertex_capacity > 0) cs.vertices = {IdRange{0, cs.vertex_capacity}};
        if (cs.slot_capacity > 0) cs.triangles = {IdRange{0, cs.slot_capacity}};
    } else {
        cs.vertices = merge_into_ranges(std::move(taken.vertices));
        cs.triangles = merge_into_ranges(std::move(taken.slots));
    }
    // This reader has now seen the deaths it reports: those every reader has seen are recycled
    // (unless recycling is held: then at the first take after it is let go).
    if (!m.recycling_held) m.recycle_seen_deaths();
    return cs;
}

}  // namespace

ChangeSet Tin::take_changes() {
    Impl& m = *impl_;
    if (m.default_reader == Impl::kNoReader) return counts_only(m);
    return take_reader(m, m.default_reader);
}

void Tin::hold_id_recycling(bool held) {
    impl_->recycling_held = held;
}

bool Tin::tracks_changes() const {
    return impl_->default_reader != Impl::kNoReader;
}

void Tin::set_track_changes(bool on) {
    Impl& m = *impl_;
    m.options.track_changes = on;
    if (on) {
        m.open_default_reader();
    } else if (m.default_reader != Impl::kNoReader) {
        m.journal.close_range_reader(m.default_reader);
        m.default_reader = Impl::kNoReader;
        m.recycle_seen_deaths();
    }
}

std::uint32_t Tin::open_change_reader() {
    return impl_->journal.open_range_reader(true);
}

void Tin::close_change_reader(std::uint32_t reader) {
    Impl& m = *impl_;
    if (reader == m.default_reader || !m.journal.is_open(reader)) return;
    m.journal.close_range_reader(reader);
    if (!m.recycling_held) m.recycle_seen_deaths();
}

ChangeSet Tin::take_changes(std::uint32_t reader) {
    Impl& m = *impl_;
    if (!m.journal.is_open(reader)) {
        throw std::invalid_argument("take_changes: change reader " + std::to_string(reader) +
                                    " is not open");
    }
    return take_reader(m, reader);
}

std::uint32_t Tin::subscribe_vertex_changes() {
    return impl_->journal.subscribe_vertex_feed();
}

void Tin::unsubscribe_vertex_changes(std::uint32_t subscription) {
    impl_->journal.unsubscribe_vertex_feed(subscription);
}

VertexChanges Tin::take_vertex_changes(std::uint32_t subscription) {
    auto [attributes, topology] = impl_->journal.take_vertex_feed(subscription);
    VertexChanges out;
    out.attributes.reserve(attributes.size());
    for (std::uint32_t id : attributes)
        out.attributes.push_back(VertexId{id});
    out.topology.reserve(topology.size());
    for (std::uint32_t id : topology)
        out.topology.push_back(VertexId{id});
    return out;
}

}  // namespace sandtin
