#include "default_sandbox.hpp"

#include <cmath>
#include <random>
#include <vector>

#include "physics/sand_physics.hpp"
#include "tin/flat_bedrock.hpp"

namespace sandtin::editor {

/// A new sandbox: 1 m x 1 m of sand 2 to 10 cm deep over a flat bedrock, with two crossing dune
/// trains and wind ripples, and a band of moist sand along the south edge. Random points (no
/// cocircular quads inside, so undo restores the exact triangulation), 40 000 of them: about
/// 5 mm apart, fine enough for the ripples. At rest under the default relaxation.
Tin default_sandbox() {
    const Rect domain{{0.0, 0.0}, {1.0, 1.0}};
    auto height = [](Vec2 p) {
        const double dunes = 0.018 * std::sin(8.0 * p.x + 2.2 * std::sin(3.5 * p.y)) +
                             0.008 * std::cos(11.0 * p.y - 4.0 * p.x);
        const double ripples =
            0.0015 * std::sin(95.0 * p.x + 25.0 * p.y + 6.0 * std::sin(5.0 * p.y));
        return 0.06 + dunes + ripples;
    };
    // Random interior points, plus points every 5 mm along the border so the dunes reach the
    // edge (with only the corners there, long slivers would join the dunes to straight edges).
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<Vec2> points;
    for (int i = 0; i < 40000; ++i)
        points.push_back({u(rng), u(rng)});
    constexpr int kBorder = 200;
    for (int i = 0; i <= kBorder; ++i) {
        const double t = static_cast<double>(i) / kBorder;
        points.insert(points.end(), {{t, 0.0}, {t, 1.0}, {0.0, t}, {1.0, t}});
    }
    std::vector<double> heights;
    heights.reserve(points.size());
    for (Vec2 p : points)
        heights.push_back(height(p));
    Tin tin = Tin::from_points(domain, points, heights);
    lay_flat_bedrock(tin, 0.02);
    const VertexArrays& va = tin.vertices();
    for (std::uint32_t i = 0; i < va.size(); ++i) {
        if (!va.alive[i]) continue;
        const VertexId v{i};
        if (va.position[i].y < 0.18 + 0.04 * std::sin(9.0 * va.position[i].x)) {
            tin.set_material(v, 1);
            tin.set_moisture(v, 0.3f);
        }
    }
    // At rest before anyone touches it: under the face rule a few of the random points' thin
    // triangles stand steeper than repose on the dunes' flanks, and a new sandbox would
    // otherwise slide (by about 1e-5 m) as soon as the erosion first ran.
    SandPhysics physics(tin, MaterialTable::presets(), TalusSettings{});
    physics.activate_all();
    physics.run_to_rest(100000);
    return tin;
}

}  // namespace sandtin::editor
