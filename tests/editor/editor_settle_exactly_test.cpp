// The Erosion panel's Settle exactly (issue 39): the sand projected onto its angle of repose on
// a worker under the progress bar, applied as one undo level. Oracles: every triangle's own
// gradient against its sand's tan(alpha), the volume held, the analytic cone of that volume
// at repose, undo restoring the exact heights, and a cancelled run leaving them as they were.

#include <algorithm>
#include <cmath>

#include "editor_harness.hpp"
#include "io/scene_materials.hpp"
#include "physics/material.hpp"
#include "tin/vertex_arrays.hpp"

namespace sandtin::editor_test::settle_exactly {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// A 45-degree cone 0.2 m high on a flat 1 m sandbox of a 41 x 41 lattice (a lattice: a
/// random TIN's slivers can stand steeper than the surface they sample).
fs::path steep_cone_scene(const std::string& name) {
    std::vector<Vec2> points;
    std::vector<double> heights;
    for (int i = 0; i <= 40; ++i) {
        for (int j = 0; j <= 40; ++j) {
            const Vec2 p{i / 40.0, j / 40.0};
            points.push_back(p);
            heights.push_back(std::max(0.0, 0.2 - length(p - Vec2{0.5, 0.5})));
        }
    }
    Session session;
    session.terrain = Tin::from_points(Rect::from_size(1.0, 1.0), points, heights).snapshot();
    const fs::path path = kWork / (name + ".sandtin");
    fs::create_directories(kWork);
    save_session(path, session);
    return path;
}

std::string save_op(const fs::path& p) {
    return R"({"op": "save", "path": ")" + p.string() + R"("})";
}

/// The largest |grad h| / tan(alpha) over the triangles, each triangle's tan(alpha) the mean
/// of its corners' (their material and moisture), as the panel's Slope overlay judges.
double steepest_face_ratio(const Session& s) {
    const Tin tin = Tin::from_snapshot(s.terrain);
    const MaterialTable materials = materials_or_presets(s.metadata_json);
    const VertexArrays& va = tin.vertices();
    double worst = 0.0;
    for (const auto& t : tin.triangles()) {
        const Vec2 a = tin.position(t[0]), b = tin.position(t[1]), c = tin.position(t[2]);
        const double za = tin.height(t[0]), zb = tin.height(t[1]), zc = tin.height(t[2]);
        const Vec2 e1 = b - a, e2 = c - a;
        const double det = cross(e1, e2);
        const Vec2 g{((zb - za) * e2.y - (zc - za) * e1.y) / det,
                     (e1.x * (zc - za) - e2.x * (zb - za)) / det};
        double tan_alpha = 0.0;
        for (VertexId v : t)
            tan_alpha += materials.at(va.material[v.value])
                             .talus_slope(static_cast<double>(va.moisture[v.value])) /
                         3.0;
        worst = std::max(worst, length(g) / tan_alpha);
    }
    return worst;
}

/// The run's settle job's record (its saves are jobs too).
nlohmann::json settle_job(const EditorRun& r) {
    for (const nlohmann::json& job : r.stats.at("jobs")) {
        if (job.at("kind") == "settle") return job;
    }
    ADD_FAILURE() << "no settle job in " << r.stats.at("jobs");
    return {{"kind", "none"}, {"outcome", "none"}, {"fractions_shown", 0}};
}

double highest(const Session& s) {
    const Tin tin = Tin::from_snapshot(s.terrain);
    const VertexArrays& va = tin.vertices();
    double top = -1e300;
    for (std::size_t v = 0; v < va.size(); ++v) {
        if (va.alive[v]) top = std::max(top, va.height[v]);
    }
    return top;
}

TEST_F(EditorXvfb, SettleExactlyBringsAConeToReposeHoldingItsVolumeAndUndoesAsOneLevel) {
    const fs::path scene = steep_cone_scene("settle-cone");
    const fs::path before = kWork / "settle-before.sandtin",
                   settled = kWork / "settle-after.sandtin",
                   undone = kWork / "settle-undone.sandtin";
    // Erosion paused (an opened scene waits for Run): only the button moves the sand.
    const EditorRun r =
        run_editor("settle-exactly",
                   "[" + save_op(before) + R"(, {"op": "click", "widget": "Settle exactly"},
            {"op": "job", "until": "done", "frames": 3000}, )" +
                       save_op(settled) + R"(, {"op": "click", "widget": "Settle exactly"},
            {"op": "job", "until": "done", "frames": 3000},
            {"op": "key", "key": "z", "ctrl": true},
            {"op": "wait", "frames": 2}, )" +
                       save_op(undone) + "]",
                   scene.string() + fresh_settings("settle-exactly"));
    ASSERT_EQ(r.exit_code, 0) << r.log;
    EXPECT_EQ(r.stats.at("validation_messages").get<int>(), 0);
    const nlohmann::json job = settle_job(r);
    EXPECT_EQ(job.at("kind"), "settle") << job;
    EXPECT_EQ(job.at("outcome"), "done") << job;

    const Session s0 = load_session(before), s1 = load_session(settled), s2 = load_session(undone);
    const double tan_alpha = MaterialTable::presets().at(0).talus_slope(0.0);
    ASSERT_GT(steepest_face_ratio(s0), 1.5);  // 45 degrees against 32
    // At rest on every triangle, to the projection's tolerance (5e-5) and rounding.
    EXPECT_LE(steepest_face_ratio(s1), 1.0 + 1e-4);
    // The same sand: the volume over the lumped areas, exact to rounding.
    const Tin t0 = Tin::from_snapshot(s0.terrain), t1 = Tin::from_snapshot(s1.terrain);
    ASSERT_TRUE(t1.check_valid().ok()) << t1.check_valid().summary();
    EXPECT_NEAR(t1.volume(), t0.volume(), 1e-12 * t0.volume());
    // The cone of that volume at repose (V = pi H^3 / (3 tan^2 alpha)); the lattice's 2.5 cm
    // spacing rounds the apex (0.134 against 0.146 m in a direct projection of this lattice).
    const double apex = std::cbrt(3.0 * t0.volume() * tan_alpha * tan_alpha / kPi);
    EXPECT_NEAR(highest(s1), apex, 0.12 * apex);
    EXPECT_LT(highest(s1), highest(s0) - 0.03);
    // Pressed again on the settled sand, it finds nothing to do and adds no level.
    bool nothing_to_do = false;
    for (const auto& m : r.stats.at("messages"))
        nothing_to_do =
            nothing_to_do || m.get<std::string>().find("nothing is steeper") != std::string::npos;
    EXPECT_TRUE(nothing_to_do) << r.stats.at("messages");
    // One undo level: Ctrl+Z gives back the heights bit for bit.
    EXPECT_EQ(s2.terrain.vertices.height, s0.terrain.vertices.height);
    EXPECT_EQ(s2.terrain.vertices.position, s0.terrain.vertices.position);
}

TEST_F(EditorXvfb, SettleExactlyWithFitToeAndCrestPutsVerticesOnTheBendsAsOneLevel) {
    // With Fit toe and crest, a second projection follows one round of vertices on the first
    // one's bends (physics/settle_fitted_to_kinks.hpp): two settle jobs, the vertices and the
    // heights one undo level, the sand the same and at repose.
    const fs::path scene = steep_cone_scene("settle-fit-cone");
    const fs::path before = kWork / "settle-fit-before.sandtin",
                   settled = kWork / "settle-fit-after.sandtin",
                   undone = kWork / "settle-fit-undone.sandtin";
    const EditorRun r =
        run_editor("settle-fit",
                   "[" + save_op(before) + R"(, {"op": "click", "widget": "Fit toe and crest"},
            {"op": "click", "widget": "Settle exactly"},
            {"op": "job", "until": "done", "frames": 6000}, )" +
                       save_op(settled) + R"(, {"op": "key", "key": "z", "ctrl": true},
            {"op": "wait", "frames": 2}, )" +
                       save_op(undone) + "]",
                   scene.string() + fresh_settings("settle-fit"));
    ASSERT_EQ(r.exit_code, 0) << r.log;
    EXPECT_EQ(r.stats.at("validation_messages").get<int>(), 0);
    int settles = 0;
    for (const nlohmann::json& job : r.stats.at("jobs")) {
        if (job.at("kind") != "settle") continue;
        ++settles;
        EXPECT_EQ(job.at("outcome"), "done") << job;
    }
    EXPECT_EQ(settles, 2) << r.stats.at("jobs");
    bool fitted_said = false;
    for (const auto& m : r.stats.at("messages"))
        fitted_said = fitted_said ||
                      m.get<std::string>().find("vertices put on its bends") != std::string::npos;
    EXPECT_TRUE(fitted_said) << r.stats.at("messages");

    const Session s0 = load_session(before), s1 = load_session(settled), s2 = load_session(undone);
    const Tin t0 = Tin::from_snapshot(s0.terrain), t1 = Tin::from_snapshot(s1.terrain),
              t2 = Tin::from_snapshot(s2.terrain);
    ASSERT_TRUE(t1.check_valid().ok()) << t1.check_valid().summary();
    EXPECT_GT(t1.vertex_count(), t0.vertex_count() + 20);  // the toe's ring, at least
    EXPECT_NEAR(t1.volume(), t0.volume(), 1e-12 * t0.volume());
    EXPECT_LE(steepest_face_ratio(s1), 1.0 + 1e-4);
    // One undo level takes both away: the fitted vertices and the heights.
    EXPECT_EQ(t2.vertex_count(), t0.vertex_count());
    for (std::size_t v = 0; v < t0.vertices().size(); ++v) {
        if (!t0.vertices().alive[v]) continue;
        const VertexId id{static_cast<std::uint32_t>(v)};
        ASSERT_TRUE(t2.is_alive(id)) << v;
        EXPECT_EQ(t2.height(id), t0.height(id)) << v;
        EXPECT_EQ(t2.position(id), t0.position(id)) << v;
    }
}

TEST_F(EditorXvfb, ACancelledSettleShowedItsBarAndLeftTheTerrainAsItWas) {
    const fs::path scene = steep_cone_scene("settle-cancel-cone");
    const fs::path before = kWork / "settle-cancel-before.sandtin",
                   after = kWork / "settle-cancel-after.sandtin";
    const EditorRun r =
        run_editor("settle-cancel",
                   "[" + save_op(before) + R"(, {"op": "jobs", "wait": false, "pause_at": 0.3},
            {"op": "click", "widget": "Settle exactly"},
            {"op": "job", "until": "paused"}, {"op": "wait", "frames": 3},
            {"op": "cancel_job"}, {"op": "job", "until": "done"},
            {"op": "jobs", "wait": true}, {"op": "wait", "frames": 2}, )" +
                       save_op(after) + "]",
                   scene.string() + fresh_settings("settle-cancel"));
    ASSERT_EQ(r.exit_code, 0) << r.log;
    const nlohmann::json job = settle_job(r);
    EXPECT_EQ(job.at("kind"), "settle") << job;
    EXPECT_EQ(job.at("outcome"), "cancelled") << job;
    ASSERT_GT(job.at("fractions_shown").get<int>(), 0) << job;
    EXPECT_GE(job.at("fraction_max_shown").get<double>(), 0.3) << job;
    EXPECT_LT(job.at("fraction_max_shown").get<double>(), 1.0) << job;
    EXPECT_EQ(load_session(after).terrain.vertices.height,
              load_session(before).terrain.vertices.height);
    EXPECT_EQ(r.stats.at("validation_messages").get<int>(), 0);
}

}  // namespace
}  // namespace sandtin::editor_test::settle_exactly
