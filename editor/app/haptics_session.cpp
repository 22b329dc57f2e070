#include "haptics_session.hpp"

#include <cmath>
#include <stdexcept>
#include <thread>

#include "haptics/simulated_device.hpp"
#include "haptics/snapshot_builder.hpp"
#include "haptics/udp_device.hpp"

namespace sandtin::editor {

HapticsSession::HapticsSession(HapticDeviceKind kind, double rate_hz, std::uint16_t udp_port,
                               Vec3 start) {
    if (kind == HapticDeviceKind::SimulatedSpring) {
        haptics::SpringParams params;
        params.rate_hz = rate_hz;
        auto device = std::make_unique<haptics::SimulatedDevice>(
            haptics::SimulatedDevice::spring(params, start));
        spring_ = device.get();
        device_ = std::move(device);
    } else {
        haptics::UdpDeviceConfig config;
        config.port = udp_port;
        device_ = std::make_unique<haptics::UdpDevice>(config);
    }
    haptics::ForceLoopConfig config;
    config.rate_hz = rate_hz;
    config.try_realtime = false;  // an editor does not ask for real-time scheduling
    // With two or more CPUs, a backup thread runs any tick whose wake-up is over 250 µs late
    // (force_loop.hpp): on virtual machines one CPU's timer wake-ups are sometimes late by
    // milliseconds, and the other CPU covers them (late ticks 48 -> 16 over 540 s in `sandtin
    // bench haptics`). Neither thread is pinned: the editor does not own the CPUs.
    config.backup_thread = std::thread::hardware_concurrency() >= 2;
    loop_ = std::make_unique<haptics::ForceLoop>(*device_, config);
    // A quarter of the staleness limit: three missed wake-ups before the force would fade.
    heartbeat_ = std::make_unique<haptics::SnapshotHeartbeat>(
        *loop_, std::chrono::nanoseconds(config.renderer.stale_after_ns / 4));
    started_ns_ = haptics::monotonic_ns();
    loop_->start();
}

HapticsSession::~HapticsSession() {
    heartbeat_.reset();  // nothing is published to the loop after this
    if (loop_) loop_->stop();
}

void HapticsSession::hold() {
    heartbeat_->hold();
}

void HapticsSession::release() {
    heartbeat_->release();
}

void HapticsSession::update(const Tin& tin, const Tool& tool, const ToolPlacement& at,
                            const MaterialTable& materials, Vec3 target) {
    heartbeat_->publish(haptics::build_snapshot(tin, tool, at, materials, &hint_));
    if (spring_ != nullptr) spring_->set_target(target);
}

HapticsLive HapticsSession::live() {
    HapticsLive l;
    l.device = device_->name();
    l.backup_thread = loop_->config().backup_thread;
    if (loop_->poll(latest_)) {
        const std::int64_t dt = latest_.time_ns - rate_from_.time_ns;
        if (rate_from_.tick == 0) {
            rate_from_ = latest_;
        } else if (dt > 250'000'000) {  // re-measure four times a second
            rate_hz_ =
                static_cast<double>(latest_.tick - rate_from_.tick) * 1e9 / static_cast<double>(dt);
            rate_from_ = latest_;
        }
    }
    // Until the first re-measurement, the mean rate since the loop started.
    if (rate_hz_ == 0.0 && latest_.tick > 1 && latest_.time_ns > started_ns_) {
        l.rate_hz = static_cast<double>(latest_.tick) * 1e9 /
                    static_cast<double>(latest_.time_ns - started_ns_);
    } else {
        l.rate_hz = rate_hz_;
    }
    l.ticks = latest_.tick;
    l.force_n = std::sqrt(dot(latest_.force, latest_.force));
    l.contact = latest_.contact;
    l.stale = latest_.stale;
    l.pen = latest_.device.position;
    l.device_lost = !loop_->running();
    return l;
}

}  // namespace sandtin::editor
