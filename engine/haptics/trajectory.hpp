#pragma once
// Device trajectories: one pose per loop tick. The simulated device replays them and
// sandtin-haptic-replay plays them over UDP.
//
// Text file format (".traj"), one record per line, '#' starts a comment line:
//
//   sandtin-haptic-trajectory 1
//   rate_hz 1000
//   samples 3
//   0.5 0.5 0.1 0          x y z (m, terrain frame) and the button bits (decimal)
//   0.5 0.5 0.099 0
//   0.5 0.5 0.098 1
//
// Numbers are written with 17 significant digits so a file round-trips exactly. Readers check
// the header, the count, finiteness and the button field, and name the line of any problem.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "geom/vec3.hpp"

namespace sandtin::haptics {

struct TrajectorySample {
    Vec3 position;  ///< m
    std::uint32_t buttons = 0;
    friend bool operator==(const TrajectorySample&, const TrajectorySample&) = default;
};

struct Trajectory {
    double rate_hz = 1000.0;
    std::vector<TrajectorySample> samples;
};

inline constexpr std::string_view kTrajectoryMagic = "sandtin-haptic-trajectory";
inline constexpr int kTrajectoryVersion = 1;

std::string format_trajectory(const Trajectory& trajectory);
/// Throws std::runtime_error "<name>:<line>: <problem>".
Trajectory parse_trajectory(std::string_view text, const std::string& name = "trajectory");

Trajectory load_trajectory(const std::filesystem::path& path);
void save_trajectory(const std::filesystem::path& path, const Trajectory& trajectory);

/// A normal stroke, for tests, assets and benchmarks: the pen hovers above `start`, descends
/// to `depth` metres below `surface`, presses the button, drags to `end` at `speed` m/s,
/// releases and lifts back. Ticks at `rate_hz`.
struct StrokeTrajectorySpec {
    double rate_hz = 1000.0;
    double surface = 0.0;         ///< m, terrain height along the stroke
    double hover = 0.01;          ///< m above the surface at the start and end
    double depth = 0.004;         ///< m below the surface while dragging
    double descend_speed = 0.05;  ///< m/s, vertical
    double speed = 0.1;           ///< m/s, along the stroke
    double dwell = 0.05;          ///< s at rest at the bottom before and after the drag
    double start_x = 0.3, start_y = 0.5;
    double end_x = 0.7, end_y = 0.5;
};
Trajectory make_stroke_trajectory(const StrokeTrajectorySpec& spec);

/// Circles of `radius` around (cx, cy), each one pressed `depth` below `surface` while the
/// button is down, with a lift between circles: a long periodic workload for benchmarks.
struct CircleTrajectorySpec {
    double rate_hz = 1000.0;
    double seconds = 10.0;
    double surface = 0.0;
    double depth = 0.003;
    double hover = 0.005;
    double cx = 0.5, cy = 0.5;
    double radius = 0.25;
    double period_s = 2.5;  ///< one circle
};
Trajectory make_circle_trajectory(const CircleTrajectorySpec& spec);

}  // namespace sandtin::haptics
