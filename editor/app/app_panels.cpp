// The ImGui panels: File, Tools, Materials, Erosion, Haptics, Stats, recovery prompt.

#include "app.hpp"

namespace sandtin::editor {

namespace {

/// A slider over `range` at the terrain size `size` (metres, or m³), shown in the unit that
/// suits its largest value: "name (unit per)". The ImGui id is the name alone, so a change of
/// unit is not a new widget. A value typed in (Ctrl+click) is clamped to the range, as a drag
/// is: a tool never receives a size, depth or volume it would refuse.
bool range_slider(const char* name, const char* per, double& value, const SettingRange& range,
                  double size, const char* format) {
    const DisplayUnit unit = range.scaling == Scaling::Volume ? volume_unit(range.hi_at(size))
                                                              : length_unit(range.hi_at(size));
    const std::string label =
        std::string(name) + " (" + unit.suffix + per + ")###" + std::string(name);
    auto shown = [&](double v) { return static_cast<float>(v / unit.metres); };
    float v = shown(value);
    if (!ImGui::SliderFloat(label.c_str(), &v, shown(range.lo_at(size)), shown(range.hi_at(size)),
                            format, ImGuiSliderFlags_AlwaysClamp))
        return false;
    value = range.clamp(static_cast<double>(v) * unit.metres, size);
    return true;
}

/// A plain slider over `range` (no unit scaling), clamped as range_slider is.
bool plain_slider(const char* label, double& value, const SettingRange& range, const char* format,
                  double shown_per_unit = 1.0, ImGuiSliderFlags flags = ImGuiSliderFlags_None) {
    float v = static_cast<float>(value * shown_per_unit);
    if (!ImGui::SliderFloat(label, &v, static_cast<float>(range.lo * shown_per_unit),
                            static_cast<float>(range.hi * shown_per_unit), format,
                            flags | ImGuiSliderFlags_AlwaysClamp))
        return false;
    value = range.clamp(static_cast<double>(v) / shown_per_unit, 1.0);
    return true;
}

/// A material's name as the panels show it: "dry_sand" reads "dry sand".
std::string shown_name(std::string name) {
    std::replace(name.begin(), name.end(), '_', ' ');
    return name;
}

/// The label the panels' label column is sized for: the longest one beside a control.
constexpr const char* kWidestLabel = "Settle margin (%)";

/// A path field filling its row with its button at the right end, "[path ......][Button]";
/// `hint` shows while the field is empty, and hovering the field shows its whole path. The
/// field is noted in `widgets` as `field_name`. True when the button was pressed; the caller's
/// `ui` that follows names and explains the button.
bool path_field(WidgetMap& widgets, const char* field_name, const char* hint, char* buffer,
                std::size_t size, const char* button) {
    const ImGuiStyle& style = ImGui::GetStyle();
    const float button_width = ImGui::CalcTextSize(button).x + 2.0f * style.FramePadding.x;
    ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x - button_width - style.ItemSpacing.x);
    ImGui::InputTextWithHint((std::string("##") + field_name).c_str(), hint, buffer, size);
    widgets.note(field_name);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", buffer[0] != '\0' ? buffer : hint);
    ImGui::SameLine();
    return ImGui::Button(button);
}

}  // namespace

// ---- Panels ---------------------------------------------------------------------------------

void App::draw_panels() {
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    // The status line (save and autosave failures, the terrain-scaling notice) has its own
    // window in the bottom-left corner, and the panel ends above it: when the panel is taller
    // than the window it scrolls, and the status line must never scroll out of sight with it.
    const float status_height = status_window_height();
    const float panel_bottom =
        std::max(display.y - kPanelMargin - status_height, 2.0f * kPanelMargin);
    ImGui::SetNextWindowPos(ImVec2(kPanelMargin, kPanelMargin), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(kPanelWidth, 0), ImGuiCond_Always);
    ImGui::SetNextWindowSizeConstraints(ImVec2(kPanelWidth, 0.0f),
                                        ImVec2(kPanelWidth, panel_bottom - kPanelMargin));
    ImGui::Begin("sandtin", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize);
    // Controls take the width left of a column wide enough for the longest label; the layout
    // probe reports any control that still reaches past the panel's edge.
    ImGui::PushItemWidth(
        -(ImGui::CalcTextSize(kWidestLabel).x + ImGui::GetStyle().ItemInnerSpacing.x));
    const auto section = [&](const char* name, ImGuiTreeNodeFlags flags, void (App::*draw)()) {
        if (open_panels_) ImGui::SetNextItemOpen(*open_panels_);
        if (!ImGui::CollapsingHeader(name, flags)) return;
        layout_.begin(name);
        (this->*draw)();
        layout_.end();
    };
    section("File", ImGuiTreeNodeFlags_DefaultOpen, &App::panel_file);
    section("Tools", ImGuiTreeNodeFlags_DefaultOpen, &App::panel_tools);
    section("Materials", 0, &App::panel_materials);
    section("Erosion", ImGuiTreeNodeFlags_DefaultOpen, &App::panel_erosion);
    section("Haptics", 0, &App::panel_haptics);
    open_panels_.reset();
    ImGui::PopItemWidth();
    ImGui::End();
    status_window(status_height);
    ImGui::SetNextWindowPos(ImVec2(display.x - 8, 8), ImGuiCond_Always, ImVec2(1, 0));
    // As wide as its widest line: the stage times at their usual magnitudes, or the terrain's
    // counts and volume, which a large or high terrain makes longer.
    float stats_text_width = ImGui::CalcTextSize("upload 00.00  bake 00.00  render 000.00 ms").x;
    const std::array<std::string, 2> terrain_lines = stats_terrain_lines();
    for (const std::string& line : terrain_lines)
        stats_text_width = std::max(stats_text_width, ImGui::CalcTextSize(line.c_str()).x);
    const float stats_width = stats_text_width + 2.0f * ImGui::GetStyle().WindowPadding.x;
    ImGui::SetNextWindowSize(ImVec2(stats_width, 0), ImGuiCond_Always);
    ImGui::Begin("Stats", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize);
    layout_.begin("Stats");
    panel_stats(terrain_lines);
    layout_.end();
    ImGui::End();
    recovery_prompt();
    discard_prompt();
    overwrite_prompt();
}

float App::status_window_height() const {
    if (status_.empty()) return 0.0f;
    const ImGuiStyle& style = ImGui::GetStyle();
    const float wrap = kPanelWidth - 2.0f * style.WindowPadding.x;
    return ImGui::CalcTextSize(status_.c_str(), nullptr, false, wrap).y +
           2.0f * style.WindowPadding.y + kPanelMargin;
}

void App::status_window(float height) {
    if (status_.empty()) return;
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos(ImVec2(kPanelMargin, display.y - kPanelMargin), ImGuiCond_Always,
                            ImVec2(0.0f, 1.0f));
    ImGui::SetNextWindowSize(ImVec2(kPanelWidth, height - kPanelMargin), ImGuiCond_Always);
    ImGui::Begin("##status", nullptr,
                 ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                     ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav);
    ImGui::TextWrapped("%s", status_.c_str());
    layout_.item_visible("status");
    ImGui::End();
}

void App::tip(const char* text) {
    if (!ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) return;
    ImGui::SetTooltip("%s", text);
    widgets_.note_tooltip(text);
}

void App::ui(const std::string& name, const char* text) {
    widgets_.note(name);
    tip(text);
}

void App::panel_file() {
    ImGui::InputText("Scene", path_buf_, sizeof(path_buf_));
    ui("Scene", "Path used by Open, Save As and Ctrl+S when the scene has no file yet");
    if (ImGui::Button("New")) replace_document("New", [this] { new_document(); });
    ui("New", "Start a new 1 m x 1 m sandbox with dunes (Ctrl+N)");
    ImGui::SameLine();
    if (ImGui::Button("Open")) replace_document("Open", [this] { open_reporting(); });
    ui("Open", "Open the .sandtin session named above (Ctrl+O)");
    ImGui::SameLine();
    if (ImGui::Button("Save")) request_save(save_path());
    ui("Save",
       "Save the scene to its file (Ctrl+S); the autosave is then removed. An untitled\n"
       "scene is saved under the path above");
    ImGui::SameLine();
    if (ImGui::Button("Save As")) request_save(path_buf_);
    ui("Save As", "Save the scene under the path above (asks before replacing another file)");
    if (path_field(widgets_, "Heightmap", "heightmap to import", import_buf_, sizeof(import_buf_),
                   "Import"))
        replace_document("Import", [this] { import_document(); });
    ui("Import",
       "Import the heightmap named on the left as a new, untitled scene (an error-bounded\n"
       "TIN): PNG (16-bit or Terrain-RGB), EXR, GeoTIFF or ESRI ASCII grid");
    if (path_field(widgets_, "Export path", "file to export to", export_buf_, sizeof(export_buf_),
                   "Export")) {
        try {
            export_to(export_buf_);
        } catch (const std::exception& e) {
            report(std::string("export failed: ") + e.what());
        }
    }
    ui("Export",
       "Write the terrain to the file named on the left: a mesh (.obj .ply .stl .gltf .glb)\n"
       "or a heightmap (.png .exr); the extension picks the format");
    ImGui::BeginDisabled(!undo_log_.can_undo());
    if (ImGui::Button("Undo")) undo();
    ImGui::EndDisabled();
    ui("Undo",
       "Undo the last stroke with its settling, brush, pour, erosion run or material\n"
       "edit (Ctrl+Z)");
    ImGui::SameLine();
    ImGui::BeginDisabled(!undo_log_.can_redo());
    if (ImGui::Button("Redo")) redo();
    ImGui::EndDisabled();
    ui("Redo", "Redo (Ctrl+Y)");
    ImGui::SameLine();
    ImGui::TextUnformatted(undo_levels_text(undo_log_.levels(), doc_.history->bytes()).c_str());
}

void App::panel_tools() {
    // The palette by kind, three to a row after a column of headings. A column is as wide as
    // the widest tool's button, so that no label runs into the next button.
    const ImGuiStyle& style = ImGui::GetStyle();
    const std::array<const char*, 3> headings{"Stamps", "Sand", "Brushes"};
    float heading_width = 0.0f;
    for (const char* h : headings)
        heading_width = std::max(heading_width, ImGui::CalcTextSize(h).x);
    float button_width = 0.0f;
    for (int i = 0; i < kToolCount; ++i) {
        button_width = std::max(button_width, ImGui::GetFrameHeight() + style.ItemInnerSpacing.x +
                                                  ImGui::CalcTextSize(kTools[i].label).x);
    }
    const float left = heading_width + style.ItemSpacing.x;
    const float column = std::max(button_width + style.ItemSpacing.x,
                                  (ImGui::GetContentRegionAvail().x - left) / 3.0f);
    const auto group = [&](const char* heading, auto member) {
        int placed = 0;
        for (int i = 0; i < kToolCount; ++i) {
            if (!member(kTools[i])) continue;
            if (placed % 3 == 0) ImGui::TextDisabled("%s", placed == 0 ? heading : "");
            ImGui::SameLine(left + column * static_cast<float>(placed % 3));
            if (ImGui::RadioButton(kTools[i].label, settings_.tool == i)) {
                end_gesture();
                settings_.tool = i;
            }
            ui(kTools[i].label, kTools[i].help);
            ++placed;
        }
    };
    group(headings[0], [](const ToolEntry& t) { return t.kind == ToolKind::Stamp; });
    group(headings[1], [](const ToolEntry& t) {
        return t.kind == ToolKind::Pour || t.kind == ToolKind::Remove;
    });
    group(headings[2], [](const ToolEntry& t) { return t.kind == ToolKind::Brush; });

    const ToolEntry& tool = kTools[settings_.tool];
    const double size = settings_.scene_size;
    // Only the sliders that act on this tool: Size does not size the box, rake, letter or
    // foot, and Depth acts on stamps and on the haptic pen only.
    const bool round_stamp = tool.kind == ToolKind::Stamp && sized_by_slider(cursor_tool().spec());
    const ToolSliders sliders = sliders_for(tool, round_stamp, haptics_ != nullptr);
    if (sliders.size) {
        range_slider("Size", "", settings_.tool_radius, kToolRadiusRange, size, "%.1f");
        ui("Size", "Radius of round tools (circle, ball), brushes and the pour");
    } else {
        stamp_size_readout();
    }
    if (sliders.depth) {
        range_slider("Depth", "", settings_.tool_depth, kToolDepthRange, size, "%.1f");
        ui("Depth",
           "How deep a stamp tool presses below the terrain ahead of it, and how deep\n"
           "the haptic pen's tip rests in the sand");
    }
    switch (tool.kind) {
        case ToolKind::Stamp: {
            plain_slider("Spacing", settings_.stroke_spacing_ratio, kStrokeSpacingRange,
                         "%.0f %% of size", 100.0, ImGuiSliderFlags_Logarithmic);
            ui("Spacing",
               "Distance between stamps along a stroke, as a share of the tool's\n"
               "radius (independent of frame rate)");
            ImGui::Checkbox("Extrude", &settings_.extrude);
            ui("Extrude",
               "Push the displaced sand into a rim beside and ahead of the tool (volume "
               "conserved).");
            ImGui::SameLine();
            ImGui::Checkbox("Follow path", &settings_.follow_path);
            ui("Follow path",
               "Turn the tool with the stroke direction; otherwise use the fixed orientation");
            ImGui::BeginDisabled(settings_.follow_path);
            plain_slider("Orientation", settings_.tool_angle, kToolAngleRange, "%.0f deg");
            ImGui::EndDisabled();
            ui("Orientation",
               "Tool heading when it does not follow the path (turn Follow path off to set it)");
            break;
        }
        case ToolKind::Pour:
        case ToolKind::Remove: {
            range_slider("Pour", "", settings_.pour_volume, kPourVolumeRange, size, "%.0f");
            ui("Pour",
               "Sand poured or removed per dab. A click is one dab; a drag adds one\n"
               "every quarter of the Size along the stroke, however fast the mouse\n"
               "moves; holding the button still adds four dabs a second (4 x this\n"
               "volume per second)");
            break;
        }
        case ToolKind::Brush: {
            if (tool.brush == BrushKind::Raise || tool.brush == BrushKind::Lower) {
                range_slider("Height", "/dab", settings_.brush_strength, kBrushStrengthRange, size,
                             "%.1f");
                ui("Height", "Height a Raise or Lower dab adds or takes at its centre");
            } else if (tool.brush == BrushKind::Smooth || tool.brush == BrushKind::Flatten) {
                plain_slider("Strength", settings_.brush_blend, kBrushBlendRange, "%.2f");
                ui("Strength",
                   "Fraction of the way to the smooth surface (Smooth) or to the stroke's\n"
                   "starting level (Flatten) that one dab goes at the brush centre");
            }
            if (tool.brush != BrushKind::PaintMaterial) {
                int falloff = static_cast<int>(
                    falloff_named(settings_.brush_falloff).value_or(Falloff::Smooth));
                if (ImGui::Combo("Falloff", &falloff, kFalloffNames.data(),
                                 static_cast<int>(kFalloffNames.size())))
                    settings_.brush_falloff = kFalloffNames[static_cast<std::size_t>(falloff)];
                ui("Falloff",
                   "How a dab's effect fades from its centre to its rim: constant, linear,\n"
                   "smooth (flat centre, soft rim) or gaussian (1 % at the rim)");
            } else if (settings_.material >= 0 &&
                       settings_.material < static_cast<int>(doc_.materials.size())) {
                ImGui::TextWrapped(
                    "Paints %s (pick the material under Materials)",
                    shown_name(
                        doc_.materials.all()[static_cast<std::size_t>(settings_.material)].name)
                        .c_str());
            }
            break;
        }
    }
}

void App::stamp_size_readout() {
    double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
    for (const Vec2 p : cursor_tool().shape().inner) {
        x0 = std::min(x0, p.x);
        y0 = std::min(y0, p.y);
        x1 = std::max(x1, p.x);
        y1 = std::max(y1, p.y);
    }
    // The unit the Size slider shows on this terrain.
    const DisplayUnit unit = length_unit(0.15 * settings_.scene_size);
    ImGui::LabelText("Size", "%.1f x %.1f %s", (x1 - x0) / unit.metres, (y1 - y0) / unit.metres,
                     unit.suffix);
    ui("Size",
       "This tool's own size (its shape, scaled to the terrain); the Size slider sets\n"
       "the radius of round tools only");
}

void App::panel_materials() {
    std::vector<Material> all = doc_.materials.all();
    for (std::size_t i = 0; i < all.size(); ++i) {
        const Material& m = all[i];
        ImGui::ColorButton(("##c" + std::to_string(i)).c_str(),
                           ImVec4(m.colour[0], m.colour[1], m.colour[2], 1.0f));
        tip("Material colour (linear RGB)");
        ImGui::SameLine();
        const std::string label = shown_name(m.name) + "##material" + std::to_string(i);
        if (ImGui::RadioButton(label.c_str(), settings_.material == static_cast<int>(i)))
            settings_.material = static_cast<int>(i);
        ui("material " + std::to_string(i),
           "Select: the Paint brush and the pour use this material; edit it below");
        ImGui::SameLine();
        ImGui::Text("%.0f / %.0f deg", m.repose_dry * 57.2957795, m.repose_wet * 57.2957795);
        tip("Angle of repose dry / with capillary moisture");
    }
    if (settings_.material < 0 || settings_.material >= static_cast<int>(all.size())) return;
    Material& m = all[static_cast<std::size_t>(settings_.material)];
    float dry = static_cast<float>(m.repose_dry * 57.2957795);
    float wet = static_cast<float>(m.repose_wet * 57.2957795);
    bool edited = false;
    // Typed values are clamped to the sliders' ranges, as everywhere (AlwaysClamp).
    ImGui::SliderFloat("Repose dry", &dry, 10.0f, 50.0f, "%.1f deg", ImGuiSliderFlags_AlwaysClamp);
    ui("Repose dry", "Steepest stable slope of the dry material");
    edited |= ImGui::IsItemDeactivatedAfterEdit();
    ImGui::SliderFloat("Repose moist", &wet, dry, 70.0f, "%.1f deg", ImGuiSliderFlags_AlwaysClamp);
    ui("Repose moist",
       "Steepest stable slope with capillary moisture (the plateau before "
       "slumping)");
    edited |= ImGui::IsItemDeactivatedAfterEdit();
    ImGui::ColorEdit3("Colour", m.colour, ImGuiColorEditFlags_Float);
    ui("Colour", "Albedo of the material (linear RGB)");
    edited |= ImGui::IsItemDeactivatedAfterEdit();
    ImGui::SliderFloat("Paint moisture", &m.default_moisture, 0.0f, 1.0f, "%.2f",
                       ImGuiSliderFlags_AlwaysClamp);
    ui("Paint moisture", "Saturation the Paint brush gives the sand it paints with this material");
    edited |= ImGui::IsItemDeactivatedAfterEdit();
    for (float& c : m.colour)
        c = std::clamp(c, 0.0f, 1.0f);  // an albedo: a typed 3 is white, not a light source
    m.repose_dry = static_cast<double>(std::clamp(dry, 10.0f, 50.0f)) / 57.2957795;
    m.repose_wet = static_cast<double>(std::clamp(std::max(wet, dry), dry, 70.0f)) / 57.2957795;
    // Applied when the control is released.
    if (edited) edit_material(settings_.material, m);
}

void App::panel_erosion() {
    // "Run###Run": one control, whatever it says, for the scripts and the test that find it.
    if (ImGui::Button(erosion_runs() ? "Pause###Run" : "Run###Run")) toggle_erosion();
    ui("Run",
       "Run or pause talus relaxation. An opened or imported scene waits for Run, so\n"
       "an elevation model does not melt as it appears. A stroke and the settling it\n"
       "causes are one undo level");
    ImGui::SameLine();
    ImGui::TextUnformatted(erosion_status().c_str());
    tip("Paused, at rest, or sliding with the number of vertices the relaxation still looks at");
    ImGui::SliderInt("Steps/frame", &settings_.erosion_steps,
                     static_cast<int>(kErosionStepsRange.lo),
                     static_cast<int>(kErosionStepsRange.hi), "%d", ImGuiSliderFlags_AlwaysClamp);
    ui("Steps/frame", "Relaxation iterations per frame");
    // Auto, CPU or GPU; Auto says where it resolved on this device.
    const bool on_gpu = doc_.physics->backend() == ErosionBackend::Gpu;
    const std::string auto_label = std::string("Auto (") + (on_gpu ? "GPU" : "CPU") + ")###Auto";
    std::string choice = settings_.physics;
    if (ImGui::RadioButton(auto_label.c_str(), choice == "auto")) choice = "auto";
    ui("Auto",
       "Relaxation on the GPU when the Vulkan device is a hardware GPU, on the CPU on a\n"
       "software device (lavapipe), where the CPU solver is faster and exact");
    ImGui::SameLine();
    if (ImGui::RadioButton("CPU", choice == "cpu")) choice = "cpu";
    ui("CPU", "Relaxation on the CPU: the reference solver (sequential active list)");
    ImGui::SameLine();
    if (ImGui::RadioButton("GPU", choice == "gpu")) choice = "gpu";
    ui("GPU",
       "Relaxation on the GPU (Jacobi, two phases over the active list); the heights are read\n"
       "back into the terrain after every batch, so tools, saves and undo see them");
    if (choice != settings_.physics) {
        end_action();
        settings_.physics = choice;
        attach_physics(true);
    }
    range_slider("r_S", "", settings_.relocation_radius, kRelocationRadiusRange,
                 settings_.scene_size, "%.1f");
    ui("r_S", "Relocation radius: material never jumps farther; longer edges are split");
    plain_slider("Settle margin (%)", settings_.settle_margin, kSettleMarginRange, "%.1f", 100.0);
    ui("Settle margin",
       "Sand that slides comes to rest this much below its angle of repose (the dynamic\n"
       "angle is 1-3 degrees lower). 0 = the seeds' rule: a dug slope creeps for much longer");
    if (range_slider("Simplify", "", settings_.simplify_tolerance, kSimplifyToleranceRange,
                     settings_.scene_size, "%.2f"))
        doc_.context->settings.simplify.tolerance = settings_.simplify_tolerance;
    ui("Simplify",
       "Vertices within this distance of a common plane with their neighbours are removed");
    ImGui::Checkbox("Wireframe", &settings_.overlay_wireframe);
    ui("Wireframe", "Show the triangulation; constrained edges (tool rims) in magenta");
    ImGui::SameLine();
    ImGui::Checkbox("Active", &settings_.overlay_active);
    ui("Active", "Highlight vertices that moved in the last erosion step");
    ImGui::Checkbox("Sand depth", &settings_.overlay_thickness);
    ui("Sand depth", "Sand thickness above bedrock: blue thin, yellow 5 cm or more");
    ImGui::SameLine();
    ImGui::Checkbox("Slope", &settings_.overlay_slope);
    ui("Slope",
       "Slope against the angle of repose: green stable, yellow at repose, red over-steep");
    plain_slider("Contrast", settings_.contrast, kContrastRange, "%.3f");
    ui("Contrast", "Strength of the height contrast curve (histogram stretch)");
    if (ImGui::Checkbox("VSync", &settings_.vsync)) {
        int w = 0, h = 0;
        glfwGetFramebufferSize(window_, &w, &h);
        swapchain_->recreate({static_cast<std::uint32_t>(w), static_cast<std::uint32_t>(h)},
                             settings_.vsync);
    }
    ui("VSync", "Wait for the display's refresh when presenting");
}

void App::panel_haptics() {
    const bool connected = haptics_ != nullptr;
    ImGui::BeginDisabled(connected);
    const char* devices[] = {"Simulated pen", "UDP driver"};
    ImGui::Combo("Device", &haptic_device_, devices, 2);
    tip("Simulated: a virtual pen pulled to the tool cursor by a spring and pushed back by the "
        "sand. UDP: a separate driver process that owns the hardware (see engine/haptics)");
    ImGui::SliderInt("Loop (Hz)", &haptic_rate_hz_, 250, 4000, "%d", ImGuiSliderFlags_AlwaysClamp);
    ui("Loop", "Rate of the force loop thread");
    if (haptic_device_ == static_cast<int>(HapticDeviceKind::Udp)) {
        ImGui::InputInt("UDP port", &haptic_udp_port_);
        tip("Loopback port the driver sends poses to (0: any free port)");
    }
    ImGui::EndDisabled();
    if (ImGui::Button(connected ? "Disconnect###Connect" : "Connect###Connect")) {
        if (connected) {
            haptics_.reset();
        } else {
            try {
                const Vec3 start = cursor_.value_or(
                    Vec3{doc_.tin->domain().centre().x, doc_.tin->domain().centre().y, 0.1});
                haptics_ = std::make_unique<HapticsSession>(
                    static_cast<HapticDeviceKind>(haptic_device_), haptic_rate_hz_,
                    static_cast<std::uint16_t>(std::clamp(haptic_udp_port_, 0, 65535)), start);
                haptics_error_.clear();
                haptic_forces_.clear();
            } catch (const std::exception& e) {
                haptics_error_ = e.what();
            }
        }
    }
    ui("Connect", "Start or stop the force loop; the tool under the cursor is what the pen feels");
    if (!haptics_error_.empty()) ImGui::TextWrapped("%s", haptics_error_.c_str());
    if (!haptics_) return;
    const HapticsLive l = haptics_->live();
    ImGui::Text("%s", l.device.c_str());
    ImGui::Text("%.0f Hz, %llu ticks%s", l.rate_hz, static_cast<unsigned long long>(l.ticks),
                l.device_lost ? ", device lost" : "");
    tip("Measured loop rate and ticks since connecting");
    ImGui::Text("backup tick thread %s", l.backup_thread ? "on" : "off (one CPU)");
    tip("With two or more CPUs a second thread runs any tick whose wake-up is more than\n"
        "0.25 ms late, so a stalled CPU does not stall the force");
    ImGui::Text("force %.2f N %s", l.force_n, l.contact ? "(in contact)" : "");
    // Wrapped: on one line with the force it ran 68 px past a 1280-wide window's panel, which
    // the layout test saw only when a loaded machine made the snapshot late.
    if (l.stale) ImGui::TextWrapped("fading: the terrain snapshot is late");
    tip("Force the device renders now. When the editor falls more than 100 ms behind\n"
        "(a very slow frame), the force fades out rather than push with an old surface");
    haptic_forces_.push_back(static_cast<float>(l.force_n));
    if (haptic_forces_.size() > 240) haptic_forces_.pop_front();
    std::vector<float> plot(haptic_forces_.begin(), haptic_forces_.end());
    ImGui::PlotLines("##force", plot.data(), static_cast<int>(plot.size()), 0, "force N", 0.0f,
                     10.0f, ImVec2(0, 40));
    tip("Force over the last 240 frames (0-10 N)");
}

std::array<std::string, 2> App::stats_terrain_lines() const {
    const Tin& t = *doc_.tin;
    // Litres on the 1 m sandbox, cubic metres on a terrain a hundred times larger.
    const double size = settings_.scene_size;
    const DisplayUnit unit = volume_unit(1e-2 * size * size * size);
    char counts[96], volume[160];
    std::snprintf(counts, sizeof(counts), "%zu vertices, %zu triangles", t.vertex_count(),
                  t.triangle_count());
    std::snprintf(volume, sizeof(volume), "%zu constrained edges, volume %.3f %s",
                  t.constrained_edge_count(), t.volume() / unit.metres, unit.suffix);
    return {counts, volume};
}

void App::panel_stats(const std::array<std::string, 2>& terrain_lines) {
    for (const std::string& line : terrain_lines)
        ImGui::TextUnformatted(line.c_str());
    const double frame_ms = StageTimes::median(times_.frame);
    ImGui::Text("%.1f fps (%.1f ms)", frame_ms > 0.0 ? 1000.0 / frame_ms : 0.0, frame_ms);
    ImGui::Text("tool %.2f  physics %.2f  mesh %.2f", StageTimes::median(times_.tool),
                StageTimes::median(times_.physics), StageTimes::median(times_.mesh));
    ImGui::Text("upload %.2f  bake %.2f  render %.2f ms", StageTimes::median(times_.upload),
                StageTimes::median(times_.bake), StageTimes::median(times_.render));
    tip("Median milliseconds per frame of each stage over the last 240 frames (bake: GPU mirror\n"
        "sync and normal-map re-bake of the changed rectangle)");
    ImGui::Text("normal map %ux%u, re-baked %llu", normal_map_ ? normal_map_->grid().width : 0u,
                normal_map_ ? normal_map_->grid().height : 0u,
                static_cast<unsigned long long>(normal_map_texels_));
    tip("The baked normal map is re-baked only inside the rectangle the last change touched");
    std::vector<float> plot(times_.frame.begin(), times_.frame.end());
    ImGui::PlotLines("##frame", plot.data(), static_cast<int>(plot.size()), 0, "frame ms", 0.0f,
                     100.0f, ImVec2(0, 40));
    tip("Frame time over the last 240 frames (0-100 ms)");
}

void App::discard_prompt() {
    if (!pending_replacement_) return;
    ImGui::OpenPopup("Unsaved edits");
    if (ImGui::BeginPopupModal("Unsaved edits", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
        ImGui::Text("The untitled scene has unsaved edits.");
        const std::string target = save_path().string();
        ImGui::Text("Save writes it to %s (the Scene field under File).", target.c_str());
        const std::string& then = pending_replacement_label_;
        // The answer is taken after the popup is closed and its frame's items are done with:
        // it may replace the document.
        std::optional<DiscardChoice> choice;
        if (ImGui::Button(("Save and " + then).c_str())) choice = DiscardChoice::Save;
        ui("unsaved/Save",
           "Save the scene to the path in the Scene field, then go on; if the\n"
           "save fails, the scene stays and the status line says why");
        ImGui::SameLine();
        if (ImGui::Button(("Discard and " + then).c_str())) choice = DiscardChoice::Discard;
        ui("unsaved/Discard", "The edits are lost");
        ImGui::SameLine();
        if (ImGui::Button("Cancel")) choice = DiscardChoice::Cancel;
        ui("unsaved/Cancel", "Keep the scene open as it is");
        if (choice) ImGui::CloseCurrentPopup();
        ImGui::EndPopup();
        if (choice) answer_discard(*choice);
    }
}

void App::overwrite_prompt() {
    if (!pending_overwrite_) return;
    ImGui::OpenPopup("Replace file?");
    if (ImGui::BeginPopupModal("Replace file?", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
        const std::string target = pending_overwrite_->path.string();
        std::error_code ec;
        if (std::filesystem::exists(pending_overwrite_->path, ec))
            ImGui::Text("%s already exists; this scene is not that file.", target.c_str());
        if (find_autosave(pending_overwrite_->path))
            ImGui::Text("Its autosave holds edits that were never saved; it goes too.");
        std::optional<bool> replace;
        if (ImGui::Button("Replace")) replace = true;
        ui("overwrite/Replace", "Save this scene over that file");
        ImGui::SameLine();
        if (ImGui::Button("Cancel")) replace = false;
        ui("overwrite/Cancel", "Save nothing; type another name in the Scene field");
        if (replace) ImGui::CloseCurrentPopup();
        ImGui::EndPopup();
        if (replace) {
            const PendingOverwrite pending = std::move(*pending_overwrite_);
            pending_overwrite_.reset();
            if (!*replace)
                report("not saved: " + target + " exists (type another name in the Scene field)");
            else if (save_reporting(pending.path) && pending.then)
                pending.then();
        }
    }
}

void App::recovery_prompt() {
    if (!recovery_for_) return;
    ImGui::OpenPopup("Recover autosave?");
    if (ImGui::BeginPopupModal("Recover autosave?", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
        ImGui::Text("An autosave newer than %s exists.", recovery_for_->c_str());
        std::optional<bool> recover;
        if (ImGui::Button("Recover")) recover = true;
        ui("recovery/Recover", "Load the autosave; save to keep it");
        ImGui::SameLine();
        if (ImGui::Button("Discard")) recover = false;
        ui("recovery/Discard", "Delete the autosave and keep the scene as saved");
        if (recover) ImGui::CloseCurrentPopup();
        ImGui::EndPopup();
        if (recover) answer_recovery(*recover);
    }
}

}  // namespace sandtin::editor
