#pragma once
// Helpers for the TIN-side haptics tests: the test tool and terrain, terrain equality, and
// running a child process (sandtin, sandtin-haptic-replay).

#include <fcntl.h>
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/wait.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "haptics/haptic_recording.hpp"
#include "tin/tin.hpp"

extern char** environ;

namespace sandtin::haptics::test {

inline nlohmann::json circle_tool_json() {
    return {{"contour", "circle"}, {"radius", 0.04}, {"control_points", 12}};
}

/// 1 x 1 m of sand 5 cm deep on 400 random points.
inline ScriptTerrain test_terrain() {
    ScriptTerrain t;
    t.size = {1.0, 1.0};
    t.points = 400;
    t.seed = 7;
    t.height = 0.05;
    return t;
}

/// A headless session's TIN, as `sandtin run` makes it: no change journal. With a journal
/// (the editor's GPU mirror) freed ids are recycled only when the mirror takes the changes, so
/// vertex ids depend on frame timing; without one, ids depend only on the edits.
inline TinOptions headless() {
    TinOptions o;
    o.track_changes = false;
    return o;
}

/// Same vertices (ids, positions, heights, liveness) and same triangles in the same slots.
inline void expect_same_terrain(const Tin& a, const Tin& b) {
    const TinSnapshot sa = a.snapshot();
    const TinSnapshot sb = b.snapshot();
    ASSERT_EQ(sa.vertices.size(), sb.vertices.size());
    EXPECT_TRUE(sa.vertices.alive == sb.vertices.alive);
    EXPECT_TRUE(sa.vertices.height == sb.vertices.height);
    EXPECT_TRUE(sa.vertices.position == sb.vertices.position);
    EXPECT_TRUE(sa.slots == sb.slots);
    EXPECT_TRUE(sa.constraints == sb.constraints);
    EXPECT_EQ(a.volume(), b.volume());
}

/// Starts argv[0] with the arguments, stdout and stderr to files; returns its pid (or -1).
inline pid_t start_process(const std::vector<std::string>& args, const std::filesystem::path& out,
                           const std::filesystem::path& err) {
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    std::vector<char*> argv;
    for (const std::string& a : args)
        argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    pid_t pid = 0;
    const int rc = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    return rc == 0 ? pid : -1;
}

/// Waits for a started process; its exit code, or -1 when it did not exit normally.
inline int wait_process(pid_t pid) {
    if (pid <= 0) return -1;
    int status = 0;
    if (waitpid(pid, &status, 0) != pid) return -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/// Runs a process to completion (see start_process).
inline int run_process(const std::vector<std::string>& args, const std::filesystem::path& out,
                       const std::filesystem::path& err) {
    return wait_process(start_process(args, out, err));
}

/// A fresh directory under the build tree for one test.
inline std::filesystem::path scratch_dir(const std::string& name) {
    const std::filesystem::path d = std::filesystem::current_path() / ("haptics-" + name);
    std::filesystem::remove_all(d);
    std::filesystem::create_directories(d);
    return d;
}

inline std::string read_text(const std::filesystem::path& p) {
    std::ifstream in(p);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace sandtin::haptics::test
