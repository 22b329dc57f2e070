#pragma once
// The terrain as the GPU shows it: the render mesh and the renderer's buffers, the GPU mirror
// (which the normal map is baked from and the GPU solver relaxes on), the baked normal map, the
// active-vertex overlay and the contrast curve's range. Built whole for a document (nothing of
// another terrain stays in it) and updated each frame from the TIN's change journal, each of
// the mesh, the mirror and the normal map through a reader of its own: nothing changed, nothing
// recomputed, nothing uploaded.

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "document.hpp"
#include "gpu/mirror_seed.hpp"
#include "gpu/render/normal_map.hpp"
#include "gpu/render/terrain_mesh.hpp"
#include "gpu/render/terrain_renderer.hpp"
#include "gpu/tin_mirror.hpp"
#include "gpu/vulkan_context.hpp"
#include "io/progress.hpp"
#include "tin/change_reader.hpp"

namespace sandtin::editor {

/// What TerrainView::rebuild() builds, built beforehand on the worker thread that opened,
/// imported or recovered the document (app_jobs.cpp): the render mesh and its GPU buffers, the
/// GPU mirror uploaded whole, the normal map baked whole, and the contrast range. The UI thread
/// only adopts them: on lavapipe, at 10^6 vertices, the uploads were 1.9 s of the install
/// frame, and the map's bake 8 frames of 100-260 ms. The readers of the TIN's journal were
/// opened before what they follow was built, so whatever changes later still reaches it. It
/// must go before the document's TIN does (PreparedDocument keeps that order).
struct PreparedView {
    std::unique_ptr<ChangeReader> mesh_changes;  ///< opened before the mesh was built
    std::unique_ptr<render::TerrainMesh> mesh;
    render::MeshBuffers mesh_buffers;                      ///< `mesh`, written whole
    std::unique_ptr<gpu::TinMirror> mirror;                ///< synced, its uploads landed
    std::unique_ptr<ChangeReader> normal_map_changes;      ///< opened before the map was baked
    std::unique_ptr<render::TerrainNormalMap> normal_map;  ///< complete; reads `mirror`
    std::optional<std::pair<double, double>> contrast;     ///< low and high heights (m)
};

/// A document read on a worker thread and its view prepared there: the UI thread only uploads
/// (App::install_document). Members go in reverse order: the view's readers before the TIN.
struct PreparedDocument {
    Document document;
    PreparedView view;
};

/// The normal map's longer side (texels), and the rows of it baked per update while a new
/// terrain's map is made: 8 updates for the whole map.
inline constexpr std::uint32_t kNormalMapSide = 1024;
inline constexpr std::uint32_t kNormalMapRowsPerFrame = 128;

/// What one update did and took (milliseconds), for the Stats window.
struct ViewUpdate {
    double mesh_ms = 0.0, upload_ms = 0.0, bake_ms = 0.0;
    std::uint64_t upload_bytes = 0;
};

class TerrainView {
  public:
    /// `renderer` draws what this view uploads; both outlive it.
    TerrainView(gpu::VulkanContext& context, render::TerrainRenderer& renderer);
    ~TerrainView();
    TerrainView(const TerrainView&) = delete;
    TerrainView& operator=(const TerrainView&) = delete;

    /// Tears down everything built for the previous terrain and builds the mesh, the mirror
    /// and the normal map of `doc`'s (the GPU must be idle, and no solver may still relax on
    /// the old mirror). Safe in the middle of a frame: the next draw sees only the new terrain.
    void rebuild(Document& doc);
    /// The same, with the mesh, the mirror and their uploads done beforehand by prepare() on
    /// `doc` (its TIN must be the one prepared): what is left is adopting them and starting the
    /// normal map, which is baked a band a frame.
    void rebuild(Document& doc, PreparedView prepared);
    /// rebuild()'s work but the normal map, for `doc`'s terrain: runs on any thread that has
    /// `doc` to itself, while other threads use `context` (it submits under the context's queue
    /// lock and waits for its own uploads). `progress` names the parts and may throw
    /// (Cancelled).
    static PreparedView prepare(Document& doc, gpu::VulkanContext& context,
                                const ProgressCallback& progress = {});
    /// Drops everything built for the current terrain (its readers of the TIN's journal, the
    /// mirror, the normal map and the renderer's buffers), before that terrain goes. No solver
    /// may still relax on the mirror, and the GPU must be idle.
    void release();
    /// The TIN on the GPU, for a GPU solver to relax on (it syncs it before each step; the
    /// view syncs it before each bake). Exists after rebuild().
    gpu::TinMirror& mirror() { return *mirror_; }
    /// Brings the mesh, its buffers, the mirror and the normal map up to the TIN (the GPU must
    /// not be reading the buffers). `wait_idle` is called before the buffers are written.
    ViewUpdate update(Document& doc, const std::function<void()>& wait_idle);
    /// The vertices the erosion moved in its last frame: the active overlay shows them.
    void set_active(std::span<const VertexId> active);
    /// Clears the active overlay (the erosion stopped).
    void clear_active();

    /// Heights (m) the contrast curve stretches over its range.
    double contrast_low() const { return contrast_low_; }
    double contrast_high() const { return contrast_high_; }
    const render::TerrainMesh& mesh() const { return *mesh_; }
    const render::TerrainNormalMap* normal_map() const { return normal_map_.get(); }
    /// The new terrain's normal map is still being baked (a band of rows an update): the
    /// caller keeps drawing frames until it is done. Shaded with vertex normals meanwhile.
    bool baking_normal_map() const { return !normal_map_ || !normal_map_->complete(); }
    /// GPU work so far: normal-map bakes and mirror upload batches (an idle editor adds none).
    std::uint64_t gpu_work() const;
    std::uint64_t normal_map_bakes() const { return normal_map_bakes_; }
    std::uint64_t last_texels_baked() const { return normal_map_texels_; }
    std::uint64_t mesh_updates() const { return mesh_updates_; }
    std::uint64_t mesh_rebuilds() const { return mesh_rebuilds_; }
    std::uint64_t vertices_recomputed() const { return mesh_recomputed_; }

  private:
    /// What both rebuilds share once the mesh and the mirror exist.
    void start(Document& doc);
    void update_normal_map(Document& doc);
    void update_contrast_range(const Tin& tin);

    gpu::VulkanContext& context_;
    render::TerrainRenderer& renderer_;
    std::uint64_t materials_version_ = ~std::uint64_t{0};
    std::unique_ptr<render::TerrainMesh> mesh_;
    std::unique_ptr<ChangeReader> mesh_changes_;        ///< the mesh's reader of the journal
    std::unique_ptr<gpu::TinMirror> mirror_;            ///< syncs from a reader of its own
    std::unique_ptr<ChangeReader> normal_map_changes_;  ///< the bake's dirty rectangle
    std::unique_ptr<render::TerrainNormalMap> normal_map_;
    bool stale_ = true;                     ///< the mesh is rebuilt whole at the next update
    std::vector<std::uint8_t> active_;      ///< by VertexId: moved in the erosion's last frame
    std::vector<VertexId> active_ids_;      ///< those flagged now
    std::vector<VertexId> active_flipped_;  ///< flags that changed since the last update
    double contrast_low_ = 0.0, contrast_high_ = 0.1;
    std::chrono::steady_clock::time_point contrast_at_{};
    bool contrast_stale_ = true;
    std::uint64_t normal_map_bakes_ = 0, normal_map_texels_ = 0;
    std::uint64_t mesh_updates_ = 0, mesh_rebuilds_ = 0, mesh_recomputed_ = 0;
};

}  // namespace sandtin::editor
