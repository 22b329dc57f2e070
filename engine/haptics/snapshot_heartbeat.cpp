#include "snapshot_heartbeat.hpp"

#include <stdexcept>

namespace sandtin::haptics {

SnapshotHeartbeat::SnapshotHeartbeat(ForceLoop& loop, std::chrono::nanoseconds period)
    : loop_(loop), period_(period) {
    if (period_.count() <= 0)
        throw std::invalid_argument("snapshot heartbeat: the period must be positive");
    thread_ = std::thread([this] { run(); });
}

SnapshotHeartbeat::~SnapshotHeartbeat() {
    {
        const std::lock_guard lock(mutex_);
        stopping_ = true;
    }
    changed_.notify_all();
    thread_.join();
}

void SnapshotHeartbeat::publish(const HapticSnapshot& snapshot) {
    const std::lock_guard lock(mutex_);
    last_ = snapshot;
    has_last_ = true;
    published_at_ = std::chrono::steady_clock::now();
    loop_.publish(snapshot);
}

void SnapshotHeartbeat::hold() {
    {
        const std::lock_guard lock(mutex_);
        held_ = true;
    }
    changed_.notify_all();
}

void SnapshotHeartbeat::release() {
    const std::lock_guard lock(mutex_);
    held_ = false;
}

bool SnapshotHeartbeat::held() const {
    const std::lock_guard lock(mutex_);
    return held_;
}

std::uint64_t SnapshotHeartbeat::republished() const {
    const std::lock_guard lock(mutex_);
    return republished_;
}

void SnapshotHeartbeat::run() {
    std::unique_lock lock(mutex_);
    while (!stopping_) {
        if (!held_ || !has_last_) {
            changed_.wait(lock, [this] { return stopping_ || (held_ && has_last_); });
            continue;
        }
        // One period after the newest publication, by either producer. A release (or a new
        // publication) meanwhile is seen on waking: the deadline is recomputed.
        const auto due = published_at_ + period_;
        if (std::chrono::steady_clock::now() < due) {
            changed_.wait_until(lock, due);
            continue;
        }
        published_at_ = std::chrono::steady_clock::now();
        loop_.publish(last_);
        ++republished_;
    }
}

}  // namespace sandtin::haptics
