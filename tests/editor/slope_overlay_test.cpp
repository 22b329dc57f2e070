// The Slope overlay judges faces, not vertices: on screen, against the same criterion as
// physics/face_slopes (|grad h| > tan(alpha) (1 + 1e-3) is red). Oracles: planes whose every
// face has a known gradient, and a single raised vertex whose faces are steep while the mean
// plane around every vertex is gentle (what the per-vertex overlay showed green).

#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "editor_harness.hpp"
#include "formats/png_image.hpp"
#include "io/session_file.hpp"
#include "physics/face_slopes.hpp"
#include "physics/material.hpp"
#include "tin/tin.hpp"

namespace sandtin {
namespace {

using namespace editor_test;

double dry_tan() {
    return MaterialTable::presets().at(0).talus_slope(0.0);
}

/// Pixels the overlay paints red (over-steep), anywhere in the frame.
int red_pixels(const PngImage& im) {
    int n = 0;
    for (std::uint32_t y = 0; y < im.height; ++y) {
        for (std::uint32_t x = 0; x < im.width; ++x) {
            const Rgb c = pixel(im, x, y);
            if (c.r > 80.0 && c.r > 1.6 * c.g && c.r > 1.6 * c.b) ++n;
        }
    }
    return n;
}

/// Screenshot of `terrain` with the Slope overlay on and erosion off; returns its red pixels.
int red_pixels_of(const std::string& name, const Tin& terrain) {
    const fs::path scene = kWork / (name + ".sandtin");
    const fs::path shot = kWork / (name + ".png");
    Session session;
    session.terrain = terrain.snapshot();
    fs::create_directories(scene.parent_path());
    save_session(scene, session);
    const EditorRun r = run_editor(name,
                                   R"([{"op": "set", "erosion": false, "slope": true},
                                       {"op": "wait", "frames": 2}])",
                                   scene.string() + " --frames 2 --screenshot " + shot.string());
    EXPECT_EQ(r.exit_code, 0) << r.log;
    EXPECT_EQ(r.stats.at("validation_messages").get<int>(), 0);
    return red_pixels(read_png(shot));
}

Tin plane(double gradient) {
    return Tin::regular_grid(Rect::from_size(1, 1), 24, 24,
                             [gradient](Vec2 p) { return 0.05 + gradient * 0.1 * p.x; });
}

TEST_F(EditorXvfb, SlopeOverlayIsRedOnFacesSteeperThanReposeOnly) {
    // 0.1 m over the 1 m side at these ratios, against dry sand's repose.
    const Tin gentle = plane(0.95 * dry_tan() / 0.1);
    const Tin steep = plane(1.05 * dry_tan() / 0.1);
    ASSERT_EQ(measure_face_slopes(gentle, MaterialTable::presets()).steep_faces, 0u);
    ASSERT_EQ(measure_face_slopes(steep, MaterialTable::presets()).steep_faces,
              steep.triangle_count());
    EXPECT_EQ(red_pixels_of("slope-gentle", gentle), 0);
    // The terrain fills a good part of the 1280 x 720 frame.
    EXPECT_GT(red_pixels_of("slope-steep", steep), 50000);
}

TEST_F(EditorXvfb, SlopeOverlayShowsASteepBumpThatEveryVertexsMeanPlaneHides) {
    // One vertex of a flat 24 x 24 grid raised by 3 cm: its six faces rise 3 cm over a cell
    // (4.2 cm), far steeper than repose, while the mean plane around it (and around each of its
    // neighbours) stays well under it.
    Tin bump = Tin::regular_grid(Rect::from_size(1, 1), 24, 24, [](Vec2) { return 0.05; });
    const Location at = bump.locate({0.5, 0.5});
    ASSERT_EQ(at.kind, Location::Kind::OnVertex);
    int corner = 0;
    for (int k = 1; k < 3; ++k)
        if (at.barycentric[k] > at.barycentric[corner]) corner = k;
    bump.set_height(at.corners[corner], 0.08);
    const FaceSlopeReport faces = measure_face_slopes(bump, MaterialTable::presets());
    ASSERT_GE(faces.steep_faces, 6u);
    ASSERT_GT(faces.max_ratio, 1.1);
    EXPECT_GT(red_pixels_of("slope-bump", bump), 100);
}

}  // namespace
}  // namespace sandtin
