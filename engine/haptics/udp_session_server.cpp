#include "haptics/udp_session_server.hpp"

#include <chrono>
#include <stdexcept>
#include <thread>

#include "haptics/diagnostics/loop_diagnostics.hpp"
#include "haptics/live_session.hpp"
#include "tools/tool_json.hpp"

namespace sandtin::haptics {

UdpServeResult serve_udp_session(Tin& tin, SculptContext& context, const UdpServeOptions& o) {
    if (!(o.max_seconds > 0.0)) throw std::invalid_argument("haptic session: max_seconds > 0");
    if (!(o.simulation_hz > 0.0)) throw std::invalid_argument("haptic session: simulation_hz > 0");
    auto tool = std::make_shared<const Tool>(
        Tool::build(parse_tool_spec(o.tool, o.tool_base_dir, "haptic session: tool")));
    const Generation start_generation = context.peek_generation();
    const TerrainSummary start = summarise(tin);
    LiveEditor editor(tin, tool, context, o.edit);
    UdpDevice device(o.device);
    ForceLoopConfig loop_config = o.loop;
    if (loop_config.record_capacity == 0) {
        // Every tick of the longest session (bounded: 4 kHz x 600 s is 2.4 M ticks, ~200 MB).
        loop_config.record_capacity =
            static_cast<std::size_t>(std::min(o.max_seconds, 600.0) * loop_config.rate_hz + 16.0);
    }
    LoopDiagnostics diagnostics(loop_config);
    ForceLoop loop(device, loop_config, &diagnostics);
    LiveSession session(editor, loop);
    loop.start();
    if (o.on_listening) o.on_listening(device.port());

    UdpServeResult result;
    const auto period = std::chrono::duration<double>(1.0 / o.simulation_hz);
    const auto end =
        std::chrono::steady_clock::now() + std::chrono::duration<double>(o.max_seconds);
    auto next = std::chrono::steady_clock::now();
    while (loop.running()) {
        if (std::chrono::steady_clock::now() >= end) {
            result.time_limit_reached = true;
            break;
        }
        result.stamps += session.step().edit.stamps;
        next += std::chrono::duration_cast<std::chrono::steady_clock::duration>(period);
        std::this_thread::sleep_until(next);
        next = std::max(next, std::chrono::steady_clock::now());
    }
    result.stamps += session.step().edit.stamps;  // the last tick the loop published
    loop.stop();
    result.loop = loop.report();
    result.jitter = diagnostics.jitter();
    result.device = device.counters();
    result.simulation_steps = session.steps();
    result.recording =
        make_recording(loop_config.rate_hz, o.tool, o.edit, o.terrain, start_generation, start,
                       loop.records(), session.edits(), tin);
    return result;
}

}  // namespace sandtin::haptics
