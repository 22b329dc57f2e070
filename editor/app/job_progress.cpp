#include "job_progress.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace sandtin::editor {

std::optional<double> estimate_remaining_seconds(double fraction, double elapsed_seconds) {
    if (!(fraction >= 0.02) || fraction >= 1.0 || !(elapsed_seconds >= 1.0)) return std::nullopt;
    return elapsed_seconds * (1.0 - fraction) / fraction;
}

std::string duration_text(double seconds) {
    const long s = std::lround(std::max(0.0, seconds));
    char text[48];
    if (s < 60)
        std::snprintf(text, sizeof(text), "%ld s", s);
    else if (s < 3600)
        std::snprintf(text, sizeof(text), "%ld min %02ld s", s / 60, s % 60);
    else
        std::snprintf(text, sizeof(text), "%ld h %02ld min", s / 3600, (s % 3600) / 60);
    return text;
}

std::string job_times_text(const JobProgress& p) {
    std::string text = duration_text(p.elapsed_seconds) + " elapsed, ";
    if (const std::optional<double> left =
            estimate_remaining_seconds(p.fraction, p.elapsed_seconds))
        return text + "about " + duration_text(*left) + " left";
    return text + "time left not known yet";
}

std::string percent_text(double fraction) {
    const int percent = static_cast<int>(std::floor(100.0 * std::clamp(fraction, 0.0, 1.0)));
    return std::to_string(percent) + " %";
}

}  // namespace sandtin::editor
