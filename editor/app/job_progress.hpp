#pragma once
// What a progress bar shows of long work (an import, an export, opening a scene, the erosion
// settling to rest): a plain value the panel draws, with the words and numbers it prints. No
// ImGui here: the text is unit-tested.

#include <optional>
#include <string>

namespace sandtin::editor {

struct JobProgress {
    std::string title;      ///< what runs: "Importing bay.png"
    std::string stage;      ///< what it does now, in the work's own words
    double fraction = 0.0;  ///< of the whole job, in [0, 1], never decreasing
    double elapsed_seconds = 0.0;
    bool cancel_requested = false;  ///< Cancel was pressed; the work stops at its next check
};

/// Seconds left at the rate so far, elapsed * (1 - f) / f: nothing before 2 % of the job and
/// one second have passed (the first moments say little about the rate), nor once done.
std::optional<double> estimate_remaining_seconds(double fraction, double elapsed_seconds);

/// "8 s", "2 min 05 s", "1 h 03 min".
std::string duration_text(double seconds);

/// The line under the bar: "12 s elapsed, about 30 s left" (or "time left not known yet").
std::string job_times_text(const JobProgress& p);

/// The bar's overlay: "42 %" (whole percents, rounded down so 100 % means done).
std::string percent_text(double fraction);

}  // namespace sandtin::editor
