#pragma once
// Shared helpers of the benchmark drivers: timing, medians and the benchmark configuration.

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <ctime>
#include <string>
#include <string_view>
#include <vector>

#include "io/progress.hpp"

namespace sandtin::bench {

struct BenchConfig {
    bool quick = false;  ///< small sizes, for smoke tests of the drivers themselves
    /// groove: a tool asset (assets/tools/<name>.json, or a path) instead of the seeds' circle
    std::string tool;
    /// Where the benchmark reports what it measures now (engine/io/progress.hpp's contract);
    /// empty: no reports. The measurements are the same either way: reports fall between timed
    /// sections, never inside one.
    ProgressCallback progress;
};

/// Progress through work made of parts of estimated relative cost: start(stage, weight)
/// reports the stage at the fraction of the estimated cost done before it; done() reports 1.
/// The weights shape the percentages and the time-left estimate only.
class WeightedProgress {
  public:
    WeightedProgress(const ProgressCallback& whole, double total_weight)
        : whole_(whole), total_(total_weight) {}
    void start(std::string_view stage, double weight) {
        if (whole_ && total_ > 0.0) whole_({std::min(done_ / total_, 1.0), stage});
        done_ += weight;
    }
    void done() {
        if (whole_) whole_({1.0, "done"});
    }

  private:
    const ProgressCallback& whole_;
    double total_;
    double done_ = 0.0;
};

class Stopwatch {
  public:
    Stopwatch() : start_(std::chrono::steady_clock::now()) {}
    double ms() const {
        return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_)
            .count();
    }

  private:
    std::chrono::steady_clock::time_point start_;
};

/// CPU time of the calling thread: on a shared virtual machine it is far less noisy than wall
/// time, because time the hypervisor gives to other guests is not counted.
class CpuStopwatch {
  public:
    CpuStopwatch() : start_(now()) {}
    double ms() const { return now() - start_; }

  private:
    static double now() {
        timespec t{};
        clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
        return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) * 1e-6;
    }
    double start_;
};

inline double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace sandtin::bench
