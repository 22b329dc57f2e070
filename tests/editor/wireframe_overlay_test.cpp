// The Wireframe overlay draws every triangle's edges over the surface (from the triangles'
// own index buffer, as line polygons, where the device has them). Oracle: a flat 24 x 24 grid
// seen with and without it: with it, dark lines darken a share of the sand's pixels that is
// neither nothing nor the whole terrain, and no sand pixel gets brighter.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>

#include "editor_harness.hpp"
#include "formats/png_image.hpp"
#include "io/session_file.hpp"
#include "tin/tin.hpp"

namespace sandtin {
namespace {

using namespace editor_test;

PngImage screenshot(const std::string& name, const fs::path& scene, bool wireframe) {
    const fs::path shot = kWork / (name + ".png");
    const EditorRun r =
        run_editor(name,
                   std::string(R"([{"op": "set", "erosion": false, "wireframe": )") +
                       (wireframe ? "true" : "false") + R"(}, {"op": "wait", "frames": 2}])",
                   scene.string() + " --frames 2 --screenshot " + shot.string());
    EXPECT_EQ(r.exit_code, 0) << r.log;
    EXPECT_EQ(r.stats.at("validation_messages").get<int>(), 0);
    return read_png(shot);
}

double brightness(const Rgb& c) {
    return (c.r + c.g + c.b) / 3.0;
}

TEST_F(EditorXvfb, WireframeDrawsTheTrianglesEdgesOverTheSurface) {
    const fs::path scene = kWork / "wireframe-grid.sandtin";
    Session session;
    session.terrain =
        Tin::regular_grid(Rect::from_size(1, 1), 24, 24, [](Vec2) { return 0.05; }).snapshot();
    fs::create_directories(scene.parent_path());
    save_session(scene, session);
    const PngImage off = screenshot("wireframe-off", scene, false);
    const PngImage on = screenshot("wireframe-on", scene, true);
    ASSERT_EQ(off.width, on.width);
    ASSERT_EQ(off.height, on.height);
    int darkened = 0, brightened = 0, sand = 0;
    for (std::uint32_t y = 0; y < on.height; ++y) {
        for (std::uint32_t x = 0; x < on.width; ++x) {
            const Rgb a = pixel(off, x, y), b = pixel(on, x, y);
            // The lit sand only: not the sky, nor the panels, whose timings differ run to run.
            if (!(a.r > 100.0 && a.r > a.b + 20.0)) continue;
            ++sand;
            const double d = brightness(b) - brightness(a);
            if (d < -30.0) ++darkened;
            if (d > 30.0) ++brightened;
        }
    }
    ASSERT_GT(sand, 100000) << "the grid fills a good part of the frame";
    // 24 x 24 cells, each with a diagonal: about 1 900 edges on screen, a few pixels wide.
    EXPECT_GT(darkened, sand / 50) << darkened << " of " << sand;
    EXPECT_LT(darkened, sand / 2) << darkened << " of " << sand;
    EXPECT_EQ(brightened, 0);
}

}  // namespace
}  // namespace sandtin
