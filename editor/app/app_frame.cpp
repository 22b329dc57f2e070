// One frame: the held tool and the erosion, the terrain's GPU views, the panels, drawing. And
// the solver the Erosion panel asks for.

#include "app.hpp"

#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "erosion_status.hpp"
#include "gpu/device_selection.hpp"
#include "gpu/gpu_error.hpp"
#include "gpu/make_relaxation_solver.hpp"
#include "tool_palette.hpp"

namespace sandtin::editor {

// ---- The solver ---------------------------------------------------------------------------

bool App::gpu_physics_wanted() const {
    if (gpu_physics_failed_ || !window_) return false;
    if (settings_.physics == "gpu") return true;
    if (settings_.physics == "cpu") return false;
    return gpu::prefers_gpu_physics(window_->context().properties().deviceType);
}

std::string App::physics_placement_text() const {
    const bool gpu = doc_.solver().device() == SolverDevice::Gpu;
    std::string text = std::string("relaxation on the ") + (gpu ? "GPU" : "CPU");
    if (settings_.physics == "auto" && window_) {
        const gpu::VulkanContext& c = window_->context();
        text += " (Auto: " + c.device_name() +
                (gpu::prefers_gpu_physics(c.properties().deviceType) ? " is a GPU)"
                                                                     : " is a software device)");
    }
    return text;
}

void App::attach_solver(bool switched) {
    const SolverDevice want = gpu_physics_wanted() ? SolverDevice::Gpu : SolverDevice::Cpu;
    if (doc_.solver().device() == want) return;
    // The solver being replaced may still have GPU work in flight.
    window_->wait_idle();
    const MaterialTable materials = doc_.materials();
    const TalusSettings settings = doc_.solver().settings();
    const auto make = [&](SolverDevice device) {
        // The GPU solver relaxes on the terrain view's mirror: the TIN is on the GPU once.
        return [&, device](Tin& tin) {
            return gpu::make_relaxation_solver(
                tin, materials, settings,
                gpu::RelaxationPlacement{.device = device,
                                         .mirror = &view_->mirror(),
                                         .slide_gain = gpu::kEditorSlideGain});
        };
    };
    try {
        doc_.replace_solver(make(want));
    } catch (const gpu::GpuError& e) {
        gpu_physics_failed_ = true;  // not tried again this session
        report(std::string("GPU erosion unavailable, using the CPU: ") + e.what());
        doc_.replace_solver(make(SolverDevice::Cpu));
    }
    if (switched) {
        doc_.solver().activate_all();
        report(physics_placement_text());
    }
    sculpting_.kick();
}

void App::toggle_erosion() {
    if (erosion_runs()) {
        sculpting_.close_level(doc_);  // what slid so far is its level
        settings_.erosion_running = false;
        return;
    }
    settings_.erosion_running = true;
    doc_.release_erosion();  // the artist let this scene settle
    sculpting_.kick();
}

std::string App::erosion_status() const {
    if (doc_.erosion_held() && settings_.erosion_running)
        return "paused for the opened scene: Run lets it settle";
    return erosion_status_text(erosion_runs(), doc_.solver().at_rest(), erosion_active_);
}

// ---- One frame ----------------------------------------------------------------------------

void App::update_water() {
    // The water's seconds are the frame's (a scripted frame counts 1/60 s), at most a tenth of
    // a second: a stall (a long stamp, a dialog) is not made up for in one frame.
    const auto now = Clock::now();
    const double seconds =
        options_.scripted()
            ? kScriptFrameSeconds
            : std::min(0.1, std::chrono::duration<double>(now - water_clock_).count());
    water_clock_ = now;
    if (busy()) return;  // a job's worker may be reading the terrain
    const LiveWaterFrame w = sculpting_.flow_water(doc_, settings_, seconds, kWaterBudgetMs);
    if (w.ran) water_summary_ = doc_.water().measure();
}

void App::update_simulation() {
    const auto t0 = Clock::now();
    // A held button keeps pouring with time (a scripted frame counts 1/60 s).
    if (left_down_) {
        const auto now = Clock::now();
        const double seconds = options_.scripted()
                                   ? kScriptFrameSeconds
                                   : std::chrono::duration<double>(now - hold_clock_).count();
        hold_clock_ = now;
        sculpting_.hold(doc_, seconds, settings_);
    }
    // While a job runs the sand waits: the job's worker has the CPU, and an import or open
    // replaces this terrain anyway.
    if (erosion_runs() && !busy()) {
        const ErosionFrame e = sculpting_.erode(doc_, settings_, kErosionBudgetMs);
        if (e.ran) {
            erosion_active_ = e.active;
            view_->set_active(e.changed);
        }
        update_settle(e);
    } else {
        if (!busy()) view_->clear_active();
        update_settle({});
    }
    update_water();
    for (const std::string& m : sculpting_.take_messages())
        report(m);
    times_.push(times_.physics, elapsed_ms(t0));
    times_.push(times_.tool, sculpting_.take_tool_ms());
    doc_.follow_edits_for_autosave();
    autosave_if_due();
}

void App::update_haptics() {
    if (!haptics_ || !cursor_) return;
    const ToolEntry& t = kTools[settings_.tool];
    if (!haptic_tool_ || haptic_tool_index_ != settings_.tool ||
        haptic_tool_radius_ != settings_.tool_radius) {
        // Brushes and the pour are felt as a round tool of their radius.
        if (t.kind == ToolKind::Stamp) {
            haptic_tool_ = build_tool(settings_);
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
    haptics_->update(doc_.tin(), *haptic_tool_, at, doc_.materials(),
                     {cursor_->x, cursor_->y, bottom});
}

const Tool& App::cursor_tool() {
    if (!cursor_tool_ || cursor_tool_index_ != settings_.tool ||
        cursor_tool_radius_ != settings_.tool_radius || cursor_tool_extrude_ != settings_.extrude) {
        cursor_tool_ = build_tool(settings_);
        cursor_tool_index_ = settings_.tool;
        cursor_tool_radius_ = settings_.tool_radius;
        cursor_tool_extrude_ = settings_.extrude;
    }
    return *cursor_tool_;
}

std::vector<std::array<float, 3>> App::footprint_outline() {
    const Tool& tool = cursor_tool();
    const double angle = settings_.follow_path && sculpting_.stroking()
                             ? sculpting_.heading()
                             : settings_.tool_angle * std::numbers::pi / 180.0;
    const ToolPlacement at{{cursor_->x, cursor_->y}, angle, cursor_->z};
    const Vec2 c = doc_.tin().domain().centre();
    const std::vector<Vec2>& inner = tool.shape().inner;
    std::vector<std::array<float, 3>> loop;
    const double lift = 0.0005 * settings_.scene_size;  // above the sand, so it is not hidden
    LocateHint hint;
    for (std::size_t i = 0; i < inner.size(); ++i) {
        // Subdivided so the outline follows the sand between the contour's corners.
        const Vec2 a = inner[i], b = inner[(i + 1) % inner.size()];
        constexpr int kPieces = 6;
        for (int k = 0; k < kPieces; ++k) {
            const Vec2 w = tool.to_world(at, lerp(a, b, static_cast<double>(k) / kPieces));
            const double z = doc_.tin().height_at(w, &hint).value_or(cursor_->z);
            loop.push_back({static_cast<float>(w.x - c.x), static_cast<float>(w.y - c.y),
                            static_cast<float>(z + lift)});
        }
    }
    return loop;
}

void App::draw_terrain(const Mat4& vp) {
    Swapchain& swapchain = window_->swapchain();
    render::TerrainRenderer& renderer = window_->renderer();
    render::TerrainPush push{};
    std::copy(vp.begin(), vp.end(), push.view_projection);
    const float l[3] = {0.55f, -0.45f, 0.5f};  // low sun: sand relief reads well
    const float ln = std::sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
    push.light_dir[0] = l[0] / ln;
    push.light_dir[1] = l[1] / ln;
    push.light_dir[2] = l[2] / ln;
    push.light_dir[3] = static_cast<float>(settings_.contrast);
    const Rect domain = doc_.tin().domain();
    const Vec2 c = domain.centre();
    // Stamps show their outline (below): only the centre dot; the nozzle its jet's ring.
    const ToolKind kind = kTools[settings_.tool].kind;
    const double ring = kind == ToolKind::Stamp   ? 0.0
                        : kind == ToolKind::Water ? settings_.water_jet
                                                  : settings_.tool_radius;
    if (cursor_) {
        push.cursor[0] = static_cast<float>(cursor_->x - c.x);
        push.cursor[1] = static_cast<float>(cursor_->y - c.y);
        // Round tools show a ring of their radius; stamp tools their outline (below), plus the
        // centre dot (radius 0 draws no ring).
        push.cursor[2] = static_cast<float>(ring);
        push.cursor[3] = 1.0f;
    }
    push.overlays[0] = (settings_.overlay_wireframe ? render::kOverlayWireframe : 0.0f) +
                       (settings_.overlay_water ? render::kOverlayWaterDepth : 0.0f) +
                       (settings_.overlay_water_speed ? render::kOverlayWaterSpeed : 0.0f) +
                       (settings_.overlay_sediment ? render::kOverlaySediment : 0.0f);
    push.overlays[1] = settings_.overlay_active ? 1.0f : 0.0f;
    push.overlays[2] = settings_.overlay_thickness ? 1.0f : 0.0f;
    push.overlays[3] = settings_.overlay_slope ? 1.0f : 0.0f;
    push.contrast[0] = static_cast<float>(view_->contrast_low());
    push.contrast[1] = static_cast<float>(view_->contrast_high());
    push.contrast[2] = static_cast<float>(1.0 / domain.width());
    push.contrast[3] = static_cast<float>(1.0 / domain.height());
    const Vec3 e = camera_.eye();
    const float eye[3] = {static_cast<float>(e.x), static_cast<float>(e.y),
                          static_cast<float>(e.z)};
    renderer.draw(swapchain.command_buffer(), push, eye, swapchain.extent(), view_->mesh());
    if (cursor_ && kTools[settings_.tool].kind == ToolKind::Stamp) {
        // Stamp tools: the footprint's inner contour on the terrain, turned as the next stamp
        // will be.
        const std::vector<std::array<float, 3>> loop = footprint_outline();
        const float cyan[4] = {0.1f, 0.9f, 1.0f, 1.0f};
        renderer.draw_outline(swapchain.command_buffer(), push.view_projection, loop, cyan);
    }
}

bool App::frame(bool capture) {
    const auto t0 = Clock::now();
    last_frame_at_ = t0;
    // The simulation and the panels may edit the terrain: the haptic snapshot is not held
    // through them, so a long edit fades the force as the loop's staleness rule intends.
    if (haptics_) haptics_->release();
    poll_job();
    update_simulation();
    const ViewUpdate u = view_->update(doc_, [this] { window_->swapchain().wait_idle(); });
    times_.push(times_.mesh, u.mesh_ms);
    times_.push(times_.upload, u.upload_ms);
    times_.push(times_.bake, u.bake_ms);
    last_upload_bytes_ = u.upload_bytes;

    widgets_.begin_frame();
    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    draw_panels();
    if (busy()) widgets_.note_state("job");  // after the panels: a job they started counts
    ImGui::Render();
    widgets_.end_frame();
    // From here until the next event or frame nothing edits the terrain: the snapshot built
    // now stays true while the frame is drawn (which on a CPU renderer can take longer than
    // the loop's staleness limit) and while the editor waits for input.
    update_haptics();
    if (haptics_) haptics_->hold();

    const auto t1 = Clock::now();
    window_->fit_swapchain(settings_.vsync);
    Swapchain& swapchain = window_->swapchain();
    const float clear[3] = {0.09f, 0.10f, 0.12f};
    if (!swapchain.begin_frame(clear)) {
        window_->recreate_swapchain(settings_.vsync);  // out of date
        return false;
    }
    const VkExtent2D extent = swapchain.extent();
    draw_terrain(camera_.view_projection(static_cast<double>(extent.width) / extent.height));
    ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), swapchain.command_buffer());
    const bool ok = swapchain.end_frame(capture);
    times_.push(times_.render, elapsed_ms(t1));
    times_.push(times_.frame, elapsed_ms(t0));
    if (!ok) window_->recreate_swapchain(settings_.vsync);
    return true;
}

}  // namespace sandtin::editor
