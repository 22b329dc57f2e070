#include "pour_flow.hpp"

namespace sandtin::editor {

std::vector<Vec2> PourFlow::press(Vec2 p) {
    cursor_ = p;
    since_dab_ = 0.0;
    // The sampler's first sample is this point again: move() skips it.
    (void)sampler_.add_point(p);
    return {p};
}

std::vector<Vec2> PourFlow::move(Vec2 p) {
    if (!cursor_) return press(p);
    cursor_ = p;
    std::vector<Vec2> dabs;
    for (const StrokeSample& s : sampler_.add_point(p)) {
        if (s.arc_length > 0.0) dabs.push_back(s.position);  // the press poured the start
    }
    if (!dabs.empty()) since_dab_ = 0.0;
    return dabs;
}

std::vector<Vec2> PourFlow::hold(double seconds) {
    if (!cursor_) return {};
    since_dab_ += seconds;
    std::vector<Vec2> dabs;
    while (since_dab_ >= kPourHoldSeconds) {
        since_dab_ -= kPourHoldSeconds;
        dabs.push_back(*cursor_);
    }
    return dabs;
}

}  // namespace sandtin::editor
