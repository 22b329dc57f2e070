#include "tools/straying_samples.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <stdexcept>

namespace sandtin {

namespace {

constexpr int kMaxFullPasses = 8;

}  // namespace

std::vector<VertexId> insert_straying_samples(Tin& tin, std::span<const Vec2> samples,
                                              std::span<const double> targets, double tolerance,
                                              LocateHint* hint, EditReport* edit) {
    if (samples.size() != targets.size())
        throw std::invalid_argument("insert_straying_samples: one target height per sample");
    if (!(tolerance >= 0.0))
        throw std::invalid_argument("insert_straying_samples: tolerance must be >= 0");
    std::vector<VertexId> inserted;
    std::vector<Vec2> points;
    std::vector<double> heights;
    const Rect domain = tin.domain();
    // Inserts the samples of one pass that stray; returns how many went in.
    auto pass = [&](std::size_t stride, std::size_t skip_stride) {
        points.clear();
        heights.clear();
        for (std::size_t k = 0; k < samples.size(); k += stride) {
            if (skip_stride != 0 && k % skip_stride == 0) continue;  // an earlier pass's sample
            const Vec2 p = samples[k];
            if (!domain.contains(p) || !std::isfinite(targets[k])) continue;
            const std::optional<double> surface = tin.height_at(p, hint);
            if (!surface) continue;
            // Interpolation at a vertex's own position can round a few ulps off its height; a
            // miss that small is not a stray (it would be inserted again and again).
            const double slack = 8.0 * std::numeric_limits<double>::epsilon() *
                                 std::max(std::abs(*surface), std::abs(targets[k]));
            if (!(std::abs(*surface - targets[k]) <= tolerance + slack)) {
                points.push_back(p);
                heights.push_back(targets[k]);
            }
        }
        if (points.empty()) return std::size_t{0};
        const std::vector<VertexId> ids = tin.insert_points(points, heights, hint, edit);
        inserted.insert(inserted.end(), ids.begin(), ids.end());
        return points.size();
    };
    pass(64, 0);
    pass(16, 64);
    pass(4, 16);
    // Every sample, until the surface holds them all: an insertion re-triangulates its
    // neighbourhood, which can move the surface at samples checked before it. A sample once
    // inserted is a vertex at its target for good (within the rounding slack), so each round
    // that inserts anything fixes at least one more sample; the cap only stops samples that
    // share a position but not a target from taking turns forever.
    for (int round = 0; round < kMaxFullPasses && pass(1, 0) != 0; ++round) {
    }
    return inserted;
}

}  // namespace sandtin
