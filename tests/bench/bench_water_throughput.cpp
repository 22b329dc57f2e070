#include "bench_water_throughput.hpp"

#include <cmath>
#include <memory>
#include <string>

#include "bench_common.hpp"
#include "gpu/gpu_error.hpp"
#include "gpu/gpu_water.hpp"
#include "gpu/tin_mirror.hpp"
#include "gpu/vulkan_context.hpp"
#include "tin/tin.hpp"
#include "util/thread_pool.hpp"
#include "water/tin_water_mesh.hpp"
#include "water/virtual_pipes.hpp"

namespace sandtin::bench {

namespace {

/// `n` random points at about 1 m spacing, a lake 1 m deep over 0.3 m bumps, and a 0.2 m
/// swell in one corner: every vertex wet, the water moving everywhere within a few seconds.
Tin wet_terrain(std::size_t n) {
    const double side = std::sqrt(static_cast<double>(n));
    Tin tin = Tin::random_points(Rect::from_size(side, side), n, 41, [](Vec2 p) {
        return 0.3 * std::sin(0.7 * p.x) * std::cos(0.5 * p.y);
    });
    const VertexArrays& va = tin.vertices();
    for (std::uint32_t v = 0; v < va.size(); ++v) {
        if (!va.alive[v]) continue;
        const double r = length(va.position[v] - Vec2{0.25 * side, 0.25 * side});
        const double swell = 0.2 * std::exp(-r * r / (0.01 * side * side));
        tin.set_water_depth(VertexId{v}, 1.0 - va.height[v] + swell);
    }
    return tin;
}

nlohmann::json rate(const std::vector<double>& step_ms, std::size_t vertices) {
    const double ms = median(step_ms);
    return {{"step_ms_median", ms},
            {"vertex_steps_per_s", static_cast<double>(vertices) / (ms * 1e-3)}};
}

/// CPU steps of the pipes on `threads` threads, timed on the wall clock (the threads'
/// CPU time would add up): the 1- and 2-thread rows run side by side on the same lake.
nlohmann::json cpu_rate(const Tin& tin, int steps, int threads) {
    VirtualPipes pipes(water_mesh_of(tin));
    load_water_depths(pipes, tin);
    ThreadPool pool(threads);
    const double dt = pipes.stable_time_step();
    pipes.step(dt, pool);  // the scratch arrays warm
    std::vector<double> ms;
    for (int i = 0; i < steps; ++i) {
        const Stopwatch clock;
        pipes.step(dt, pool);
        ms.push_back(clock.ms());
    }
    nlohmann::json j = rate(ms, tin.vertex_count());
    j["threads"] = threads;
    j["clock"] = "wall";
    return j;
}

nlohmann::json gpu_rate(gpu::VulkanContext& context, Tin& tin, int steps) {
    gpu::TinMirror mirror(context, tin);
    gpu::GpuWater water(mirror);
    const double dt = water.stable_time_step();
    water.run(1, dt);  // pipelines and caches warm
    // Submissions of `steps` steps each (one wait per submission, as a frame would): the
    // per-step figure includes the submission's share.
    std::vector<double> ms;
    for (int i = 0; i < 5; ++i) {
        const Stopwatch clock;
        water.run(steps, dt);
        ms.push_back(clock.ms() / steps);
    }
    nlohmann::json j = rate(ms, tin.vertex_count());
    j["device"] = context.device_name();
    j["steps_per_submission"] = steps;
    return j;
}

}  // namespace

nlohmann::json water_throughput(const std::vector<std::size_t>& vertices, int steps) {
    std::unique_ptr<gpu::VulkanContext> context;
    std::string unavailable;
    try {
        context = std::make_unique<gpu::VulkanContext>(gpu::ContextOptions{});
    } catch (const gpu::GpuUnavailable& e) {
        unavailable = e.what();
    }
    nlohmann::json rows = nlohmann::json::array();
    for (const std::size_t n : vertices) {
        Tin tin = wet_terrain(n);
        nlohmann::json row{{"vertices", tin.vertex_count()}, {"cpu", cpu_rate(tin, steps, 1)}};
        row["cpu_2_threads"] = cpu_rate(tin, steps, 2);
        row["cpu_2_threads"]["speedup"] = row["cpu"]["step_ms_median"].get<double>() /
                                          row["cpu_2_threads"]["step_ms_median"].get<double>();
        row["gpu"] =
            context ? gpu_rate(*context, tin, steps) : nlohmann::json{{"unavailable", unavailable}};
        rows.push_back(row);
    }
    return rows;
}

}  // namespace sandtin::bench
