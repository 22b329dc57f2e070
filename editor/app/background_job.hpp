#pragma once
// Long document work off the UI thread: importing a heightmap, opening a scene, exporting.
// The work runs on a thread of its own, on its own copy of its inputs, and hands its result
// over through what it captured; the UI thread draws frames meanwhile, reads progress() for
// the bar, and once outcome() is no longer Running takes the result (app_jobs.cpp).
//
// Cancel sets the job's CancellationToken (io/cancellation.hpp): the work stops at its next
// progress report short of the end, with the Cancelled outcome, having changed nothing.
//
// Test hook: a job made with `pause_at` holds at its first report at or past that fraction
// until resume() or cancel(), so an Xvfb test can see the bar mid-way and press Cancel
// whatever the machine's speed (frames keep drawing meanwhile).

#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "io/cancellation.hpp"
#include "io/progress.hpp"
#include "job_progress.hpp"

namespace sandtin::editor {

enum class JobOutcome { Running, Done, Cancelled, Failed };

const char* to_string(JobOutcome outcome);

class BackgroundJob {
  public:
    /// The work: reports through the callback it is given, which throws Cancelled once the
    /// job was cancelled. Its result goes wherever it captured (a shared slot).
    using Work = std::function<void(const ProgressCallback&)>;

    /// Starts `work` on its own thread now.
    BackgroundJob(std::string title, Work work, std::optional<double> pause_at = {});
    /// Cancels the work and waits for its thread.
    ~BackgroundJob();
    BackgroundJob(const BackgroundJob&) = delete;
    BackgroundJob& operator=(const BackgroundJob&) = delete;

    /// What the bar shows now.
    JobProgress progress() const;
    /// Running until the work returned (Done), stopped for Cancel (Cancelled) or threw
    /// (Failed, with error()).
    JobOutcome outcome() const;
    std::string error() const;
    /// Asks the work to stop at its next check (a paused job wakes to stop).
    void cancel();
    bool cancel_requested() const { return token_.cancelled(); }
    /// Test hook: whether the job holds at its pause point, and letting it run on.
    bool paused() const;
    void resume();

  private:
    /// The work's progress reports, on the worker thread.
    void hear(const Progress& p);
    void run(const Work& work);

    const std::string title_;
    const std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
    const std::optional<double> pause_at_;
    CancellationToken token_;
    mutable std::mutex mutex_;
    std::condition_variable wake_;
    std::string stage_ = "starting";
    double fraction_ = 0.0;
    bool paused_ = false;
    bool resumed_ = false;
    JobOutcome outcome_ = JobOutcome::Running;
    std::string error_;
    double finished_after_ = 0.0;  ///< seconds the work took, once it ended
    /// Last: started once everything it uses exists, joined before any of it goes.
    std::jthread thread_;
};

}  // namespace sandtin::editor
