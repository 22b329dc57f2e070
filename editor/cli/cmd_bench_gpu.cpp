// sandtin bench gpu: GPU relaxation throughput against the CPU Jacobi schedule (1 and 2
// threads), upload bytes per stamp on a 10^6-vertex mirror, per-kernel GPU times (timestamp
// queries), normals and bake times, and the device it ran on. Printed as JSON.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <nlohmann/json.hpp>
#include <vector>

#include "arguments.hpp"
#include "commands.hpp"
#include "gpu/gpu_error.hpp"
#include "gpu/gpu_relaxation.hpp"
#include "gpu/surface_maps.hpp"
#include "gpu/tin_mirror.hpp"
#include "gpu/vulkan_context.hpp"
#include "physics/active_set.hpp"
#include "physics/talus_solver.hpp"
#include "progress_line.hpp"
#include "tools/stamp.hpp"
#include "tools/tool.hpp"

namespace sandtin::cli {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Rough sand: every vertex starts far above its angle of repose, so the whole terrain stays
// active for the measured iterations.
double rough(Vec2 p) {
    const double s = std::sin(p.x * 12.9898 + p.y * 78.233) * 43758.5453;
    return 0.3 * (s - std::floor(s));
}

std::vector<uint32_t> live(const Tin& tin) {
    std::vector<uint32_t> ids;
    const VertexArrays& va = tin.vertices();
    for (uint32_t v = 0; v < va.size(); ++v)
        if (va.alive[v]) ids.push_back(v);
    return ids;
}

// CPU Jacobi on a copy of the heights: vertex-updates per second.
double cpu_rate(const Tin& tin, const gpu::TinMirror& mirror, int threads, int iterations) {
    TalusSettings s;
    s.schedule = Schedule::Jacobi;
    s.threads = threads;
    TalusSolver solver(s);
    const VertexArrays& va = tin.vertices();
    std::vector<double> h(va.height.begin(), va.height.end());
    std::vector<double> tan_alpha(va.size());
    for (uint32_t v = 0; v < va.size(); ++v)
        tan_alpha[v] = mirror.materials().at(va.material[v]).talus_slope(va.moisture[v]);
    const TalusArrays arrays{h.data(), va.lumped_area.data(), va.bedrock.data(), tan_alpha.data(),
                             va.size()};
    ActiveSet active;
    active.activate(live(tin));
    uint64_t updates = 0;
    const auto t0 = Clock::now();
    for (int i = 0; i < iterations; ++i)
        updates += solver.iterate(mirror.graph(), arrays, active).processed;
    return static_cast<double>(updates) / seconds_since(t0);
}

nlohmann::json bench_size(gpu::VulkanContext& ctx, std::size_t vertices, int iterations) {
    Tin tin = Tin::random_points(Rect::from_size(1.0, 1.0), vertices, 99, rough);
    gpu::TinMirror mirror(ctx, tin);
    mirror.sync();
    nlohmann::json j;
    j["vertices"] = tin.vertex_count();
    j["iterations"] = iterations;
    j["cpu_jacobi_1_thread_updates_per_s"] = cpu_rate(tin, mirror, 1, iterations);
    j["cpu_jacobi_2_threads_updates_per_s"] = cpu_rate(tin, mirror, 2, iterations);

    // GPU, wall clock (submission + wait), then again with per-kernel timestamps.
    for (bool profile : {false, true}) {
        gpu::TinMirror m(ctx, tin);
        m.sync();
        gpu::GpuRelaxationSettings gs;
        gs.profile = profile;
        gpu::GpuRelaxation relax(m, gs);
        relax.activate(live(tin));
        relax.run(1);  // seeding and pipeline warm-up outside the measurement
        const auto t0 = Clock::now();
        const gpu::GpuRunStats s = relax.run(iterations);
        const double wall = seconds_since(t0);
        if (!profile) {
            j["gpu_updates_per_s"] = static_cast<double>(s.vertex_updates) / wall;
            j["gpu_ms_per_iteration"] = 1e3 * wall / iterations;
            j["gpu_dispatches_per_iteration"] =
                static_cast<double>(s.dispatches) / static_cast<double>(iterations);
        } else {
            nlohmann::json k;
            for (const auto& [name, ns] : relax.timer().totals_ns())
                k[name] = ns / 1e6 / (iterations + 1);
            j["gpu_kernel_ms_per_iteration"] = k;
        }
    }
    gpu::SurfaceMaps maps(mirror);
    maps.compute_normals();  // warm-up
    auto t0 = Clock::now();
    maps.compute_normals();
    j["normals_ms"] = 1e3 * seconds_since(t0);
    const MapGrid grid(tin.domain(), 1024, 1024, SampleAt::Centres);
    t0 = Clock::now();
    maps.bake(grid);
    j["bake_1024_ms"] = 1e3 * seconds_since(t0);
    return j;
}

nlohmann::json bench_upload(gpu::VulkanContext& ctx, std::size_t vertices, int stamps) {
    Tin tin = Tin::random_points(Rect::from_size(1.0, 1.0), vertices, 7,
                                 [](Vec2 p) { return 0.2 + 0.05 * p.x; });
    gpu::TinMirror mirror(ctx, tin);
    const gpu::SyncStats first = mirror.sync();
    SculptContext context(tin.domain());
    ToolSpec spec;
    spec.radius = 0.04;
    spec.control_points = 12;
    const Tool tool = Tool::build(spec);
    std::vector<double> bytes;
    for (int i = 0; i < stamps; ++i) {
        const Vec2 at{0.2 + 0.6 * (i % 4) / 3.0, 0.3 + 0.4 * (i / 4 % 2)};
        stamp(tin, tool, ToolPlacement{at, 0.0, 0.15}, context);
        bytes.push_back(static_cast<double>(mirror.sync().bytes));
    }
    std::sort(bytes.begin(), bytes.end());
    const double median = bytes[bytes.size() / 2];
    nlohmann::json j;
    j["vertices"] = tin.vertex_count();
    j["mirrored_bytes"] = mirror.mirrored_bytes();
    j["first_sync_bytes"] = first.bytes;
    j["stamps"] = stamps;
    j["stamp_upload_bytes_median"] = median;
    j["stamp_upload_bytes_max"] = bytes.back();
    j["stamp_upload_fraction"] = median / static_cast<double>(mirror.mirrored_bytes());
    return j;
}

}  // namespace

int run_bench_gpu(const std::vector<std::string>& raw) {
    const Arguments args(raw, {{"--quick", 0}, {"--json", 0}});
    args.require_positionals(0, "sandtin bench gpu [--quick] [--json]");
    const bool quick = args.has("--quick");
    std::unique_ptr<gpu::VulkanContext> ctx;
    try {
        ctx = std::make_unique<gpu::VulkanContext>(gpu::ContextOptions{});
    } catch (const gpu::GpuUnavailable& e) {
        throw std::runtime_error(std::string("bench gpu: no Vulkan device (") + e.what() +
                                 "); the CPU physics still works (--physics cpu)");
    }
    nlohmann::json out;
    out["benchmark"] = "gpu";
    out["device"] = ctx->describe();
    out["device_name"] = ctx->device_name();
    out["device_type"] = ctx->device_type();
    out["quick"] = quick;
    // Progress by section; the 10⁶-vertex relaxation is the long one.
    ProgressLine progress("bench gpu");
    nlohmann::json sizes = nlohmann::json::array();
    progress.report({0.0, quick ? "relaxation on 2·10⁴ vertices" : "relaxation on 10⁵ vertices"});
    sizes.push_back(bench_size(*ctx, quick ? 20000 : 100000, quick ? 5 : 20));
    if (!quick) {
        progress.report({0.2, "relaxation on 10⁶ vertices"});
        sizes.push_back(bench_size(*ctx, 1000000, 5));
    }
    out["relaxation"] = sizes;
    progress.report({quick ? 0.5 : 0.8, "uploads after stamps"});
    out["upload"] = bench_upload(*ctx, quick ? 100000 : 1000000, 8);
    progress.finish();
    out["target_gpu_updates_per_s_at_1e6"] = 2e9;
    out["note"] =
        "vertex-updates/s = active vertices processed per second; the GPU target applies to a "
        "real GPU, not lavapipe";
    std::cout << out.dump(2) << "\n";
    return 0;
}

}  // namespace sandtin::cli
