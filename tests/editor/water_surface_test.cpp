// The water's surface (issue 40, item 7): drawn over the terrain on the triangles with a wet
// corner only, semi-transparent and tinted by depth. Oracles: the triangles drawn are the
// scene's triangles with a wet corner, counted from the saved scene; a dry scene records no
// water pass; at the same spot, shallow water lets the sand show (redder than deep water) and
// is bluer than dry sand, and deep water is bluer still (Beer-Lambert along the view path).

#include <gtest/gtest.h>

#include <cstddef>
#include <fstream>
#include <string>

#include "editor_harness.hpp"
#include "formats/png_image.hpp"
#include "io/session_file.hpp"
#include "tin/tin.hpp"

namespace sandtin {
namespace {

using namespace editor_test;

/// A flat sandbox (40 x 40 cells at 5 cm) with `depth` metres of water on a disc of 0.35 m
/// about the middle.
fs::path pond_scene(const std::string& name, double depth) {
    Tin tin = Tin::regular_grid(Rect::from_size(1, 1), 40, 40, [](Vec2) { return 0.05; });
    for (std::uint32_t v = 0; v < tin.vertex_capacity(); ++v)
        if (length(tin.position(VertexId{v}) - Vec2{0.5, 0.5}) < 0.35)
            tin.set_water_depth(VertexId{v}, depth);
    Session session;
    session.terrain = tin.snapshot();
    const fs::path scene = kWork / (name + ".sandtin");
    fs::create_directories(scene.parent_path());
    save_session(scene, session);
    return scene;
}

/// Triangles of the saved scene with a wet corner.
std::size_t wet_triangles_in(const fs::path& scene) {
    const Tin tin = Tin::from_snapshot(load_session(scene).terrain);
    std::size_t n = 0;
    for (TriangleSlot s = 0; s < tin.slot_capacity(); ++s) {
        const auto c = tin.slot_triangle(s);
        if (!c[0].valid()) continue;
        bool wet = false;
        for (VertexId v : c)
            wet = wet || tin.vertices().water_depth[v.index()] > 0.0;
        n += wet ? 1 : 0;
    }
    return n;
}

struct Shot {
    Rgb centre;
    long long surface_triangles;
};

/// The pond seen by the default camera with the water standing still (not flowing, from the
/// first frame on: the settings say so) and the sand at rest.
Shot look_at(const std::string& name, const fs::path& scene) {
    const fs::path shot = kWork / (name + ".png");
    const fs::path settings = kWork / (name + ".settings.json");
    std::ofstream(settings) << R"({"water_flowing": false, "erosion_running": false})";
    const EditorRun r = run_editor(name, R"([{"op": "wait", "frames": 2}])",
                                   scene.string() + " --settings " + settings.string() +
                                       " --frames 2 --screenshot " + shot.string());
    EXPECT_EQ(r.exit_code, 0) << r.log;
    EXPECT_EQ(r.stats.at("validation_messages").get<int>(), 0);
    const PngImage im = read_png(shot);
    return {pixel(im, im.width / 2, im.height / 2),
            r.stats.at("water").at("surface_triangles").get<long long>()};
}

TEST_F(EditorXvfb, TheWaterSurfaceCoversTheWetTrianglesTintedByItsDepth) {
    const fs::path dry = pond_scene("pond-dry", 0.0);
    const fs::path shallow = pond_scene("pond-shallow", 0.002);
    const fs::path deep = pond_scene("pond-deep", 0.06);
    const Shot d = look_at("pond-dry", dry);
    const Shot s = look_at("pond-shallow", shallow);
    const Shot w = look_at("pond-deep", deep);

    EXPECT_EQ(d.surface_triangles, 0);  // a dry terrain records no water pass
    const std::size_t wet = wet_triangles_in(shallow);
    ASSERT_GT(wet, 100u);
    EXPECT_LT(wet, 3200u);  // the disc, not the whole sandbox
    EXPECT_EQ(s.surface_triangles, static_cast<long long>(wet));
    EXPECT_EQ(w.surface_triangles, static_cast<long long>(wet_triangles_in(deep)));

    // Sand is yellow; water over it turns it blue-green the more, the deeper it is.
    EXPECT_GT(d.centre.r, d.centre.b + 20.0);
    const auto blueness = [](const Rgb& c) { return c.b - c.r; };
    EXPECT_GT(blueness(s.centre), blueness(d.centre) + 5.0);
    EXPECT_GT(blueness(w.centre), blueness(s.centre) + 5.0);
    EXPECT_GT(w.centre.b, w.centre.r);
    // Semi-transparent: the sand under 2 mm of water still shows, redder than under 6 cm.
    EXPECT_GT(s.centre.r, w.centre.r + 20.0);
}

}  // namespace
}  // namespace sandtin
