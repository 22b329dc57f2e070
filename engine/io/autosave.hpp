#pragma once
// Autosave and crash recovery for session files.
//
// The editor autosaves to "<scene>.autosave" next to the scene (atomically, so a crash during
// an autosave leaves the previous autosave). An explicit save writes the scene and then
// deletes the autosave. So an autosave that exists when a scene is opened holds edits the
// last session never saved: find_autosave() tells the editor whether to offer recovery.

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>

#include "io/session_file.hpp"

namespace sandtin {

/// "<scene>.autosave": the scene's full file name plus the suffix.
std::filesystem::path autosave_path(const std::filesystem::path& session_path);

/// Writes the autosave of `session_path` atomically; the scene file itself is not touched.
void write_autosave(const std::filesystem::path& session_path, const Session& session,
                    const WriteInterruption& interruption = {});

/// Saves the scene, then removes its autosave (now obsolete).
void save_session_clearing_autosave(const std::filesystem::path& session_path,
                                    const Session& session,
                                    const WriteInterruption& interruption = {});

struct AutosaveInfo {
    std::filesystem::path path;
    bool scene_exists = false;
    /// The autosave was written after the scene file (or there is no scene file).
    bool newer_than_scene = false;
    /// Empty when the autosave loads; else why it does not (it is then not worth offering).
    std::string problem;
    /// Offer recovery: the autosave loads and is newer than the scene.
    bool offer_recovery() const { return problem.empty() && newer_than_scene; }
};

/// Describes the autosave of `session_path`, or nullopt when there is none. Never throws for
/// a damaged autosave: that is reported in `problem`.
std::optional<AutosaveInfo> find_autosave(const std::filesystem::path& session_path);

/// Loads the autosave (throws like load_session()).
Session recover_autosave(const std::filesystem::path& session_path);

/// Deletes the autosave if there is one; returns whether one was deleted.
bool discard_autosave(const std::filesystem::path& session_path);

/// When to autosave: after the first unsaved edit, once `interval` has passed since that edit
/// or since the last autosave, and never while nothing changed.
class AutosaveSchedule {
  public:
    using Clock = std::chrono::steady_clock;
    explicit AutosaveSchedule(Clock::duration interval = std::chrono::minutes(2))
        : interval_(interval) {}

    void edited(Clock::time_point now) {
        if (!dirty_) since_ = now;
        dirty_ = true;
    }
    /// After an autosave or a save: nothing is pending until the next edit.
    void saved(Clock::time_point now) {
        dirty_ = false;
        since_ = now;
    }
    bool due(Clock::time_point now) const { return dirty_ && now - since_ >= interval_; }
    bool dirty() const { return dirty_; }

  private:
    Clock::duration interval_;
    Clock::time_point since_{};
    bool dirty_ = false;
};

}  // namespace sandtin
