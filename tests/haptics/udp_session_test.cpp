// The network path end to end: sandtin-haptic-replay (a separate process standing in for a
// hardware driver) plays the stroke over UDP on loopback to a headless session here (force
// loop on its thread with a UdpDevice, simulation on the test thread). Checks the round trip
// (every pose answered; every force the driver logged is one the loop recorded for that pose)
// and that replaying the session's recording in-process gives the same terrain.

#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <thread>

#include "haptics/live_session.hpp"
#include "haptics/recording_replay.hpp"
#include "haptics/udp_device.hpp"
#include "test_support.hpp"
#include "tools/tool_json.hpp"

namespace sandtin::haptics {
namespace {

struct LoggedForce {
    std::uint32_t ack = 0;
    Vec3 position;
    Vec3 force;
};

std::vector<LoggedForce> read_force_log(const std::filesystem::path& path) {
    std::ifstream in(path);
    std::string line;
    std::getline(in, line);  // header
    std::vector<LoggedForce> out;
    while (std::getline(in, line)) {
        std::replace(line.begin(), line.end(), ',', ' ');
        std::istringstream ss(line);
        LoggedForce f;
        std::uint32_t buttons = 0, flags = 0;
        ss >> f.ack >> f.position.x >> f.position.y >> f.position.z >> buttons >> flags >>
            f.force.x >> f.force.y >> f.force.z;
        EXPECT_FALSE(ss.fail()) << line;
        out.push_back(f);
    }
    return out;
}

// With `backup`, a second loop thread races the primary for every tick (margin 0), so the UDP
// device is driven from both threads in turn; the round trip must be just as exact.
void check_replay_process_drives_a_headless_session(bool backup) {
    const std::filesystem::path dir = test::scratch_dir(backup ? "udp_backup" : "udp");
    const std::string trajectory_path = SANDTIN_HAPTICS_ASSETS "/stroke.traj";
    const Trajectory trajectory = load_trajectory(trajectory_path);
    const ScriptTerrain terrain = test::test_terrain();
    Tin live = make_recording_terrain(terrain, test::headless());
    SculptContext context(live.domain());
    const TerrainSummary start = summarise(live);
    auto tool = std::make_shared<const Tool>(
        Tool::build(parse_tool_spec(test::circle_tool_json(), ".", "tool")));
    LiveEditor editor(live, tool, context, {});

    UdpDeviceConfig udp;
    udp.loss_timeout_ns = 5'000'000'000;  // a loaded machine may pause the driver
    UdpDevice device(udp);
    ForceLoopConfig config;
    config.record_capacity = 4 * trajectory.samples.size();
    config.try_realtime = false;
    config.backup_thread = backup;
    config.backup_margin_ns = 0;
    ForceLoop loop(device, config);
    LiveSession session(editor, loop);
    loop.start();

    // The driver runs as its own process; the simulation steps here until it says bye.
    const std::string port = std::to_string(device.port());
    std::thread driver_thread;
    int driver_rc = -1;
    driver_thread = std::thread([&] {
        driver_rc = test::run_process(
            {SANDTIN_HAPTIC_REPLAY, "play", trajectory_path, "--port", port, "--lockstep",
             "--timeout-ms", "2000", "--log", (dir / "forces.csv").string()},
            dir / "replay.json", dir / "replay.err");
    });
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(90);
    while (loop.running() && std::chrono::steady_clock::now() < give_up) {
        session.step();
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    session.step();
    loop.stop();
    driver_thread.join();
    ASSERT_EQ(driver_rc, 0) << test::read_text(dir / "replay.err")
                            << test::read_text(dir / "replay.json");
    const UdpDeviceCounters counters = device.counters();
    EXPECT_TRUE(counters.bye);
    EXPECT_EQ(counters.malformed, 0u);
    EXPECT_EQ(counters.poses, trajectory.samples.size());

    // Round trip: the driver logged one force per pose, each one the loop rendered for the
    // pose it acknowledges, bit for bit.
    const std::vector<LoggedForce> logged = read_force_log(dir / "forces.csv");
    ASSERT_EQ(logged.size(), trajectory.samples.size());
    const std::vector<TickRecord>& records = loop.records();
    ASSERT_LT(records.size(), records.capacity()) << "record capacity too small";
    std::size_t r = 0;
    double max_force = 0.0;
    for (const LoggedForce& f : logged) {
        EXPECT_EQ(f.position, trajectory.samples[f.ack - 1].position);
        // Records are in tick order and acks increase: walk forward to the first tick that
        // used this pose.
        while (r < records.size() &&
               !(records[r].device.valid && records[r].device.sequence == f.ack)) {
            ++r;
        }
        ASSERT_LT(r, records.size()) << "no tick used pose " << f.ack;
        EXPECT_EQ(records[r].device.position, f.position);
        EXPECT_EQ(records[r].force, f.force) << "pose " << f.ack;
        max_force = std::max(max_force, length(f.force));
    }
    EXPECT_GT(max_force, 3.0);  // the stroke was felt through the network

    // The session's recording replays in-process into the same terrain.
    save_recording(dir / "session.haptic.json",
                   make_recording(1000.0, test::circle_tool_json(), {}, terrain, 1, start, records,
                                  session.edits(), live));
    const HapticRecording rec = load_recording(dir / "session.haptic.json");
    EXPECT_GT(editor.total_stamps(), 20u);
    Tin replayed = make_recording_terrain(*rec.terrain, test::headless());
    SculptContext replay_context(replayed.domain());
    const nlohmann::json report = replay_recording(rec, replayed, replay_context, dir);
    EXPECT_TRUE(report["result_matches_recording"].get<bool>());
    test::expect_same_terrain(live, replayed);
    // Every tick ran once, in order, whichever thread ran it.
    for (std::size_t i = 0; i < records.size(); ++i)
        ASSERT_EQ(records[i].tick, i);
}

TEST(UdpSession, ReplayProcessDrivesAHeadlessSessionOverLoopback) {
    check_replay_process_drives_a_headless_session(false);
}

TEST(UdpSession, WithABackupLoopThreadTheRoundTripIsAsExact) {
    check_replay_process_drives_a_headless_session(true);
}

}  // namespace
}  // namespace sandtin::haptics
