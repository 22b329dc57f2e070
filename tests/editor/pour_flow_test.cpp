// The pour flow: the dabs of a held Pour or Remove depend on the gesture (its path and how
// long it is held), never on how many mouse events or frames delivered it.

#include <gtest/gtest.h>

#include <cmath>

#include "pour_flow.hpp"

namespace sandtin::editor {
namespace {

/// Every dab of a straight drag from (0, 0) to (length, 0) delivered as `events` moves.
std::vector<Vec2> drag(double spacing, double length, int events) {
    PourFlow flow(spacing);
    std::vector<Vec2> dabs = flow.press({0.0, 0.0});
    for (int i = 1; i <= events; ++i) {
        for (Vec2 p : flow.move({length * i / events, 0.0}))
            dabs.push_back(p);
    }
    return dabs;
}

TEST(PourFlow, AClickIsOneDab) {
    PourFlow flow(0.01);
    const std::vector<Vec2> dabs = flow.press({0.3, 0.4});
    ASSERT_EQ(dabs.size(), 1u);
    EXPECT_EQ(dabs[0].x, 0.3);
    EXPECT_TRUE(flow.move({0.3, 0.4}).empty()) << "a move that goes nowhere pours again";
}

TEST(PourFlow, ADragDabsByDistanceNotByEvents) {
    // 0.095 m at 0.01 m: the press and nine more, however many events carried the drag.
    for (int events : {1, 2, 3, 41, 500}) {
        const std::vector<Vec2> dabs = drag(0.01, 0.095, events);
        ASSERT_EQ(dabs.size(), 10u) << events << " events";
        for (std::size_t i = 0; i < dabs.size(); ++i)
            EXPECT_NEAR(dabs[i].x, 0.01 * static_cast<double>(i), 1e-12) << events << " events";
    }
}

TEST(PourFlow, HoldingStillDabsFourTimesASecondWhateverTheFrameRate) {
    for (double fps : {10.0, 60.0, 144.0}) {
        PourFlow flow(0.01);
        std::size_t dabs = flow.press({0.5, 0.5}).size();
        // 2.1 s held: 8 more dabs at 4 a second.
        const int frames = static_cast<int>(std::lround(2.1 * fps));
        for (int f = 0; f < frames; ++f)
            dabs += flow.hold(1.0 / fps).size();
        EXPECT_EQ(dabs, 1u + 8u) << fps << " frames a second";
    }
}

TEST(PourFlow, TimeCountsFromTheLastDab) {
    // A drag that keeps dabbing is not given timed dabs on top.
    PourFlow flow(0.01);
    flow.press({0.0, 0.0});
    (void)flow.hold(0.2);
    EXPECT_EQ(flow.move({0.01, 0.0}).size(), 1u);
    EXPECT_TRUE(flow.hold(0.2).empty()) << "0.2 s since the last dab";
    EXPECT_EQ(flow.hold(0.05).size(), 1u);
}

}  // namespace
}  // namespace sandtin::editor
