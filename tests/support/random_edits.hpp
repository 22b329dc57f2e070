#pragma once
// A driver of random mixed edits for property tests: point insertion (given height, on the
// surface), removal, segment and ring constraints (crossing ones included), releases by
// generation / age / polygon / id, and attribute setters. Each step says what volume
// behaviour the edit promises, so the caller can check it against the measured volume.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "support/tin_oracles.hpp"
#include "tin/tin.hpp"

namespace sandtin::test {

struct StepResult {
    std::string name;
    /// The edit promises to keep the volume (VolumePolicy::Conserve, or no topology change).
    bool conserves = false;
    /// The edit reported its volume change in `report` (VolumePolicy::Report or insert_point).
    bool reported = false;
    /// The volume change is known exactly from outside (attribute edits): `known_change`.
    bool known = false;
    double known_change = 0.0;
    EditReport report;
    /// The step made exactly one edit call (the ring step makes several).
    bool single_edit = true;
};

class RandomEditor {
  public:
    struct Options {
        bool attribute_edits = false;   ///< also set heights, moisture, material, ...
        double long_constraint = 0.03;  ///< probability that a segment spans the domain
    };

    RandomEditor(Tin& tin, std::uint64_t seed, Options options)
        : tin_(tin), rng_(test_rng(seed)), options_(options) {}

    StepResult step() {
        const double r = uniform(0.0, 1.0);
        if (r < 0.20) return insert_given();
        if (r < 0.42) return insert_on_surface(VolumePolicy::Conserve);
        if (r < 0.47) return insert_on_surface(VolumePolicy::Report);
        if (r < 0.60) return remove(VolumePolicy::Conserve);
        if (r < 0.65) return remove(VolumePolicy::Report);
        if (r < 0.78) return segment();
        if (r < 0.82) return ring();
        if (r < 0.90) return release();
        if (r < 0.94) return release_one();
        if (options_.attribute_edits) return attribute();
        return insert_on_surface(VolumePolicy::Conserve);
    }

    Generation generation() const { return generation_; }

  private:
    double uniform(double lo, double hi) {
        return std::uniform_real_distribution<double>(lo, hi)(rng_);
    }
    std::size_t index(std::size_t n) {
        return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng_);
    }

    Vec2 random_point() {
        const Rect d = tin_.domain();
        // Now and then exactly on the border, which has its own code paths.
        const double r = uniform(0.0, 1.0);
        if (r < 0.03) return {uniform(d.min.x, d.max.x), r < 0.015 ? d.min.y : d.max.y};
        if (r < 0.06) return {r < 0.045 ? d.min.x : d.max.x, uniform(d.min.y, d.max.y)};
        return {uniform(d.min.x, d.max.x), uniform(d.min.y, d.max.y)};
    }

    Vec2 clamp_to_domain(Vec2 p) const {
        const Rect d = tin_.domain();
        return {std::clamp(p.x, d.min.x, d.max.x), std::clamp(p.y, d.min.y, d.max.y)};
    }

    VertexId random_vertex() {
        const VertexArrays& va = tin_.vertices();
        for (;;) {
            const auto i = static_cast<std::uint32_t>(index(va.size()));
            if (va.alive[i]) return VertexId{i};
        }
    }

    /// A live vertex near p (a corner of the triangle containing it).
    VertexId vertex_near(Vec2 p) {
        const Location loc = tin_.locate(clamp_to_domain(p), &hint_);
        return loc.corners[index(3)];
    }

    StepResult insert_given() {
        StepResult s{"insert_point", false, true, false, 0.0, {}};
        const Vec2 p = random_point();
        const double h = tin_.height_at(p).value() + uniform(-0.2, 0.2);
        tin_.insert_point(p, h, &hint_, &s.report);
        return s;
    }

    StepResult insert_on_surface(VolumePolicy policy) {
        StepResult s{"insert_point_on_surface",
                     policy == VolumePolicy::Conserve,
                     policy == VolumePolicy::Report,
                     false,
                     0.0,
                     {}};
        tin_.insert_point_on_surface(random_point(), &hint_, policy, &s.report);
        return s;
    }

    StepResult remove(VolumePolicy policy) {
        StepResult s{"remove_vertex",
                     policy == VolumePolicy::Conserve,
                     policy == VolumePolicy::Report,
                     false,
                     0.0,
                     {}};
        for (int tries = 0; tries < 10; ++tries) {
            const VertexId v = random_vertex();
            if (tin_.is_boundary(v) || tin_.is_on_constraint(v)) continue;
            tin_.remove_vertex(v, policy, &s.report);
            return s;
        }
        s.name = "remove_vertex (refused)";
        s.conserves = true;
        s.reported = false;
        // Refused removals change nothing at all.
        const VertexId v = random_vertex();
        if (tin_.is_boundary(v) || tin_.is_on_constraint(v))
            tin_.remove_vertex(v, policy, &s.report);
        return s;
    }

    StepResult segment() {
        StepResult s{"insert_constraint", true, false, false, 0.0, {}};
        const VertexId a = random_vertex();
        VertexId b;
        if (uniform(0.0, 1.0) < options_.long_constraint) {
            b = random_vertex();
        } else {
            const double angle = uniform(0.0, 2.0 * std::numbers::pi);
            const double len = uniform(0.05, 0.25) * tin_.domain().width();
            b = vertex_near(tin_.position(a) + Vec2{std::cos(angle), std::sin(angle)} * len);
        }
        if (a == b) return insert_on_surface(VolumePolicy::Conserve);
        tin_.insert_constraint(a, b, generation_++, VolumePolicy::Conserve, &s.report);
        return s;
    }

    StepResult ring() {
        StepResult s{"insert_constraint (ring)", true, false, false, 0.0, {}};
        s.single_edit = false;
        const Rect d = tin_.domain();
        const double radius = uniform(0.03, 0.1) * d.width();
        const Vec2 c{uniform(d.min.x + radius, d.max.x - radius),
                     uniform(d.min.y + radius, d.max.y - radius)};
        const int n = 5 + static_cast<int>(index(6));
        const double phase = uniform(0.0, 1.0);
        std::vector<VertexId> rim;
        for (int i = 0; i < n; ++i) {
            const double angle = 2.0 * std::numbers::pi * (i + phase) / n;
            rim.push_back(
                tin_.insert_point_on_surface(c + Vec2{std::cos(angle), std::sin(angle)} * radius,
                                             &hint_, VolumePolicy::Conserve, &s.report));
        }
        // Rim points may land on existing vertices; drop consecutive repeats.
        rim.erase(std::unique(rim.begin(), rim.end()), rim.end());
        while (rim.size() > 1 && rim.front() == rim.back())
            rim.pop_back();
        if (rim.size() >= 3)
            tin_.insert_constraint(rim, true, generation_++, VolumePolicy::Conserve, &s.report);
        return s;
    }

    StepResult release() {
        const bool report = uniform(0.0, 1.0) < 0.25;
        StepResult s{"release_constraints", !report, report, false, 0.0, {}};
        ReleaseFilter f;
        const double r = uniform(0.0, 1.0);
        std::vector<Vec2> polygon;
        if (r < 0.3 && generation_ > 1) {
            f.generation =
                1 + static_cast<Generation>(index(static_cast<std::size_t>(generation_ - 1)));
        } else if (r < 0.6) {
            f.older_than = generation_ > 20 ? generation_ - 20 : 1;
        } else {
            const Rect d = tin_.domain();
            const Vec2 c{uniform(d.min.x, d.max.x), uniform(d.min.y, d.max.y)};
            const double w = uniform(0.05, 0.3) * d.width();
            polygon = {c, c + Vec2{w, 0.1 * w}, c + Vec2{0.6 * w, w}, c + Vec2{0.2 * w, 0.4 * w}};
            f.touching_polygon = polygon;
            if (r < 0.8) f.older_than = generation_;
        }
        tin_.release_constraints(f, report ? VolumePolicy::Report : VolumePolicy::Conserve,
                                 &s.report);
        return s;
    }

    StepResult release_one() {
        StepResult s{"release_constraint", true, false, false, 0.0, {}};
        const std::vector<ConstraintInfo> all = tin_.constraints();
        if (all.empty()) return insert_on_surface(VolumePolicy::Conserve);
        tin_.release_constraint(all[index(all.size())].id, VolumePolicy::Conserve, &s.report);
        return s;
    }

    StepResult attribute() {
        StepResult s{"set attribute", true, false, false, 0.0, {}};
        const VertexId v = random_vertex();
        switch (index(5)) {
            case 0: {
                const double h = tin_.height(v) + uniform(-0.1, 0.1);
                s.name = "set_height";
                s.conserves = false;
                s.known = true;
                s.known_change = tin_.vertices().lumped_area[v.index()] * (h - tin_.height(v));
                tin_.set_height(v, h);
                break;
            }
            case 1:
                s.name = "set_moisture";
                tin_.set_moisture(v, static_cast<float>(uniform(0.0, 1.0)));
                break;
            case 2:
                s.name = "set_material";
                tin_.set_material(v, static_cast<std::uint16_t>(index(4)));
                break;
            case 3:
                s.name = "set_slide";
                tin_.set_slide(v, {static_cast<float>(uniform(0.0, 1.0)), 0.25f});
                break;
            default:
                s.name = "set_height (unchanged)";
                tin_.set_height(v, tin_.height(v));
                break;
        }
        return s;
    }

    Tin& tin_;
    std::mt19937_64 rng_;
    Options options_;
    LocateHint hint_;
    Generation generation_ = 1;
};

}  // namespace sandtin::test
