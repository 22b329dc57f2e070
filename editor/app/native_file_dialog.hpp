#pragma once
// The desktop's file dialog: `zenity` or `kdialog` run as a child process (as portable
// file-dialog libraries do), without a shell (its arguments are an argv, so any path is safe),
// and waited for on a thread of its own so that the editor keeps drawing while it is open. Its
// answer is taken on the UI thread (take_result). No UI here: tests/editor/
// native_file_dialog_test.cpp runs it against a fake dialog program.

#include <sys/types.h>

#include <atomic>
#include <filesystem>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "file_dialog_request.hpp"

namespace sandtin::editor {

struct DialogProgram {
    enum class Kind { Zenity, KDialog };
    Kind kind = Kind::Zenity;
    std::filesystem::path path;
};

/// The dialog program found on `search_path` (a PATH value): zenity, else kdialog; kdialog
/// first when `desktop` (XDG_CURRENT_DESKTOP) names KDE. Nothing when neither is there.
std::optional<DialogProgram> find_dialog_program(std::string_view search_path,
                                                 std::string_view desktop);

/// The arguments (argv[1..]) that ask `program` for `request`: its title, the folder (and the
/// name proposed) it starts at, and its filters.
std::vector<std::string> dialog_arguments(const DialogProgram& program,
                                          const FileDialogRequest& request);

struct NativeDialogResult {
    enum class Outcome { Chosen, Cancelled, Failed };
    Outcome outcome = Outcome::Failed;
    std::filesystem::path path;  ///< Chosen: the file
    std::string error;           ///< Failed: why (the program's exit code and its last words)
};

/// Runs `program` with `arguments` and waits for it: what it printed on stdout is the file
/// chosen (exit 0), exit 1 is a cancel, anything else (another code, a signal, no path
/// printed, a program that cannot start) a failure. When `stop` becomes true the program is
/// killed and the result is a failure.
NativeDialogResult run_dialog_program(const std::filesystem::path& program,
                                      const std::vector<std::string>& arguments,
                                      const std::atomic<bool>& stop);

/// One dialog at a time, waited for off the UI thread.
class NativeFileDialog {
  public:
    /// `wake` is called on the waiting thread when the dialog has answered (the editor posts
    /// an empty event, so a loop blocked waiting for input draws the frame that takes it).
    explicit NativeFileDialog(std::function<void()> wake = {}) : wake_(std::move(wake)) {}
    /// A dialog still open is closed (its program killed).
    ~NativeFileDialog();
    NativeFileDialog(const NativeFileDialog&) = delete;
    NativeFileDialog& operator=(const NativeFileDialog&) = delete;

    /// Starts the dialog; throws std::logic_error when one is open already.
    void start(const DialogProgram& program, const FileDialogRequest& request);
    /// A dialog was started and its answer not yet taken.
    bool busy() const { return busy_; }
    /// The answer, once (nothing while the dialog is open).
    std::optional<NativeDialogResult> take_result();

  private:
    void join();

    std::function<void()> wake_;
    std::thread thread_;
    std::atomic<bool> stop_{false};
    bool busy_ = false;
    std::mutex mutex_;
    std::optional<NativeDialogResult> result_;  ///< guarded by mutex_
};

}  // namespace sandtin::editor
