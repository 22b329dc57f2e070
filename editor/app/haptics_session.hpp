#pragma once
// The Haptics panel's connection: a device and the 1 kHz force loop (engine/haptics) running
// beside the editor. The editor publishes a snapshot of the terrain under the tool cursor each
// frame and reads back the loop's live rate
// and force; the loop never waits for the editor.
//
// Devices offered: the simulated pen on a virtual spring that follows the mouse cursor (you
// see the force as the pen lagging where the sand resists), and a UDP device for a separate
// driver process that owns real hardware (engine/haptics/udp_protocol.hpp).

#include <cstdint>
#include <memory>
#include <string>

#include "geom/vec3.hpp"
#include "haptics/force_loop.hpp"
#include "haptics/haptic_device.hpp"
#include "haptics/simulated_device.hpp"
#include "haptics/snapshot_heartbeat.hpp"
#include "physics/material.hpp"
#include "tin/tin.hpp"
#include "tools/tool.hpp"

namespace sandtin::editor {

enum class HapticDeviceKind : int { SimulatedSpring = 0, Udp = 1 };

struct HapticsLive {
    std::string device;
    double rate_hz = 0.0;  ///< ticks per second between the last two reads
    double force_n = 0.0;  ///< |F| of the newest tick
    bool contact = false;
    /// The newest tick found our latest snapshot older than the loop's staleness limit, so
    /// the force was fading out.
    bool stale = false;
    bool device_lost = false;
    bool backup_thread = false;  ///< a second thread covers late ticks (2+ CPUs)
    std::uint64_t ticks = 0;
    Vec3 pen;  ///< device position of the newest tick (m)
};

class HapticsSession {
  public:
    /// Opens the device and starts the loop. Throws std::runtime_error naming the problem
    /// (e.g. the UDP port is taken).
    HapticsSession(HapticDeviceKind kind, double rate_hz, std::uint16_t udp_port, Vec3 start);
    ~HapticsSession();
    HapticsSession(const HapticsSession&) = delete;
    HapticsSession& operator=(const HapticsSession&) = delete;

    /// Publishes the terrain under the tool at `at` and, for the simulated pen, moves its
    /// spring target (m).
    void update(const Tin& tin, const Tool& tool, const ToolPlacement& at,
                const MaterialTable& materials, Vec3 target);
    HapticsLive live();
    /// The terrain and the cursor will not change until release(): the last snapshot stays
    /// true, and the heartbeat keeps it fresh for the loop (haptics/snapshot_heartbeat.hpp).
    /// The editor holds while it draws and waits for input.
    void hold();
    /// Before anything that may edit the terrain or move the cursor.
    void release();

  private:
    std::unique_ptr<haptics::HapticDevice> device_;
    haptics::SimulatedDevice* spring_ = nullptr;  ///< device_ when it is the simulated pen
    std::unique_ptr<haptics::ForceLoop> loop_;
    std::unique_ptr<haptics::SnapshotHeartbeat> heartbeat_;  ///< the only publisher to loop_
    haptics::TickRecord latest_{};
    haptics::TickRecord rate_from_{};  ///< the tick the rate is measured from
    double rate_hz_ = 0.0;
    std::int64_t started_ns_ = 0;
    LocateHint hint_;
};

}  // namespace sandtin::editor
