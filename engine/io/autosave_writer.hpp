#pragma once
// Autosaves written on a worker thread. Encoding and writing a large scene takes a while
// (0.26 s for 10^6 vertices, measured), which would stall the editor's frame once a minute.
// The frame hands over a session, or a source that makes it here (SessionKeeper: the copy of
// the terrain is then made on this thread too).
//
// A failed write (full disk, read-only folder) never throws into the caller: its message is
// kept for the caller to show (take_error), and the next autosave tries again. An autosave
// that throws in the editor's frame would close the editor and lose exactly the edits the
// autosave was for.

#include <condition_variable>
#include <cstddef>
#include <filesystem>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "io/autosave.hpp"

namespace sandtin {

class AutosaveWriter {
  public:
    AutosaveWriter();
    /// Writes what is still queued, then stops: quitting must not lose the last autosave.
    ~AutosaveWriter();
    AutosaveWriter(const AutosaveWriter&) = delete;
    AutosaveWriter& operator=(const AutosaveWriter&) = delete;

    /// Queues `session` as the autosave of `scene` (written to autosave_path(scene)). A queued
    /// autosave that has not started is replaced: only the newest state is worth writing.
    /// `interruption` is the atomic writer's test hook.
    void submit(std::filesystem::path scene, Session session, WriteInterruption interruption = {});
    /// The same with the session made on the writer's thread, by calling `source` once when its
    /// turn comes (SessionKeeper::hand_out: the frame then never copies the terrain). A source
    /// replaced or cancelled before its turn is dropped uncalled.
    void submit(std::filesystem::path scene, SessionSource source,
                WriteInterruption interruption = {});
    /// Drops a queued autosave that has not started and waits for the one being written. Call
    /// it before saving the scene or discarding its autosave, so that no late autosave brings
    /// back a file the caller just retired.
    void cancel();
    /// Waits until every submitted autosave is written or has failed.
    void flush();
    /// The message of the last failed write since the previous call, naming the file.
    std::optional<std::string> take_error();
    /// The same with the scene whose autosave failed (the editor may have moved on to another
    /// scene since it submitted it).
    struct Failure {
        std::filesystem::path scene;
        std::string message;
    };
    std::optional<Failure> take_failure();
    /// Autosaves written since construction.
    std::size_t written() const;

  private:
    struct Job {
        std::filesystem::path scene;
        SessionSource source;
        WriteInterruption interruption;
    };
    void run();

    mutable std::mutex mutex_;
    std::condition_variable work_;  ///< to the worker: a job or stop
    std::condition_variable idle_;  ///< to waiters: a write ended
    std::optional<Job> queued_;
    bool writing_ = false;
    bool stop_ = false;
    std::optional<Failure> error_;
    std::size_t written_ = 0;
    std::thread worker_;  ///< last: starts once the members above exist
};

}  // namespace sandtin
