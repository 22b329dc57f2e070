#include "tools/straying_samples.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>

#include "tin/vertex_change_feed.hpp"
#include "util/visit_marks.hpp"

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
    const Rect domain = tin.domain();
    // The triangle each sample was last evaluated in, by its corners: its surface height stays
    // what it was until one of them changes height or star (reported through `feed`).
    std::vector<std::array<VertexId, 3>> evaluated_in(samples.size());
    VertexChangeFeed feed(tin);

    std::vector<std::size_t> visit;
    std::vector<Vec2> at;
    std::vector<double> surface;
    std::vector<std::array<VertexId, 3>> corners;
    std::vector<Vec2> points;
    std::vector<double> heights;
    // Evaluates the samples in `visit` (one batch: consecutive samples are neighbours, so most
    // start in the triangle of the one before) and inserts those that stray; returns how many
    // went in.
    auto pass = [&]() {
        at.clear();
        for (std::size_t k : visit)
            at.push_back(samples[k]);
        surface.resize(at.size());
        corners.resize(at.size());
        tin.heights_at(at, surface, hint, corners);
        points.clear();
        heights.clear();
        for (std::size_t j = 0; j < visit.size(); ++j) {
            const std::size_t k = visit[j];
            evaluated_in[k] = corners[j];
            if (std::isnan(surface[j])) continue;
            // Interpolation at a vertex's own position can round a few ulps off its height; a
            // miss that small is not a stray (it would be inserted again and again).
            const double slack = 8.0 * std::numeric_limits<double>::epsilon() *
                                 std::max(std::abs(surface[j]), std::abs(targets[k]));
            if (!(std::abs(surface[j] - targets[k]) <= tolerance + slack)) {
                points.push_back(samples[k]);
                heights.push_back(targets[k]);
            }
        }
        if (points.empty()) return std::size_t{0};
        const std::vector<VertexId> ids = tin.insert_points(points, heights, hint, edit);
        inserted.insert(inserted.end(), ids.begin(), ids.end());
        return points.size();
    };
    auto usable = [&](std::size_t k) {
        return domain.contains(samples[k]) && std::isfinite(targets[k]);
    };
    // Coarse to fine: every 64th sample, then the 16th and 4th not visited yet.
    for (const auto [stride, skip_stride] :
         {std::array<std::size_t, 2>{64, 0}, {16, 64}, {4, 16}}) {
        visit.clear();
        for (std::size_t k = 0; k < samples.size(); k += stride) {
            if (skip_stride != 0 && k % skip_stride == 0) continue;  // an earlier pass's sample
            if (usable(k)) visit.push_back(k);
        }
        pass();
    }
    // Every sample, until the surface holds them all: an insertion re-triangulates its
    // neighbourhood, which can move the surface at samples checked before it. After the first
    // full pass only the samples whose triangle changed are looked at again; the others keep
    // their height, and so their verdict (they did not stray). A sample once inserted is a
    // vertex at its target for good (within the rounding slack), so each round that inserts
    // anything fixes at least one more sample; the cap only stops samples that share a
    // position but not a target from taking turns forever.
    static thread_local VisitMarks changed;
    for (int round = 0; round < kMaxFullPasses; ++round) {
        visit.clear();
        if (round == 0) {
            feed.take();  // what the coarse passes changed: every sample is visited anyway
            for (std::size_t k = 0; k < samples.size(); ++k) {
                if (usable(k)) visit.push_back(k);
            }
        } else {
            const VertexChanges c = feed.take();
            changed.clear();
            for (VertexId v : c.attributes)
                changed.mark(v.value);
            for (VertexId v : c.topology)
                changed.mark(v.value);
            for (std::size_t k = 0; k < samples.size(); ++k) {
                const std::array<VertexId, 3>& t = evaluated_in[k];
                if (!t[0].valid()) continue;  // no surface there, and none will come
                if (changed.contains(t[0].value) || changed.contains(t[1].value) ||
                    changed.contains(t[2].value)) {
                    visit.push_back(k);
                }
            }
        }
        if (pass() == 0) break;
    }
    return inserted;
}

}  // namespace sandtin
