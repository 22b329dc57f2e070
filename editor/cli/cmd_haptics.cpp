// sandtin haptics serve: a headless live-editing session over the haptic UDP protocol. A driver
// process (real hardware, or sandtin-haptic-replay) sends poses to the port; the tool follows
// them, the button strokes, and forces go back every tick. When the driver says bye (or goes
// silent, or the time limit passes) the terrain and, with --record, the session's recording
// are saved; `sandtin run recording.haptic.json` replays the recording into the same terrain.

#include <fstream>
#include <iostream>
#include <thread>

#include "arguments.hpp"
#include "commands.hpp"
#include "haptics/haptic_recording.hpp"
#include "haptics/udp_session_server.hpp"
#include "io/session_file.hpp"
#include "io/session_terrain.hpp"
#include "session_output.hpp"
#include "terrain_report.hpp"
#include "util/atomic_file.hpp"
#include "util/json_document.hpp"

namespace sandtin::cli {

namespace {

constexpr const char* kHapticsUsage =
    "sandtin haptics serve -o out.sandtin [-i in.sandtin | --size W H --height Z --points N "
    "--seed S] [--port P] [--port-file F] [--tool tool.json | --tool-json '{...}'] "
    "[--spacing M] [--erode N] [--relocation-radius M] [--rate HZ] [--max-seconds S] "
    "[--record rec.haptic.json] [--backup] [--json]";

nlohmann::json read_tool_file(const std::filesystem::path& path) {
    nlohmann::json j = read_json_document(path, "tool file");
    if (!j.is_object()) throw UsageError(path.string() + ": not a JSON object (a tool definition)");
    return j;
}

/// The live session's options from the command line: the device's port, the loop's rate and
/// backup thread, the time limit, the edit settings and the tool. Throws UsageError.
haptics::UdpServeOptions serve_options(const Arguments& args) {
    using namespace sandtin::haptics;
    UdpServeOptions options;
    const std::uint64_t port = args.count_or("--port", 0);
    if (port > 65535) throw UsageError("--port must be at most 65535");
    options.device.port = static_cast<std::uint16_t>(port);
    options.loop.rate_hz = args.number_or("--rate", 1000.0);
    if (!(options.loop.rate_hz > 0.0) || options.loop.rate_hz > kMaxLoopRateHz)
        throw UsageError("--rate must be in (0, 4000]");
    options.loop.spin_ns = std::min<std::int64_t>(
        options.loop.spin_ns, static_cast<std::int64_t>(0.5e9 / options.loop.rate_hz));
    // --backup: a second loop thread on another CPU takes any tick whose primary woke late
    // (force_loop.hpp); it only helps from another CPU, so with 2+ CPUs both are pinned.
    if (args.has("--backup")) {
        options.loop.backup_thread = true;
        const int cpus = static_cast<int>(std::thread::hardware_concurrency());
        if (cpus >= 2) {
            options.loop.realtime.cpu = cpus - 1;
            options.loop.backup_cpu = 0;
        }
    }
    options.max_seconds = args.number_or("--max-seconds", 600.0);
    if (!(options.max_seconds > 0.0) || options.max_seconds > 600.0)
        throw UsageError("--max-seconds must be in (0, 600]");
    options.edit.spacing = args.number_or("--spacing", options.edit.spacing);
    if (!(options.edit.spacing > 0.0)) throw UsageError("--spacing must be positive");
    const std::uint64_t erode = args.count_or("--erode", 0);
    if (erode > 1000) throw UsageError("--erode must be at most 1000");
    options.edit.erode_iterations = static_cast<int>(erode);
    options.edit.physics.relocation_radius = args.number_or("--relocation-radius", 0.0);
    if (options.edit.physics.relocation_radius < 0.0)
        throw UsageError("--relocation-radius must be >= 0");
    if (args.has("--tool") && args.has("--tool-json"))
        throw UsageError("give --tool or --tool-json, not both");
    if (args.has("--tool")) {
        options.tool = read_tool_file(args.text("--tool"));
        options.tool_base_dir = std::filesystem::path(args.text("--tool")).parent_path();
    } else if (args.has("--tool-json")) {
        options.tool = parse_json_document(args.text("--tool-json"), "--tool-json");
        if (!options.tool.is_object()) throw UsageError("--tool-json is not a JSON object");
    }

    return options;
}

/// What the session did, as `sandtin haptics serve` reports it.
nlohmann::json session_report(const haptics::UdpServeResult& r,
                              const haptics::UdpServeOptions& options, const Tin& tin,
                              const std::string& out, const Arguments& args) {
    nlohmann::json j;
    j["ticks"] = r.loop.ticks;
    j["period_ms"] = {{"p50", r.loop.periods.p50_ms},
                      {"p99", r.loop.periods.p99_ms},
                      {"max", r.loop.periods.max_ms}};
    j["overruns"] = r.loop.periods.overruns;
    // Where late ticks' time went (loop_jitter.hpp); "work" includes the device's socket I/O.
    const auto& jitter = r.jitter;
    j["late_ticks"] = {{"over_ms", r.loop.periods.target_ms * 1.5},
                       {"count", jitter.late_ticks},
                       {"by_work", jitter.late_by_work},
                       {"by_wakeup", jitter.late_by_wakeup},
                       {"by_spin_gap", jitter.late_by_spin_gap},
                       {"max_wake_late_ms", static_cast<double>(jitter.max_wake_late_ns) * 1e-6},
                       {"max_spin_gap_ms", static_cast<double>(jitter.max_spin_gap_ns) * 1e-6},
                       {"max_work_ms", static_cast<double>(jitter.max_work_ns) * 1e-6}};
    j["realtime"] = {{"sched_fifo", r.loop.realtime_grant.fifo},
                     {"refused", r.loop.realtime_grant.refused},
                     {"backup_thread", options.loop.backup_thread},
                     {"ticks_by_backup", r.loop.ticks_by_backup}};
    j["force_n"] = {{"max", r.loop.max_force}, {"max_jump", r.loop.max_force_jump}};
    j["device"] = {{"poses", r.device.poses},
                   {"malformed", r.device.malformed},
                   {"out_of_order", r.device.out_of_order},
                   {"forces_sent", r.device.forces_sent},
                   {"bye", r.device.bye},
                   {"timed_out", r.device.timed_out}};
    j["edits"] = r.recording.edits.size();
    j["stamps"] = r.stamps;
    j["time_limit_reached"] = r.time_limit_reached;
    j["terrain"] = describe_terrain(tin);
    j["file"] = out;
    if (args.has("--record")) j["recording"] = args.text("--record");
    return j;
}

}  // namespace

int run_haptics(const std::vector<std::string>& raw) {
    using namespace sandtin::haptics;
    const Arguments args(raw, {{"-o", 1},
                               {"-i", 1},
                               {"--size", 2},
                               {"--height", 1},
                               {"--points", 1},
                               {"--seed", 1},
                               {"--port", 1},
                               {"--port-file", 1},
                               {"--tool", 1},
                               {"--tool-json", 1},
                               {"--spacing", 1},
                               {"--erode", 1},
                               {"--relocation-radius", 1},
                               {"--rate", 1},
                               {"--max-seconds", 1},
                               {"--record", 1},
                               {"--backup", 0},
                               {"--json", 0}});
    args.require_positionals(1, kHapticsUsage);
    if (args.positionals()[0] != "serve")
        throw UsageError("unknown haptics command '" + args.positionals()[0] +
                         "'\nusage: " + kHapticsUsage);
    const std::string out = args.text("-o");

    UdpServeOptions options = serve_options(args);

    Session session;
    TinOptions tin_options;
    tin_options.track_changes = false;  // headless: ids depend only on the edits (replayable)
    Tin tin = [&] {
        if (args.has("-i")) {
            if (args.has("--size") || args.has("--height") || args.has("--points") ||
                args.has("--seed"))
                throw UsageError("-i and a generated terrain (--size ...) exclude each other");
            session = load_session(args.text("-i"));
            return take_session_terrain(session, args.text("-i"), tin_options);
        }
        ScriptTerrain t;
        if (args.has("--size")) t.size = {args.number("--size", 0), args.number("--size", 1)};
        if (!(t.size.x > 0.0) || !(t.size.y > 0.0)) throw UsageError("--size must be positive");
        t.height = args.number_or("--height", 0.05);
        t.points = args.count_or("--points", 0);
        if (t.points > 10'000'000) throw UsageError("--points must be at most 10000000");
        t.seed = args.count_or("--seed", 1);
        options.terrain = t;
        return make_recording_terrain(t, tin_options);
    }();
    SculptContext context(tin.domain());
    context.set_next_generation(session.next_generation);

    if (args.has("--port-file")) {
        const std::filesystem::path port_file = args.text("--port-file");
        options.on_listening = [port_file](std::uint16_t bound) {
            const std::string text = std::to_string(bound) + "\n";
            write_file_atomically(
                port_file, std::span<const std::uint8_t>(
                               reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
        };
    } else {
        options.on_listening = [](std::uint16_t bound) {
            std::cerr << "sandtin haptics: listening on 127.0.0.1:" << bound << "\n";
        };
    }
    // A live session cannot be run again: where its results go is checked before it starts,
    // and the recording (which replays it) is saved first.
    check_session_output(out);
    if (args.has("--record")) check_writable(args.text("--record"));
    const UdpServeResult r = serve_udp_session(tin, context, options);

    if (args.has("--record")) save_recording(args.text("--record"), r.recording);
    session.terrain = tin.snapshot();
    session.next_generation = context.peek_generation();
    save_session(out, session);

    const nlohmann::json j = session_report(r, options, tin, out, args);
    if (args.has("--json")) {
        std::cout << j.dump(2) << "\n";
    } else {
        std::cout << "haptic session: " << r.loop.ticks << " ticks, " << r.device.poses
                  << " poses, " << r.stamps << " stamps; wrote " << out << "\n";
    }
    return j["terrain"]["valid"].get<bool>() ? 0 : 1;
}

}  // namespace sandtin::cli
