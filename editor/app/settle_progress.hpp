#pragma once
// The erosion settling to rest after Run (an opened or imported scene steeper than repose, a
// material made steeper), as a progress bar: the relaxation already runs in frame-sized
// slices (Sculpting::erode, within kErosionBudgetMs), so nothing here runs off the UI thread;
// this only measures how far the settle has come.
//
// The measure, honestly: the share of the vertices the relaxation looked at when the settle
// was at its widest that no longer move, 1 - active / peak active, and never going back (sand
// that sets its neighbours sliding widens the active set again; the bar then holds still).
// It is not a share of the time: the last few vertices can take as long as the first many.
// A short settle (a stroke's) shows no bar: only one lasting kShowAfterSeconds.

#include <algorithm>
#include <cstddef>
#include <string>

#include "job_progress.hpp"

namespace sandtin::editor {

class SettleProgress {
  public:
    /// Seconds a settle lasts before its bar shows (scripted frames count 1/60 s).
    static constexpr double kShowAfterSeconds = 0.5;

    /// One frame of the settle: `active` vertices still looked at, `seconds` since the last.
    void step(std::size_t active, double seconds) {
        if (!running_) *this = SettleProgress{};
        running_ = true;
        elapsed_ += seconds;
        peak_ = std::max(peak_, active);
        active_ = active;
        if (peak_ > 0)
            fraction_ =
                std::max(fraction_, 1.0 - static_cast<double>(active) / static_cast<double>(peak_));
    }
    /// The sand rests, the erosion paused, or a gesture took over: the settle is over.
    void end() { running_ = false; }
    bool running() const { return running_; }
    bool shown() const { return running_ && elapsed_ >= kShowAfterSeconds; }

    JobProgress progress() const {
        JobProgress p;
        p.title = "Settling the sand";
        p.stage =
            std::to_string(active_) + " of " + std::to_string(peak_) + " vertices still sliding";
        p.fraction = fraction_;
        p.elapsed_seconds = elapsed_;
        return p;
    }

  private:
    bool running_ = false;
    double elapsed_ = 0.0;
    std::size_t peak_ = 0;
    std::size_t active_ = 0;
    double fraction_ = 0.0;
};

}  // namespace sandtin::editor
