#pragma once
// Per-stage frame timings kept for the Stats panel and the stats file.

#include <algorithm>
#include <deque>
#include <vector>

namespace sandtin::editor {

/// Per-stage timings (ms) of recent frames, for the Stats panel and the stats file.
struct StageTimes {
    static constexpr std::size_t kKeep = 240;
    std::deque<float> frame, tool, physics, mesh, upload, bake, render;
    void push(std::deque<float>& d, double v) {
        d.push_back(static_cast<float>(v));
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
