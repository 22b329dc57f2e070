#pragma once
// Per-stage frame timings kept for the Stats panel and the stats file.

#include <algorithm>
#include <deque>
#include <optional>
#include <vector>

namespace sandtin::editor {

/// Per-stage timings (ms) of recent frames, for the Stats panel and the stats file.
struct StageTimes {
    static constexpr std::size_t kKeep = 240;
    std::deque<float> frame, tool, physics, mesh, upload, bake, render;
    /// Every stage of every frame is recorded as taking this long instead of what it took: a
    /// test shows the Stats window as a slow machine would (the script's "stage_times" op),
    /// whatever the speed of the machine it runs on.
    std::optional<double> forced_ms;
    void push(std::deque<float>& d, double v) {
        d.push_back(static_cast<float>(forced_ms.value_or(v)));
        if (d.size() > kKeep) d.pop_front();
    }
    static double median(const std::deque<float>& d) {
        if (d.empty()) return 0.0;
        std::vector<float> v(d.begin(), d.end());
        std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
        return v[v.size() / 2];
    }
};

}  // namespace sandtin::editor
