// Trajectory files: exact round trip, clear errors, and the synthetic strokes' shape.

#include <gtest/gtest.h>

#include "haptics/haptic_device.hpp"
#include "haptics/trajectory.hpp"

namespace sandtin::haptics {
namespace {

std::string error_of(const std::string& text) {
    try {
        parse_trajectory(text, "t.traj");
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "";
}

TEST(Trajectory, RoundTripsExactly) {
    Trajectory t;
    t.rate_hz = 2000.0;
    t.samples = {{{0.1, 0.2, 1.0 / 3.0}, 0}, {{1e-300, -0.0, 123456.789}, 5}};
    const Trajectory u = parse_trajectory(format_trajectory(t));
    EXPECT_EQ(u.rate_hz, 2000.0);
    EXPECT_EQ(u.samples, t.samples);
}

TEST(Trajectory, ErrorsNameTheLineAndProblem) {
    EXPECT_NE(error_of("hello 1\n").find("t.traj:1: not a trajectory"), std::string::npos);
    EXPECT_NE(error_of("sandtin-haptic-trajectory 2\n").find("unsupported"), std::string::npos);
    const std::string head = "sandtin-haptic-trajectory 1\nrate_hz 1000\nsamples 2\n";
    EXPECT_NE(error_of(head + "0 0 0 0\n").find("truncated"), std::string::npos);
    EXPECT_NE(error_of(head + "0 0 nan 0\n0 0 0 0\n").find("t.traj:4: z is not a finite"),
              std::string::npos);
    EXPECT_NE(error_of(head + "0 0 0\n").find("4 fields"), std::string::npos);
    EXPECT_NE(error_of(head + "0 0 0 -1\n0 0 0 0\n").find("buttons"), std::string::npos);
    EXPECT_NE(error_of(head + "0 0 0 0\n0 0 0 0\n0 0 0 0\n").find("more samples"),
              std::string::npos);
    EXPECT_NE(error_of("sandtin-haptic-trajectory 1\nrate_hz -5\n").find("rate_hz"),
              std::string::npos);
    // Comments and blank lines are fine.
    EXPECT_EQ(error_of("# c\n\nsandtin-haptic-trajectory 1\nrate_hz 1000\nsamples 0\n"), "");
}

TEST(Trajectory, SyntheticStrokeDescendsPressesDragsAndLifts) {
    StrokeTrajectorySpec spec;
    spec.surface = 0.05;
    const Trajectory t = make_stroke_trajectory(spec);
    ASSERT_GT(t.samples.size(), 4000u);  // 0.4 m at 0.1 m/s
    double lowest = 1.0;
    bool pressed_deep = false;
    for (const TrajectorySample& s : t.samples) {
        lowest = std::min(lowest, s.position.z);
        if (s.buttons & kMainButton) {
            EXPECT_NEAR(s.position.z, 0.05 - 0.004, 1e-12);
            pressed_deep = true;
        }
    }
    EXPECT_TRUE(pressed_deep);
    EXPECT_NEAR(lowest, 0.046, 1e-12);
    EXPECT_EQ(t.samples.front().buttons, 0u);
    EXPECT_EQ(t.samples.back().buttons, 0u);
    EXPECT_NEAR(t.samples.back().position.x, 0.7, 1e-12);
    // Consecutive samples never move more than speed / rate.
    for (std::size_t i = 1; i < t.samples.size(); ++i)
        EXPECT_LE(length(t.samples[i].position - t.samples[i - 1].position), 1e-4 + 1e-12);
}

TEST(Trajectory, CirclesLastTheRequestedTime) {
    CircleTrajectorySpec spec;
    spec.seconds = 3.0;
    const Trajectory t = make_circle_trajectory(spec);
    EXPECT_EQ(t.samples.size(), 3000u);
    std::size_t pressed = 0;
    for (const auto& s : t.samples)
        pressed += (s.buttons & kMainButton) ? 1 : 0;
    EXPECT_GT(pressed, 1500u);
}

}  // namespace
}  // namespace sandtin::haptics
