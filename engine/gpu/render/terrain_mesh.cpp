#include "gpu/render/terrain_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace sandtin::render {

std::uint64_t MeshUpdate::bytes() const {
    return count_in_ranges(vertices) * sizeof(RenderVertex) +
           count_in_ranges(slots) * 3 * sizeof(std::uint32_t);
}

TerrainMesh::TerrainMesh(MaterialTable materials) : materials_(std::move(materials)) {}

void TerrainMesh::compute_vertex(const Tin& tin, std::uint32_t id, std::vector<VertexId>& ring) {
    RenderVertex& out = vertices_[id];
    out = RenderVertex{};
    const VertexArrays& va = tin.vertices();
    if (!va.alive[id]) {
        wet_.forget(id);
        return;
    }
    const Vec2 origin = tin.domain().centre();
    const Vec2 p = va.position[id];
    const double h = va.height[id];
    // Faces around the vertex: consecutive counter-clockwise neighbours. Around a border vertex
    // the ring has a gap (the outside), where the pair turns clockwise or straight: skipped.
    tin.neighbours(VertexId{id}, ring);
    double nx = 0.0, ny = 0.0, nz = 0.0;
    for (std::size_t k = 0; k < ring.size(); ++k) {
        const std::size_t a = ring[k].index(), b = ring[(k + 1) % ring.size()].index();
        const Vec2 ea = va.position[a] - p, eb = va.position[b] - p;
        const double det = cross(ea, eb);
        if (ring.size() < 2 || det <= 0.0) continue;
        const double za = va.height[a] - h, zb = va.height[b] - h;
        // (ea, za) x (eb, zb): twice the face's area times its unit normal.
        const double cx = ea.y * zb - za * eb.y, cy = za * eb.x - ea.x * zb;
        nx += cx;
        ny += cy;
        nz += det;
    }
    const double n = std::sqrt(nx * nx + ny * ny + nz * nz);
    if (n > 0.0) {
        out.normal[0] = static_cast<float>(nx / n);
        out.normal[1] = static_cast<float>(ny / n);
        out.normal[2] = static_cast<float>(nz / n);
    } else {
        out.normal[2] = 1.0f;
    }
    out.position[0] = static_cast<float>(p.x - origin.x);
    out.position[1] = static_cast<float>(p.y - origin.y);
    out.position[2] = static_cast<float>(h);
    colour_vertex(tin, id);
    out.overlay[1] =
        va.bedrock[id] <= kNoBedrock ? 0.0f : static_cast<float>(std::max(0.0, h - va.bedrock[id]));
    out.overlay[2] = id < active_.size() && active_[id] ? 1.0f : 0.0f;
    out.slide[0] = va.slide[id].x;
    out.slide[1] = va.slide[id].y;
    out.water = static_cast<float>(va.water_depth[id]);
    out.speed = id < speed_.size() && out.water > 0.0f ? speed_[id] : 0.0f;
    out.sediment = id < sediment_.size() && out.water > 0.0f ? sediment_[id] : 0.0f;
    double surface = h + va.water_depth[id];
    if (!(va.water_depth[id] > 0.0)) {
        double level = -std::numeric_limits<double>::infinity();
        for (VertexId w : ring)
            if (va.water_depth[w.index()] > 0.0)
                level = std::max(level, va.height[w.index()] + va.water_depth[w.index()]);
        surface = std::min(h, level);
        if (level == -std::numeric_limits<double>::infinity()) surface = h;
    }
    out.surface = static_cast<float>(surface);
    wet_.refan(tin, id, ring);
}

namespace {

/// Whether two materials give every vertex the same albedo and the same tan(repose).
bool drawn_alike(const Material& a, const Material& b) {
    return a.colour[0] == b.colour[0] && a.colour[1] == b.colour[1] && a.colour[2] == b.colour[2] &&
           a.repose_dry == b.repose_dry && a.repose_wet == b.repose_wet &&
           a.moisture_scale == b.moisture_scale && a.slurry_start == b.slurry_start &&
           a.repose_saturated == b.repose_saturated;
}

}  // namespace

std::vector<std::uint16_t> TerrainMesh::set_materials(MaterialTable materials) {
    std::vector<std::uint16_t> changed;
    for (std::size_t k = 0; k < materials.size(); ++k) {
        const auto id = static_cast<std::uint16_t>(k);
        if (k >= materials_.size() || !drawn_alike(materials_.at(id), materials.at(id)))
            changed.push_back(id);
    }
    materials_ = std::move(materials);
    return changed;
}

void TerrainMesh::colour_vertex(const Tin& tin, std::uint32_t id) {
    const VertexArrays& va = tin.vertices();
    RenderVertex& out = vertices_[id];
    const Material& m = materials_.at(va.material[id]);
    const float wet = 1.0f - (1.0f - kWetReflectance) * std::clamp(va.moisture[id], 0.0f, 1.0f);
    for (int j = 0; j < 3; ++j)
        out.albedo[j] = m.colour[j] * wet;
    // The Slope overlay judges each face's own gradient (the fragment shader takes it from the
    // face's plane) against tan(alpha) interpolated from its corners: this vertex's.
    out.overlay[0] = static_cast<float>(m.talus_slope(va.moisture[id]));
}

MeshUpdate TerrainMesh::recolour(const Tin& tin, std::span<const std::uint16_t> changed) {
    if (vertices_.empty()) return rebuild(tin);
    std::vector<std::uint8_t> recoloured(materials_.size(), 0);
    for (std::uint16_t k : changed)
        if (k < recoloured.size()) recoloured[k] = 1;
    const VertexArrays& va = tin.vertices();
    const auto n = static_cast<std::uint32_t>(std::min(vertices_.size(), va.size()));
    MeshUpdate u;
    for (std::uint32_t id = 0; id < n; ++id) {
        const std::uint16_t k = va.material[id];
        if (!va.alive[id] || k >= recoloured.size() || !recoloured[k]) continue;
        colour_vertex(tin, id);
        if (!u.vertices.empty() && u.vertices.back().end == id)
            ++u.vertices.back().end;
        else
            u.vertices.push_back({id, id + 1});
    }
    return u;
}

void TerrainMesh::write_slot(const Tin& tin, TriangleSlot slot) {
    const auto c = tin.slot_triangle(slot);
    for (std::size_t k = 0; k < 3; ++k)
        indices_[3 * std::size_t{slot} + k] = c[0].valid() ? c[k].value : 0u;
}

namespace {

/// Pairs (a, b) flattened, each undirected edge once, in a canonical order.
std::vector<std::uint32_t> unique_edges(std::vector<std::pair<std::uint32_t, std::uint32_t>> e) {
    std::sort(e.begin(), e.end());
    e.erase(std::unique(e.begin(), e.end()), e.end());
    std::vector<std::uint32_t> out;
    out.reserve(e.size() * 2);
    for (const auto& [a, b] : e) {
        out.push_back(a);
        out.push_back(b);
    }
    return out;
}

}  // namespace

void TerrainMesh::collect_constrained(const Tin& tin) {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
    for (TriangleSlot s = 0; s < tin.slot_capacity(); ++s) {
        const std::uint8_t mask = tin.slot_constraint_mask(s);
        if (mask == 0) continue;
        const auto c = tin.slot_triangle(s);
        if (!c[0].valid()) continue;
        for (std::size_t i = 0; i < 3; ++i) {
            if (!(mask & (1u << i))) continue;
            const std::uint32_t a = c[(i + 1) % 3].value, b = c[(i + 2) % 3].value;
            edges.emplace_back(std::min(a, b), std::max(a, b));
        }
    }
    constrained_ = unique_edges(std::move(edges));
}

MeshUpdate TerrainMesh::rebuild(const Tin& tin) {
    vertices_.assign(tin.vertex_capacity(), RenderVertex{});
    indices_.assign(std::size_t{tin.slot_capacity()} * 3, 0u);
    wet_.clear();
    std::vector<VertexId> ring;
    for (std::uint32_t i = 0; i < tin.vertex_capacity(); ++i)
        compute_vertex(tin, i, ring);
    for (TriangleSlot s = 0; s < tin.slot_capacity(); ++s)
        write_slot(tin, s);
    collect_constrained(tin);
    wet_.settle();
    MeshUpdate u;
    u.resized = true;
    u.edges_changed = true;
    u.water_changed = true;
    if (!vertices_.empty()) u.vertices.push_back({0, static_cast<std::uint32_t>(vertices_.size())});
    if (tin.slot_capacity() > 0) u.slots.push_back({0, tin.slot_capacity()});
    return u;
}

MeshUpdate TerrainMesh::update(const Tin& tin, const ChangeSet& changes,
                               std::span<const VertexId> active_flipped) {
    if (vertices_.empty()) return rebuild(tin);
    // New ids and slots beyond the arrays: grow with headroom (the journal names the new
    // entries, so nothing else needs recomputing; the renderer reallocates its buffers).
    MeshUpdate u;
    // The new tail (headroom included) is on no upload range, and a GPU buffer that was big
    // enough already holds whatever it held before there (another terrain's triangles after a
    // document was replaced, undefined memory on a fresh allocation): a resized mesh is
    // uploaded whole. Growth is geometric, so this is amortised.
    if (tin.vertex_capacity() > vertices_.size()) {
        vertices_.resize(tin.vertex_capacity() + tin.vertex_capacity() / 2, RenderVertex{});
        u.resized = true;
    }
    if (std::size_t{tin.slot_capacity()} * 3 > indices_.size()) {
        indices_.resize((std::size_t{tin.slot_capacity()} + tin.slot_capacity() / 2) * 3, 0u);
        u.resized = true;
    }
    // Vertices to recompute: those the journal names, the corners of changed slots, the
    // flipped active flags, and the neighbours of all of them.
    std::vector<std::uint32_t> seeds;
    for (const IdRange& r : changes.vertices) {
        for (std::uint32_t i = r.begin; i < r.end; ++i)
            seeds.push_back(i);
    }
    for (const IdRange& r : changes.triangles) {
        for (TriangleSlot s = r.begin; s < r.end; ++s) {
            write_slot(tin, s);
            for (std::size_t k = 0; k < 3; ++k)
                seeds.push_back(indices_[3 * std::size_t{s} + k]);
        }
    }
    for (VertexId v : active_flipped)
        seeds.push_back(v.value);
    std::sort(seeds.begin(), seeds.end());
    seeds.erase(std::unique(seeds.begin(), seeds.end()), seeds.end());
    mark_.resize(vertices_.size(), 0);
    std::vector<std::uint32_t> dirty;
    std::vector<VertexId> ring;
    auto add = [&](std::uint32_t id) {
        if (id < mark_.size() && !mark_[id]) {
            mark_[id] = 1;
            dirty.push_back(id);
        }
    };
    for (std::uint32_t id : seeds) {
        add(id);
        if (id < tin.vertex_capacity() && tin.is_alive(VertexId{id})) {
            tin.neighbours(VertexId{id}, ring);
            for (VertexId n : ring)
                add(n.value);
        }
    }
    const std::uint64_t water_before = wet_.version();
    for (std::uint32_t id : dirty) {
        compute_vertex(tin, id, ring);
        mark_[id] = 0;
    }
    wet_.settle();
    u.water_changed = wet_.version() != water_before;
    u.vertices = merge_into_ranges(std::move(dirty));
    u.slots = changes.triangles;
    if (!changes.triangles.empty()) {
        // Constraint flags live on slots; the list is small, so it is recollected.
        const std::vector<std::uint32_t> before = constrained_;
        collect_constrained(tin);
        u.edges_changed = before != constrained_;
    }
    return u;
}

std::vector<std::uint32_t> TerrainMesh::all_edges() const {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
    edges.reserve(indices_.size());
    for (std::size_t s = 0; s + 2 < indices_.size(); s += 3) {
        if (indices_[s] == indices_[s + 1]) continue;  // free slot
        for (std::size_t k = 0; k < 3; ++k) {
            const std::uint32_t a = indices_[s + k], b = indices_[s + (k + 1) % 3];
            edges.emplace_back(std::min(a, b), std::max(a, b));
        }
    }
    return unique_edges(std::move(edges));
}

}  // namespace sandtin::render
