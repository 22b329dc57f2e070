#pragma once
// Progress of a long command on stderr, when stderr is a terminal: one line redrawn in place,
//
//   import dem.png: refining: 5120 points, worst error 0.84 m  42%  elapsed 3.1 s  left ~4.3 s
//
// at most ten times a second, ended by a newline. When stderr is not a terminal (a pipe, a
// file, a test) nothing is drawn at all, so --json consumers and logs never see it. The work
// reports through the engine's ProgressCallback (engine/io/progress.hpp).

#include <chrono>
#include <cstddef>
#include <string>
#include <string_view>

#include "io/progress.hpp"

namespace sandtin::cli {

/// Whether stderr is a terminal, the only place progress is drawn.
bool stderr_is_terminal();

/// "3.1 s", "2 min 05 s", "1 h 02 min": a duration as a person reads it.
std::string format_duration(double seconds);

/// The text of one progress line (without the carriage return): the title, the stage when
/// there is one, the whole percent done (rounded down, so 100 % means done), the elapsed time
/// and the time left, estimated as elapsed × (1 − f) / f once f > 0.
std::string progress_text(std::string_view title, std::string_view stage, double fraction,
                          double elapsed_seconds);

class ProgressLine {
  public:
    /// `title` names the command's work ("import dem.png"). Draws only when `enabled`.
    explicit ProgressLine(std::string title, bool enabled = stderr_is_terminal());
    /// Stops an unfinished line (the work threw), so the error message starts a line of its own.
    ~ProgressLine();
    ProgressLine(const ProgressLine&) = delete;
    ProgressLine& operator=(const ProgressLine&) = delete;

    /// Takes a report: redraws when the last drawing is 100 ms old (or none was drawn yet).
    void report(const Progress& progress);
    /// report() as the callback engine functions take; empty when nothing is drawn, so the
    /// work does not even compute its reports.
    ProgressCallback callback();
    /// Draws the finished line (100 %) and ends it.
    void finish();
    /// Ends the line where the work stopped (it failed), without claiming 100 %: whatever
    /// the command prints next starts a line of its own.
    void stop();

  private:
    void draw();

    std::string title_;
    bool enabled_;
    bool ended_ = false;
    std::chrono::steady_clock::time_point start_;
    std::chrono::steady_clock::time_point last_draw_{};
    bool drawn_ = false;
    double fraction_ = 0.0;
    std::string stage_;
    std::size_t width_ = 0;  ///< characters of the last line drawn, to blank what it leaves
};

}  // namespace sandtin::cli
