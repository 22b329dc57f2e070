// One frame: physics within its budget, mesh update from the journal, drawing.

#include "app.hpp"

#include <algorithm>

#include "gpu/device_selection.hpp"

namespace sandtin::editor {

// ---- Per frame ------------------------------------------------------------------------------

bool App::gpu_physics_wanted() const {
    if (gpu_physics_failed_ || !context_) return false;
    if (settings_.physics == "gpu") return true;
    if (settings_.physics == "cpu") return false;
    return gpu::prefers_gpu_physics(context_->properties().deviceType);
}

std::string App::physics_placement_text() const {
    const bool gpu = doc_.physics && doc_.physics->backend() == ErosionBackend::Gpu;
    std::string text = std::string("relaxation on the ") + (gpu ? "GPU" : "CPU");
    if (settings_.physics == "auto" && context_)
        text += " (Auto: " + context_->device_name() +
                (gpu::prefers_gpu_physics(context_->properties().deviceType)
                     ? " is a GPU)"
                     : " is a software device)");
    return text;
}

void App::attach_physics(bool switched) {
    const ErosionBackend want = gpu_physics_wanted() ? ErosionBackend::Gpu : ErosionBackend::Cpu;
    if (doc_.physics && doc_.physics->backend() == want) return;
    wait_gpu_idle();  // the solver being replaced, and the normal map, may still be in use
    doc_.physics.reset();
    normal_map_.reset();  // may refer to the old solver's mirror
    if (want == ErosionBackend::Gpu && context_) {
        try {
            ChangeFanout* fanout = fanout_.get();
            doc_.physics = make_gpu_erosion(*doc_.tin, *context_, doc_.materials, [fanout] {
                return fanout->take(ChangeFanout::Mirror);
            });
        } catch (const gpu::GpuError& e) {
            gpu_physics_failed_ = true;  // not tried again this session
            report(std::string("GPU erosion unavailable, using the CPU: ") + e.what());
        }
    }
    if (!doc_.physics) doc_.physics = make_cpu_erosion(*doc_.tin, doc_.materials);
    if (switched) {
        doc_.physics->activate_all();
        report(physics_placement_text());
    }
    physics_kick_ = true;
    // The normal map went with the old solver's mirror: it is baked again now, so a frame
    // drawn after this (the panel's switch is pressed in the middle of one) samples a map
    // that exists.
    if (renderer_ && mesh_) update_normal_map();
}

void App::toggle_erosion() {
    if (erosion_runs()) {
        end_action();  // what slid so far is its level
        settings_.erosion_running = false;
        return;
    }
    settings_.erosion_running = true;
    doc_.erosion_held = false;  // the artist let this scene settle
    physics_kick_ = true;
}

void App::update_simulation() {
    const auto t0 = Clock::now();
    // The physics learns about edits when it steps, so an edit "kicks" it.
    if (erosion_runs() && (physics_kick_ || !doc_.physics->at_rest())) {
        physics_kick_ = false;
        doc_.physics->settings().parameters.relocation_radius = settings_.relocation_radius;
        // Clamped: a hand-edited settings file must not stop the physics.
        doc_.physics->settings().parameters.settle_margin =
            std::clamp(settings_.settle_margin, 0.0, kMaxSettleMargin);
        // Up to the chosen iterations, but within a time budget so the editor stays responsive
        // while a large region slides.
        std::vector<VertexId> changed;
        if (doc_.physics->backend() == ErosionBackend::Gpu) {
            // One call: the GPU physics batches the iterations into few submissions (64 per
            // submission), each followed by the read-back of the heights into the TIN.
            doc_.physics->step(settings_.erosion_steps, &changed);
        } else {
            for (int i = 0; i < settings_.erosion_steps; ++i) {
                doc_.physics->step(1, &changed);
                if (doc_.physics->at_rest() || ms_since(t0) > kErosionBudgetMs) break;
            }
        }
        erosion_active_ = doc_.physics->active_count();
        std::sort(changed.begin(), changed.end());
        changed.erase(std::unique(changed.begin(), changed.end()), changed.end());
        // What the sand moved is simplified once it rests (below), as an edit's vertices are.
        doc_.context->simplifier.enqueue(changed);
        // Active flags for the overlay: clear the old ones, set the new ones; the mesh
        // recomputes only the flags that flipped.
        if (active_.size() < doc_.tin->vertex_capacity())
            active_.resize(doc_.tin->vertex_capacity(), 0);
        for (VertexId v : active_ids_) {
            active_[v.index()] = 0;
            active_flipped_.push_back(v);
        }
        active_ids_.clear();
        for (VertexId v : changed) {
            if (v.index() < active_.size() && !active_[v.index()]) {
                active_[v.index()] = 1;
                active_ids_.push_back(v);
                active_flipped_.push_back(v);
            }
        }
        // Sand the erosion moved belongs to the open level (the gesture that disturbed it), or
        // makes a level of its own.
        if (!changed.empty() && open_level_.empty()) open_level_ = kErosionLevel;
        if (doc_.physics->at_rest() && !open_level_.empty() && !left_down_) settle_erosion();
    } else if (!active_ids_.empty()) {
        for (VertexId v : active_ids_) {
            active_[v.index()] = 0;
            active_flipped_.push_back(v);
        }
        active_ids_.clear();
    }
    times_.push(times_.physics, ms_since(t0));
    times_.push(times_.tool, tool_ms_);
    tool_ms_ = 0.0;
    autosave_if_due();
}

void App::update_haptics() {
    if (!haptics_ || !cursor_) return;
    const ToolEntry& t = kTools[settings_.tool];
    if (!haptic_tool_ || haptic_tool_index_ != settings_.tool ||
        haptic_tool_radius_ != settings_.tool_radius) {
        // Brushes and the pour are felt as a round tool of their radius.
        if (t.kind == ToolKind::Stamp) {
            haptic_tool_ = build_tool();
        } else {
            ToolSpec spec;
            spec.radius = settings_.tool_radius;
            haptic_tool_ = Tool::build(spec);
        }
        haptic_tool_index_ = settings_.tool;
        haptic_tool_radius_ = settings_.tool_radius;
    }
    // The pen rests at the cursor, its tip the tool depth below the surface there.
    const double bottom = cursor_->z - settings_.tool_depth;
    const ToolPlacement at{{cursor_->x, cursor_->y}, 0.0, bottom};
    haptics_->update(*doc_.tin, *haptic_tool_, at, doc_.materials,
                     {cursor_->x, cursor_->y, bottom});
}

void App::update_contrast_range() {
    // The contrast curve stretches the 2nd..98th percentile of the heights over the full
    // range (the seeds' histogram stretch). O(n): refreshed at most twice a second.
    if (!contrast_stale_ && Clock::now() - contrast_at_ < std::chrono::milliseconds(500)) return;
    const VertexArrays& va = doc_.tin->vertices();
    std::vector<double> h;
    h.reserve(doc_.tin->vertex_count());
    for (std::size_t i = 0; i < va.size(); ++i) {
        if (va.alive[i]) h.push_back(va.height[i]);
    }
    if (h.size() < 2) return;
    const auto at = [&](double q) {
        auto it = h.begin() + static_cast<long>(q * static_cast<double>(h.size() - 1));
        std::nth_element(h.begin(), it, h.end());
        return *it;
    };
    contrast_low_ = at(0.02);
    contrast_high_ = std::max(at(0.98), contrast_low_ + 1e-4);
    contrast_at_ = Clock::now();
    contrast_stale_ = false;
}

const Tool& App::cursor_tool() {
    if (!cursor_tool_ || cursor_tool_index_ != settings_.tool ||
        cursor_tool_radius_ != settings_.tool_radius || cursor_tool_extrude_ != settings_.extrude) {
        cursor_tool_ = build_tool();
        cursor_tool_index_ = settings_.tool;
        cursor_tool_radius_ = settings_.tool_radius;
        cursor_tool_extrude_ = settings_.extrude;
    }
    return *cursor_tool_;
}

std::vector<std::array<float, 3>> App::footprint_outline() {
    cursor_tool();
    const double angle = settings_.follow_path && sampler_
                             ? last_heading_
                             : settings_.tool_angle * 3.14159265358979 / 180.0;
    const ToolPlacement at{{cursor_->x, cursor_->y}, angle, cursor_->z};
    const Vec2 c = doc_.tin->domain().centre();
    const std::vector<Vec2>& inner = cursor_tool_->shape().inner;
    std::vector<std::array<float, 3>> loop;
    const double lift = 0.0005 * settings_.scene_size;  // above the sand, so it is not hidden
    LocateHint hint;
    for (std::size_t i = 0; i < inner.size(); ++i) {
        // Subdivided so the outline follows the sand between the contour's corners.
        const Vec2 a = inner[i], b = inner[(i + 1) % inner.size()];
        constexpr int kPieces = 6;
        for (int k = 0; k < kPieces; ++k) {
            const Vec2 w = cursor_tool_->to_world(at, lerp(a, b, static_cast<double>(k) / kPieces));
            const double z = doc_.tin->height_at(w, &hint).value_or(cursor_->z);
            loop.push_back({static_cast<float>(w.x - c.x), static_cast<float>(w.y - c.y),
                            static_cast<float>(z + lift)});
        }
    }
    return loop;
}

void App::update_mesh() {
    // The journal says what changed; nothing changed means no recomputation and no upload.
    const ChangeSet changes = fanout_->take(ChangeFanout::Mesh);
    if (!mesh_stale_ && changes.empty() && active_flipped_.empty() && normal_map_) {
        times_.push(times_.mesh, 0.0);
        times_.push(times_.upload, 0.0);
        times_.push(times_.bake, 0.0);
        last_upload_bytes_ = 0;
        return;
    }
    const auto t0 = Clock::now();
    mesh_->set_active(active_);
    const render::MeshUpdate update = mesh_stale_
                                          ? mesh_->rebuild(*doc_.tin)
                                          : mesh_->update(*doc_.tin, changes, active_flipped_);
    active_flipped_.clear();
    mesh_stale_ = false;
    ++mesh_updates_;
    mesh_recomputed_ += count_in_ranges(update.vertices);
    if (update.resized) ++mesh_rebuilds_;
    times_.push(times_.mesh, ms_since(t0));
    const auto t1 = Clock::now();
    swapchain_->wait_idle();
    const std::uint64_t before = renderer_->bytes_uploaded();
    renderer_->upload(*mesh_, update);
    last_upload_bytes_ = renderer_->bytes_uploaded() - before;
    update_contrast_range();
    times_.push(times_.upload, ms_since(t1));
    const auto t2 = Clock::now();
    update_normal_map();
    times_.push(times_.bake, ms_since(t2));
}

void App::update_normal_map() {
    gpu::TinMirror* mirror = doc_.physics->mirror();
    if (mirror == nullptr) {
        if (!own_mirror_) own_mirror_ = std::make_unique<gpu::TinMirror>(*context_, doc_.materials);
        mirror = own_mirror_.get();
    } else {
        own_mirror_.reset();
    }
    // Edits the GPU physics has not seen yet (erosion paused, or tools after its step): the
    // mirror takes them now, and the physics looks at those vertices on its next step.
    const ChangeSet changes = fanout_->take(ChangeFanout::Mirror);
    const gpu::SyncStats synced = mirror->sync(*doc_.tin, changes);
    if (doc_.physics->mirror() != nullptr && !synced.dirty_vertices.empty()) {
        std::vector<VertexId> ids;
        ids.reserve(synced.dirty_vertices.size());
        for (std::uint32_t v : synced.dirty_vertices)
            ids.push_back(VertexId{v});
        doc_.physics->activate(ids);
    }
    const ChangeSet dirty = fanout_->take(ChangeFanout::NormalMap);
    if (!normal_map_ || &normal_map_->mirror() != mirror) {
        normal_map_ = std::make_unique<render::TerrainNormalMap>(*mirror, doc_.tin->domain());
        renderer_->set_normal_map(normal_map_->view(), normal_map_->sampler());
        ++normal_map_bakes_;
    } else if (const auto texels = normal_map_->rebake(*doc_.tin, dirty)) {
        ++normal_map_bakes_;
        normal_map_texels_ = std::uint64_t{texels->width()} * texels->height();
    }
}

bool App::frame(bool capture) {
    const auto t0 = Clock::now();
    last_frame_at_ = t0;
    // The simulation and the panels may edit the terrain: the haptic snapshot is not held
    // through them, so a long edit fades the force as the loop's staleness rule intends.
    if (haptics_) haptics_->release();
    pour_while_held();
    update_simulation();
    update_mesh();

    widgets_.begin_frame();
    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    draw_panels();
    ImGui::Render();
    // From here until the next event or frame nothing edits the terrain: the snapshot built
    // now stays true while the frame is drawn (which on a CPU renderer can take longer than
    // the loop's staleness limit) and while the editor waits for input.
    update_haptics();
    if (haptics_) haptics_->hold();

    const auto t1 = Clock::now();
    // A resized window: not every presentation engine reports the old swapchain out of date,
    // so compare sizes every frame.
    {
        int w = 0, h = 0;
        glfwGetFramebufferSize(window_, &w, &h);
        const VkExtent2D e = swapchain_->extent();
        if (w > 0 && h > 0 &&
            (static_cast<std::uint32_t>(w) != e.width ||
             static_cast<std::uint32_t>(h) != e.height)) {
            swapchain_->recreate({static_cast<std::uint32_t>(w), static_cast<std::uint32_t>(h)},
                                 settings_.vsync);
        }
    }
    const float clear[3] = {0.09f, 0.10f, 0.12f};
    if (!swapchain_->begin_frame(clear)) {
        int w = 0, h = 0;
        glfwGetFramebufferSize(window_, &w, &h);
        if (w > 0 && h > 0)
            swapchain_->recreate({static_cast<std::uint32_t>(w), static_cast<std::uint32_t>(h)},
                                 settings_.vsync);
        return false;
    }
    const VkExtent2D extent = swapchain_->extent();
    render::TerrainPush push{};
    const Mat4 vp = camera_.view_projection(static_cast<double>(extent.width) / extent.height);
    std::copy(vp.begin(), vp.end(), push.view_projection);
    const float l[3] = {0.55f, -0.45f, 0.5f};  // low sun: sand relief reads well
    const float ln = std::sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
    push.light_dir[0] = l[0] / ln;
    push.light_dir[1] = l[1] / ln;
    push.light_dir[2] = l[2] / ln;
    push.light_dir[3] = static_cast<float>(settings_.contrast);
    const Vec2 c = doc_.tin->domain().centre();
    if (cursor_) {
        push.cursor[0] = static_cast<float>(cursor_->x - c.x);
        push.cursor[1] = static_cast<float>(cursor_->y - c.y);
        push.cursor[2] = static_cast<float>(settings_.tool_radius);
        // Round tools show a ring of their radius; stamp tools their outline (below), plus the
        // centre dot (radius 0 draws no ring).
        push.cursor[3] = 1.0f;
        if (kTools[settings_.tool].kind == ToolKind::Stamp) push.cursor[2] = 0.0f;
    }
    push.overlays[0] = settings_.overlay_wireframe ? 1.0f : 0.0f;
    push.overlays[1] = settings_.overlay_active ? 1.0f : 0.0f;
    push.overlays[2] = settings_.overlay_thickness ? 1.0f : 0.0f;
    push.overlays[3] = settings_.overlay_slope ? 1.0f : 0.0f;
    push.contrast[0] = static_cast<float>(contrast_low_);
    push.contrast[1] = static_cast<float>(contrast_high_);
    push.contrast[2] = static_cast<float>(1.0 / doc_.tin->domain().width());
    push.contrast[3] = static_cast<float>(1.0 / doc_.tin->domain().height());
    renderer_->draw(swapchain_->command_buffer(), push, extent, *mesh_);
    if (cursor_ && kTools[settings_.tool].kind == ToolKind::Stamp) {
        // Stamp tools: the footprint's inner contour on the terrain, turned as the next stamp
        // will be.
        const std::vector<std::array<float, 3>> loop = footprint_outline();
        const float cyan[4] = {0.1f, 0.9f, 1.0f, 1.0f};
        renderer_->draw_outline(swapchain_->command_buffer(), push.view_projection, loop, cyan);
    }
    ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), swapchain_->command_buffer());
    const bool ok = swapchain_->end_frame(capture);
    times_.push(times_.render, ms_since(t1));
    times_.push(times_.frame, ms_since(t0));
    if (!ok) {
        int w = 0, h = 0;
        glfwGetFramebufferSize(window_, &w, &h);
        if (w > 0 && h > 0)
            swapchain_->recreate({static_cast<std::uint32_t>(w), static_cast<std::uint32_t>(h)},
                                 settings_.vsync);
    }
    return true;
}

}  // namespace sandtin::editor
