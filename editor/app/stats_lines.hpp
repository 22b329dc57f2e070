#pragma once
// The Stats window's timing lines. Their numbers grow with the machine's slowness (a frame of
// 11 ms on one machine is 9 999 ms on another), so each is written in at most
// kCappedNumberChars characters: the window can be made as wide as the widest such line,
// whatever the numbers, and does not change width as they change.

#include <array>
#include <string>

namespace sandtin::editor {

inline constexpr std::size_t kCappedNumberChars = 6;

/// A non-negative reading in at most kCappedNumberChars characters, with the precision its
/// magnitude deserves: "0.42", "12.34", "123.4", "12345", and ">99999" beyond; "-" for a
/// value that is not a finite non-negative number.
std::string capped_number(double value);

/// Medians of the frame's stages, in milliseconds (stage_times.hpp).
struct StageMedians {
    double frame = 0, tool = 0, physics = 0, mesh = 0, upload = 0, bake = 0, render = 0;
};

/// "12.3 fps (81.30 ms)", "tool 0.42  physics 12.00  mesh 0.10",
/// "upload 0.01  bake 0.00  render 60.12 ms".
std::array<std::string, 3> stats_timing_lines(const StageMedians& m);

/// The same lines with every number as wide as capped_number writes one: the width the Stats
/// window is made for.
std::array<std::string, 3> widest_stats_timing_lines();

}  // namespace sandtin::editor
