#include "haptics/simulated_device.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>

#include "haptics/force_model.hpp"

namespace sandtin::haptics {

namespace {
// Moving a device is single-threaded (before open), so the source's buffer can be drained.
Vec3 latest(TripleBuffer<Vec3>& buffer) {
    buffer.update();
    return buffer.front();
}
}  // namespace

SimulatedDevice::SimulatedDevice(Mode mode, double max_force) : mode_(mode), max_force_(max_force) {
    if (!(max_force > 0.0) || !std::isfinite(max_force))
        throw std::invalid_argument("simulated device: max_force must be positive");
}

SimulatedDevice::SimulatedDevice(SimulatedDevice&& o) noexcept
    : mode_(o.mode_),
      max_force_(o.max_force_),
      opened_(o.opened_),
      trajectory_(std::move(o.trajectory_)),
      next_(o.next_),
      forces_(std::move(o.forces_)),
      spring_(o.spring_),
      target_(latest(o.target_)),
      buttons_(o.buttons_.load()),
      position_(o.position_),
      velocity_(o.velocity_),
      last_force_(o.last_force_) {}

SimulatedDevice SimulatedDevice::replay(Trajectory trajectory, double max_force) {
    SimulatedDevice d(Mode::Replay, max_force);
    d.trajectory_ = std::move(trajectory);
    return d;
}

SimulatedDevice SimulatedDevice::spring(const SpringParams& params, const Vec3& start) {
    if (!(params.mass > 0.0) || !(params.stiffness > 0.0) || !(params.damping >= 0.0) ||
        !(params.rate_hz > 0.0)) {
        throw std::invalid_argument(
            "simulated device: spring mass, stiffness and rate must be positive");
    }
    SimulatedDevice d(Mode::Spring, params.max_force);
    d.spring_ = params;
    d.position_ = start;
    d.target_.write(start);
    return d;
}

std::string SimulatedDevice::name() const {
    return mode_ == Mode::Replay ? "simulated (trajectory replay)" : "simulated (mouse spring)";
}

void SimulatedDevice::open() {
    if (opened_) throw std::runtime_error(name() + ": already open");
    opened_ = true;
    next_ = 0;
    // One force per sample plus the loop's final zero. Written once here so that the loop
    // thread's push_back never allocates nor touches a fresh page (a page fault can wait for
    // another thread's mmap/munmap).
    forces_.assign(trajectory_.samples.size() + 1, Vec3{});
    forces_.clear();
}

void SimulatedDevice::close() {
    opened_ = false;
}

void SimulatedDevice::set_target(const Vec3& target) {
    target_.write(target);
}

ReadStatus SimulatedDevice::read(DeviceState& state) {
    if (!opened_) return ReadStatus::Lost;
    if (mode_ == Mode::Replay) {
        if (next_ >= trajectory_.samples.size()) return ReadStatus::Lost;
        const TrajectorySample& s = trajectory_.samples[next_];
        state.position = s.position;
        state.buttons = s.buttons;
        state.sequence = static_cast<std::uint32_t>(next_);
        state.valid = true;
        ++next_;
        return ReadStatus::Ok;
    }
    // Semi-implicit Euler, one tick: the spring pulls towards the target, the rendered force
    // pushes back.
    target_.update();
    const Vec3 target = target_.front();
    const double dt = 1.0 / spring_.rate_hz;
    const Vec3 accel =
        (spring_.stiffness * (target - position_) - spring_.damping * velocity_ + last_force_) *
        (1.0 / spring_.mass);
    velocity_ += accel * dt;
    position_ += velocity_ * dt;
    state.position = position_;
    state.buttons = buttons_.load(std::memory_order_relaxed);
    state.sequence = 0;
    state.valid = true;
    return ReadStatus::Ok;
}

void SimulatedDevice::write_force(const ForceCommand& command) {
    const Vec3 f = clamp_magnitude(command.force, max_force_);
    if (mode_ == Mode::Replay) {
        forces_.push_back(f);
    } else {
        last_force_ = f;
    }
}

}  // namespace sandtin::haptics
