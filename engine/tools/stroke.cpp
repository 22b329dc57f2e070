#include "tools/stroke.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace sandtin {

StrokeSampler::StrokeSampler(double spacing) : spacing_(spacing) {
    if (!(spacing > 0.0) || !std::isfinite(spacing)) {
        throw std::invalid_argument("stroke: spacing must be a positive number of metres");
    }
}

std::vector<StrokeSample> StrokeSampler::add_point(Vec2 p) {
    std::vector<StrokeSample> out;
    if (!is_finite(p)) throw std::invalid_argument("stroke: path point is not finite");
    if (!last_) {
        last_ = p;
        start_pending_ = true;
        next_index_ = 1;
        return out;
    }
    const Vec2 a = *last_;
    const double len = distance(a, p);
    if (len <= 0.0) return out;
    const Vec2 dir = (p - a) / len;
    if (start_pending_) {
        out.push_back({a, dir, 0.0});
        start_pending_ = false;
    }
    // Samples at arc lengths k * spacing within this segment. Positions are computed from the
    // segment start and the arc length, so splitting a straight segment into pieces gives the
    // same samples. A sample within rounding of the segment's end belongs to it: whether a path
    // whose length is a whole number of spacings (0.2 -> 0.5 at 0.1) gets its end stamped must
    // not depend on the last bit of length / spacing, nor on the scale of the scene.
    const double end = travelled_ + len;
    const double slack = 1e-9 * std::max(end, spacing_);
    for (double at = static_cast<double>(next_index_) * spacing_; at <= end + slack;
         at = static_cast<double>(++next_index_) * spacing_) {
        const double t = std::min((at - travelled_) / len, 1.0);
        out.push_back({lerp(a, p, t), dir, at});
    }
    travelled_ += len;
    last_ = p;
    return out;
}

std::vector<StrokeSample> StrokeSampler::finish() {
    std::vector<StrokeSample> out;
    // A path that never moved has no direction: its stamp has no motion either.
    if (start_pending_ && last_) out.push_back({*last_, std::nullopt, 0.0});
    start_pending_ = false;
    return out;
}

std::vector<Vec2> catmull_rom(std::span<const Vec2> control, double max_step) {
    if (control.size() < 3 || !(max_step > 0.0))
        return std::vector<Vec2>(control.begin(), control.end());
    const std::size_t n = control.size();
    auto point = [&](std::ptrdiff_t i) {
        // Reflect the end points so the curve starts and ends at the first and last control.
        if (i < 0) return control[0] * 2.0 - control[1];
        if (i >= static_cast<std::ptrdiff_t>(n)) return control[n - 1] * 2.0 - control[n - 2];
        return control[static_cast<std::size_t>(i)];
    };
    std::vector<Vec2> out = {control[0]};
    std::vector<Vec2> piece;
    for (std::size_t seg = 0; seg + 1 < n; ++seg) {
        const auto i = static_cast<std::ptrdiff_t>(seg);
        const Vec2 p0 = point(i - 1), p1 = point(i), p2 = point(i + 1), p3 = point(i + 2);
        // Centripetal knots (alpha = 1/2).
        auto knot = [](Vec2 a, Vec2 b) { return std::sqrt(std::max(distance(a, b), 1e-12)); };
        const double t0 = 0.0, t1 = t0 + knot(p0, p1), t2 = t1 + knot(p1, p2),
                     t3 = t2 + knot(p2, p3);
        auto eval = [&](double t) {
            const Vec2 a1 = p0 * ((t1 - t) / (t1 - t0)) + p1 * ((t - t0) / (t1 - t0));
            const Vec2 a2 = p1 * ((t2 - t) / (t2 - t1)) + p2 * ((t - t1) / (t2 - t1));
            const Vec2 a3 = p2 * ((t3 - t) / (t3 - t2)) + p3 * ((t - t2) / (t3 - t2));
            const Vec2 b1 = a1 * ((t2 - t) / (t2 - t0)) + a2 * ((t - t0) / (t2 - t0));
            const Vec2 b2 = a2 * ((t3 - t) / (t3 - t1)) + a3 * ((t - t1) / (t3 - t1));
            return b1 * ((t2 - t) / (t2 - t1)) + b2 * ((t - t1) / (t2 - t1));
        };
        // The curve is longer than its chord: double the steps until no piece exceeds max_step.
        int steps = std::max(1, static_cast<int>(std::ceil(distance(p1, p2) / max_step)));
        for (int attempt = 0; attempt < 20; ++attempt, steps *= 2) {
            piece.clear();
            Vec2 previous = p1;
            bool ok = true;
            for (int k = 1; k <= steps; ++k) {
                const Vec2 q = k == steps ? p2 : eval(t1 + (t2 - t1) * k / steps);
                ok = ok && distance(previous, q) <= max_step;
                piece.push_back(q);
                previous = q;
            }
            if (ok) break;
        }
        out.insert(out.end(), piece.begin(), piece.end());
    }
    return out;
}

ToolPlacement placement_for(const Tin& tin, const Tool& tool, const StrokeSample& sample,
                            const StrokeSettings& settings, LocateHint* hint) {
    ToolPlacement at;
    // Rounded to 0.1 nm and 1 nrad: the same path sampled at another rate gives samples that
    // differ in the last bits, and a stamp's rim draping reacts to every bit; rounded, they
    // stamp identically.
    auto round_to = [](double v, double quantum) { return std::round(v / quantum) * quantum; };
    at.centre = {round_to(sample.position.x, 1e-10), round_to(sample.position.y, 1e-10)};
    const std::optional<Vec2>& dir = sample.direction;
    at.angle =
        round_to(settings.follow_path && dir ? std::atan2(dir->y, dir->x) : settings.angle, 1e-9);
    if (settings.depth_mode == DepthMode::Absolute) {
        at.bottom = settings.depth;
    } else {
        const Rect d = tin.domain();
        Vec2 front = sample.position + dir.value_or(Vec2{}) * tool.radius();
        front = {std::clamp(front.x, d.min.x, d.max.x), std::clamp(front.y, d.min.y, d.max.y)};
        const std::optional<double> h = tin.height_at(front, hint);
        const std::optional<double> hc =
            tin.height_at({std::clamp(sample.position.x, d.min.x, d.max.x),
                           std::clamp(sample.position.y, d.min.y, d.max.y)},
                          hint);
        at.bottom = (h ? *h : hc.value_or(0.0)) - settings.depth;
    }
    return at;
}

StampReport apply_stroke(Tin& tin, const Tool& tool, std::span<const Vec2> path,
                         const StrokeSettings& settings, SculptContext& context,
                         std::vector<StampReport>* per_stamp,
                         const std::function<void(const StampReport&)>& after_stamp) {
    StampReport total;
    StrokeSampler sampler(settings.spacing);
    auto run = [&](const std::vector<StrokeSample>& samples) {
        for (const StrokeSample& s : samples) {
            const ToolPlacement at = placement_for(tin, tool, s, settings, &context.hint);
            const StampReport r = stamp(tin, tool, at, context, s.direction);
            if (per_stamp != nullptr) per_stamp->push_back(r);
            total.accumulate(r);
            if (after_stamp) after_stamp(r);
        }
    };
    for (Vec2 p : path)
        run(sampler.add_point(p));
    run(sampler.finish());
    return total;
}

}  // namespace sandtin
