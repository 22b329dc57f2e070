// A very long stroke (issue 9 §2): 10⁵ stamps in one stroke that keeps re-working the same
// trail. Re-stamping sand that already holds the imprint changes nothing, older rims under a
// footprint are released and their vertices simplified away, and constraints expire without a
// scan of all of them, so the vertex and constraint counts follow the worked area rather than
// the number of stamps, the mesh stays valid and the stroke reports what the terrain lost.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "stress/terrain_invariants.hpp"
#include "tin/tin.hpp"
#include "tools/sculpt_context.hpp"
#include "tools/stroke.hpp"
#include "tools/tool.hpp"

namespace sandtin {
namespace {

double mean(const std::vector<std::size_t>& c, double from, double to) {
    const auto i0 = static_cast<std::size_t>(from * static_cast<double>(c.size()));
    const auto i1 = static_cast<std::size_t>(to * static_cast<double>(c.size()));
    double sum = 0.0;
    for (std::size_t i = i0; i < i1; ++i)
        sum += static_cast<double>(c[i]);
    return sum / static_cast<double>(i1 - i0);
}

std::size_t peak(const std::vector<std::size_t>& c, double from, double to) {
    const auto i0 = static_cast<std::size_t>(from * static_cast<double>(c.size()));
    const auto i1 = static_cast<std::size_t>(to * static_cast<double>(c.size()));
    return *std::max_element(c.begin() + static_cast<std::ptrdiff_t>(i0),
                             c.begin() + static_cast<std::ptrdiff_t>(i1));
}

TEST(LongStroke, HundredThousandStampsStayBoundedAndValid) {
    Tin tin = Tin::random_points(
        Rect::from_size(1.0, 1.0), 400, 21, [](Vec2) { return 0.1; },
        TinOptions{.track_changes = false});
    SculptContext ctx(tin.domain());
    ToolSpec spec;
    spec.contour = ContourKind::Circle;
    spec.radius = 0.004;
    spec.control_points = 12;
    const Tool tool = Tool::build(spec);

    // Loops round a circle, the tool's bottom 5 mm under the 0.1 m sand, following the path.
    // The stamps sit 2.5 radii apart (a dotted trail that later laps fill in at other offsets,
    // the hardest case: every lap meets the previous laps' rims at new places). After the
    // first laps the tool only re-works its own trail. (A relative depth would dig 2 mm deeper
    // every lap, a different test.)
    const double stamps_wanted = 1.0e5;
    StrokeSettings s;
    s.spacing = 2.5 * spec.radius;
    s.depth_mode = DepthMode::Absolute;
    s.depth = 0.095;
    const double loop_radius = 0.1;
    const double circumference = 2.0 * std::numbers::pi * loop_radius;
    const int per_lap = 90;
    const int laps = static_cast<int>(std::ceil(stamps_wanted * s.spacing / circumference)) + 1;
    std::vector<Vec2> path;
    for (int k = 0; k <= laps * per_lap; ++k) {
        const double a = 2.0 * std::numbers::pi * k / per_lap;
        path.push_back({0.5 + loop_radius * std::cos(a), 0.5 + loop_radius * std::sin(a)});
    }

    const double v0 = tin.volume();
    std::vector<std::size_t> constraints;
    std::vector<std::size_t> vertices;
    std::string invalid;
    const StampReport r = apply_stroke(tin, tool, path, s, ctx, nullptr, [&](const StampReport&) {
        constraints.push_back(tin.constraint_count());
        vertices.push_back(tin.vertex_count());
        if (vertices.size() % 20000 == 0 && invalid.empty()) {
            const ValidationReport v = tin.check_valid();
            if (!v.ok()) invalid = "after " + std::to_string(vertices.size()) + ": " + v.summary();
        }
    });
    EXPECT_EQ(invalid, "");
    const std::size_t stamps = constraints.size();
    ASSERT_GE(stamps, static_cast<std::size_t>(stamps_wanted));
    const auto v = check_terrain_invariants(tin, ctx.peek_generation(), {});
    EXPECT_FALSE(v.has_value()) << v->invariant << ": " << v->detail;
    EXPECT_NEAR(tin.volume() - v0, r.volume_change, 1e-9);
    EXPECT_LT(tin.volume(), v0);

    // Plateau: the second half of the stroke must add less than a quarter of what the first
    // half added (middle and end are window means, to smooth stamp-to-stamp jitter). A count that
    // grows with the number of stamps grows about as much in both halves (ratio 1); one that
    // follows the worked area levels off once the trail is carved.
    for (const auto& [name, c] :
         {std::pair{"vertices", &vertices}, std::pair{"constraints", &constraints}}) {
        const auto start = static_cast<double>(c->front());
        const double middle = mean(*c, 0.45, 0.55);
        const double end = mean(*c, 0.9, 1.0);
        EXPECT_LE(end - middle, 0.25 * (middle - start))
            << name << ": " << start << " -> " << middle << " (middle) -> " << end
            << " (end); peak " << peak(*c, 0.0, 1.0);
    }
    std::cout << "[ info     ] " << stamps << " stamps; vertices " << vertices.front() << " -> "
              << peak(vertices, 0.0, 1.0) << " (peak) -> " << vertices.back() << ", constraints "
              << constraints.back() << "\n";
}

}  // namespace
}  // namespace sandtin
