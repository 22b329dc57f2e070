// sandtin bench haptics: the force loop at 1 kHz (configurable) on its own thread for 10 s
// while the simulation, on this thread, follows a simulated device that strokes circles into
// the sand, stamping and eroding after every stamp and publishing a snapshot after every step.
// Reports the loop's period statistics and the force jumps as JSON, and, to attribute late
// ticks, the loop's own phase timings (loop_jitter.hpp), its scheduler counters and page
// faults over the run, every CPU's steal time, and for each late tick what a 2 ms observer
// (sched_sampler.hpp) saw the kernel and the hypervisor do meanwhile.

#include <malloc.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <optional>
#include <string>
#include <thread>

#include "arguments.hpp"
#include "commands.hpp"
#include "haptics/diagnostics/cpu_wake_latency.hpp"
#include "haptics/diagnostics/loop_diagnostics.hpp"
#include "haptics/diagnostics/os_counters.hpp"
#include "haptics/diagnostics/sched_sampler.hpp"
#include "haptics/diagnostics/spin_probe.hpp"
#include "haptics/haptic_recording.hpp"
#include "haptics/live_session.hpp"
#include "haptics/realtime_thread.hpp"
#include "haptics/simulated_device.hpp"
#include "tools/tool_json.hpp"

namespace sandtin::cli {

namespace {
constexpr const char* kBenchHapticsUsage =
    "sandtin bench haptics [--seconds S] [--rate HZ] [--spin-us US] [--points N] [--quick] "
    "[--idle [--burn] | --probe] [--pin | --loop-cpu N] [--mlock] [--wake-latency-zero] "
    "[--keep-heap] "
    "[--relative-sleep] "
    "[--no-stack-prefault] "
    "[--no-timer-slack] "
    "[--no-sampler] [--json]";

std::string load_average() {
    const auto text = haptics::read_small_file("/proc/loadavg");
    if (!text) return "unknown";
    std::string s = *text;
    // "0.41 1.39 1.72 2/345 6789": keep the three averages.
    std::size_t spaces = 0;
    for (std::size_t i = 0; i < s.size(); ++i) {
        if (s[i] == ' ' && ++spaces == 3) return s.substr(0, i);
    }
    return s;
}

nlohmann::json counters_json(const haptics::ThreadCounters& c) {
    return {{"cpu_ms", static_cast<double>(c.sched.cpu_ns) * 1e-6},
            {"run_queue_wait_ms", static_cast<double>(c.sched.run_delay_ns) * 1e-6},
            {"times_scheduled", c.sched.slices},
            {"voluntary_switches", c.voluntary_switches},
            {"involuntary_switches", c.involuntary_switches},
            {"minor_faults", c.minor_faults},
            {"major_faults", c.major_faults}};
}

double ms(std::int64_t ns) {
    return static_cast<double>(ns) * 1e-6;
}

// --probe: no loop, no simulation; a SCHED_FIFO thread spins in 10 ms bursts (50 % duty) and
// reports every gap > 20 us between consecutive clock reads, against the CPUs' steal time.
int run_spin_probe_bench(double seconds, bool pin, bool wake_latency_zero) {
    using namespace sandtin::haptics;
    SpinProbeOptions o;
    o.seconds = seconds;
    const int cpus = static_cast<int>(std::thread::hardware_concurrency());
    o.realtime.cpu = pin ? cpus - 1 : -1;
    const std::string load_before = load_average();
    std::optional<CpuWakeLatencyHold> hold;
    if (wake_latency_zero) hold.emplace(0);
    const SpinProbeResult r = run_spin_probe(o);
    nlohmann::json steal = nlohmann::json::array();
    for (const std::int64_t s : r.steal_ns)
        steal.push_back(ms(s));
    const auto& b = r.gaps.bucket_counts();
    nlohmann::json j;
    j["benchmark"] = "haptics_spin_probe";
    j["seconds"] = seconds;
    j["load_average_before"] = load_before;
    j["load_average_after"] = load_average();
    j["sched_fifo"] = r.grant.fifo;
    j["cpu"] = r.grant.cpu;
    j["cpu_wake_latency_zero"] = hold && hold->held();
    j["burst_ms"] = ms(o.burst_ns);
    j["sleep_ms"] = ms(o.sleep_ns);
    j["threshold_us"] = static_cast<double>(o.threshold_ns) * 1e-3;
    j["spinning_ms"] = ms(r.gaps.observed_ns());
    j["gaps"] = r.gaps.gaps();
    j["gaps_total_ms"] = ms(r.gaps.stolen_ns());
    j["max_gap_ms"] = ms(r.gaps.max_gap_ns());
    j["gaps_by_size"] = {{"20us_100us", b[0]}, {"100us_500us", b[1]}, {"500us_1ms", b[2]},
                         {"1ms_2ms", b[3]},    {"2ms_10ms", b[4]},    {"over_10ms", b[5]}};
    j["probe_thread"] = counters_json(r.during);
    j["steal_ms_per_cpu"] = steal;
    std::cout << j.dump(2) << "\n";
    return 0;
}

/// The force loop's configuration from the command line: rate, spin, CPUs and the real-time
/// measures. `pin`: the loop on the last CPU (the simulation takes the first).
haptics::ForceLoopConfig loop_config(const Arguments& args, double rate, bool pin, int cpus) {
    using namespace sandtin::haptics;
    ForceLoopConfig config;
    config.rate_hz = rate;
    const double spin_us = args.number_or("--spin-us", 300.0);
    if (!(spin_us >= 0.0) || spin_us * 1e-6 * rate >= 1.0)
        throw UsageError("--spin-us must be in [0, one period)");
    config.spin_ns = std::min<std::int64_t>(static_cast<std::int64_t>(spin_us * 1e3),
                                            static_cast<std::int64_t>(0.5e9 / rate));
    config.realtime.cpu = pin ? cpus - 1 : -1;
    if (args.has("--loop-cpu")) {
        if (pin) throw UsageError("--pin and --loop-cpu exclude each other");
        config.realtime.cpu = static_cast<int>(args.count("--loop-cpu"));
    }
    config.realtime.lock_memory = args.has("--mlock");
    config.realtime.timer_slack = !args.has("--no-timer-slack");
    config.realtime.prefault_stack_bytes = args.has("--no-stack-prefault") ? 0 : 256 * 1024;
    config.absolute_sleep = !args.has("--relative-sleep");
    // The backup tick thread (force_loop.hpp) is on by default with 2+ CPUs: on this VM the
    // timer wake-ups of one CPU are sometimes milliseconds late, and the other CPU covers them.
    // It covers the primary's CPU only from another CPU, so unless told otherwise the primary
    // takes the last CPU and the backup the first. --no-backup measures the loop alone.
    config.backup_thread = !args.has("--no-backup") && cpus >= 2;
    if (config.backup_thread && cpus >= 2) {
        if (config.realtime.cpu < 0) config.realtime.cpu = cpus - 1;
        config.backup_cpu = config.realtime.cpu == 0 ? 1 : 0;
    }
    return config;
}

/// Where the loop's time went: its late ticks by phase and cause, the worst first (capped, so
/// the report stays readable), each with the scheduler's view of its window when sampled.
void report_jitter(const haptics::LoopDiagnostics& diagnostics,
                   const haptics::ForceLoopReport& report, double rate,
                   const std::optional<haptics::SchedSampler>& sampler, nlohmann::json& j) {
    using namespace sandtin::haptics;
    const JitterSummary js = diagnostics.jitter();
    j["jitter"] = {{"max_work_ms", ms(js.max_work_ns)},
                   {"max_wake_late_ms", ms(js.max_wake_late_ns)},
                   {"max_spin_gap_ms", ms(js.max_spin_gap_ns)},
                   {"wakes_after_deadline", js.wakes_after_deadline},
                   {"spin_gaps_over_50us", js.long_spin_gaps},
                   {"spin_gaps_over_50us_total_ms", ms(js.long_spin_gap_total_ns)},
                   {"late_threshold_ms", report.periods.target_ms * 1.5},
                   {"late_ticks", js.late_ticks},
                   {"late_by_work", js.late_by_work},
                   {"late_by_wakeup", js.late_by_wakeup},
                   {"late_by_spin_gap", js.late_by_spin_gap}};
    j["loop_thread_during_ticks"] = counters_json(diagnostics.during_ticks());
    std::int64_t late_total = 0;
    for (const TickPhases& t : diagnostics.late_ticks())
        late_total += t.period_ns - static_cast<std::int64_t>(1e9 / rate);
    j["late_ticks_total_excess_ms"] = ms(late_total);
    nlohmann::json late = nlohmann::json::array();
    const std::vector<TickPhases>& late_ticks = diagnostics.late_ticks();
    // The worst first; the list is capped so the report stays readable.
    std::vector<TickPhases> worst(late_ticks.begin(), late_ticks.end());
    std::sort(worst.begin(), worst.end(),
              [](const TickPhases& a, const TickPhases& b) { return a.period_ns > b.period_ns; });
    for (std::size_t i = 0; i < std::min<std::size_t>(worst.size(), 12); ++i) {
        const TickPhases& t = worst[i];
        nlohmann::json e = {{"tick", t.tick},
                            {"start_monotonic_ns", t.start_ns},
                            {"period_ms", ms(t.period_ns)},
                            {"cause", to_string(late_cause(t))},
                            {"previous_work_ms", ms(t.work_ns)},
                            {"slept", t.slept},
                            {"wake_late_ms", ms(t.wake_late_ns)},
                            {"spin_gap_ms", ms(t.spin_gap_ns)},
                            {"cpu", t.cpu}};
        if (sampler) {
            const WindowAttribution a =
                attribute_window(sampler->samples(), t.start_ns - t.period_ns, t.start_ns, t.cpu);
            if (a.covered) {
                e["observed_over_ms"] = ms(a.span_ns);
                e["loop_run_queue_wait_ms"] = ms(a.run_delay_ns);
                e["steal_on_cpu_ms"] = ms(a.steal_on_cpu_ns);
                e["steal_all_cpus_ms"] = ms(a.steal_all_cpus_ns);
            }
        }
        late.push_back(e);
    }
    j["late_ticks_worst_first"] = late;
}

/// Samples the loop thread's scheduler statistics every 2 ms into `sampler` while the loop runs
/// (once its thread exists; left empty when the loop ended before it had one). The sampler is
/// not movable, hence the out-parameter.
void start_sampler(const haptics::ForceLoop& loop, double seconds,
                   std::optional<haptics::SchedSampler>& sampler) {
    while (loop.thread_id() == 0 && loop.running())
        std::this_thread::sleep_for(std::chrono::microseconds(100));
    if (loop.thread_id() == 0) return;
    constexpr std::int64_t kSampleNs = 2'000'000;
    sampler.emplace(loop.thread_id(), kSampleNs,
                    static_cast<std::size_t>(seconds * 1e9 / kSampleNs) + 1000);
    sampler->start();
}

/// What the bench itself arranged around the loop, reported beside the loop's own grant.
struct RealtimeExtras {
    int simulation_cpu = -1;
    bool keep_heap = false;
    bool wake_latency_zero = false;
    std::string wake_latency_error;
};

/// The loop's real-time grant, its periods against the target, and its forces.
void report_loop(const haptics::ForceLoopReport& report, const haptics::ForceLoopConfig& config,
                 const RealtimeExtras& extras, nlohmann::json& j) {
    using namespace sandtin::haptics;
    const RealtimeGrant& g = report.realtime_grant;
    j["realtime"] = {{"sched_fifo", g.fifo},
                     {"loop_cpu", g.cpu},
                     {"simulation_cpu", extras.simulation_cpu},
                     {"timer_slack_1ns", g.timer_slack},
                     {"mlockall", g.memory_locked},
                     {"stack_prefaulted_kib", g.stack_prefaulted_bytes / 1024},
                     {"absolute_sleep", config.absolute_sleep},
                     {"keep_heap", extras.keep_heap},
                     {"backup_thread", config.backup_thread},
                     {"backup_cpu", config.backup_cpu},
                     {"ticks_by_backup", report.ticks_by_backup},
                     {"cpu_wake_latency_zero", extras.wake_latency_zero},
                     {"refused", g.refused}};
    if (!extras.wake_latency_error.empty())
        j["realtime"]["refused_wake_latency"] = extras.wake_latency_error;
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
}

/// The simulation thread's steps (sorted here): how many, how fast, their p50, p99 and max (ms),
/// the stamps they made; `idle` and `burn` say what the thread did instead.
nlohmann::json simulation_json(std::vector<double>& step_ms, double wall_seconds,
                               std::size_t stamps, bool idle, bool burn) {
    std::sort(step_ms.begin(), step_ms.end());
    const auto pct = [&](double q) {
        if (step_ms.empty()) return 0.0;
        const auto k = static_cast<std::size_t>(std::ceil(q * static_cast<double>(step_ms.size())));
        return step_ms[std::clamp<std::size_t>(k, 1, step_ms.size()) - 1];
    };
    return {{"idle", idle},
            {"burn", burn},
            {"steps", step_ms.size()},
            {"steps_per_second", static_cast<double>(step_ms.size()) / wall_seconds},
            {"stamps", stamps},
            {"step_ms_p50", pct(0.5)},
            {"step_ms_p99", pct(0.99)},
            {"step_ms_max", step_ms.empty() ? 0.0 : step_ms.back()}};
}

/// The loop's targets: p99 within 10 % of the period, no period over twice it.
nlohmann::json loop_targets_json(const haptics::ForceLoopReport& report) {
    const double target_p99 = report.periods.target_ms * 1.1;
    const double target_max = report.periods.target_ms * 2.0;
    return {{"p99_ms", target_p99},
            {"max_ms", target_max},
            {"p99_met", report.periods.p99_ms <= target_p99},
            {"max_met", report.periods.max_ms <= target_max}};
}

}  // namespace

int run_bench_haptics(const std::vector<std::string>& raw) {
    using namespace sandtin::haptics;
    const Arguments args(raw, {{"--seconds", 1},
                               {"--rate", 1},
                               {"--points", 1},
                               {"--spin-us", 1},
                               {"--quick", 0},
                               {"--idle", 0},
                               {"--probe", 0},
                               {"--burn", 0},
                               {"--pin", 0},
                               {"--loop-cpu", 1},
                               {"--mlock", 0},
                               {"--wake-latency-zero", 0},
                               {"--keep-heap", 0},
                               {"--no-backup", 0},
                               {"--relative-sleep", 0},
                               {"--no-stack-prefault", 0},
                               {"--no-timer-slack", 0},
                               {"--no-sampler", 0},
                               {"--json", 0}});
    args.require_positionals(0, kBenchHapticsUsage);
    const double seconds = args.number_or("--seconds", args.has("--quick") ? 2.0 : 10.0);
    const double rate = args.number_or("--rate", 1000.0);
    const std::uint64_t points = args.count_or("--points", 10000);
    if (!(seconds > 0.0) || seconds > 3600.0) throw UsageError("--seconds must be in (0, 3600]");
    if (!(rate > 0.0) || rate > kMaxLoopRateHz) throw UsageError("--rate must be in (0, 4000]");
    const bool idle = args.has("--idle");
    // --keep-heap: the allocator never gives memory back (no trimming, no mmap'd chunks), so
    // the simulation's large frees never munmap: a test of whether its address-space changes
    // (mmap lock, TLB shootdowns, pages returned to the hypervisor) delay the loop.
    const bool keep_heap = args.has("--keep-heap");
    if (keep_heap) {
        mallopt(M_TRIM_THRESHOLD, 1 << 30);
        mallopt(M_MMAP_MAX, 0);
    }
    // --idle --burn: instead of the simulation, this thread computes without system calls or
    // memory traffic, to tell "the other CPU is busy" apart from "the simulation's kernel work".
    const bool burn = args.has("--burn");
    if (burn && !idle) throw UsageError("--burn goes with --idle");
    if (args.has("--probe")) {
        if (idle) throw UsageError("--probe and --idle exclude each other");
        return run_spin_probe_bench(seconds, args.has("--pin"), args.has("--wake-latency-zero"));
    }
    const int cpus = static_cast<int>(std::thread::hardware_concurrency());
    // Pinning: the loop on the last CPU, the simulation (this thread) on the first.
    const bool pin = args.has("--pin") && cpus >= 2;
    const std::string load_before = load_average();

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
    ForceLoopConfig config = loop_config(args, rate, pin, cpus);
    int simulation_pinned = -1;
    if (pin && pin_this_thread(0) == 0) simulation_pinned = 0;
    LoopDiagnostics diagnostics(config, 256);
    ForceLoop loop(device, config, &diagnostics);
    LiveSession session(editor, loop);

    std::vector<double> step_ms;
    step_ms.reserve(100000);
    std::size_t stamps = 0;
    const std::vector<std::int64_t> steal_before = read_cpu_steal_ns();
    const auto t0 = std::chrono::steady_clock::now();
    // While the loop runs, every CPU's wake-up latency is held at 0 when asked (idle CPUs poll
    // instead of halting; cpu_wake_latency.hpp). Machine-wide while held.
    std::optional<CpuWakeLatencyHold> wake_latency;
    if (args.has("--wake-latency-zero")) wake_latency.emplace(0);
    loop.start();
    std::optional<SchedSampler> sampler;
    if (!args.has("--no-sampler")) start_sampler(loop, seconds, sampler);
    while (loop.running()) {
        const SessionStepReport r = idle ? SessionStepReport{} : session.step();
        if (r.consumed) {
            step_ms.push_back(r.ms);
            stamps += r.edit.stamps;
        } else if (burn) {
            const std::int64_t until = monotonic_ns() + 10'000'000;
            while (monotonic_ns() < until) {
            }
        } else {
            std::this_thread::sleep_for(std::chrono::microseconds(idle ? 10000 : 200));
        }
    }
    loop.stop();
    const bool wake_latency_held = wake_latency && wake_latency->held();
    const std::string wake_latency_error = wake_latency ? wake_latency->error() : std::string();
    wake_latency.reset();
    if (sampler) sampler->stop();
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const std::vector<std::int64_t> steal_after = read_cpu_steal_ns();
    const ForceLoopReport report = loop.report();

    nlohmann::json j;
    j["benchmark"] = "haptics";
    j["rate_hz"] = rate;
    j["seconds"] = seconds;
    j["wall_seconds"] = wall;
    j["ticks"] = report.ticks;
    j["load_average_before"] = load_before;
    j["load_average_after"] = load_average();
    j["realtime_priority"] = report.realtime;
    report_loop(report, config,
                RealtimeExtras{simulation_pinned, keep_heap, wake_latency_held, wake_latency_error},
                j);
    j["stale_ticks"] = report.stale_ticks;
    j["snapshots_taken"] = report.snapshots_taken;

    nlohmann::json steal = nlohmann::json::array();
    for (std::size_t c = 0; c < std::min(steal_before.size(), steal_after.size()); ++c)
        steal.push_back(ms(steal_after[c] - steal_before[c]));
    j["steal_ms_per_cpu"] = steal;
    report_jitter(diagnostics, report, rate, sampler, j);
    if (sampler) {
        j["sampler"] = {{"available", sampler->available()},
                        {"samples", sampler->samples().size()},
                        {"interval_ms", 2.0}};
    }

    j["simulation"] = simulation_json(step_ms, wall, stamps, idle, burn);
    j["simulation"]["erode_iterations_per_stamp"] = edit.erode_iterations;
    j["simulation"]["vertices_at_end"] = tin.vertex_count();
    j["targets"] = loop_targets_json(report);
    j["hardware_threads"] = std::thread::hardware_concurrency();
    std::cout << j.dump(2) << "\n";
    return 0;
}

}  // namespace sandtin::cli
