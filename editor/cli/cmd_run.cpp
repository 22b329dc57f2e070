// sandtin run: apply a script to a terrain and save the result.

#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include "arguments.hpp"
#include "commands.hpp"
#include "gpu/device_selection.hpp"
#include "gpu/gpu_error.hpp"
#include "gpu/make_relaxation_solver.hpp"
#include "gpu/vulkan_context.hpp"
#include "haptics/recording_replay.hpp"
#include "io/script.hpp"
#include "io/session_file.hpp"
#include "io/session_terrain.hpp"
#include "progress_line.hpp"
#include "session_output.hpp"
#include "terrain_report.hpp"
#include "util/atomic_file.hpp"

namespace sandtin::cli {

namespace {
constexpr const char* kRunUsage =
    "sandtin run (script.json | recording.haptic.json) [-i in.sandtin] -o out.sandtin "
    "[--physics auto|cpu|gpu] [--json]";
}

int run_run(const std::vector<std::string>& raw) {
    const Arguments args(raw, {{"-i", 1}, {"-o", 1}, {"--json", 0}, {"--physics", 1}});
    args.require_positionals(1, kRunUsage);
    const std::filesystem::path script_path = args.positionals()[0];
    const std::string out = args.text("-o");
    check_session_output(out);  // before the work, not after it
    // -i and -o may be one session (an edit in place); the script must survive its run.
    check_not_overwriting(out, script_path, "the script being run");
    const std::vector<std::uint8_t> bytes = read_file(script_path, 1u << 28);
    const std::string text(bytes.begin(), bytes.end());
    // Parse everything before touching any terrain: a bad script changes nothing.
    // A recorded haptic session replays like a script (engine/haptics/recording_replay.hpp).
    const Script script =
        haptics::is_haptic_recording(text)
            ? haptics::recording_script(text, script_path.string(), script_path.parent_path())
            : parse_script(text, script_path.string(), script_path.parent_path());
    // A checkpoint that cannot be written fails now, before any work.
    for (std::size_t k = 0; k < script.steps.size(); ++k) {
        const ScriptStep& step = script.steps[k];
        if (const auto* save = std::get_if<SaveOp>(&step.operation)) {
            try {
                check_writable(save->path);
                check_not_overwriting(save->path, script_path, "the script being run");
            } catch (const std::runtime_error& e) {
                throw std::runtime_error(script_path.string() + ":" + std::to_string(step.line) +
                                         ": operation " + std::to_string(k + 1) +
                                         " (save): " + e.what());
            }
        }
    }

    // --physics gpu: the relaxation runs on the GPU (engine/gpu), fed by the TIN's journal.
    // auto (the default): on the GPU when the Vulkan device is a hardware GPU, on the CPU
    // on a software device (lavapipe) or without one; the device is asked only when the script
    // erodes.
    const std::string choice = args.text_or("--physics", "auto");
    if (choice != "auto" && choice != "cpu" && choice != "gpu") {
        throw UsageError("--physics must be auto, cpu or gpu, not '" + choice +
                         "'\nusage: " + std::string(kRunUsage));
    }
    std::unique_ptr<gpu::VulkanContext> gpu_context;
    if (choice == "gpu") {
        try {
            gpu_context = std::make_unique<gpu::VulkanContext>(gpu::ContextOptions{});
        } catch (const gpu::GpuUnavailable& e) {
            throw std::runtime_error(std::string("--physics gpu: no Vulkan device (") + e.what() +
                                     "); use --physics cpu");
        }
    } else if (choice == "auto" && script.uses_physics) {
        try {
            gpu_context = std::make_unique<gpu::VulkanContext>(gpu::ContextOptions{});
            if (!gpu::prefers_gpu_physics(gpu_context->properties().deviceType))
                gpu_context.reset();
        } catch (const gpu::GpuUnavailable&) {
            // No Vulkan device: the CPU, as asked for.
        }
    }
    const std::string physics = gpu_context ? "gpu" : "cpu";
    RelaxationSolverFactory make_solver;
    if (gpu_context) {
        make_solver = [&gpu_context](Tin& t, const TalusSettings& s, const MaterialTable& m) {
            return gpu::make_relaxation_solver(
                t, m, s,
                gpu::RelaxationPlacement{.device = SolverDevice::Gpu,
                                         .context = gpu_context.get()});
        };
    }

    Session session;
    TinOptions options;
    options.track_changes = false;  // the GPU mirror reads the journal with a reader of its own
    Tin tin = [&] {
        if (args.has("-i")) {
            session = load_session(args.text("-i"));
            return take_session_terrain(session, args.text("-i"), options);
        }
        if (!script.terrain) {
            throw UsageError(
                "no terrain: give -i in.sandtin or a \"terrain\" object in the script\nusage: " +
                std::string(kRunUsage));
        }
        return make_script_terrain(*script.terrain, options);
    }();
    SculptContext context(tin.domain());
    context.set_next_generation(session.next_generation);
    const double volume_before = tin.volume();
    ProgressLine progress("run " + script_path.filename().string());
    const nlohmann::json steps =
        run_script(script, tin, context, make_solver, &session, progress.callback());
    progress.finish();
    for (const nlohmann::json& step : steps) {
        if (const auto w = step.find("warning"); w != step.end() && w->is_string()) {
            std::cerr << "sandtin run: warning: " << w->get<std::string>() << "\n";
        }
    }

    session.terrain = tin.snapshot();
    session.next_generation = context.peek_generation();
    save_session(out, session);
    nlohmann::json j;
    j["steps"] = steps;
    j["terrain"] = describe_terrain(tin);
    j["volume_before"] = volume_before;
    j["physics"] = physics;
    if (gpu_context) j["device"] = gpu_context->describe();
    j["file"] = out;
    if (args.has("--json")) {
        std::cout << j.dump(2) << "\n";
    } else {
        std::cout << "ran " << steps.size() << " operations; wrote " << out << ": "
                  << tin.vertex_count() << " vertices, " << tin.triangle_count()
                  << " triangles, volume " << tin.volume() << " m^3 (was " << volume_before
                  << ")\n";
    }
    return j["terrain"]["valid"].get<bool>() ? 0 : 1;
}

}  // namespace sandtin::cli
