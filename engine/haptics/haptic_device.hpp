#pragma once
// A haptic device as the force loop sees it: open, read the pose and buttons once per tick,
// write a force, close. Positions are the device point (the tool's lowest point) in the
// terrain frame, metres; forces are newtons in the same frame. Mapping the device's own
// workspace to the terrain (seed 004 Eqs. 5.3.1-5.3.2) is the back-end's job.
//
// The loop calls open() and close() on the thread that starts and stops it, and read() and
// write_force() on the loop thread only.

#include <cstdint>
#include <string>

#include "geom/vec3.hpp"

namespace sandtin::haptics {

/// Bit of DeviceState::buttons for the stylus button (the PHANToM has one; seed 004 §5.3).
inline constexpr std::uint32_t kMainButton = 1u;

struct DeviceState {
    Vec3 position;               ///< m, terrain frame
    std::uint32_t buttons = 0;   ///< bit set = pressed
    std::uint32_t sequence = 0;  ///< the device's sample number (network devices), else 0
    bool valid = false;          ///< false until the device has reported a pose
};

/// What the loop sends each tick.
struct ForceCommand {
    Vec3 force;  ///< N
    bool contact = false;
    bool stale = false;  ///< the simulation's snapshot is stale; the force is ramping down
};

enum class ReadStatus : std::uint8_t {
    Ok,    ///< `state` holds the current pose (possibly invalid: no pose yet)
    Lost,  ///< the device is gone (unplugged, timed out, end of a recording): stop the loop
};

class HapticDevice {
  public:
    virtual ~HapticDevice() = default;
    HapticDevice() = default;
    HapticDevice(const HapticDevice&) = delete;
    HapticDevice& operator=(const HapticDevice&) = delete;

    /// Throws std::runtime_error naming the problem when the device cannot be opened.
    virtual void open() = 0;
    virtual ReadStatus read(DeviceState& state) = 0;
    virtual void write_force(const ForceCommand& command) = 0;
    virtual void close() = 0;
    /// The largest force the device can render (N).
    virtual double max_force() const = 0;
    virtual std::string name() const = 0;
};

}  // namespace sandtin::haptics
