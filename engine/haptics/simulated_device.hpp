#pragma once
// A device without hardware, in one of two modes:
//  - replay: plays a recorded trajectory, one sample per tick, and reports Lost after the last
//    sample (so a loop driven by it stops by itself). Every force written is kept, so a test
//    or a recording can read what the user would have felt.
//  - spring: the pen is a small mass pulled by a virtual spring towards a target the editor
//    moves (the mouse), and pushed by the rendered force: the "haptic without hardware" mode.
//    The force shows up as the pen lagging behind the mouse where the sand resists.

#include <atomic>
#include <cstdint>
#include <string>
#include <vector>

#include "haptics/haptic_device.hpp"
#include "haptics/trajectory.hpp"
#include "haptics/triple_buffer.hpp"

namespace sandtin::haptics {

struct SpringParams {
    double mass = 0.05;        ///< kg of the virtual pen
    double stiffness = 400.0;  ///< N/m of the spring to the target
    /// N s/m; the default is critical damping 2 sqrt(k m), so the pen settles without ringing.
    double damping = 8.94427190999916;
    double rate_hz = 1000.0;  ///< integration step = one loop tick
    double max_force = 10.0;  ///< N
};

class SimulatedDevice final : public HapticDevice {
  public:
    static SimulatedDevice replay(Trajectory trajectory, double max_force = 10.0);
    static SimulatedDevice spring(const SpringParams& params, const Vec3& start);

    SimulatedDevice(SimulatedDevice&& other) noexcept;
    SimulatedDevice& operator=(SimulatedDevice&&) = delete;

    void open() override;
    ReadStatus read(DeviceState& state) override;
    void write_force(const ForceCommand& command) override;
    void close() override;
    double max_force() const override { return max_force_; }
    std::string name() const override;

    // ---- Spring mode, from any single other thread (the editor) ----
    void set_target(const Vec3& target);
    void set_buttons(std::uint32_t buttons) { buttons_.store(buttons, std::memory_order_relaxed); }

    /// Forces written, one per read sample (replay mode); read after the loop stopped.
    const std::vector<Vec3>& forces() const { return forces_; }
    std::size_t samples_played() const { return next_; }

  private:
    enum class Mode : std::uint8_t { Replay, Spring };
    SimulatedDevice(Mode mode, double max_force);

    Mode mode_;
    double max_force_;
    bool opened_ = false;
    // Replay
    Trajectory trajectory_;
    std::size_t next_ = 0;
    std::vector<Vec3> forces_;
    // Spring
    SpringParams spring_;
    TripleBuffer<Vec3> target_;
    std::atomic<std::uint32_t> buttons_{0};
    Vec3 position_;
    Vec3 velocity_;
    Vec3 last_force_;
};

}  // namespace sandtin::haptics
