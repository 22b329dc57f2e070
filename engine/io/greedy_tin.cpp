#include "io/greedy_tin.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

#include "io/greedy_decimation.hpp"
#include "io/greedy_scan.hpp"
#include "io/lattice_delaunay.hpp"
#include "io/lattice_raster.hpp"
#include "util/elapsed_ms.hpp"

namespace sandtin {

namespace {

using greedy_detail::canonical;
using greedy_detail::Corner;
using greedy_detail::Plane;
using greedy_detail::SampleTriangle;
using greedy_detail::scan;
using greedy_detail::Worst;

/// Candidates per triangle id (lattice triangles, or TIN slots) in a max-heap with lazy
/// deletion: an entry is live while its stamp equals its triangle's current stamp.
class CandidateQueue {
  public:
    void reserve(std::size_t ids) {
        if (stamps_.size() < ids) {
            stamps_.resize(ids, 0);
            samples_.resize(ids, 0);
        }
    }
    /// Forgets the triangle's old candidate and queues the new one (when it has an error).
    void set(std::uint32_t id, const Worst& w) {
        ++stamps_[id];
        samples_[id] = w.sample;
        if (w.error > 0.0) {
            heap_.push_back({w.error, id, stamps_[id]});
            std::push_heap(heap_.begin(), heap_.end());
        }
    }
    void invalidate(std::uint32_t id) { ++stamps_[id]; }
    /// The worst live candidate, if any.
    std::optional<std::pair<double, std::uint32_t>> top() {
        while (!heap_.empty() && heap_.front().stamp != stamps_[heap_.front().id])
            pop();
        if (heap_.empty()) return std::nullopt;
        return std::make_pair(heap_.front().error, heap_.front().id);
    }
    void pop() {
        std::pop_heap(heap_.begin(), heap_.end());
        heap_.pop_back();
    }
    std::uint32_t sample(std::uint32_t id) const { return samples_[id]; }

  private:
    struct Entry {
        double error;
        std::uint32_t id;
        std::uint32_t stamp;
        /// Larger errors first; among equal errors the smaller id, so runs are deterministic.
        friend bool operator<(const Entry& x, const Entry& y) {
            return x.error < y.error || (x.error == y.error && x.id > y.id);
        }
    };
    std::vector<std::uint32_t> stamps_;
    std::vector<std::uint32_t> samples_;  ///< per id: raster index of its worst sample
    std::vector<Entry> heap_;
};

/// Every triangle of `mesh` as its corners' raster indices, canonically rotated, sorted.
std::vector<SampleTriangle> sample_triangles(const LatticeMesh& mesh, const HeightRaster& r) {
    std::vector<SampleTriangle> out;
    out.reserve(mesh.triangles.size());
    for (const std::array<std::uint32_t, 3>& t : mesh.triangles) {
        SampleTriangle tri{};
        for (std::size_t k = 0; k < 3; ++k) {
            const LatticePoint p = mesh.points[t[k]];
            tri[k] = (r.height - 1 - static_cast<std::uint32_t>(p.y)) * r.width +
                     static_cast<std::uint32_t>(p.x);
        }
        out.push_back(canonical(tri));
    }
    std::sort(out.begin(), out.end());
    return out;
}

/// How far a greedy insertion has come, for progress reports. The insertion does not know how
/// many points it will need, so the share done is estimated from the worst error left: on a
/// smooth surface linear interpolation's error falls with the square of the spacing, and the
/// points grow with its inverse square, so the points needed at error e grow as 1 / e and the
/// share done at worst error e is about (1/e - 1/e0) / (1/bound - 1/e0), e0 the first worst
/// error. A point limit gives points / limit, and the points placed over the samples are a
/// floor that also covers a bound of 0. Reported only every kEvery insertions, and never
/// decreasing (the worst error may rise for a step).
class GreedyProgress {
  public:
    GreedyProgress(const ProgressCallback& progress, const GreedyOptions& options,
                   std::size_t samples)
        : progress_(progress), options_(options), samples_(static_cast<double>(samples)) {}

    /// After an insertion: `worst` is the worst error left, `points` the vertices now.
    void inserted(double worst, std::size_t points) {
        if (!progress_) return;
        if (first_error_ == 0.0) first_error_ = worst;
        if (++insertions_ % kEvery != 0) return;
        double f = static_cast<double>(points) / samples_;
        if (options_.max_points != 0)
            f = std::max(f, static_cast<double>(points) / static_cast<double>(options_.max_points));
        if (options_.max_error > 0.0 && worst < first_error_) {
            f = std::max(f, (1.0 / worst - 1.0 / first_error_) /
                                (1.0 / options_.max_error - 1.0 / first_error_));
        }
        done_ = std::max(done_, std::min(f, 0.999));
        char stage[96];
        std::snprintf(stage, sizeof stage, "refining: %zu points, error %.2g m", points, worst);
        progress_({done_, stage});
    }

  private:
    static constexpr std::size_t kEvery = 256;
    const ProgressCallback& progress_;
    const GreedyOptions& options_;
    double samples_;
    double first_error_ = 0.0;
    double done_ = 0.0;
    std::size_t insertions_ = 0;
};

/// Phase 1: greedy insertion on the lattice Delaunay triangulation, free of any TIN
/// bookkeeping. Returns the chosen points.
class LatticeGreedy {
  public:
    explicit LatticeGreedy(const HeightRaster& raster)
        : r_(raster),
          dt_(static_cast<std::int32_t>(raster.width - 1),
              static_cast<std::int32_t>(raster.height - 1)) {
        for (std::uint32_t t = 0; t < dt_.triangle_count(); ++t)
            changed_.push_back(t);
        rescan_changed();
    }

    /// Returns whether the bound holds (false when max_points stopped it).
    bool run(double max_error, std::size_t max_points, GreedyProgress& progress) {
        while (const auto top = queue_.top()) {
            if (top->first <= max_error) return true;
            progress.inserted(top->first, dt_.point_count());
            if (max_points != 0 && dt_.point_count() >= max_points) return false;
            const std::uint32_t t = top->second;
            const std::uint32_t sample = queue_.sample(t);
            queue_.pop();
            queue_.invalidate(t);
            const LatticePoint p{static_cast<std::int32_t>(sample % r_.width),
                                 static_cast<std::int32_t>(r_.height - 1 - sample / r_.width)};
            dt_.insert(p, t, changed_);
            rescan_changed();
        }
        return true;
    }

    /// The triangulation as points and triangles.
    LatticeMesh mesh() const {
        LatticeMesh m;
        m.points.reserve(dt_.point_count());
        for (std::uint32_t v = 0; v < dt_.point_count(); ++v)
            m.points.push_back(dt_.point(v));
        m.triangles.reserve(dt_.triangle_count());
        for (std::uint32_t t = 0; t < dt_.triangle_count(); ++t)
            m.triangles.push_back(dt_.triangle(t));
        return m;
    }

  private:
    Corner corner(std::uint32_t v) const {
        const LatticePoint p = dt_.point(v);
        return {p.x, p.y,
                r_.heights[(r_.height - 1 - static_cast<std::uint32_t>(p.y)) * r_.width +
                           static_cast<std::uint32_t>(p.x)]};
    }

    void rescan_changed() {
        queue_.reserve(dt_.triangle_count());
        if (scanned_.size() < dt_.triangle_count()) scanned_.resize(dt_.triangle_count(), 0);
        ++step_;
        for (std::uint32_t t : changed_) {
            if (scanned_[t] == step_) continue;  // listed twice by successive flips
            scanned_[t] = step_;
            const std::array<std::uint32_t, 3> v = dt_.triangle(t);
            queue_.set(t, scan(corner(v[0]), corner(v[1]), corner(v[2]), r_));
        }
        changed_.clear();
    }

    const HeightRaster& r_;
    LatticeDelaunay dt_;
    CandidateQueue queue_;
    std::vector<std::uint32_t> changed_;
    std::vector<std::uint32_t> scanned_;  ///< per triangle: the step it was last scanned in
    std::uint32_t step_ = 0;
};

/// Phase 2: the same greedy rule on the TIN itself, driven by its change journal. It checks
/// every triangle of the TIN built from phase 1's points and inserts whatever the bound still
/// needs, so the result never depends on the two triangulations agreeing.
class TinGreedy {
  public:
    /// `settled`: triangles phase 1 already measured within the bound (sorted); the TIN's
    /// identical triangles need no rescan, since the same corners give bit-identical errors.
    TinGreedy(const HeightRaster& raster, Tin& tin, const std::vector<SampleTriangle>& settled)
        : r_(raster), tin_(tin) {
        rescan_changed(&settled);
    }

    /// Returns how many points were inserted; `reached` says whether the bound holds.
    std::size_t run(double max_error, std::size_t max_points, bool& reached) {
        std::size_t inserted = 0;
        reached = true;
        while (const auto top = queue_.top()) {
            if (top->first <= max_error) break;
            if (max_points != 0 && tin_.vertex_count() >= max_points) {
                reached = false;
                break;
            }
            const TriangleSlot slot = top->second;
            const std::uint32_t sample = queue_.sample(slot);
            queue_.pop();
            // A corner of the split triangle is next to the new point: a short walk.
            LocateHint hint{tin_.slot_triangle(slot)[0]};
            const std::uint32_t col = sample % r_.width;
            const std::uint32_t row = sample / r_.width;
            tin_.insert_point(r_.position(col, row), r_.heights[sample], &hint);
            ++inserted;
            rescan_changed();
        }
        return inserted;
    }

  private:
    Corner corner(VertexId v) const {
        const VertexArrays& va = tin_.vertices();
        const Vec2 p = va.position[v.index()];
        return {std::llround((p.x - r_.origin.x) / r_.cell_size),
                std::llround((p.y - r_.origin.y) / r_.row_spacing()), va.height[v.index()]};
    }

    std::uint32_t sample_of(const Corner& c) const {
        return static_cast<std::uint32_t>(
            (static_cast<std::int64_t>(r_.height) - 1 - c.j) * r_.width + c.i);
    }

    void rescan_changed(const std::vector<SampleTriangle>* settled = nullptr) {
        const ChangeSet changes = tin_.take_changes();
        queue_.reserve(changes.slot_capacity);
        for (const IdRange& range : changes.triangles) {
            for (TriangleSlot s = range.begin; s < range.end; ++s) {
                const std::array<VertexId, 3> t = tin_.slot_triangle(s);
                if (!t[0].valid()) {
                    queue_.invalidate(s);
                    continue;
                }
                const Corner a = corner(t[0]);
                const Corner b = corner(t[1]);
                const Corner c = corner(t[2]);
                if (settled != nullptr &&
                    std::binary_search(settled->begin(), settled->end(),
                                       canonical({sample_of(a), sample_of(b), sample_of(c)}))) {
                    queue_.invalidate(s);
                    continue;
                }
                queue_.set(s, scan(a, b, c, r_));
            }
        }
    }

    const HeightRaster& r_;
    Tin& tin_;
    CandidateQueue queue_;
};

}  // namespace

GreedyResult greedy_tin(const HeightRaster& raster, const GreedyOptions& options,
                        const ProgressCallback& progress) {
    if (!(std::isfinite(options.max_error) && options.max_error >= 0.0)) {
        throw std::invalid_argument(
            "greedy insertion: the maximum error must be a finite "
            "number of metres >= 0");
    }
    if (options.max_points != 0 && options.max_points < 4) {
        throw std::invalid_argument(
            "greedy insertion: the point limit must be at least 4 (the domain corners)");
    }
    check_raster(raster, "greedy insertion");
    const auto start = std::chrono::steady_clock::now();
    double decimate_ms = 0.0;

    // A rough split of the work: the insertion is most of it, then the decimation, the
    // measurement one pass.
    const ProgressCallback insertion = progress_part(progress, 0.0, 0.75);
    GreedyProgress insertion_progress(insertion, options, raster.size());
    if (insertion) insertion({0.0, "refining: scanning the raster"});
    LatticeGreedy lattice(raster);
    const bool lattice_reached =
        lattice.run(options.max_error, options.max_points, insertion_progress);
    LatticeMesh mesh = lattice.mesh();
    DecimationStats decimation;
    // After a point-limit stop the bound does not hold, and there is nothing to keep it for.
    if (options.decimate && lattice_reached) {
        const auto decimate_start = std::chrono::steady_clock::now();
        decimation = decimate_within_bound(mesh, raster, options.max_error,
                                           progress_part(progress, 0.75, 0.85));
        decimate_ms = elapsed_ms(decimate_start);
    }
    if (progress) progress({0.85, "building the TIN"});
    std::vector<Vec2> positions;
    std::vector<double> heights;
    positions.reserve(mesh.points.size());
    heights.reserve(mesh.points.size());
    for (const LatticePoint& p : mesh.points) {
        const auto col = static_cast<std::uint32_t>(p.x);
        const auto row = raster.height - 1 - static_cast<std::uint32_t>(p.y);
        positions.push_back(raster.position(col, row));
        heights.push_back(raster.at(col, row));
    }
    // The journal names the slots each fix-up insertion changed; that is all phase 2 needs.
    Tin tin = Tin::from_points(raster.domain(), positions, heights);
    bool reached = true;
    // After a point-limit stop phase 1's triangles are not all within the bound: rescan all.
    const std::vector<SampleTriangle> settled =
        lattice_reached ? sample_triangles(mesh, raster) : std::vector<SampleTriangle>{};
    if (progress) progress({0.88, "checking the TIN against the raster"});
    TinGreedy fix_up(raster, tin, settled);
    const std::size_t fix_ups = fix_up.run(options.max_error, options.max_points, reached);
    const double build_ms = elapsed_ms(start);

    if (progress) progress({0.9, "measuring the error of every sample"});
    GreedyStats stats = measure_tin_error(tin, raster);
    stats.reached_error = reached;
    stats.build_ms = build_ms;
    stats.fix_up_points = fix_ups;
    stats.decimated_points = decimation.removed;
    stats.decimate_ms = decimate_ms;
    // The measurement uses the scan's arithmetic, so only a corner's rounding (which the scan
    // ignores) may exceed the bound, by a few ulps.
    double z_scale = 1.0;
    for (double z : raster.heights)
        z_scale = std::max(z_scale, std::abs(z));
    if (reached && stats.max_error > options.max_error + 1e-12 * z_scale) {
        // The incremental bookkeeping and the independent pass disagree: a bug, not bad input.
        throw std::logic_error("greedy insertion: the final TIN misses the error bound");
    }
    if (progress) progress({1.0, "done"});
    return {std::move(tin), stats};
}

GreedyStats measure_tin_error(const Tin& tin, const HeightRaster& raster) {
    const auto start = std::chrono::steady_clock::now();
    const double s = raster.cell_size;
    const double sy = raster.row_spacing();
    const std::int64_t top = static_cast<std::int64_t>(raster.height) - 1;
    std::vector<std::uint8_t> seen(raster.size(), 0);
    double max_error = 0.0;
    long double sum_sq = 0.0L;
    std::size_t samples = 0;
    auto record = [&](std::size_t k, double z) {
        seen[k] = 1;
        if (!raster.is_valid(k)) return;
        const double e = std::abs(z - raster.heights[k]);
        max_error = std::max(max_error, e);
        sum_sq += static_cast<long double>(e) * e;
        ++samples;
    };
    const VertexArrays& va = tin.vertices();
    for (const std::array<VertexId, 3>& t : tin.triangles()) {
        // Lattice units: exact integers for vertices on samples, so the inside test is exact.
        std::array<double, 3> u{};
        std::array<double, 3> v{};
        std::array<double, 3> z{};
        for (std::size_t k = 0; k < 3; ++k) {
            u[k] = (va.position[t[k].index()].x - raster.origin.x) / s;
            v[k] = (va.position[t[k].index()].y - raster.origin.y) / sy;
            z[k] = va.height[t[k].index()];
        }
        const double area2 = (u[1] - u[0]) * (v[2] - v[0]) - (v[1] - v[0]) * (u[2] - u[0]);
        if (!(area2 > 0.0)) continue;
        const Plane plane = Plane::through(u, v, z);
        const auto integral = [](double w) { return w == std::floor(w); };
        if (integral(u[0]) && integral(u[1]) && integral(u[2]) && integral(v[0]) &&
            integral(v[1]) && integral(v[2])) {
            // Corners on samples (every greedy TIN): exact spans, and the scan's arithmetic.
            const auto n = [](double w) { return static_cast<std::int64_t>(w); };
            for_each_lattice_span({n(u[0]), n(u[1]), n(u[2])}, {n(v[0]), n(v[1]), n(v[2])},
                                  [&](std::int64_t j, std::int64_t lo, std::int64_t hi) {
                                      const double z_row = plane.row_start(static_cast<double>(j));
                                      const std::size_t row =
                                          static_cast<std::size_t>(top - j) * raster.width;
                                      for (std::int64_t i = std::max<std::int64_t>(lo, 0);
                                           i <= std::min<std::int64_t>(hi, raster.width - 1); ++i) {
                                          const std::size_t k = row + static_cast<std::size_t>(i);
                                          if (!seen[k]) {
                                              record(k, plane.at(z_row, static_cast<double>(i)));
                                          }
                                      }
                                  });
            continue;
        }
        const double eps = 1e-9 * area2;
        const auto i0 = std::max<std::int64_t>(
            0, static_cast<std::int64_t>(std::ceil(std::min({u[0], u[1], u[2]}) - 1e-9)));
        const auto i1 = std::min<std::int64_t>(
            raster.width - 1,
            static_cast<std::int64_t>(std::floor(std::max({u[0], u[1], u[2]}) + 1e-9)));
        const auto j0 = std::max<std::int64_t>(
            0, static_cast<std::int64_t>(std::ceil(std::min({v[0], v[1], v[2]}) - 1e-9)));
        const auto j1 = std::min<std::int64_t>(
            top, static_cast<std::int64_t>(std::floor(std::max({v[0], v[1], v[2]}) + 1e-9)));
        for (std::int64_t j = j0; j <= j1; ++j) {
            const double y = static_cast<double>(j);
            const double z_row = plane.row_start(y);
            const std::size_t row = static_cast<std::size_t>(top - j) * raster.width;
            for (std::int64_t i = i0; i <= i1; ++i) {
                const std::size_t k = row + static_cast<std::size_t>(i);
                if (seen[k]) continue;
                const double x = static_cast<double>(i);
                const double w0 = (u[1] - x) * (v[2] - y) - (v[1] - y) * (u[2] - x);
                const double w1 = (u[2] - x) * (v[0] - y) - (v[2] - y) * (u[0] - x);
                const double w2 = (u[0] - x) * (v[1] - y) - (v[0] - y) * (u[1] - x);
                if (w0 < -eps || w1 < -eps || w2 < -eps) continue;
                record(k, plane.at(z_row, x));
            }
        }
    }
    // Samples that rounding kept out of every triangle (only possible for vertices off the
    // lattice) are located one by one.
    LocateHint hint;
    for (std::size_t k = 0; k < seen.size(); ++k) {
        if (seen[k]) continue;
        const auto col = static_cast<std::uint32_t>(k % raster.width);
        const auto row = static_cast<std::uint32_t>(k / raster.width);
        const std::optional<double> z = tin.height_at(raster.position(col, row), &hint);
        if (!z) throw std::invalid_argument("measure_tin_error: the TIN does not cover the raster");
        record(k, *z);
    }
    GreedyStats stats;
    stats.points = tin.vertex_count();
    stats.triangles = tin.triangle_count();
    stats.max_error = max_error;
    stats.samples = samples;
    stats.rmsd = samples > 0 ? static_cast<double>(std::sqrt(sum_sq / samples)) : 0.0;
    stats.measure_ms = elapsed_ms(start);
    return stats;
}

}  // namespace sandtin
