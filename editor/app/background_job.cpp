#include "background_job.hpp"

#include <algorithm>
#include <exception>
#include <utility>

namespace sandtin::editor {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

const char* to_string(JobOutcome outcome) {
    switch (outcome) {
        case JobOutcome::Running:
            return "running";
        case JobOutcome::Done:
            return "done";
        case JobOutcome::Cancelled:
            return "cancelled";
        case JobOutcome::Failed:
            return "failed";
    }
    return "unknown";
}

BackgroundJob::BackgroundJob(std::string title, Work work, std::optional<double> pause_at)
    : title_(std::move(title)), pause_at_(pause_at) {
    thread_ = std::jthread([this, work = std::move(work)] { run(work); });
}

BackgroundJob::~BackgroundJob() {
    cancel();
    // thread_ joins as the first member to go.
}

void BackgroundJob::run(const Work& work) {
    JobOutcome outcome = JobOutcome::Done;
    std::string error;
    try {
        work(cancellable([this](const Progress& p) { hear(p); }, token_));
    } catch (const Cancelled&) {
        outcome = JobOutcome::Cancelled;
    } catch (const std::exception& e) {
        outcome = JobOutcome::Failed;
        error = e.what();
    } catch (...) {
        outcome = JobOutcome::Failed;
        error = "an unknown error";
    }
    const std::lock_guard lock(mutex_);
    outcome_ = outcome;
    error_ = std::move(error);
    finished_after_ = seconds_since(start_);
}

void BackgroundJob::hear(const Progress& p) {
    std::unique_lock lock(mutex_);
    fraction_ = std::max(fraction_, std::clamp(p.fraction, 0.0, 1.0));
    stage_ = std::string(p.stage);
    if (pause_at_ && !resumed_ && fraction_ >= *pause_at_ && fraction_ < 1.0) {
        paused_ = true;
        wake_.wait(lock, [this] { return resumed_ || token_.cancelled(); });
        paused_ = false;
        resumed_ = true;
        lock.unlock();
        token_.throw_if_cancelled();
    }
}

JobProgress BackgroundJob::progress() const {
    const std::lock_guard lock(mutex_);
    JobProgress p;
    p.title = title_;
    p.stage = stage_;
    p.fraction = fraction_;
    p.elapsed_seconds = outcome_ == JobOutcome::Running ? seconds_since(start_) : finished_after_;
    p.cancel_requested = token_.cancelled();
    return p;
}

JobOutcome BackgroundJob::outcome() const {
    const std::lock_guard lock(mutex_);
    return outcome_;
}

std::string BackgroundJob::error() const {
    const std::lock_guard lock(mutex_);
    return error_;
}

void BackgroundJob::cancel() {
    token_.cancel();
    const std::lock_guard lock(mutex_);
    wake_.notify_all();
}

bool BackgroundJob::paused() const {
    const std::lock_guard lock(mutex_);
    return paused_;
}

void BackgroundJob::resume() {
    const std::lock_guard lock(mutex_);
    resumed_ = true;
    wake_.notify_all();
}

}  // namespace sandtin::editor
