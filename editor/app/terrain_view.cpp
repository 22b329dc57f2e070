#include "terrain_view.hpp"
#include "util/elapsed_ms.hpp"

#include <algorithm>
#include <stdexcept>

namespace sandtin::editor {

namespace {

using Clock = std::chrono::steady_clock;

/// The 2nd and 98th percentiles of the live heights (m), high at least 0.1 mm above low;
/// nothing for fewer than two vertices.
std::optional<std::pair<double, double>> contrast_range(const Tin& tin) {
    const VertexArrays& va = tin.vertices();
    std::vector<double> h;
    h.reserve(tin.vertex_count());
    for (std::size_t i = 0; i < va.size(); ++i) {
        if (va.alive[i]) h.push_back(va.height[i]);
    }
    if (h.size() < 2) return std::nullopt;
    const auto at = [&](double q) {
        auto it = h.begin() + static_cast<long>(q * static_cast<double>(h.size() - 1));
        std::nth_element(h.begin(), it, h.end());
        return *it;
    };
    const double low = at(0.02);
    return std::pair{low, std::max(at(0.98), low + 1e-4)};
}

}  // namespace

TerrainView::TerrainView(gpu::VulkanContext& context, render::TerrainRenderer& renderer)
    : context_(context), renderer_(renderer) {}

TerrainView::~TerrainView() = default;

void TerrainView::release() {
    // The renderer forgets its buffers, so nothing of that terrain stays in memory it draws
    // from; the readers close on the TIN while it still exists.
    renderer_.use_vertex_normals();  // the map it samples goes next
    normal_map_.reset();
    normal_map_changes_.reset();
    mirror_.reset();
    mesh_changes_.reset();
    renderer_.drop_mesh();
    mesh_.reset();
}

void TerrainView::rebuild(Document& doc) {
    release();  // everything built for the old terrain goes
    mesh_ = std::make_unique<render::TerrainMesh>(doc.materials());
    materials_version_ = doc.materials_version();
    mesh_changes_ = std::make_unique<ChangeReader>(doc.tin());
    mirror_ = std::make_unique<gpu::TinMirror>(context_, doc.tin(), doc.materials());
    start(doc);
    update(doc, [] {});  // the mesh, the mirror and the normal map exist before anything draws
}

void TerrainView::rebuild(Document& doc, PreparedView prepared) {
    if (!prepared.mesh || !prepared.mesh_changes || !prepared.mirror || !prepared.normal_map ||
        !prepared.normal_map_changes || &prepared.mesh_changes->tin() != &doc.tin() ||
        &prepared.mirror->tin() != &doc.tin() || !prepared.normal_map->complete())
        throw std::logic_error("TerrainView::rebuild: the view was prepared for another terrain");
    release();
    mesh_changes_ = std::move(prepared.mesh_changes);
    mesh_ = std::move(prepared.mesh);
    // The table moved with the document (whose version a move bumps): the one the mesh has.
    materials_version_ = doc.materials_version();
    renderer_.adopt(std::move(prepared.mesh_buffers), *mesh_);
    mirror_ = std::move(prepared.mirror);
    start(doc);
    normal_map_changes_ = std::move(prepared.normal_map_changes);
    normal_map_ = std::move(prepared.normal_map);
    renderer_.set_normal_map(normal_map_->view(), normal_map_->sampler());
    ++normal_map_bakes_;
    // What changed since the preparation reaches the mesh, the mirror and the map through
    // their readers, below.
    stale_ = false;
    if (prepared.contrast) {
        contrast_low_ = prepared.contrast->first;
        contrast_high_ = prepared.contrast->second;
        contrast_at_ = Clock::now();
        contrast_stale_ = false;
    }
    update(doc, [] {});
}

void TerrainView::start(Document& doc) {
    normal_map_changes_ = std::make_unique<ChangeReader>(doc.tin());
    active_.clear();
    active_ids_.clear();
    active_flipped_.clear();
    stale_ = true;
    contrast_stale_ = true;
}

PreparedView TerrainView::prepare(Document& doc, gpu::VulkanContext& context,
                                  const ProgressCallback& progress) {
    // Shares of the time measured on a 10^6-vertex scene (6.3 s on lavapipe while the UI thread
    // drew the bar): the mesh 8 %, the mirror's graph 28 %, the uploads 51 %, the map 13 %.
    PreparedView out;
    if (progress) progress({0.0, "building the render mesh"});
    out.mesh_changes = std::make_unique<ChangeReader>(doc.tin());
    out.mesh_changes->take();  // "everything": the mesh below is built from everything
    out.mesh = std::make_unique<render::TerrainMesh>(doc.materials());
    out.mesh->rebuild(doc.tin());
    out.contrast = contrast_range(doc.tin());
    if (progress) progress({0.1, "building the GPU copy's graph"});
    gpu::MirrorSeed seed = gpu::prepare_mirror_seed(doc.tin());
    if (progress) progress({0.35, "uploading the terrain to the GPU"});
    write_whole_mesh(context, *out.mesh, out.mesh_buffers);
    out.mirror = std::make_unique<gpu::TinMirror>(context, std::move(seed), doc.materials());
    out.mirror->sync();
    out.mirror->staging().wait_idle();  // nothing in flight is handed to the UI thread
    // The map a band at a time, as frames bake it: the context's one-shot submissions, which
    // the UI thread shares, are never held for long.
    out.normal_map_changes = std::make_unique<ChangeReader>(doc.tin());
    out.normal_map_changes->take();  // "everything": the bake covers it
    out.normal_map = std::make_unique<render::TerrainNormalMap>(*out.mirror, doc.tin().domain(),
                                                                kNormalMapSide, false);
    for (std::uint32_t row = 0; !out.normal_map->complete(); row += kNormalMapRowsPerFrame) {
        if (progress)
            progress({0.85 + 0.15 * row / out.normal_map->grid().height, "baking the normal map"});
        out.normal_map->bake_rows(kNormalMapRowsPerFrame);
    }
    if (progress) progress({1.0, "done"});
    return out;
}

ViewUpdate TerrainView::update(Document& doc, const std::function<void()>& wait_idle) {
    ViewUpdate out;
    // The colours and slope ratios of the vertices whose material was edited: recomputed and
    // uploaded before this frame's changes (which may overwrite some of them again).
    std::optional<render::MeshUpdate> recoloured;
    if (doc.materials_version() != materials_version_) {
        const std::vector<std::uint16_t> changed = mesh_->set_materials(doc.materials());
        mirror_->set_materials(doc.materials());
        materials_version_ = doc.materials_version();
        if (!stale_ && !changed.empty()) recoloured = mesh_->recolour(doc.tin(), changed);
    }
    // The journal says what changed; nothing changed means no recomputation and no upload.
    const ChangeSet changes = mesh_changes_->take();
    if (recoloured) {
        wait_idle();
        renderer_.upload(*mesh_, *recoloured);
        mesh_recomputed_ += count_in_ranges(recoloured->vertices);
    }
    if (!stale_ && changes.empty() && active_flipped_.empty() && !baking_normal_map()) return out;
    const auto t0 = Clock::now();
    mesh_->set_active(active_);
    mesh_->set_water_speed(doc.water().speeds());
    mesh_->set_water_sediment(doc.water().sediment());
    const render::MeshUpdate update =
        stale_ ? mesh_->rebuild(doc.tin()) : mesh_->update(doc.tin(), changes, active_flipped_);
    active_flipped_.clear();
    stale_ = false;
    ++mesh_updates_;
    mesh_recomputed_ += count_in_ranges(update.vertices);
    if (update.resized) ++mesh_rebuilds_;
    out.mesh_ms = elapsed_ms(t0);
    const auto t1 = Clock::now();
    wait_idle();
    const std::uint64_t before = renderer_.bytes_uploaded();
    renderer_.upload(*mesh_, update);
    out.upload_bytes = renderer_.bytes_uploaded() - before;
    update_contrast_range(doc.tin());
    out.upload_ms = elapsed_ms(t1);
    const auto t2 = Clock::now();
    update_normal_map(doc);
    out.bake_ms = elapsed_ms(t2);
    return out;
}

void TerrainView::update_normal_map(Document& doc) {
    // The mirror takes what changed since its last sync, whoever synced it last (a GPU
    // solver's step syncs it too; the solver wakes what changed through a feed of its own).
    mirror_->sync();
    if (!normal_map_) {
        normal_map_changes_->take();  // "everything": the first bake covers it
        normal_map_ = std::make_unique<render::TerrainNormalMap>(*mirror_, doc.tin().domain(),
                                                                 kNormalMapSide, false);
        return;  // the frame that installs a terrain uploads it; the bands come after
    }
    if (!normal_map_->complete()) {
        // A new terrain's map is baked a band of rows a frame (a 1024-row bake took 145 ms on 10^5
        // vertices of a frame on a CPU renderer); meanwhile the renderer shades with vertex
        // normals. What changes meanwhile stays in the reader, and is re-baked once the map is
        // whole.
        normal_map_->bake_rows(kNormalMapRowsPerFrame);
        if (!normal_map_->complete()) return;
        renderer_.set_normal_map(normal_map_->view(), normal_map_->sampler());
        ++normal_map_bakes_;
    }
    const ChangeSet dirty = normal_map_changes_->take();
    if (const auto texels = normal_map_->rebake(doc.tin(), dirty)) {
        ++normal_map_bakes_;
        normal_map_texels_ = std::uint64_t{texels->width()} * texels->height();
    }
}

void TerrainView::update_contrast_range(const Tin& tin) {
    // The contrast curve stretches the 2nd..98th percentile of the heights over the full
    // range (the seeds' histogram stretch). O(n): refreshed at most twice a second.
    if (!contrast_stale_ && Clock::now() - contrast_at_ < std::chrono::milliseconds(500)) return;
    const std::optional<std::pair<double, double>> range = contrast_range(tin);
    if (!range) return;
    contrast_low_ = range->first;
    contrast_high_ = range->second;
    contrast_at_ = Clock::now();
    contrast_stale_ = false;
}

void TerrainView::set_active(std::span<const VertexId> active) {
    // Clear the old flags, set the new ones; the mesh recomputes only the flags that flipped.
    for (VertexId v : active_ids_) {
        active_[v.index()] = 0;
        active_flipped_.push_back(v);
    }
    active_ids_.clear();
    for (VertexId v : active) {
        if (v.index() >= active_.size()) active_.resize(v.index() + 1 + active_.size() / 2, 0);
        if (!active_[v.index()]) {
            active_[v.index()] = 1;
            active_ids_.push_back(v);
            active_flipped_.push_back(v);
        }
    }
}

void TerrainView::clear_active() {
    for (VertexId v : active_ids_) {
        active_[v.index()] = 0;
        active_flipped_.push_back(v);
    }
    active_ids_.clear();
}

std::uint64_t TerrainView::gpu_work() const {
    return normal_map_bakes_ + (mirror_ ? mirror_->staging().batches_submitted() : 0);
}

}  // namespace sandtin::editor
