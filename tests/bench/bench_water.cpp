#include "bench_water.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "bench_water_throughput.hpp"
#include "support/scattered_tin.hpp"
#include "support/swashes.hpp"
#include "water/live_water.hpp"
#include "water/shallow_water.hpp"
#include "water/tin_water_mesh.hpp"
#include "water/virtual_pipes.hpp"
#include "water/water_sources.hpp"

namespace sandtin::bench {

namespace {

constexpr double kDam = 5.0, kDamTime = 6.0, kUpstream = 0.005;

enum class Scheme { Pipes, FiniteVolume1, FiniteVolume2 };

const char* name_of(Scheme s) {
    switch (s) {
        case Scheme::Pipes:
            return "pipes";
        case Scheme::FiniteVolume1:
            return "finite_volume_order1";
        case Scheme::FiniteVolume2:
            return "finite_volume_order2";
    }
    return "";
}

void set_initial(VirtualPipes& w, std::size_t v, double h, Vec2) {
    w.set_depth(v, h);
}
void set_initial(ShallowWater& w, std::size_t v, double h, Vec2 u) {
    w.set_state(v, h, u);
}

/// Runs `w` for `seconds` at its stable step; the steps taken.
template <class Water>
std::size_t run_for(Water& w, double seconds) {
    double t = 0.0;
    std::size_t steps = 0;
    while (t < seconds) {
        const double dt = std::min(w.stable_time_step(), seconds - t);
        if (!std::isfinite(dt)) break;
        w.step(dt);
        t += dt;
        ++steps;
    }
    return steps;
}

template <class Water, class Exact>
double relative_l1(const Water& w, Exact exact) {
    double error = 0.0, norm = 0.0;
    for (std::size_t v = 0; v < w.vertex_count(); ++v) {
        const double a = w.mesh().area[v], e = exact(w.mesh().position[v]);
        error += a * std::abs(w.depth(v) - e);
        norm += a * e;
    }
    return error / norm;
}

/// One run of a scheme on a mesh, from an initial state to an exact answer at `seconds`.
template <class Water, class Initial, class Exact>
nlohmann::json measure(Water w, double spacing, double seconds, Initial initial, Exact exact) {
    for (std::size_t v = 0; v < w.vertex_count(); ++v) {
        if (!(w.mesh().area[v] > 0.0)) continue;
        const auto [h, u] = initial(w.mesh().position[v]);
        if (h > 0.0) set_initial(w, v, h, u);
    }
    const CpuStopwatch clock;
    const std::size_t steps = run_for(w, seconds);
    const double ms = clock.ms();
    return {
        {"spacing_m", spacing},
        {"cells", w.vertex_count()},
        {"steps", steps},
        {"cpu_ms", ms},
        {"l1", relative_l1(w, exact)},
        {"cell_updates_per_second", static_cast<double>(steps * w.vertex_count()) / (ms * 1e-3)}};
}

template <class Initial, class Exact>
nlohmann::json measure(Scheme s, const Tin& tin, double spacing, double seconds, Initial initial,
                       Exact exact) {
    if (s == Scheme::Pipes) {
        VirtualPipeOptions o;
        o.friction = 0.0;  // the analytic solutions are frictionless
        return measure(VirtualPipes(water_mesh_of(tin), o), spacing, seconds, initial, exact);
    }
    ShallowWaterOptions o;
    o.order = s == Scheme::FiniteVolume1 ? 1 : 2;
    return measure(ShallowWater(water_mesh_of(tin), o), spacing, seconds, initial, exact);
}

/// The least-squares slope of log(l1) against log(spacing) over the levels.
double fitted_order(const nlohmann::json& levels) {
    double sx = 0, sy = 0, sxx = 0, sxy = 0, n = 0;
    for (const nlohmann::json& l : levels) {
        const double x = std::log(l.at("spacing_m").get<double>());
        const double y = std::log(l.at("l1").get<double>());
        sx += x;
        sy += y;
        sxx += x * x;
        sxy += x * y;
        n += 1.0;
    }
    return n > 1.0 ? (n * sxy - sx * sy) / (n * sxx - sx * sx) : 0.0;
}

constexpr Scheme kSchemes[] = {Scheme::Pipes, Scheme::FiniteVolume1, Scheme::FiniteVolume2};

nlohmann::json dam_breaks(const std::vector<double>& spacings, WeightedProgress& progress) {
    nlohmann::json out = nlohmann::json::array();
    for (const double downstream : {0.0, 0.001}) {
        const std::string name = downstream == 0.0 ? "ritter" : "stoker";
        nlohmann::json schemes = nlohmann::json::object();
        for (const Scheme s : kSchemes) {
            nlohmann::json levels = nlohmann::json::array();
            for (const double spacing : spacings) {
                progress.start(name + " " + name_of(s), 0.08 / spacing);
                const Tin strip =
                    support::scattered_tin(Rect{{0.0, 0.0}, {10.0, 0.2}}, spacing, 21);
                const auto initial = [downstream](Vec2 p) {
                    return std::pair{p.x < kDam ? kUpstream : downstream, Vec2{}};
                };
                const auto exact = [downstream](Vec2 p) {
                    return downstream == 0.0
                               ? swashes::ritter(p.x, kDam, kUpstream, kDamTime)
                               : swashes::stoker(p.x, kDam, kUpstream, downstream, kDamTime);
                };
                levels.push_back(measure(s, strip, spacing, kDamTime, initial, exact));
            }
            schemes[name_of(s)] = {{"levels", levels}, {"fitted_order", fitted_order(levels)}};
        }
        out.push_back({{"case", name}, {"downstream_m", downstream}, {"schemes", schemes}});
    }
    return out;
}

nlohmann::json thacker(const std::vector<double>& spacings, WeightedProgress& progress) {
    const swashes::ThackerPlanar t;
    // Only the finite volumes: the pipes carry no velocity, so they cannot start the lake's
    // sloshing (their front speed is measured on the dam breaks).
    nlohmann::json schemes = nlohmann::json::object();
    for (const Scheme s : {Scheme::FiniteVolume1, Scheme::FiniteVolume2}) {
        nlohmann::json levels = nlohmann::json::array();
        for (const double spacing : spacings) {
            progress.start(std::string("thacker ") + name_of(s), 0.5 / spacing);
            const Tin bowl = support::scattered_tin(Rect{{-1.6, -1.6}, {1.6, 1.6}}, spacing, 22,
                                                    [&](Vec2 p) { return t.bed(p); });
            const auto initial = [&](Vec2 p) {
                return std::pair{t.depth(p, 0.0), t.velocity(0.0)};
            };
            const auto exact = [&](Vec2 p) { return t.depth(p, t.period()); };
            levels.push_back(measure(s, bowl, spacing, t.period(), initial, exact));
        }
        schemes[name_of(s)] = {{"levels", levels}, {"fitted_order", fitted_order(levels)}};
    }
    return {{"period_s", t.period()}, {"schemes", schemes}};
}

double bumpy(Vec2 p) {
    return 0.05 * std::sin(7.0 * p.x) * std::cos(5.0 * p.y) + 0.03 * p.x;
}

nlohmann::json lake_at_rest(std::size_t steps) {
    const Tin tin = support::scattered_tin(Rect::from_size(1, 1), 0.04, 23, bumpy);
    ShallowWater w(water_mesh_of(tin));
    const double level = 0.02;
    for (std::size_t v = 0; v < w.vertex_count(); ++v) {
        if (w.mesh().area[v] > 0.0) w.set_state(v, std::max(0.0, level - w.mesh().bed[v]));
    }
    const double dt = w.stable_time_step();
    const CpuStopwatch clock;
    for (std::size_t k = 0; k < steps; ++k)
        w.step(dt);
    const double ms = clock.ms();
    double fastest = 0.0, off_level = 0.0;
    for (std::size_t v = 0; v < w.vertex_count(); ++v) {
        fastest = std::max(fastest, length(w.velocity(v)));
        if (w.depth(v) > 0.0) off_level = std::max(off_level, std::abs(w.surface(v) - level));
    }
    return {{"scheme", name_of(Scheme::FiniteVolume2)},
            {"cells", w.vertex_count()},
            {"steps", steps},
            {"largest_speed_m_per_s", fastest},
            {"largest_surface_error_m", off_level},
            {"cpu_ms", ms}};
}

/// ms per step (median of `steps`) of rain at 50 mm/h on a slope of `spacing`, after 2 s
/// of it; and a dry terrain's step.
template <class Water>
nlohmann::json rain_cost(const Tin& tin, std::size_t steps) {
    Water w(water_mesh_of(tin));
    WaterSources rain;
    rain.rain.push_back({50.0, {}, 0.0});
    const CpuStopwatch dry_clock;
    w.step(0.01);
    const double dry_ms = dry_clock.ms();
    double t = 0.0;
    std::vector<double> ms;
    while (t < 2.0 || ms.size() < steps) {
        const double dt = std::min(w.stable_time_step(), 0.05);
        apply_sources(w, rain, dt);
        const CpuStopwatch clock;
        w.step(dt);
        if (t >= 2.0) ms.push_back(clock.ms());
        t += dt;
    }
    return {{"step_ms_median", median(ms)}, {"dry_step_ms", dry_ms}};
}

/// The editor's water (water/live_water.hpp) on a bowl of `spacing`: CPU ms per 1/60 s frame
/// (unbounded budget) with a 0.1 L/s nozzle held at its centre for a second; the simulated
/// seconds until the pond rests; then the frame after an edit far from the pond (the erosion
/// sliding on a far slope: it must not wake the water) and after one under it, and an idle
/// frame.
nlohmann::json live_water_cost(double spacing) {
    Tin tin = support::scattered_tin(Rect::from_size(1, 1), spacing, 27, [](Vec2 p) {
        return 0.2 * ((p.x - 0.5) * (p.x - 0.5) + (p.y - 0.5) * (p.y - 0.5));
    });
    LiveWater water(tin);
    LiveWaterSettings settings;
    settings.friction = 4.0;
    constexpr double kFrame = 1.0 / 60.0;
    const auto timed_frame = [&](std::vector<double>& ms, std::size_t* steps = nullptr) {
        const CpuStopwatch clock;
        const LiveWaterFrame f = water.advance(kFrame, settings, 1e9);
        ms.push_back(clock.ms());
        if (steps) *steps += f.steps;
        return f;
    };
    std::vector<double> nozzle_ms;
    std::size_t nozzle_steps = 0;
    for (int i = 0; i < 60; ++i) {
        water.add_nozzle({{0.5, 0.5}, 0.1});
        timed_frame(nozzle_ms, &nozzle_steps);
    }
    double to_rest = 1.0;
    while (!water.resting() && to_rest < 600.0) {
        water.advance(1.0, settings, 1e9);
        to_rest += 1.0;
    }
    const bool rested = water.resting();
    // The vertex farthest from the pond, and the deepest one.
    const VertexArrays& va = tin.vertices();
    VertexId far, deep;
    for (std::uint32_t v = 0; v < va.size(); ++v) {
        if (!va.alive[v]) continue;
        if (!far.valid() || length(va.position[v] - Vec2{0.5, 0.5}) >
                                length(va.position[far.index()] - Vec2{0.5, 0.5}))
            far = VertexId{v};
        if (!deep.valid() || va.water_depth[v] > va.water_depth[deep.index()]) deep = VertexId{v};
    }
    std::vector<double> far_ms, idle_ms, under_ms;
    std::size_t woke_far = 0;
    for (int i = 0; i < 30; ++i) {
        tin.set_height(far, tin.height(far) - 1e-5);
        woke_far += timed_frame(far_ms).ran ? 1 : 0;
        timed_frame(idle_ms);
    }
    tin.set_height(deep, tin.height(deep) - 1e-4);
    const bool woke_under = timed_frame(under_ms).ran;
    return {{"cells", tin.vertex_count()},
            {"nozzle_frame_ms_median", median(nozzle_ms)},
            {"nozzle_steps_per_frame", static_cast<double>(nozzle_steps) / 60.0},
            {"seconds_to_rest", rested ? nlohmann::json(to_rest) : nlohmann::json()},
            {"far_edit_frame_ms_median", median(far_ms)},
            {"far_edits_that_woke_it", woke_far},
            {"idle_frame_ms_median", median(idle_ms)},
            {"edit_under_water_frame_ms", under_ms.front()},
            {"edit_under_water_woke_it", woke_under}};
}

}  // namespace

nlohmann::json bench_water(const BenchConfig& config) {
    const std::vector<double> dam_spacings =
        config.quick ? std::vector<double>{0.08, 0.04} : std::vector<double>{0.08, 0.04, 0.02};
    const std::vector<double> bowl_spacings =
        config.quick ? std::vector<double>{0.1} : std::vector<double>{0.1, 0.05};
    double weight = 0.0;
    for (double s : dam_spacings)
        weight += 2.0 * 3.0 * 0.08 / s;
    for (double s : bowl_spacings)
        weight += 2.0 * 0.5 / s;
    weight += config.quick ? 8.0 : 30.0;
    WeightedProgress progress(config.progress, weight);

    nlohmann::json j;
    j["bench"] = "water";
    j["quick"] = config.quick;
    j["dam_breaks"] = dam_breaks(dam_spacings, progress);
    j["thacker"] = thacker(bowl_spacings, progress);
    progress.start("lake at rest", 2.0);
    j["lake_at_rest"] = lake_at_rest(config.quick ? 1000 : 10000);
    progress.start("rain", 2.0);
    nlohmann::json rain = nlohmann::json::array();
    for (const double spacing :
         config.quick ? std::vector<double>{0.02} : std::vector<double>{0.02, 0.005}) {
        const Tin slope = support::scattered_tin(Rect::from_size(1, 1), spacing, 24,
                                                 [](Vec2 p) { return 0.1 * p.x; });
        rain.push_back({{"cells", slope.vertex_count()},
                        {"pipes", rain_cost<VirtualPipes>(slope, 20)},
                        {"finite_volume_order2", rain_cost<ShallowWater>(slope, 20)}});
    }
    j["rain_on_a_slope"] = rain;
    progress.start("live water", 2.0);
    nlohmann::json live = nlohmann::json::array();
    for (const double spacing :
         config.quick ? std::vector<double>{0.01} : std::vector<double>{0.01, 0.005})
        live.push_back(live_water_cost(spacing));
    j["live_water"] = live;
    progress.start("throughput, CPU and GPU", config.quick ? 2.0 : 24.0);
    j["throughput"] = water_throughput(
        config.quick ? std::vector<std::size_t>{20000} : std::vector<std::size_t>{100000, 1000000},
        config.quick ? 5 : 10);
    progress.done();
    return j;
}

}  // namespace sandtin::bench
