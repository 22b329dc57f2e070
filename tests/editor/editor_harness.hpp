#pragma once
// The harness of the editor's Xvfb tests: runs the sandtin-editor binary under a private X
// server on whatever Vulkan device exists (lavapipe in CI), driven by a script of real input
// (X events, editor/app/x_input.hpp), with the validation layer on, and reads back its exit
// code, its stats and its log. Oracles the tests build on: pixel statistics of screenshots,
// and saved sessions read back through engine/io.

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "formats/png_image.hpp"
#include "geom/vec2.hpp"
#include "io/session_file.hpp"
#include "tin/tin.hpp"

namespace sandtin::editor_test {

namespace fs = std::filesystem;

/// The tests' work folder (build tree).
extern const fs::path kWork;

struct EditorRun {
    int exit_code = -1;
    nlohmann::json stats;
    std::string log;
};

bool have_xvfb();

/// Runs the editor on a script (a JSON "ops" array) with `extra` arguments (a scene, --size,
/// --settings, ...) and returns its exit code, stats and log. The settings file is
/// kWork/settings.json unless `extra` names another.
EditorRun run_editor(const std::string& name, const std::string& ops,
                     const std::string& extra = "");

struct Rgb {
    double r, g, b;
};
Rgb pixel(const PngImage& im, std::uint32_t x, std::uint32_t y);
/// Mean colour of the (2 half + 1)² pixels around (x, y), clipped to the image: a colour that
/// one glint, cursor pixel or grain of the sand's texture cannot decide.
Rgb mean_pixel(const PngImage& im, int x, int y, int half);
double luminance(Rgb c);
/// Mean absolute difference of two images over a rectangle (all channels).
double mean_diff(const PngImage& a, const PngImage& b, int x0, int y0, int x1, int y1);

/// An autosave written by write_autosave_raising_a_vertex: the session it holds and the index
/// of the vertex it raised.
struct EditedAutosave {
    Session session;
    std::size_t raised = 0;
};
/// Writes the autosave of the scene saved at `scene`: that session with its first live vertex
/// raised by `metres`.
EditedAutosave write_autosave_raising_a_vertex(const fs::path& scene, double metres);

/// A flat sandbox script: erosion off, two frames.
extern const char* const kFlat;
/// A Ball stroke across the middle of the view from (0.45, 0.5) to (0.75, 0.5), then a pour.
extern const char* const kStroke;

/// The script `ops` (a JSON array) followed by the ops in `more` (comma-separated objects).
std::string then(const std::string& ops, const std::string& more);

/// `count` points uniform in the unit square from a fixed generator (the same on every
/// platform, unlike the standard distributions).
std::vector<Vec2> unit_square_points(int count, std::uint64_t seed);

/// Writes a flat scene (at `height` metres) over `points` on a size x size terrain to `path`;
/// returns the session it wrote.
Session save_flat_scene(const fs::path& path, double size, const std::vector<Vec2>& points,
                        double height = 0.0);

/// The largest height difference between two terrains at the vertices of `a` (interpolated on
/// `b`): 0, up to the rounding of the interpolation, when they are the same surface.
double surface_difference(const Tin& a, const Tin& b);

/// " --settings <file>" naming a settings file of its own for the run `name`, removed first:
/// runs must not share what they change.
std::string fresh_settings(const std::string& name);

class EditorXvfb : public ::testing::Test {
  protected:
    void SetUp() override {
        if (!have_xvfb()) GTEST_SKIP() << "xvfb-run is not installed";
    }
};

}  // namespace sandtin::editor_test
