// Where a stamp would move sand (tools/imprint_activity.hpp), on a terrain with a trench dug
// to the tool's floor: fresh sand is active, sand already at the floor is not, and a contour
// grazing the trench's wall (less than `lateral` outside its edge) is a wall, not sand to move.

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "tin/tin.hpp"
#include "tools/imprint_activity.hpp"

namespace sandtin {
namespace {

constexpr double kTop = 0.1;
constexpr double kFloor = 0.095;
constexpr double kTrenchEdge = 0.51;  // the trench spans y in [0.49, 0.51]
constexpr double kTolerance = 1e-4;
constexpr double kLateral = 0.004;

// A 500 x 500 grid (2 mm cells) with the trench at the floor; its walls are one cell wide.
Tin trench_terrain() {
    Tin tin = Tin::regular_grid(Rect::from_size(1.0, 1.0), 500, 500, [](Vec2 p) {
        return std::abs(p.y - 0.5) <= kTrenchEdge - 0.5 + 1e-12 ? kFloor : kTop;
    });
    return tin;
}

std::vector<Vec2> square(Vec2 centre, double half) {
    return {centre + Vec2{-half, -half}, centre + Vec2{half, -half}, centre + Vec2{half, half},
            centre + Vec2{-half, half}};
}

const ImprintHeight dig_to_floor = [](Vec2, double terrain) { return std::min(terrain, kFloor); };

ImprintActivity activity_of(Tin& tin, const std::vector<Vec2>& inner) {
    LocateHint hint;
    return inner_contour_activity(tin, inner, dig_to_floor, kTolerance, kLateral, &hint);
}

TEST(ImprintActivity, FreshSandIsActiveEverywhere) {
    Tin tin = trench_terrain();
    const ImprintActivity a = activity_of(tin, square({0.3, 0.8}, 0.02));
    EXPECT_TRUE(a.any_segment);
    EXPECT_EQ(std::count(a.inner_active.begin(), a.inner_active.end(), 1), 4);
}

TEST(ImprintActivity, SandAlreadyAtTheFloorIsNot) {
    Tin tin = trench_terrain();
    const std::vector<Vec2> inner = square({0.3, 0.5}, 0.008);
    EXPECT_FALSE(activity_of(tin, inner).any_segment);
    LocateHint hint;
    EXPECT_FALSE(interior_stands_off(tin, inner, dig_to_floor, kTolerance, kLateral, {0.3, 0.5},
                                     0.012, &hint));
}

TEST(ImprintActivity, AContourGrazingTheWallIsNotActiveButOneInFreshSandIs) {
    Tin tin = trench_terrain();
    // The top edge 1 mm outside the trench's edge, on its 2 mm wall (2.5 mm above the floor
    // there): the floor is a lateral allowance further in, so that edge moves nothing. (The
    // side edges' top ends are on the wall too, with more wall further in along their inward
    // normal: they may act, carving that corner.)
    const double half = 0.01;
    const std::vector<Vec2> grazing = square({0.3, kTrenchEdge + 0.001 - half}, half);
    const ImprintActivity g = activity_of(tin, grazing);
    EXPECT_EQ(g.inner_active[0], 0);  // the bottom edge, in the trench
    EXPECT_EQ(g.inner_active[2], 0);  // the top edge, from (+h, +h) to (-h, +h), on the wall
    // The same square 10 mm outside the edge: its top edge lies in fresh sand.
    const std::vector<Vec2> beyond = square({0.3, kTrenchEdge + 0.01 - half}, half);
    const ImprintActivity b = activity_of(tin, beyond);
    EXPECT_TRUE(b.any_segment);
    EXPECT_EQ(b.inner_active[0], 0);
    EXPECT_EQ(b.inner_active[2], 1);
    // Inside the grazing square every vertex is at the floor; inside the other one, vertices
    // of the fresh sand stand off farther than the allowance from the contour.
    LocateHint hint;
    EXPECT_FALSE(interior_stands_off(tin, grazing, dig_to_floor, kTolerance, kLateral,
                                     {0.3, kTrenchEdge + 0.001 - half}, 0.02, &hint));
    EXPECT_TRUE(interior_stands_off(tin, beyond, dig_to_floor, kTolerance, kLateral,
                                    {0.3, kTrenchEdge + 0.01 - half}, 0.02, &hint));
}

}  // namespace
}  // namespace sandtin
