// The Haptics panel: the pen, its loop and the force it renders.

#include "app.hpp"

#include <algorithm>

#include "panel_layout.hpp"
#include "panel_widgets.hpp"
#include "terrain_scale.hpp"
#include "tool_palette.hpp"

namespace sandtin::editor {

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
                    Vec3{doc_.tin().domain().centre().x, doc_.tin().domain().centre().y, 0.1});
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

}  // namespace sandtin::editor
