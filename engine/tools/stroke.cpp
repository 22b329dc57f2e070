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

namespace {

Vec2 clamped(Vec2 p, const Rect& d) {
    return {std::clamp(p.x, d.min.x, d.max.x), std::clamp(p.y, d.min.y, d.max.y)};
}

std::uint64_t key_of(std::int64_t i, std::int64_t j) {
    // The low 32 bits of each index: two lattice points share a key only 2^32 cells apart,
    // farther than a stroke's million stamps reach.
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(i)) << 32) |
           static_cast<std::uint32_t>(j);
}

}  // namespace

StrokeGround::StrokeGround(double cell) : cell_(cell) {
    if (!(cell > 0.0) || !std::isfinite(cell))
        throw std::invalid_argument("stroke ground: the lattice spacing must be positive");
}

void StrokeGround::remember(const Tin& tin, Vec2 centre, double radius, LocateHint* hint) {
    const Rect d = tin.domain();
    const auto i0 = static_cast<std::int64_t>(std::floor((centre.x - radius) / cell_));
    const auto i1 = static_cast<std::int64_t>(std::ceil((centre.x + radius) / cell_));
    const auto j0 = static_cast<std::int64_t>(std::floor((centre.y - radius) / cell_));
    const auto j1 = static_cast<std::int64_t>(std::ceil((centre.y + radius) / cell_));
    for (std::int64_t j = j0; j <= j1; ++j) {
        for (std::int64_t i = i0; i <= i1; ++i) {
            const Vec2 p{static_cast<double>(i) * cell_, static_cast<double>(j) * cell_};
            if (distance(p, centre) > radius) continue;
            const std::uint64_t k = key_of(i, j);
            if (heights_.contains(k)) continue;
            if (const std::optional<double> h = tin.height_at(clamped(p, d), hint))
                heights_.emplace(k, *h);
        }
    }
}

std::optional<double> StrokeGround::node_height(const Tin& tin, std::int64_t i, std::int64_t j,
                                                LocateHint* hint) const {
    const auto it = heights_.find(key_of(i, j));
    if (it != heights_.end()) return it->second;
    const Vec2 p{static_cast<double>(i) * cell_, static_cast<double>(j) * cell_};
    return tin.height_at(clamped(p, tin.domain()), hint);
}

std::optional<double> StrokeGround::height_at(const Tin& tin, Vec2 p, LocateHint* hint) const {
    const Vec2 q = clamped(p, tin.domain());
    const double fx = q.x / cell_;
    const double fy = q.y / cell_;
    const auto i = static_cast<std::int64_t>(std::floor(fx));
    const auto j = static_cast<std::int64_t>(std::floor(fy));
    const double tx = fx - static_cast<double>(i);
    const double ty = fy - static_cast<double>(j);
    const std::optional<double> h00 = node_height(tin, i, j, hint);
    const std::optional<double> h10 = node_height(tin, i + 1, j, hint);
    const std::optional<double> h01 = node_height(tin, i, j + 1, hint);
    const std::optional<double> h11 = node_height(tin, i + 1, j + 1, hint);
    if (!h00 || !h10 || !h01 || !h11) return tin.height_at(q, hint);
    return (1.0 - ty) * ((1.0 - tx) * *h00 + tx * *h10) + ty * ((1.0 - tx) * *h01 + tx * *h11);
}

ToolPlacement placement_for(const Tin& tin, const Tool& tool, const StrokeSample& sample,
                            const StrokeSettings& settings, LocateHint* hint,
                            const StrokeGround* ground) {
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
        return at;
    }
    const Rect d = tin.domain();
    if (ground != nullptr) {
        at.bottom = ground->height_at(tin, sample.position, hint).value_or(0.0) - settings.depth;
        return at;
    }
    const Vec2 front = clamped(sample.position + dir.value_or(Vec2{}) * tool.radius(), d);
    const std::optional<double> h = tin.height_at(front, hint);
    const std::optional<double> hc = tin.height_at(clamped(sample.position, d), hint);
    at.bottom = (h ? *h : hc.value_or(0.0)) - settings.depth;
    return at;
}

Stroke::Stroke(const Tool& tool, const StrokeSettings& settings)
    : tool_(&tool),
      settings_(settings),
      sampler_(std::min(settings.spacing, tool.max_stroke_spacing())),
      // About a thousand lattice points in the disc a stamp may change, whatever the tool.
      ground_(
          (tool.shape().bounding_radius + (tool.spec().extrude ? tool.extrusion_width() : 0.0)) /
          16.0),
      reach_(tool.shape().bounding_radius + (tool.spec().extrude ? tool.extrusion_width() : 0.0) +
             2.0 * ground_.cell()) {}

std::vector<StrokeStamp> Stroke::stamp_all(Tin& tin, const std::vector<StrokeSample>& samples,
                                           SculptContext& context, const AfterStamp& after_stamp) {
    std::vector<StrokeStamp> out;
    const bool relative = settings_.depth_mode == DepthMode::Relative;
    for (const StrokeSample& s : samples) {
        const ToolPlacement at =
            placement_for(tin, *tool_, s, settings_, &context.hint, relative ? &ground_ : nullptr);
        // The ground under this stamp's reach, before it changes anything there.
        if (relative) ground_.remember(tin, at.centre, reach_, &context.hint);
        const StampReport r = stamp(tin, *tool_, at, context, s.direction);
        out.push_back({s, at, r});
        if (after_stamp) after_stamp(r);
    }
    return out;
}

std::vector<StrokeStamp> Stroke::add_point(Tin& tin, Vec2 p, SculptContext& context,
                                           const AfterStamp& after_stamp) {
    return stamp_all(tin, sampler_.add_point(p), context, after_stamp);
}

std::vector<StrokeStamp> Stroke::finish(Tin& tin, SculptContext& context,
                                        const AfterStamp& after_stamp) {
    return stamp_all(tin, sampler_.finish(), context, after_stamp);
}

StampReport apply_stroke(Tin& tin, const Tool& tool, std::span<const Vec2> path,
                         const StrokeSettings& settings, SculptContext& context,
                         std::vector<StampReport>* per_stamp, const AfterStamp& after_stamp) {
    StampReport total;
    Stroke stroke(tool, settings);
    auto take = [&](const std::vector<StrokeStamp>& stamps) {
        for (const StrokeStamp& s : stamps) {
            if (per_stamp != nullptr) per_stamp->push_back(s.report);
            total.accumulate(s.report);
        }
    };
    for (Vec2 p : path)
        take(stroke.add_point(tin, p, context, after_stamp));
    take(stroke.finish(tin, context, after_stamp));
    return total;
}

}  // namespace sandtin
