// sandtin bench haptics: the force loop at 1 kHz (configurable) on its own thread for 10 s
// while the simulation, on this thread, follows a simulated device that strokes circles into
// the sand, stamping and eroding after every stamp and publishing a snapshot after every step.
// Reports the loop's period statistics and the force jumps as JSON.

#include <algorithm>
#include <chrono>
#include <iostream>
#include <thread>

#include "arguments.hpp"
#include "commands.hpp"
#include "haptics/haptic_recording.hpp"
#include "haptics/live_session.hpp"
#include "haptics/simulated_device.hpp"
#include "tools/tool_json.hpp"

namespace sandtin::cli {

namespace {
constexpr const char* kUsage =
    "sandtin bench haptics [--seconds S] [--rate HZ] [--spin-us US] [--points N] [--quick] "
    "[--json]";
}

int run_bench_haptics(const std::vector<std::string>& raw) {
    using namespace sandtin::haptics;
    const Arguments args(raw, {{"--seconds", 1},
                               {"--rate", 1},
                               {"--points", 1},
                               {"--spin-us", 1},
                               {"--quick", 0},
                               {"--json", 0}});
    args.require_positionals(0, kUsage);
    const double seconds = args.number_or("--seconds", args.has("--quick") ? 2.0 : 10.0);
    const double rate = args.number_or("--rate", 1000.0);
    const std::uint64_t points = args.count_or("--points", 10000);
    if (!(seconds > 0.0) || seconds > 3600.0) throw UsageError("--seconds must be in (0, 3600]");
    if (!(rate > 0.0) || rate > kMaxLoopRateHz) throw UsageError("--rate must be in (0, 4000]");

    ScriptTerrain terrain;
    terrain.points = points;
    terrain.height = 0.05;
    TinOptions options;
    options.track_changes = false;
    Tin tin = make_recording_terrain(terrain, options);
    SculptContext context(tin.domain());
    const nlohmann::json tool_json = {{"contour", "circle"}, {"radius", 0.04}};
    auto tool = std::make_shared<const Tool>(Tool::build(parse_tool_spec(tool_json, ".", "tool")));
    LiveEditSettings edit;
    edit.erode_iterations = 4;
    edit.physics.relocation_radius = 0.01;
    LiveEditor editor(tin, tool, context, edit);

    CircleTrajectorySpec circles;
    circles.rate_hz = rate;
    circles.seconds = seconds;
    circles.surface = terrain.height;
    SimulatedDevice device = SimulatedDevice::replay(make_circle_trajectory(circles));
    ForceLoopConfig config;
    config.rate_hz = rate;
    config.spin_ns =
        std::min<std::int64_t>(config.spin_ns, static_cast<std::int64_t>(0.5e9 / rate));
    ForceLoop loop(device, config);
    LiveSession session(editor, loop);

    std::vector<double> step_ms;
    step_ms.reserve(100000);
    std::size_t stamps = 0;
    const auto t0 = std::chrono::steady_clock::now();
    loop.start();
    while (loop.running()) {
        const SessionStepReport r = session.step();
        if (r.consumed) {
            step_ms.push_back(r.ms);
            stamps += r.edit.stamps;
        } else {
            std::this_thread::sleep_for(std::chrono::microseconds(200));
        }
    }
    loop.stop();
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const ForceLoopReport report = loop.report();
    std::sort(step_ms.begin(), step_ms.end());
    const auto pct = [&](double q) {
        if (step_ms.empty()) return 0.0;
        const auto k = static_cast<std::size_t>(std::ceil(q * static_cast<double>(step_ms.size())));
        return step_ms[std::clamp<std::size_t>(k, 1, step_ms.size()) - 1];
    };

    nlohmann::json j;
    j["benchmark"] = "haptics";
    j["rate_hz"] = rate;
    j["seconds"] = seconds;
    j["wall_seconds"] = wall;
    j["ticks"] = report.ticks;
    j["realtime_priority"] = report.realtime;
    j["spin_us"] = static_cast<double>(config.spin_ns) * 1e-3;
    j["period_ms"] = {{"p50", report.periods.p50_ms},
                      {"p99", report.periods.p99_ms},
                      {"max", report.periods.max_ms},
                      {"mean", report.periods.mean_ms},
                      {"target", report.periods.target_ms}};
    j["overruns"] = report.periods.overruns;
    j["overrun_definition"] = "period > 110% of target";
    j["force_n"] = {{"max", report.max_force},
                    {"max_jump", report.max_force_jump},
                    {"jumps_over_0_5", report.force_jumps_over_half_newton}};
    j["stale_ticks"] = report.stale_ticks;
    j["snapshots_taken"] = report.snapshots_taken;
    j["simulation"] = {{"steps", step_ms.size()},
                       {"steps_per_second", static_cast<double>(step_ms.size()) / wall},
                       {"stamps", stamps},
                       {"step_ms_p50", pct(0.5)},
                       {"step_ms_p99", pct(0.99)},
                       {"step_ms_max", step_ms.empty() ? 0.0 : step_ms.back()},
                       {"erode_iterations_per_stamp", edit.erode_iterations},
                       {"vertices_at_end", tin.vertex_count()}};
    const double target_p99 = report.periods.target_ms * 1.1;
    const double target_max = report.periods.target_ms * 2.0;
    j["targets"] = {{"p99_ms", target_p99},
                    {"max_ms", target_max},
                    {"p99_met", report.periods.p99_ms <= target_p99},
                    {"max_met", report.periods.max_ms <= target_max}};
    j["hardware_threads"] = std::thread::hardware_concurrency();
    std::cout << j.dump(2) << "\n";
    return 0;
}

}  // namespace sandtin::cli
