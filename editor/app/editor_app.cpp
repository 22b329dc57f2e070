// The editor's main loop, document, panels, input and scripted mode.

#include "editor_app.hpp"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <fstream>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <vector>

#include <nlohmann/json.hpp>

#include "camera.hpp"
#include "editor_settings.hpp"
#include "formats/png_image.hpp"
#include "gpu/gpu_error.hpp"
#include "gpu/render/terrain_renderer.hpp"
#include "gpu/vulkan_context.hpp"
#include "history/history.hpp"
#include "io/autosave.hpp"
#include "io/export_terrain.hpp"
#include "io/heightmap_import.hpp"
#include "io/session_file.hpp"
#include "physics/sand_physics.hpp"
#include "picking.hpp"
#include "swapchain.hpp"
#include "tools/brushes.hpp"
#include "tools/sand.hpp"
#include "tools/stroke.hpp"
#include "tools/tool_json.hpp"

namespace sandtin::editor {

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

void tip(const char* text) {
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", text);
}

enum class ToolKind { Stamp, Brush, Pour, Remove };

struct ToolEntry {
    const char* label;
    ToolKind kind;
    const char* asset;  ///< Stamp: assets/tools/<asset>.json
    BrushKind brush;
    const char* help;
};

const ToolEntry kTools[] = {
    {"Circle", ToolKind::Stamp, "circle", BrushKind::Raise,
     "Flat round tool pressed along the stroke (key 1)"},
    {"Ball", ToolKind::Stamp, "ball", BrushKind::Raise, "Half-sphere: a rounded groove (key 2)"},
    {"Box", ToolKind::Stamp, "box", BrushKind::Raise, "Rectangular trowel (key 3)"},
    {"Rake", ToolKind::Stamp, "rake", BrushKind::Raise,
     "Rake with tines from a heightfield (key 4)"},
    {"Lambda", ToolKind::Stamp, "lambda", BrushKind::Raise,
     "Non-convex letter-shaped stamp (key 5)"},
    {"Pour", ToolKind::Pour, nullptr, BrushKind::Raise, "Pour sand: hold to keep pouring (key 6)"},
    {"Remove", ToolKind::Remove, nullptr, BrushKind::Raise,
     "Scoop sand away, never below bedrock (key 7)"},
    {"Raise", ToolKind::Brush, nullptr, BrushKind::Raise, "Brush: raise the surface (key 8)"},
    {"Smooth", ToolKind::Brush, nullptr, BrushKind::Smooth, "Brush: smooth bumps (key 9)"},
    {"Paint", ToolKind::Brush, nullptr, BrushKind::PaintMaterial,
     "Brush: paint the selected material (key 0)"},
};
constexpr int kToolCount = static_cast<int>(std::size(kTools));

/// Per-stage timings (ms) of recent frames, for the Stats panel and the stats file.
struct StageTimes {
    static constexpr std::size_t kKeep = 240;
    std::deque<float> frame, tool, physics, mesh, upload, render;
    void push(std::deque<float>& d, double v) {
        d.push_back(static_cast<float>(v));
        if (d.size() > kKeep) d.pop_front();
    }
    static double median(const std::deque<float>& d) {
        if (d.empty()) return 0.0;
        std::vector<float> v(d.begin(), d.end());
        std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
        return v[v.size() / 2];
    }
};

/// The terrain being edited and everything that follows its lifetime.
struct Document {
    std::filesystem::path path;
    std::unique_ptr<Tin> tin;
    std::unique_ptr<SculptContext> context;
    std::unique_ptr<SandPhysics> physics;
    std::unique_ptr<History> history;
    MaterialTable materials = MaterialTable::presets();
    bool dirty = false;
    Clock::time_point last_autosave = Clock::now();

    void adopt(Tin t, Generation next_generation, const std::filesystem::path& p) {
        history.reset();
        physics.reset();
        tin = std::make_unique<Tin>(std::move(t));
        context = std::make_unique<SculptContext>(tin->domain());
        context->set_next_generation(next_generation);
        physics = std::make_unique<SandPhysics>(*tin, materials);
        history = std::make_unique<History>(*tin);
        path = p;
        dirty = false;
    }
    Session session() const {
        Session s;
        s.terrain = tin->snapshot();
        s.next_generation = context->peek_generation();
        s.metadata_json = R"({"editor":"sandtin-editor"})";
        return s;
    }
};

/// A new sandbox: 1 m x 1 m with gentle dunes on a jittered lattice (no cocircular quads, so
/// undo restores the exact triangulation).
Tin default_sandbox() {
    const Rect domain{{0.0, 0.0}, {1.0, 1.0}};
    return Tin::random_points(domain, 20000, 7, [](Vec2 p) {
        return 0.05 + 0.015 * std::sin(9.0 * p.x + 2.0 * std::sin(4.0 * p.y)) +
               0.006 * std::cos(17.0 * p.y - 3.0 * p.x);
    });
}

class App {
  public:
    explicit App(const EditorOptions& o) : options_(o) {}
    int run();

    void load_initial_scene();
    void init_window_and_gpu();
    void init_imgui();
    void shutdown();
    bool frame(bool capture);
    void update_simulation();
    void update_mesh();
    void draw_panels();
    void panel_tools();
    void panel_materials();
    void panel_erosion();
    void panel_haptics();
    void panel_stats();
    void panel_file();
    void recovery_prompt();

    // Input, shared by GLFW callbacks and the script.
    void mouse_button(int button, bool down, double x, double y);
    void mouse_move(double x, double y);
    void scroll(double dy);
    void key(int key, bool ctrl);
    void run_script_op(const nlohmann::json& op);

    std::optional<Vec3> pick(double x, double y) const;
    void tool_at(Vec3 point);
    void end_action();
    void undo();
    void redo();
    void save(const std::filesystem::path& p);
    void open(const std::filesystem::path& p);
    void frame_terrain();
    void report(const std::string& message) { status_ = message; }
    Tool build_tool() const;

    EditorOptions options_;
    std::filesystem::path settings_path_;
    EditorSettings settings_;
    EditorSettings saved_settings_;
    GLFWwindow* window_ = nullptr;
    std::unique_ptr<gpu::VulkanContext> context_;
    std::unique_ptr<Swapchain> swapchain_;
    std::unique_ptr<render::TerrainRenderer> renderer_;
    gpu::UniqueDescriptorPool imgui_pool_;
    bool imgui_ready_ = false;
    Document doc_;
    OrbitCamera camera_;
    StageTimes times_;
    std::string status_;

    // Interaction state.
    bool left_down_ = false, right_down_ = false, middle_down_ = false;
    double mouse_x_ = 0.0, mouse_y_ = 0.0;
    std::optional<Vec3> cursor_;
    std::optional<StrokeSampler> sampler_;
    std::optional<Tool> active_tool_;
    std::optional<Vec2> last_dab_;
    std::string pending_label_;
    bool erosion_pending_ = false;
    bool physics_kick_ = true;
    std::vector<std::uint8_t> active_;
    double tool_ms_ = 0.0;
    bool mesh_stale_ = true;
    int redraw_frames_ = 2;  ///< frames still to draw after the last event (ImGui settles)
    std::optional<std::filesystem::path> recovery_for_;

    // Scripted mode.
    std::vector<nlohmann::json> script_;
    std::size_t script_pos_ = 0;
    int script_wait_ = 0;
    bool ctrl_ = false;
    char path_buf_[512] = "scene.sandtin";
    char import_buf_[512] = "";
    char export_buf_[512] = "terrain.glb";
};

App* app_of(GLFWwindow* w) {
    return static_cast<App*>(glfwGetWindowUserPointer(w));
}

void on_button(GLFWwindow* w, int b, int action, int mods) {
    double x = 0.0, y = 0.0;
    glfwGetCursorPos(w, &x, &y);
    (void)mods;
    const bool down = action == GLFW_PRESS;
    if (down && ImGui::GetIO().WantCaptureMouse) return;
    app_of(w)->mouse_button(b, down, x, y);
}
void on_cursor(GLFWwindow* w, double x, double y) {
    app_of(w)->mouse_move(x, y);
}
void on_wheel(GLFWwindow* w, double, double dy) {
    if (ImGui::GetIO().WantCaptureMouse) return;
    app_of(w)->scroll(dy);
}
void on_key(GLFWwindow* w, int key, int, int action, int mods) {
    if (action != GLFW_PRESS && action != GLFW_REPEAT) return;
    if (ImGui::GetIO().WantCaptureKeyboard) return;
    app_of(w)->key(key, (mods & GLFW_MOD_CONTROL) != 0);
}

// ---- Set-up -------------------------------------------------------------------------------

void App::load_initial_scene() {
    if (options_.scene.empty()) {
        doc_.adopt(default_sandbox(), 1, {});
        return;
    }
    if (!std::filesystem::exists(options_.scene)) {
        throw std::runtime_error("scene " + options_.scene.string() + " does not exist");
    }
    const Session s = load_session(options_.scene);
    doc_.adopt(Tin::from_snapshot(s.terrain), s.next_generation, options_.scene);
    if (const auto info = find_autosave(options_.scene); info && info->offer_recovery()) {
        if (options_.scripted()) {
            std::fprintf(stderr,
                         "sandtin-editor: an autosave newer than %s exists (%s); "
                         "scripted mode leaves it alone\n",
                         options_.scene.c_str(), info->path.c_str());
        } else {
            recovery_for_ = options_.scene;
        }
    }
}

void App::init_window_and_gpu() {
    if (glfwInit() != GLFW_TRUE) {
        throw std::runtime_error(
            "cannot open a window: no display (set DISPLAY, or run under "
            "xvfb-run -s '-screen 0 1280x720x24')");
    }
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    window_ = glfwCreateWindow(options_.width, options_.height, "sandtin", nullptr, nullptr);
    if (window_ == nullptr) throw std::runtime_error("glfwCreateWindow failed");
    glfwSetWindowUserPointer(window_, this);
    glfwSetMouseButtonCallback(window_, on_button);
    glfwSetCursorPosCallback(window_, on_cursor);
    glfwSetScrollCallback(window_, on_wheel);
    glfwSetKeyCallback(window_, on_key);

    gpu::ContextOptions o;
    std::uint32_t n = 0;
    const char** ext = glfwGetRequiredInstanceExtensions(&n);
    if (ext == nullptr) throw std::runtime_error("GLFW finds no Vulkan surface support");
    o.instance_extensions.assign(ext, ext + n);
    GLFWwindow* win = window_;
    o.make_surface = [win](VkInstance instance) {
        VkSurfaceKHR surface = VK_NULL_HANDLE;
        if (glfwCreateWindowSurface(instance, win, nullptr, &surface) != VK_SUCCESS)
            return VkSurfaceKHR{VK_NULL_HANDLE};
        return surface;
    };
    o.validation = options_.validation;
    context_ = std::make_unique<gpu::VulkanContext>(o);
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    swapchain_ = std::make_unique<Swapchain>(
        *context_, VkExtent2D{static_cast<std::uint32_t>(w), static_cast<std::uint32_t>(h)},
        settings_.vsync);
    renderer_ = std::make_unique<render::TerrainRenderer>(*context_, swapchain_->render_pass());
}

void App::init_imgui() {
    const VkDevice device = context_->device();
    VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 16};
    VkDescriptorPoolCreateInfo pool{};
    pool.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
    pool.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
    pool.maxSets = 16;
    pool.poolSizeCount = 1;
    pool.pPoolSizes = &size;
    VkDescriptorPool handle = VK_NULL_HANDLE;
    gpu::check(vkCreateDescriptorPool(device, &pool, nullptr, &handle), "vkCreateDescriptorPool");
    imgui_pool_ = gpu::UniqueDescriptorPool(device, handle);

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // panel layout is fixed; settings live in our file
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForVulkan(window_, true);
    ImGui_ImplVulkan_InitInfo info{};
    info.Instance = context_->instance();
    info.PhysicalDevice = context_->physical_device();
    info.Device = device;
    info.QueueFamily = context_->queue_family();
    info.Queue = context_->queue();
    info.DescriptorPool = handle;
    info.MinImageCount = 2;
    info.ImageCount = std::max(2u, swapchain_->image_count());
    info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
    ImGui_ImplVulkan_Init(&info, swapchain_->render_pass());
    context_->submit_and_wait([](VkCommandBuffer cb) { ImGui_ImplVulkan_CreateFontsTexture(cb); });
    ImGui_ImplVulkan_DestroyFontUploadObjects();
    imgui_ready_ = true;
}

void App::shutdown() {
    if (swapchain_) swapchain_->wait_idle();
    if (context_) vkDeviceWaitIdle(context_->device());
    if (imgui_ready_) {
        ImGui_ImplVulkan_Shutdown();
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
        imgui_ready_ = false;
    }
    renderer_.reset();
    imgui_pool_.reset();
    swapchain_.reset();
    context_.reset();
    if (window_ != nullptr) glfwDestroyWindow(window_);
    window_ = nullptr;
    glfwTerminate();
}

// ---- Document operations ------------------------------------------------------------------

void App::frame_terrain() {
    const Rect d = doc_.tin->domain();
    const VertexArrays& va = doc_.tin->vertices();
    double lo = 1e300, hi = -1e300;
    for (std::size_t i = 0; i < va.size(); ++i) {
        if (!va.alive[i]) continue;
        lo = std::min(lo, va.height[i]);
        hi = std::max(hi, va.height[i]);
    }
    camera_.frame({-0.5 * d.width(), -0.5 * d.height(), lo},
                  {0.5 * d.width(), 0.5 * d.height(), hi});
    camera_.distance *= 0.8;  // the domain's corners may leave the view a little: more terrain
}

void App::save(const std::filesystem::path& p) {
    end_action();
    save_session_clearing_autosave(p, doc_.session());
    doc_.path = p;
    doc_.dirty = false;
    report("saved " + p.string());
}

void App::open(const std::filesystem::path& p) {
    end_action();
    const Session s = load_session(p);
    doc_.adopt(Tin::from_snapshot(s.terrain), s.next_generation, p);
    mesh_stale_ = true;
    frame_terrain();
    report("opened " + p.string());
}

Tool App::build_tool() const {
    ToolSpec spec = load_tool_asset(kTools[settings_.tool].asset);
    if (spec.contour == ContourKind::Circle) spec.radius = settings_.tool_radius;
    spec.extrude = settings_.extrude;
    return Tool::build(spec);
}

void App::end_action() {
    if (sampler_) {
        const ToolEntry& t = kTools[settings_.tool];
        for (const StrokeSample& s : sampler_->finish()) {
            StrokeSettings ss;
            ss.depth = settings_.tool_depth;
            ss.follow_path = settings_.follow_path;
            ss.angle = settings_.tool_angle * 3.14159265358979 / 180.0;
            const ToolPlacement at =
                placement_for(*doc_.tin, *active_tool_, s, ss, &doc_.context->hint);
            stamp(*doc_.tin, *active_tool_, at, *doc_.context, s.direction);
        }
        sampler_.reset();
        (void)t;
    }
    if (!pending_label_.empty()) {
        if (doc_.history->record(pending_label_)) doc_.dirty = true;
        pending_label_.clear();
    }
    if (erosion_pending_) {
        if (doc_.history->record("erosion")) doc_.dirty = true;
        erosion_pending_ = false;
    }
}

void App::undo() {
    end_action();
    const HistoryStep step = doc_.history->undo();
    std::string message = step.done ? "undo " + step.label : "nothing to undo";
    if (step.done && !step.report.exact()) message += " (approximate: border vertices kept)";
    if (step.label == "erosion" && settings_.erosion_running) {
        // Running on, the physics would slide the restored sand straight back.
        settings_.erosion_running = false;
        message += "; erosion paused";
    }
    report(message);
    physics_kick_ = true;
    doc_.dirty = true;
}

void App::redo() {
    end_action();
    const HistoryStep step = doc_.history->redo();
    report(step.done ? "redo " + step.label : "nothing to redo");
    physics_kick_ = true;
    doc_.dirty = true;
}

// ---- Input ----------------------------------------------------------------------------------

std::optional<Vec3> App::pick(double x, double y) const {
    int w = 0, h = 0;
    glfwGetWindowSize(window_, &w, &h);
    const Ray ray = camera_.pixel_ray(x, y, w, h);
    const Rect d = doc_.tin->domain();
    const double step = std::max(d.width(), d.height()) / 2000.0;
    const auto hit = pick_terrain(*doc_.tin, ray, d.centre(), step, camera_.distance * 4.0);
    if (!hit) return std::nullopt;
    return hit->point;
}

void App::tool_at(Vec3 p) {
    const auto t0 = Clock::now();
    const ToolEntry& t = kTools[settings_.tool];
    const Vec2 xy{p.x, p.y};
    switch (t.kind) {
        case ToolKind::Stamp: {
            if (!sampler_) {
                active_tool_ = build_tool();
                sampler_.emplace(settings_.stroke_spacing);
            }
            StrokeSettings ss;
            ss.depth = settings_.tool_depth;
            ss.follow_path = settings_.follow_path;
            ss.angle = settings_.tool_angle * 3.14159265358979 / 180.0;
            for (const StrokeSample& s : sampler_->add_point(xy)) {
                const ToolPlacement at =
                    placement_for(*doc_.tin, *active_tool_, s, ss, &doc_.context->hint);
                stamp(*doc_.tin, *active_tool_, at, *doc_.context, s.direction);
            }
            pending_label_ = std::string("stroke (") + t.label + ")";
            break;
        }
        case ToolKind::Brush: {
            if (last_dab_ && distance(*last_dab_, xy) < settings_.tool_radius * 0.25) break;
            BrushSettings b;
            b.kind = t.brush;
            b.radius = settings_.tool_radius;
            b.strength = t.brush == BrushKind::Raise ? settings_.brush_strength : 0.5;
            b.material = static_cast<std::uint16_t>(settings_.material);
            apply_brush(*doc_.tin, xy, b, *doc_.context);
            last_dab_ = xy;
            pending_label_ = std::string("brush (") + t.label + ")";
            break;
        }
        case ToolKind::Pour:
        case ToolKind::Remove: {
            PourSettings ps;
            ps.radius = settings_.tool_radius * 0.5;
            if (t.kind == ToolKind::Pour) {
                pour_sand(*doc_.tin, xy, settings_.pour_volume, ps, *doc_.context);
                pending_label_ = "pour";
            } else {
                remove_sand(*doc_.tin, xy, settings_.pour_volume, ps, *doc_.context);
                pending_label_ = "remove sand";
            }
            break;
        }
    }
    tool_ms_ += ms_since(t0);
    mesh_stale_ = true;
    physics_kick_ = true;
}

void App::mouse_button(int button, bool down, double x, double y) {
    mouse_x_ = x;
    mouse_y_ = y;
    redraw_frames_ = 3;
    if (button == GLFW_MOUSE_BUTTON_LEFT) {
        left_down_ = down;
        if (down) {
            if (erosion_pending_) end_action();  // erosion so far is its own undo level
            last_dab_.reset();
            if (const auto p = pick(x, y)) tool_at(*p);
        } else {
            end_action();
        }
    } else if (button == GLFW_MOUSE_BUTTON_RIGHT) {
        right_down_ = down;
    } else if (button == GLFW_MOUSE_BUTTON_MIDDLE) {
        middle_down_ = down;
    }
}

void App::mouse_move(double x, double y) {
    const double dx = x - mouse_x_, dy = y - mouse_y_;
    mouse_x_ = x;
    mouse_y_ = y;
    redraw_frames_ = 3;
    if (right_down_) camera_.orbit(dx, dy);
    if (middle_down_) {
        int w = 0, h = 0;
        glfwGetWindowSize(window_, &w, &h);
        camera_.pan(dx, dy, h);
    }
    cursor_ = pick(x, y);
    if (left_down_ && cursor_) tool_at(*cursor_);
}

void App::scroll(double dy) {
    camera_.zoom(dy);
    redraw_frames_ = 3;
}

void App::key(int k, bool ctrl) {
    redraw_frames_ = 3;
    if (ctrl && k == GLFW_KEY_Z)
        undo();
    else if (ctrl && k == GLFW_KEY_Y)
        redo();
    else if (ctrl && k == GLFW_KEY_S) {
        try {
            save(doc_.path.empty() ? std::filesystem::path(path_buf_) : doc_.path);
        } catch (const std::exception& e) {
            report(std::string("save failed: ") + e.what());
        }
    } else if (k >= GLFW_KEY_0 && k <= GLFW_KEY_9) {
        end_action();
        settings_.tool = k == GLFW_KEY_0 ? 9 : k - GLFW_KEY_1;
    } else if (k == GLFW_KEY_F) {
        frame_terrain();
    }
}

// ---- Script ---------------------------------------------------------------------------------
//
// {"ops": [ {"op": "tool", "name": "Ball"} | {"op": "set", "<setting>": value, ...}
//         | {"op": "drag", "button": "left"|"right"|"middle", "path": [[fx, fy], ...], "steps": n}
//         | {"op": "click", "at": [fx, fy]} | {"op": "move", "at": [fx, fy]}
//         | {"op": "key", "key": "z", "ctrl": true}
//         | {"op": "scroll", "steps": s} | {"op": "wait", "frames": n}
//         | {"op": "erode", "frames": n} | {"op": "save", "path": "..."} ] }
// Positions are fractions of the window (0..1): scripts work at any --size.

void App::run_script_op(const nlohmann::json& op) {
    int w = 0, h = 0;
    glfwGetWindowSize(window_, &w, &h);
    const std::string kind = op.at("op").get<std::string>();
    auto px = [&](const nlohmann::json& p) {
        return std::pair<double, double>{p.at(0).get<double>() * w, p.at(1).get<double>() * h};
    };
    if (kind == "tool") {
        const std::string name = op.at("name").get<std::string>();
        for (int i = 0; i < kToolCount; ++i) {
            if (name == kTools[i].label) {
                key(i == 9 ? GLFW_KEY_0 : GLFW_KEY_1 + i, false);
                return;
            }
        }
        throw std::runtime_error("script: unknown tool '" + name + "'");
    } else if (kind == "set") {
        nlohmann::json j = op;
        j.erase("op");
        for (auto& [k2, v] : j.items()) {
            if (k2 == "radius")
                settings_.tool_radius = v.get<double>();
            else if (k2 == "depth")
                settings_.tool_depth = v.get<double>();
            else if (k2 == "material")
                settings_.material = v.get<int>();
            else if (k2 == "erosion")
                settings_.erosion_running = v.get<bool>();
            else if (k2 == "wireframe")
                settings_.overlay_wireframe = v.get<bool>();
            else if (k2 == "slope")
                settings_.overlay_slope = v.get<bool>();
            else if (k2 == "pour_volume")
                settings_.pour_volume = v.get<double>();
            else
                throw std::runtime_error("script: unknown setting '" + k2 + "'");
        }
    } else if (kind == "drag" || kind == "click") {
        const std::string b = op.value("button", "left");
        const int button = b == "right"    ? GLFW_MOUSE_BUTTON_RIGHT
                           : b == "middle" ? GLFW_MOUSE_BUTTON_MIDDLE
                                           : GLFW_MOUSE_BUTTON_LEFT;
        std::vector<std::pair<double, double>> pts;
        if (kind == "click") {
            pts.push_back(px(op.at("at")));
        } else {
            const auto& path = op.at("path");
            if (path.size() < 2) throw std::runtime_error("script: a drag needs two points");
            const int steps = std::max(1, op.value("steps", 20));
            for (std::size_t i = 0; i + 1 < path.size(); ++i) {
                const auto a = px(path[i]), c = px(path[i + 1]);
                for (int s = 0; s < steps; ++s) {
                    const double t = static_cast<double>(s) / steps;
                    pts.push_back(
                        {a.first + t * (c.first - a.first), a.second + t * (c.second - a.second)});
                }
            }
            pts.push_back(px(path.back()));
        }
        mouse_move(pts[0].first, pts[0].second);
        mouse_button(button, true, pts[0].first, pts[0].second);
        for (std::size_t i = 1; i < pts.size(); ++i)
            mouse_move(pts[i].first, pts[i].second);
        mouse_button(button, false, pts.back().first, pts.back().second);
    } else if (kind == "move") {
        const auto p = px(op.at("at"));
        mouse_move(p.first, p.second);
    } else if (kind == "key") {
        const std::string k = op.at("key").get<std::string>();
        if (k.size() != 1) throw std::runtime_error("script: key must be one character");
        const char c = static_cast<char>(std::toupper(static_cast<unsigned char>(k[0])));
        key(c >= '0' && c <= '9' ? GLFW_KEY_0 + (c - '0') : GLFW_KEY_A + (c - 'A'),
            op.value("ctrl", false));
    } else if (kind == "scroll") {
        scroll(op.at("steps").get<double>());
    } else if (kind == "wait" || kind == "erode") {
        if (kind == "erode") settings_.erosion_running = true;
        script_wait_ = op.value("frames", 1);
    } else if (kind == "save") {
        save(op.at("path").get<std::string>());
    } else {
        throw std::runtime_error("script: unknown op '" + kind + "'");
    }
}

// ---- Per frame ------------------------------------------------------------------------------

void App::update_simulation() {
    const auto t0 = Clock::now();
    // The physics learns about edits when it steps, so an edit "kicks" it.
    if (settings_.erosion_running && (physics_kick_ || !doc_.physics->at_rest())) {
        physics_kick_ = false;
        doc_.physics->settings().parameters.relocation_radius = settings_.relocation_radius;
        std::vector<VertexId> changed;
        doc_.physics->step(settings_.erosion_steps, &changed);
        if (active_.size() < doc_.tin->vertex_capacity())
            active_.resize(doc_.tin->vertex_capacity());
        std::fill(active_.begin(), active_.end(), 0);
        for (VertexId v : changed) {
            if (v.index() < active_.size()) active_[v.index()] = 1;
        }
        if (!changed.empty()) {
            mesh_stale_ = true;
            if (!left_down_) erosion_pending_ = true;
        }
        if (doc_.physics->at_rest() && erosion_pending_ && !left_down_) end_action();
    } else if (!active_.empty() && settings_.overlay_active) {
        std::fill(active_.begin(), active_.end(), 0);
    }
    times_.push(times_.physics, ms_since(t0));
    times_.push(times_.tool, tool_ms_);
    tool_ms_ = 0.0;
    // Autosave a dirty document every minute.
    if (doc_.dirty && !doc_.path.empty() && !options_.scripted() &&
        Clock::now() - doc_.last_autosave > std::chrono::seconds(60)) {
        write_autosave(doc_.path, doc_.session());
        doc_.last_autosave = Clock::now();
    }
}

void App::update_mesh() {
    // The journal says whether anything changed; nothing changed means no rebuild, no upload.
    const ChangeSet changes = doc_.tin->take_changes();
    if (!mesh_stale_ && changes.empty()) {
        times_.push(times_.mesh, 0.0);
        times_.push(times_.upload, 0.0);
        return;
    }
    const auto t0 = Clock::now();
    const std::vector<render::TerrainVertex> vertices =
        render::build_terrain_vertices(*doc_.tin, doc_.materials, active_);
    times_.push(times_.mesh, ms_since(t0));
    const auto t1 = Clock::now();
    swapchain_->wait_idle();
    renderer_->upload(vertices);
    times_.push(times_.upload, ms_since(t1));
    mesh_stale_ = false;
}

bool App::frame(bool capture) {
    const auto t0 = Clock::now();
    update_simulation();
    update_mesh();

    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    draw_panels();
    ImGui::Render();

    const auto t1 = Clock::now();
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
        push.cursor[3] = 1.0f;
    }
    push.overlays[0] = settings_.overlay_wireframe ? 1.0f : 0.0f;
    push.overlays[1] = settings_.overlay_active ? 1.0f : 0.0f;
    push.overlays[2] = settings_.overlay_thickness ? 1.0f : 0.0f;
    push.overlays[3] = settings_.overlay_slope ? 1.0f : 0.0f;
    push.contrast[0] = 0.0f;
    push.contrast[1] = 0.12f;
    renderer_->draw(swapchain_->command_buffer(), push, extent);
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

// ---- Panels ---------------------------------------------------------------------------------

void App::draw_panels() {
    ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(300, 0), ImGuiCond_Always);
    ImGui::Begin("sandtin", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize);
    if (ImGui::CollapsingHeader("File", ImGuiTreeNodeFlags_DefaultOpen)) panel_file();
    if (ImGui::CollapsingHeader("Tools", ImGuiTreeNodeFlags_DefaultOpen)) panel_tools();
    if (ImGui::CollapsingHeader("Materials")) panel_materials();
    if (ImGui::CollapsingHeader("Erosion", ImGuiTreeNodeFlags_DefaultOpen)) panel_erosion();
    if (ImGui::CollapsingHeader("Haptics")) panel_haptics();
    if (!status_.empty()) ImGui::TextWrapped("%s", status_.c_str());
    ImGui::End();
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos(ImVec2(display.x - 8, 8), ImGuiCond_Always, ImVec2(1, 0));
    ImGui::SetNextWindowSize(ImVec2(290, 0), ImGuiCond_Always);
    ImGui::Begin("Stats", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize);
    panel_stats();
    ImGui::End();
    recovery_prompt();
}

void App::panel_file() {
    ImGui::InputText("Scene", path_buf_, sizeof(path_buf_));
    tip("Path used by Open, Save As and Ctrl+S when the scene has no file yet");
    if (ImGui::Button("New")) {
        end_action();
        doc_.adopt(default_sandbox(), 1, {});
        mesh_stale_ = true;
        frame_terrain();
    }
    tip("Start a new 1 m x 1 m sandbox with dunes");
    ImGui::SameLine();
    if (ImGui::Button("Open")) {
        try {
            open(path_buf_);
        } catch (const std::exception& e) {
            report(std::string("open failed: ") + e.what());
        }
    }
    tip("Open the .sandtin session named above");
    ImGui::SameLine();
    if (ImGui::Button("Save")) {
        try {
            save(doc_.path.empty() ? std::filesystem::path(path_buf_) : doc_.path);
        } catch (const std::exception& e) {
            report(std::string("save failed: ") + e.what());
        }
    }
    tip("Save the scene to its file (Ctrl+S); the autosave is then removed");
    ImGui::SameLine();
    if (ImGui::Button("Save As")) {
        try {
            save(path_buf_);
        } catch (const std::exception& e) {
            report(std::string("save failed: ") + e.what());
        }
    }
    tip("Save the scene under the path above");
    ImGui::InputText("Heightmap", import_buf_, sizeof(import_buf_));
    tip("PNG (16-bit or Terrain-RGB), EXR, GeoTIFF or ESRI ASCII grid to import");
    ImGui::SameLine();
    if (ImGui::Button("Import")) {
        try {
            end_action();
            ImportResult r = import_heightmap(import_buf_, ImportOptions{});
            doc_.adopt(std::move(r.tin), 1, {});
            mesh_stale_ = true;
            frame_terrain();
            report("imported " + std::string(import_buf_));
        } catch (const std::exception& e) {
            report(std::string("import failed: ") + e.what());
        }
    }
    tip("Import the heightmap as an error-bounded TIN (replaces the scene)");
    ImGui::InputText("Export to", export_buf_, sizeof(export_buf_));
    tip("Mesh (.obj .ply .stl .gltf .glb) or heightmap (.png .exr); the extension picks the "
        "format");
    ImGui::SameLine();
    if (ImGui::Button("Export")) {
        try {
            end_action();
            const ExportReport r =
                export_terrain(*doc_.tin, export_buf_, export_format_for(export_buf_));
            report("exported " + std::to_string(r.files.size()) + " file(s)");
        } catch (const std::exception& e) {
            report(std::string("export failed: ") + e.what());
        }
    }
    tip("Write the terrain to the file above");
    ImGui::BeginDisabled(!doc_.history->can_undo());
    if (ImGui::Button("Undo")) undo();
    ImGui::EndDisabled();
    tip("Undo the last stroke, brush, pour or erosion run (Ctrl+Z)");
    ImGui::SameLine();
    ImGui::BeginDisabled(!doc_.history->can_redo());
    if (ImGui::Button("Redo")) redo();
    ImGui::EndDisabled();
    tip("Redo (Ctrl+Y)");
    ImGui::SameLine();
    ImGui::Text("%zu levels, %.1f MB", doc_.history->undo_levels(),
                static_cast<double>(doc_.history->bytes()) / 1048576.0);
}

void App::panel_tools() {
    for (int i = 0; i < kToolCount; ++i) {
        if (i % 4 != 0) ImGui::SameLine();
        if (ImGui::RadioButton(kTools[i].label, settings_.tool == i)) {
            end_action();
            settings_.tool = i;
        }
        tip(kTools[i].help);
    }
    float radius = static_cast<float>(settings_.tool_radius * 100.0);
    if (ImGui::SliderFloat("Size (cm)", &radius, 0.5f, 15.0f, "%.1f"))
        settings_.tool_radius = static_cast<double>(radius) / 100.0;
    tip("Radius of round tools, brushes and the pour");
    float depth = static_cast<float>(settings_.tool_depth * 1000.0);
    if (ImGui::SliderFloat("Depth (mm)", &depth, -20.0f, 40.0f, "%.1f"))
        settings_.tool_depth = static_cast<double>(depth) / 1000.0;
    tip("How deep a stamp tool presses below the terrain ahead of it");
    float spacing = static_cast<float>(settings_.stroke_spacing * 1000.0);
    if (ImGui::SliderFloat("Spacing (mm)", &spacing, 1.0f, 50.0f, "%.1f"))
        settings_.stroke_spacing = static_cast<double>(spacing) / 1000.0;
    tip("Distance between stamps along a stroke (independent of frame rate)");
    ImGui::Checkbox("Extrude", &settings_.extrude);
    tip("Push the displaced sand into a rim beside and ahead of the tool (volume conserved)");
    ImGui::SameLine();
    ImGui::Checkbox("Follow path", &settings_.follow_path);
    tip("Turn the tool with the stroke direction; otherwise use the fixed orientation");
    float angle = static_cast<float>(settings_.tool_angle);
    if (ImGui::SliderFloat("Orientation", &angle, -180.0f, 180.0f, "%.0f deg"))
        settings_.tool_angle = static_cast<double>(angle);
    tip("Tool heading when it does not follow the path");
    float strength = static_cast<float>(settings_.brush_strength * 1000.0);
    if (ImGui::SliderFloat("Brush (mm/dab)", &strength, 0.5f, 20.0f, "%.1f"))
        settings_.brush_strength = static_cast<double>(strength) / 1000.0;
    tip("Height a Raise brush dab adds at its centre");
    float pour = static_cast<float>(settings_.pour_volume * 1e6);
    if (ImGui::SliderFloat("Pour (cm3)", &pour, 1.0f, 200.0f, "%.0f"))
        settings_.pour_volume = static_cast<double>(pour) * 1e-6;
    tip("Sand volume poured or removed per click or mouse move");
}

void App::panel_materials() {
    const auto& all = doc_.materials.all();
    for (std::size_t i = 0; i < all.size(); ++i) {
        const Material& m = all[i];
        ImGui::ColorButton(("##c" + std::to_string(i)).c_str(),
                           ImVec4(m.colour[0], m.colour[1], m.colour[2], 1.0f));
        tip("Material colour (linear RGB)");
        ImGui::SameLine();
        if (ImGui::RadioButton(m.name.c_str(), settings_.material == static_cast<int>(i)))
            settings_.material = static_cast<int>(i);
        tip("Material painted by the Paint brush");
        ImGui::SameLine();
        ImGui::Text("repose %.0f deg dry, %.0f deg moist", m.repose_dry * 57.2957795,
                    m.repose_wet * 57.2957795);
    }
    ImGui::TextWrapped(
        "Paint materials with the Paint brush (key 0); moisture darkens the colour.");
}

void App::panel_erosion() {
    if (ImGui::Button(settings_.erosion_running ? "Pause" : "Run")) {
        settings_.erosion_running = !settings_.erosion_running;
        if (!settings_.erosion_running) end_action();
    }
    tip("Run or pause talus relaxation; an erosion run becomes one undo level");
    ImGui::SameLine();
    ImGui::Text("%s, %zu active", doc_.physics->at_rest() ? "at rest" : "sliding",
                doc_.physics->active_count());
    ImGui::SliderInt("Steps/frame", &settings_.erosion_steps, 1, 200);
    tip("Relaxation iterations per frame");
    ImGui::TextUnformatted("Solver: CPU (sequential active list)");
    tip("The GPU relaxation belongs to the GPU mirror; this editor build runs the CPU reference");
    float rs = static_cast<float>(settings_.relocation_radius * 1000.0);
    if (ImGui::SliderFloat("r_S (mm)", &rs, 1.0f, 50.0f, "%.1f"))
        settings_.relocation_radius = static_cast<double>(rs) / 1000.0;
    tip("Relocation radius: material never jumps farther; longer edges are split");
    float tol = static_cast<float>(settings_.simplify_tolerance * 1000.0);
    if (ImGui::SliderFloat("Simplify (mm)", &tol, 0.05f, 5.0f, "%.2f")) {
        settings_.simplify_tolerance = static_cast<double>(tol) / 1000.0;
        doc_.context->settings.simplify.tolerance = settings_.simplify_tolerance;
    }
    tip("Vertices within this distance of a common plane with their neighbours are removed");
    ImGui::Checkbox("Wireframe", &settings_.overlay_wireframe);
    tip("Show the triangulation; constrained edges (tool rims) in magenta");
    ImGui::SameLine();
    ImGui::Checkbox("Active", &settings_.overlay_active);
    tip("Highlight vertices that moved in the last erosion step");
    ImGui::Checkbox("Sand depth", &settings_.overlay_thickness);
    tip("Sand thickness above bedrock: blue thin, yellow 5 cm or more");
    ImGui::SameLine();
    ImGui::Checkbox("Slope", &settings_.overlay_slope);
    tip("Slope against the angle of repose: green stable, yellow at repose, red over-steep");
    float contrast = static_cast<float>(settings_.contrast);
    if (ImGui::SliderFloat("Contrast", &contrast, 0.0f, 1.0f))
        settings_.contrast = static_cast<double>(contrast);
    tip("Strength of the height contrast curve (histogram stretch)");
    if (ImGui::Checkbox("VSync", &settings_.vsync)) {
        int w = 0, h = 0;
        glfwGetFramebufferSize(window_, &w, &h);
        swapchain_->recreate({static_cast<std::uint32_t>(w), static_cast<std::uint32_t>(h)},
                             settings_.vsync);
    }
    tip("Wait for the display's refresh when presenting");
}

void App::panel_haptics() {
    ImGui::TextWrapped(
        "No haptic device is connected to this editor build: the force loop, devices and "
        "snapshot exchange live in engine/haptics and are driven from the sandtin CLI.");
}

void App::panel_stats() {
    const Tin& t = *doc_.tin;
    ImGui::Text("%zu vertices, %zu triangles", t.vertex_count(), t.triangle_count());
    ImGui::Text("%zu constrained edges, volume %.3f L", t.constrained_edge_count(),
                t.volume() * 1000.0);
    const double frame_ms = StageTimes::median(times_.frame);
    ImGui::Text("%.1f fps (%.1f ms)", frame_ms > 0.0 ? 1000.0 / frame_ms : 0.0, frame_ms);
    ImGui::Text("tool %.2f  physics %.2f  mesh %.2f", StageTimes::median(times_.tool),
                StageTimes::median(times_.physics), StageTimes::median(times_.mesh));
    ImGui::Text("upload %.2f  render %.2f ms", StageTimes::median(times_.upload),
                StageTimes::median(times_.render));
    tip("Median milliseconds per frame of each stage over the last 240 frames");
    std::vector<float> plot(times_.frame.begin(), times_.frame.end());
    ImGui::PlotLines("##frame", plot.data(), static_cast<int>(plot.size()), 0, "frame ms", 0.0f,
                     100.0f, ImVec2(0, 40));
    tip("Frame time over the last 240 frames (0-100 ms)");
}

void App::recovery_prompt() {
    if (!recovery_for_) return;
    ImGui::OpenPopup("Recover autosave?");
    if (ImGui::BeginPopupModal("Recover autosave?", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
        ImGui::Text("An autosave newer than %s exists.", recovery_for_->c_str());
        if (ImGui::Button("Recover")) {
            const Session s = recover_autosave(*recovery_for_);
            doc_.adopt(Tin::from_snapshot(s.terrain), s.next_generation, *recovery_for_);
            doc_.dirty = true;
            mesh_stale_ = true;
            recovery_for_.reset();
            ImGui::CloseCurrentPopup();
        }
        tip("Load the autosave; save to keep it");
        ImGui::SameLine();
        if (ImGui::Button("Discard")) {
            discard_autosave(*recovery_for_);
            recovery_for_.reset();
            ImGui::CloseCurrentPopup();
        }
        tip("Delete the autosave and keep the scene as saved");
        ImGui::EndPopup();
    }
}

// ---- Main loop ------------------------------------------------------------------------------

int App::run() {
    settings_path_ = options_.settings.empty() ? default_settings_path() : options_.settings;
    std::string problem;
    settings_ = load_settings(settings_path_, &problem);
    if (!problem.empty()) std::fprintf(stderr, "sandtin-editor: %s\n", problem.c_str());
    settings_.tool = std::clamp(settings_.tool, 0, kToolCount - 1);
    saved_settings_ = settings_;
    if (!options_.script.empty()) {
        std::ifstream in(options_.script);
        if (!in) throw std::runtime_error("cannot read script " + options_.script.string());
        const nlohmann::json j = nlohmann::json::parse(in);
        if (!j.contains("ops") || !j["ops"].is_array())
            throw std::runtime_error("script " + options_.script.string() +
                                     " has no \"ops\" array");
        for (const auto& op : j["ops"])
            script_.push_back(op);
    }
    load_initial_scene();
    if (!options_.scene.empty())
        std::snprintf(path_buf_, sizeof(path_buf_), "%s", options_.scene.c_str());
    doc_.context->settings.simplify.tolerance = settings_.simplify_tolerance;
    init_window_and_gpu();
    init_imgui();
    std::fprintf(stderr, "sandtin-editor: %s\n", context_->describe().c_str());
    frame_terrain();

    int exit_code = 0;
    std::uint64_t idle_submissions = 0;
    int frames_after_script = 0;
    if (options_.scripted()) {
        // Scripted: every op runs between frames through the real input handlers.
        while (!glfwWindowShouldClose(window_)) {
            glfwPollEvents();
            if (script_wait_ > 0) {
                --script_wait_;
            } else if (script_pos_ < script_.size()) {
                run_script_op(script_[script_pos_++]);
            } else {
                end_action();
                ++frames_after_script;
            }
            const bool last = script_pos_ >= script_.size() && script_wait_ == 0 &&
                              frames_after_script >= std::max(1, options_.frames);
            frame(last && !options_.screenshot.empty());
            if (last) break;
        }
        if (!options_.screenshot.empty()) write_png(options_.screenshot, swapchain_->screenshot());
        if (!options_.save_after.empty()) save(options_.save_after);
        if (options_.idle_seconds > 0.0) {
            // Idle: nothing changed, nothing drawn; count what reaches the queue meanwhile.
            const std::uint64_t before = swapchain_->submissions();
            const auto until = Clock::now() + std::chrono::duration<double>(options_.idle_seconds);
            settings_.erosion_running = false;
            redraw_frames_ = 0;
            while (Clock::now() < until) {
                glfwWaitEventsTimeout(std::chrono::duration<double>(until - Clock::now()).count());
                if (redraw_frames_ > 0) {
                    frame(false);
                    --redraw_frames_;
                }
            }
            idle_submissions = swapchain_->submissions() - before;
        }
    } else {
        while (!glfwWindowShouldClose(window_)) {
            const bool busy =
                redraw_frames_ > 0 || left_down_ || recovery_for_ ||
                (settings_.erosion_running && (physics_kick_ || !doc_.physics->at_rest()));
            // Idle: block until an event arrives; no frame, no submission.
            if (busy)
                glfwPollEvents();
            else
                glfwWaitEvents();
            int w = 0, h = 0;
            glfwGetFramebufferSize(window_, &w, &h);
            if (w == 0 || h == 0) continue;  // minimised: nothing to draw
            frame(false);
            if (redraw_frames_ > 0) --redraw_frames_;
            if (!(settings_ == saved_settings_)) {
                save_settings(settings_path_, settings_);
                saved_settings_ = settings_;
            }
        }
        end_action();
    }

    const std::uint64_t validation = context_->validation_message_count();
    if (!options_.stats.empty()) {
        nlohmann::json s;
        s["device"] = context_->device_name();
        s["frames"] = times_.frame.size();
        s["frame_ms_median"] = StageTimes::median(times_.frame);
        s["tool_ms_median"] = StageTimes::median(times_.tool);
        s["physics_ms_median"] = StageTimes::median(times_.physics);
        s["mesh_ms_median"] = StageTimes::median(times_.mesh);
        s["upload_ms_median"] = StageTimes::median(times_.upload);
        s["render_ms_median"] = StageTimes::median(times_.render);
        s["fps"] =
            StageTimes::median(times_.frame) > 0 ? 1000.0 / StageTimes::median(times_.frame) : 0.0;
        s["vertices"] = doc_.tin->vertex_count();
        s["triangles"] = doc_.tin->triangle_count();
        s["undo_levels"] = doc_.history->undo_levels();
        s["submissions"] = swapchain_->submissions();
        s["idle_submissions"] = idle_submissions;
        s["validation_messages"] = validation;
        if (cursor_) s["cursor"] = {cursor_->x, cursor_->y, cursor_->z};
        double px = 0, py = 0;
        int w = 0, h = 0;
        glfwGetWindowSize(window_, &w, &h);
        if (cursor_) {
            const Vec2 c = doc_.tin->domain().centre();
            if (camera_.project({cursor_->x - c.x, cursor_->y - c.y, cursor_->z}, w, h, px, py))
                s["cursor_pixel"] = {px, py};
        }
        std::ofstream(options_.stats) << s.dump(2) << "\n";
    }
    if (validation > 0) {
        for (const std::string& m : context_->validation_messages())
            std::fprintf(stderr, "validation: %s\n", m.c_str());
        exit_code = 3;
    }
    if (!options_.scripted() && !(settings_ == saved_settings_))
        save_settings(settings_path_, settings_);
    shutdown();
    return exit_code;
}

}  // namespace

int run_editor(const EditorOptions& options) {
    App app(options);
    try {
        return app.run();
    } catch (...) {
        throw;
    }
}

}  // namespace sandtin::editor
