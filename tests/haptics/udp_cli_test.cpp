// The whole network path through processes: `sandtin haptics serve` (a headless session) on
// a free port, sandtin-haptic-replay playing the stroke to it, then `sandtin run` replaying the
// session's recording. The replayed terrain must equal the served one exactly.

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "io/session_file.hpp"
#include "test_support.hpp"

namespace sandtin::haptics {
namespace {

TEST(UdpCli, ServeThenReplayProcessThenSandtinRunGiveTheSameTerrain) {
    const std::filesystem::path dir = test::scratch_dir("udp-cli");
    const std::filesystem::path port_file = dir / "port";
    const pid_t serve = test::start_process({SANDTIN_CLI,
                                             "haptics",
                                             "serve",
                                             "-o",
                                             (dir / "served.sandtin").string(),
                                             "--port-file",
                                             port_file.string(),
                                             "--points",
                                             "300",
                                             "--seed",
                                             "3",
                                             "--height",
                                             "0.05",
                                             "--erode",
                                             "2",
                                             "--relocation-radius",
                                             "0.01",
                                             "--record",
                                             (dir / "session.haptic.json").string(),
                                             "--max-seconds",
                                             "90",
                                             "--json"},
                                            dir / "serve.json", dir / "serve.err");
    ASSERT_GT(serve, 0);
    // Wait for the session to report its port.
    std::string port;
    for (int i = 0; i < 3000 && port.empty(); ++i) {
        if (std::filesystem::exists(port_file)) port = test::read_text(port_file);
        if (!port.empty() && port.back() == '\n') {
            port.pop_back();
        } else {
            port.clear();
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
    }
    ASSERT_FALSE(port.empty()) << test::read_text(dir / "serve.err");
    const int replay_rc =
        test::run_process({SANDTIN_HAPTIC_REPLAY, "play", SANDTIN_HAPTICS_ASSETS "/stroke.traj",
                           "--port", port, "--lockstep", "--timeout-ms", "2000"},
                          dir / "replay.json", dir / "replay.err");
    const int serve_rc = test::wait_process(serve);
    ASSERT_EQ(replay_rc, 0) << test::read_text(dir / "replay.err")
                            << test::read_text(dir / "replay.json");
    ASSERT_EQ(serve_rc, 0) << test::read_text(dir / "serve.err");

    const nlohmann::json replay = nlohmann::json::parse(test::read_text(dir / "replay.json"));
    EXPECT_EQ(replay["answered"], replay["sent"]);
    EXPECT_EQ(replay["timeouts"], 0);
    EXPECT_GT(replay["max_force"].get<double>(), 3.0);
    const nlohmann::json served = nlohmann::json::parse(test::read_text(dir / "serve.json"));
    EXPECT_TRUE(served["device"]["bye"].get<bool>());
    EXPECT_EQ(served["device"]["poses"], replay["sent"]);
    EXPECT_EQ(served["device"]["malformed"], 0);
    EXPECT_FALSE(served["time_limit_reached"].get<bool>());
    EXPECT_GT(served["stamps"].get<int>(), 20);

    const int run_rc =
        test::run_process({SANDTIN_CLI, "run", (dir / "session.haptic.json").string(), "-o",
                           (dir / "replayed.sandtin").string(), "--json"},
                          dir / "run.json", dir / "run.err");
    ASSERT_EQ(run_rc, 0) << test::read_text(dir / "run.err");
    const nlohmann::json run = nlohmann::json::parse(test::read_text(dir / "run.json"));
    EXPECT_TRUE(run["steps"][0]["result_matches_recording"].get<bool>());
    const Tin a = Tin::from_snapshot(load_session(dir / "served.sandtin").terrain);
    const Tin b = Tin::from_snapshot(load_session(dir / "replayed.sandtin").terrain);
    test::expect_same_terrain(a, b);
}

TEST(UdpCli, ServeRejectsBadOptions) {
    const std::filesystem::path dir = test::scratch_dir("udp-cli-bad");
    EXPECT_EQ(test::run_process(
                  {SANDTIN_CLI, "haptics", "serve", "-o", (dir / "x").string(), "--rate", "5000"},
                  dir / "out", dir / "err"),
              2);
    EXPECT_NE(test::read_text(dir / "err").find("--rate"), std::string::npos);
    EXPECT_EQ(test::run_process({SANDTIN_CLI, "haptics", "listen"}, dir / "out", dir / "err"), 2);
    EXPECT_NE(test::read_text(dir / "err").find("unknown haptics command"), std::string::npos);
    EXPECT_EQ(test::run_process(
                  {SANDTIN_HAPTIC_REPLAY, "play", (dir / "missing.traj").string(), "--port", "9"},
                  dir / "out", dir / "err"),
              1);
    EXPECT_NE(test::read_text(dir / "err").find("cannot open"), std::string::npos);
    // An output that cannot be written is refused before the live session starts (it could
    // not be run again): at once, not after --max-seconds, and naming the folder. No port is
    // ever announced.
    for (const std::vector<std::string>& outputs :
         {std::vector<std::string>{"-o", (dir / "missing" / "x.sandtin").string()},
          std::vector<std::string>{"-o", (dir / "x.sandtin").string(), "--record",
                                   (dir / "missing" / "s.haptic.json").string()}}) {
        std::vector<std::string> cmd = {
            SANDTIN_CLI,     "haptics", "serve", "--port-file", (dir / "port").string(),
            "--max-seconds", "60"};
        cmd.insert(cmd.end(), outputs.begin(), outputs.end());
        const auto t0 = std::chrono::steady_clock::now();
        EXPECT_EQ(test::run_process(cmd, dir / "out", dir / "err"), 1);
        EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(30));
        EXPECT_NE(test::read_text(dir / "err")
                      .find("'" + (dir / "missing").string() + "' does not exist"),
                  std::string::npos)
            << test::read_text(dir / "err");
        EXPECT_FALSE(std::filesystem::exists(dir / "port"));
    }
}

}  // namespace
}  // namespace sandtin::haptics
