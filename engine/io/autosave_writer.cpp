#include "io/autosave_writer.hpp"

#include <exception>
#include <memory>
#include <utility>

namespace sandtin {

AutosaveWriter::AutosaveWriter() : worker_([this] { run(); }) {}

AutosaveWriter::~AutosaveWriter() {
    {
        const std::lock_guard lock(mutex_);
        stop_ = true;
    }
    work_.notify_all();
    worker_.join();
}

void AutosaveWriter::submit(std::filesystem::path scene, Session session,
                            WriteInterruption interruption) {
    auto made = std::make_shared<Session>(std::move(session));
    submit(
        std::move(scene), [made] { return std::move(*made); }, std::move(interruption));
}

void AutosaveWriter::submit(std::filesystem::path scene, SessionSource source,
                            WriteInterruption interruption) {
    std::optional<Job> replaced;  // dropped outside the lock
    {
        const std::lock_guard lock(mutex_);
        replaced = std::exchange(queued_,
                                 Job{std::move(scene), std::move(source), std::move(interruption)});
    }
    work_.notify_all();
}

void AutosaveWriter::cancel() {
    std::unique_lock lock(mutex_);
    queued_.reset();  // its source, dropped uncalled
    idle_.wait(lock, [this] { return !writing_; });
}

void AutosaveWriter::flush() {
    std::unique_lock lock(mutex_);
    idle_.wait(lock, [this] { return !writing_ && !queued_; });
}

std::optional<std::string> AutosaveWriter::take_error() {
    const std::optional<Failure> failure = take_failure();
    if (!failure) return std::nullopt;
    return failure->message;
}

std::optional<AutosaveWriter::Failure> AutosaveWriter::take_failure() {
    const std::lock_guard lock(mutex_);
    return std::exchange(error_, std::nullopt);
}

std::size_t AutosaveWriter::written() const {
    const std::lock_guard lock(mutex_);
    return written_;
}

void AutosaveWriter::run() {
    std::unique_lock lock(mutex_);
    for (;;) {
        work_.wait(lock, [this] { return stop_ || queued_.has_value(); });
        if (!queued_) return;  // stopping, and nothing left to write
        Job job = std::move(*queued_);
        queued_.reset();
        writing_ = true;
        lock.unlock();
        std::optional<Failure> failure;
        try {
            const Session session = job.source();
            job.source = nullptr;  // a loaned copy goes back before the write
            write_autosave(job.scene, session, job.interruption);
        } catch (const std::exception& e) {
            failure = Failure{job.scene, e.what()};
        }
        job = Job{};  // what the job held goes before the next one is taken
        lock.lock();
        writing_ = false;
        if (failure) {
            error_ = std::move(failure);
        } else {
            ++written_;
        }
        idle_.notify_all();
    }
}

}  // namespace sandtin
