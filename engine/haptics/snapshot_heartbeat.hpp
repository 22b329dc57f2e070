#pragma once
// Keeps a force loop's newest snapshot current while its producer is busy with work that cannot
// change the terrain, such as drawing a frame or waiting for input.
//
// The loop fades the force out when the newest snapshot is older than
// ForceRendererConfig::stale_after_ns (100 ms): the sign of a stalled simulation, whose
// surface may no longer be the one the pen touches. A producer that is only drawing is not
// stalled, yet on a CPU renderer (lavapipe) one frame can take longer than that. So the
// producer says when the last snapshot it published stays true (hold) and when it may stop
// being true (release, before anything that can edit the terrain); while held, this class's
// thread republishes that snapshot every `period`, with a fresh sequence and time. A long
// edit, which happens released, still fades the force, as it should.
//
// Both producers publish through this class, which serialises them: ForceLoop::publish has a
// single-producer contract. The loop's side stays lock-free.

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>

#include "haptics/force_loop.hpp"
#include "haptics/haptic_snapshot.hpp"

namespace sandtin::haptics {

class SnapshotHeartbeat {
  public:
    /// `period` > 0 and well below the loop's stale_after_ns. Starts released.
    SnapshotHeartbeat(ForceLoop& loop, std::chrono::nanoseconds period);
    /// Stops the thread (waits for it).
    ~SnapshotHeartbeat();
    SnapshotHeartbeat(const SnapshotHeartbeat&) = delete;
    SnapshotHeartbeat& operator=(const SnapshotHeartbeat&) = delete;

    /// Publishes `snapshot` to the loop now and remembers it for the heartbeat.
    void publish(const HapticSnapshot& snapshot);
    /// The last published snapshot stays true until release(): republish it every period.
    /// Without a published snapshot there is nothing to keep, and nothing is republished.
    void hold();
    /// The terrain may change from now on: no republication after this returns.
    void release();

    bool held() const;
    /// Snapshots the heartbeat thread republished so far.
    std::uint64_t republished() const;

  private:
    void run();

    ForceLoop& loop_;
    const std::chrono::nanoseconds period_;
    mutable std::mutex mutex_;  ///< guards everything below and every call to loop_.publish
    std::condition_variable changed_;
    HapticSnapshot last_{};
    bool has_last_ = false;
    bool held_ = false;
    bool stopping_ = false;
    std::chrono::steady_clock::time_point published_at_{};
    std::uint64_t republished_ = 0;
    std::thread thread_;  ///< last: starts once everything above is initialised
};

}  // namespace sandtin::haptics
