#include "editor_harness.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <optional>

#include <sys/wait.h>

#include "io/autosave.hpp"
#include "tin/tin.hpp"
#include "tin/tin_snapshot.hpp"

namespace sandtin::editor_test {

const fs::path kWork = fs::path(SANDTIN_EDITOR_TEST_WORK);

bool have_xvfb() {
    return std::system("command -v xvfb-run > /dev/null 2>&1") == 0;
}

EditorRun run_editor(const std::string& name, const std::string& ops, const std::string& extra) {
    fs::create_directories(kWork);
    const fs::path script = kWork / (name + ".json");
    std::ofstream(script) << R"({"ops": )" << ops << "}";
    const fs::path stats = kWork / (name + ".stats.json");
    const fs::path log = kWork / (name + ".log");
    // The screen is larger than any window a test opens, so that the pointer (which X keeps
    // on the screen) reaches every control. Our own X authority file: without -f, xvfb-run keeps it
    // in a temporary directory whose removal at exit can fail, and then xvfb-run exits with 5
    // instead of the editor's code (seen once on CI, on a run whose editor had exited with 1 as
    // expected).
    const fs::path auth = kWork / (name + ".Xauthority");
    fs::remove(stats);
    fs::remove(auth);
    const std::string cmd = "xvfb-run -a -f " + auth.string() +
                            " -s '-screen 0 1920x1600x24' " SANDTIN_EDITOR_BINARY " --validation" +
                            std::string(" --settings ") + (kWork / "settings.json").string() +
                            " --script " + script.string() + " --stats " + stats.string() + " " +
                            extra + " > " + log.string() + " 2>&1";
    EditorRun r;
    const int status = std::system(cmd.c_str());
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    fs::remove(auth);
    std::ifstream l(log);
    r.log.assign(std::istreambuf_iterator<char>(l), {});
    if (std::ifstream s(stats); s) r.stats = nlohmann::json::parse(s);
    return r;
}

Rgb pixel(const PngImage& im, std::uint32_t x, std::uint32_t y) {
    return {static_cast<double>(im.sample(x, y, 0)), static_cast<double>(im.sample(x, y, 1)),
            static_cast<double>(im.sample(x, y, 2))};
}

Rgb mean_pixel(const PngImage& im, int x, int y, int half) {
    Rgb sum{0.0, 0.0, 0.0};
    int n = 0;
    for (int py = std::max(0, y - half); py <= std::min(int(im.height) - 1, y + half); ++py) {
        for (int px = std::max(0, x - half); px <= std::min(int(im.width) - 1, x + half); ++px) {
            const Rgb c = pixel(im, static_cast<std::uint32_t>(px), static_cast<std::uint32_t>(py));
            sum.r += c.r;
            sum.g += c.g;
            sum.b += c.b;
            ++n;
        }
    }
    if (n == 0) {
        ADD_FAILURE() << "mean_pixel: the window around (" << x << ", " << y
                      << ") lies outside the image";
        return sum;
    }
    return {sum.r / n, sum.g / n, sum.b / n};
}

EditedAutosave write_autosave_raising_a_vertex(const fs::path& scene, double metres) {
    EditedAutosave out{load_session(scene)};
    const std::vector<std::uint8_t>& alive = out.session.terrain.vertices.alive;
    while (out.raised < alive.size() && !alive[out.raised])
        ++out.raised;
    out.session.terrain.vertices.height.at(out.raised) += metres;
    write_autosave(scene, out.session);
    return out;
}

double luminance(Rgb c) {
    return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
}

/// Mean absolute difference of two images over a rectangle (all channels).
double mean_diff(const PngImage& a, const PngImage& b, int x0, int y0, int x1, int y1) {
    double sum = 0.0;
    int n = 0;
    for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; ++x) {
            for (int c = 0; c < 3; ++c) {
                sum += std::abs(
                    static_cast<double>(
                        a.sample(static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y), c)) -
                    b.sample(static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y), c));
                ++n;
            }
        }
    }
    return sum / n;
}

const char* const kFlat = R"([{"op": "set", "erosion": false}, {"op": "wait", "frames": 2}])";
// A Ball stroke across the middle of the view from (0.45, 0.5) to (0.75, 0.5), then a pour.
const char* const kStroke = R"([{"op": "set", "erosion": false},
    {"op": "tool", "name": "Ball"}, {"op": "set", "radius": 0.05, "depth": 0.015},
    {"op": "drag", "path": [[0.45, 0.5], [0.75, 0.5]], "steps": 30},
    {"op": "tool", "name": "Pour"}, {"op": "click", "at": [0.62, 0.3]},
    {"op": "move", "at": [0.62, 0.3]}, {"op": "wait", "frames": 2}])";

/// The script `ops` (a JSON array) followed by the ops in `more` (comma-separated objects).
std::string then(const std::string& ops, const std::string& more) {
    return ops.substr(0, ops.rfind(']')) + ", " + more + "]";
}

/// `count` points uniform in the unit square from a fixed generator (the same on every
/// platform, unlike the standard distributions).
std::vector<Vec2> unit_square_points(int count, std::uint64_t seed) {
    std::vector<Vec2> points;
    std::uint64_t state = seed;
    for (int i = 0; i < count; ++i) {
        Vec2 p;
        for (double* x : {&p.x, &p.y}) {
            state = state * 6364136223846793005ull + 1442695040888963407ull;
            *x = static_cast<double>(state >> 11) * 0x1.0p-53;
        }
        points.push_back(p);
    }
    return points;
}

/// Writes a flat scene (at `height` metres) over `points` on a size x size terrain to `path`;
/// returns the session it wrote.
Session save_flat_scene(const fs::path& path, double size, const std::vector<Vec2>& points,
                        double height) {
    Session session;
    session.terrain = Tin::from_points(Rect::from_size(size, size), points,
                                       std::vector<double>(points.size(), height))
                          .snapshot();
    fs::create_directories(path.parent_path());
    save_session(path, session);
    return session;
}

std::string fresh_settings(const std::string& name) {
    const fs::path p = kWork / (name + ".settings.json");
    fs::remove(p);
    return " --settings " + p.string();
}

double surface_difference(const Tin& a, const Tin& b) {
    double worst = 0.0;
    const VertexArrays& va = a.vertices();
    for (std::size_t i = 0; i < va.size(); ++i) {
        if (!va.alive[i]) continue;
        const std::optional<double> h = b.height_at(va.position[i]);
        worst = std::max(worst, h ? std::abs(*h - va.height[i]) : 1e300);
    }
    return worst;
}

}  // namespace sandtin::editor_test
