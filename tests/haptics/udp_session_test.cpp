// The network path end to end: sandtin-haptic-replay (a separate process standing in for a
// hardware driver) plays the stroke over UDP on loopback to a headless session here (force
// loop on its thread with a UdpDevice, simulation on the test thread). Checks the round trip
// (every pose answered; every force the driver logged is one the loop recorded for that pose)
// and that replaying the session's recording in-process gives the same terrain.

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <fstream>
#include <sstream>
#include <thread>

#include "haptics/live_session.hpp"
#include "haptics/recording_replay.hpp"
#include "haptics/udp_device.hpp"
#include "haptics/udp_protocol.hpp"
#include "haptics/udp_session_server.hpp"
#include "haptics/udp_socket.hpp"
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

// A driver glitch in the middle of a live session: finite poses far beyond the terrain (z =
// -2e9 m, then 1e300 m). The session served in-process (what `sandtin haptics serve` runs) drops
// them as malformed, so its recording loads and replays into the same terrain.
TEST(UdpSession, AGlitchedPoseDoesNotMakeTheRecordingUnreplayable) {
    const std::filesystem::path dir = test::scratch_dir("udp_glitch");
    const ScriptTerrain terrain = test::test_terrain();
    Tin live = make_recording_terrain(terrain, test::headless());
    SculptContext context(live.domain());
    UdpServeOptions options;
    options.device.loss_timeout_ns = 5'000'000'000;  // a loaded machine may pause the driver
    options.loop.try_realtime = false;
    options.tool = test::circle_tool_json();
    options.terrain = terrain;
    options.max_seconds = 60.0;
    std::atomic<std::uint16_t> port{0};
    options.on_listening = [&](std::uint16_t p) { port.store(p); };

    // Hover, a stroke 5 mm deep, the glitch (button up, as in the audit), the stroke again.
    std::vector<PosePacket> poses;
    for (int i = 0; i < 20; ++i)
        poses.push_back({{0.3, 0.5, 0.2}, 0});
    for (int i = 0; i < 40; ++i)
        poses.push_back({{0.3 + 0.005 * i, 0.5, 0.045}, kMainButton});
    const std::size_t glitch_begin = poses.size();
    for (int i = 0; i < 24; ++i)
        poses.push_back({i % 2 == 0 ? Vec3{0.5, 0.5, -2e9} : Vec3{1e300, 1e300, -1e300}, 0});
    const std::size_t glitch_end = poses.size();
    for (int i = 0; i < 40; ++i)
        poses.push_back({{0.5 + 0.005 * i, 0.45, 0.045}, kMainButton});
    for (int i = 0; i < 20; ++i)
        poses.push_back({{0.7, 0.45, 0.2}, 0});

    std::thread driver([&] {
        for (int i = 0; i < 5000 && port.load() == 0; ++i)
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        UdpSocket socket = UdpSocket::bind(0);
        const UdpEndpoint to{0x7F000001u, port.load()};
        std::uint32_t sequence = 0;
        for (const PosePacket& pose : poses) {
            EXPECT_TRUE(socket.send_to(encode_packet({++sequence, pose}), to));
            // Several simulation steps (500 Hz) per pose, so the glitch would be consumed.
            std::this_thread::sleep_for(std::chrono::milliseconds(3));
        }
        EXPECT_TRUE(socket.send_to(encode_packet({++sequence, ByePacket{}}), to));
    });
    const UdpServeResult served = serve_udp_session(live, context, options);
    driver.join();
    EXPECT_TRUE(served.device.bye);
    EXPECT_FALSE(served.time_limit_reached);
    EXPECT_EQ(served.device.malformed, glitch_end - glitch_begin);
    EXPECT_EQ(served.device.poses, poses.size() - (glitch_end - glitch_begin));
    EXPECT_GT(served.stamps, 10u);
    for (const EditInput& e : served.recording.edits)
        EXPECT_LT(std::abs(e.position.z), 1.0) << "tick " << e.tick;

    save_recording(dir / "session.haptic.json", served.recording);
    HapticRecording rec;
    ASSERT_NO_THROW(rec = load_recording(dir / "session.haptic.json"));
    Tin replayed = make_recording_terrain(*rec.terrain, test::headless());
    SculptContext replay_context(replayed.domain());
    const nlohmann::json report = replay_recording(rec, replayed, replay_context, dir);
    EXPECT_TRUE(report["result_matches_recording"].get<bool>());
    test::expect_same_terrain(live, replayed);
}

}  // namespace
}  // namespace sandtin::haptics
