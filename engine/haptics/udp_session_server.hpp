#pragma once
// A headless live session served over UDP: the force loop with a UdpDevice on its thread, the
// simulation (LiveSession) on the calling thread, until the driver process says bye, goes
// silent, or the time limit passes. Returns the recording of the session. This is what
// `sandtin haptics serve` runs, so a separate process can own real hardware.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>

#include <nlohmann/json.hpp>

#include "haptics/diagnostics/loop_jitter.hpp"
#include "haptics/force_loop.hpp"
#include "haptics/haptic_recording.hpp"
#include "haptics/live_editor.hpp"
#include "haptics/udp_device.hpp"

namespace sandtin::haptics {

struct UdpServeOptions {
    UdpDeviceConfig device;
    ForceLoopConfig loop;
    LiveEditSettings edit;
    nlohmann::json tool = {{"contour", "circle"}, {"radius", 0.04}};
    std::filesystem::path tool_base_dir = ".";  ///< resolves the tool's relative files
    double max_seconds = 600.0;                 ///< the session ends after this in any case
    /// Simulation steps run at most this often (the seeds' geometry loop ran at 60-100 Hz).
    double simulation_hz = 500.0;
    /// Called once the socket is bound, with its port (useful with device.port = 0).
    std::function<void(std::uint16_t)> on_listening;
    /// The "terrain" of the recording, when the terrain was generated from one.
    std::optional<ScriptTerrain> terrain;
};

struct UdpServeResult {
    ForceLoopReport loop;
    JitterSummary jitter;  ///< where the loop's ticks' time went (loop_diagnostics.hpp)
    UdpDeviceCounters device;
    HapticRecording recording;
    std::size_t stamps = 0;
    std::uint64_t simulation_steps = 0;
    bool time_limit_reached = false;
};

/// Runs the session on `tin` (throws what opening the device throws, e.g. a taken port).
UdpServeResult serve_udp_session(Tin& tin, SculptContext& context, const UdpServeOptions& options);

}  // namespace sandtin::haptics
