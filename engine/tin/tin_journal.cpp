// Tin: attributes and the change journal. The attribute setters change vertices outside edits
// and record them; take_changes() and the vertex change feeds hand what changed to their
// consumers (the GPU mirror, the physics).

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

ChangeSet Tin::take_changes() {
    Impl& m = *impl_;
    ChangeSet cs;
    cs.vertices = merge_into_ranges(m.journal_vertices.take());
    cs.triangles = merge_into_ranges(m.journal_slots.take());
    cs.vertex_capacity = m.events.vertex_ids.capacity();
    cs.slot_capacity = m.events.slots.capacity();
    cs.live_vertices = m.events.vertex_ids.live();
    cs.live_slots = m.live_triangles;
    cs.dead_slots = cs.slot_capacity - cs.live_slots;
    // The deaths are reported: their ids and slots may now be reused.
    m.events.vertex_ids.flush_deferred();
    m.events.slots.flush_deferred();
    return cs;
}

bool Tin::tracks_changes() const {
    return impl_->options.track_changes;
}

std::uint32_t Tin::subscribe_vertex_changes() {
    Impl& m = *impl_;
    for (std::uint32_t i = 0; i < m.feeds.size(); ++i) {
        if (!m.feeds[i].active) {
            m.feeds[i].active = true;
            return i;
        }
    }
    m.feeds.emplace_back();
    m.feeds.back().active = true;
    return static_cast<std::uint32_t>(m.feeds.size() - 1);
}

void Tin::unsubscribe_vertex_changes(std::uint32_t subscription) {
    Impl& m = *impl_;
    if (subscription >= m.feeds.size()) return;
    m.feeds[subscription].active = false;
    m.feeds[subscription].attributes.clear();
    m.feeds[subscription].topology.clear();
}

VertexChanges Tin::take_vertex_changes(std::uint32_t subscription) {
    Impl& m = *impl_;
    VertexChanges out;
    if (subscription >= m.feeds.size() || !m.feeds[subscription].active) return out;
    Impl::VertexFeed& f = m.feeds[subscription];
    for (std::uint32_t id : f.attributes.take())
        out.attributes.push_back(VertexId{id});
    for (std::uint32_t id : f.topology.take())
        out.topology.push_back(VertexId{id});
    return out;
}

}  // namespace sandtin
