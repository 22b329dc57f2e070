// BoxGrid: which filed boxes meet a query box. The oracle is a plain list of the live boxes and
// Rect::intersects over all of them. Boxes are drawn at every scale (points, rim segments, boxes
// wider than the wide-list limit, boxes reaching outside the extent) and many corners sit
// exactly on cell boundaries, where a box filed in one cell and queried from its neighbour
// would show.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "geom/box_grid.hpp"
#include "geom/rect.hpp"

namespace sandtin {
namespace {

struct Live {
    std::uint32_t id;
    Rect box;
};

std::vector<std::uint32_t> brute_force(const std::vector<Live>& live, const Rect& q) {
    std::vector<std::uint32_t> ids;
    for (const Live& l : live) {
        if (l.box.intersects(q)) ids.push_back(l.id);
    }
    std::sort(ids.begin(), ids.end());
    return ids;
}

/// A random box over a 4 m x 2 m extent at origin (1, -1), cells 1/16 m: sizes from a point to
/// twice the extent; a third snap their coordinates to cell boundaries.
Rect random_box(std::mt19937_64& rng) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const auto coordinate = [&](double origin, double size) {
        double c = origin - 0.5 * size + 2.0 * size * unit(rng);
        if (unit(rng) < 1.0 / 3.0) c = origin + std::round((c - origin) * 16.0) / 16.0;
        return c;
    };
    const Vec2 a{coordinate(1.0, 4.0), coordinate(-1.0, 2.0)};
    const double scale = std::pow(10.0, -4.0 + 4.5 * unit(rng));  // 0.1 mm to about 3 m
    Rect r;
    r.expand(a);
    if (unit(rng) < 0.9) r.expand(a + Vec2{scale * unit(rng), scale * unit(rng)});
    return r;
}

TEST(BoxGrid, QueriesMatchABruteForceScanThroughInsertsAndErasures) {
    const Rect extent{{1.0, -1.0}, {5.0, 1.0}};
    BoxGrid grid(extent, 128);  // 16 x 8 cells of 1/4 m: many boxes span several, some are wide
    std::mt19937_64 rng(20261130);
    std::vector<Live> live;
    std::uint32_t next_id = 0;
    std::size_t hits = 0;
    std::size_t spanning = 0;
    for (int step = 0; step < 20000; ++step) {
        const double pick = std::uniform_real_distribution<double>(0.0, 1.0)(rng);
        if (pick < 0.45 || live.empty()) {
            const Rect box = random_box(rng);
            grid.insert(next_id, box);
            live.push_back({next_id++, box});
        } else if (pick < 0.8) {
            const std::size_t k =
                std::uniform_int_distribution<std::size_t>(0, live.size() - 1)(rng);
            ASSERT_TRUE(grid.erase(live[k].id, live[k].box)) << "step " << step;
            live[k] = live.back();
            live.pop_back();
        } else {
            const Rect q = random_box(rng);
            std::vector<std::uint32_t> got = {4000000000u};  // query appends after what is there
            grid.query(q, got);
            const std::vector<std::uint32_t> want = brute_force(live, q);
            ASSERT_EQ(got.front(), 4000000000u);
            got.erase(got.begin());
            ASSERT_EQ(got, want) << "step " << step;
            hits += want.size();
            for (std::uint32_t id : want) {
                const auto it = std::find_if(live.begin(), live.end(),
                                             [&](const Live& l) { return l.id == id; });
                if (it->box.width() > 0.25 || it->box.height() > 0.25) ++spanning;
            }
        }
        ASSERT_EQ(grid.size(), live.size());
    }
    for (const Live& l : live)
        EXPECT_TRUE(grid.holds(l.id, l.box));
    // The draw must have exercised what it is for: many hits, many of them multi-cell boxes.
    EXPECT_GT(hits, 10000u);
    EXPECT_GT(spanning, 1000u);
}

TEST(BoxGrid, ClosedBoxesMeetAcrossACellBoundary) {
    BoxGrid grid(Rect{{0.0, 0.0}, {1.0, 1.0}}, 16);  // cells of 1/4 m
    const Rect left{{0.0, 0.0}, {0.25, 0.1}};        // ends on the boundary x = 1/4
    grid.insert(7, left);
    std::vector<std::uint32_t> ids;
    grid.query(Rect{{0.25, 0.05}, {0.3, 0.06}}, ids);  // starts on it: they touch
    EXPECT_EQ(ids, std::vector<std::uint32_t>{7});
    ids.clear();
    grid.query(Rect{{std::nextafter(0.25, 1.0), 0.05}, {0.3, 0.06}}, ids);
    EXPECT_TRUE(ids.empty());
}

TEST(BoxGrid, WideBoxesEmptyBoxesAndBoxesOutsideTheExtent) {
    BoxGrid grid(Rect{{0.0, 0.0}, {1.0, 1.0}}, 64);
    const Rect everywhere{{-1.0, -1.0}, {2.0, 2.0}};  // covers every cell: the wide list
    const Rect outside{{3.0, 3.0}, {3.5, 3.1}};       // filed in the corner cell
    const Rect point{{0.5, 0.5}, {0.5, 0.5}};
    grid.insert(1, everywhere);
    grid.insert(2, outside);
    grid.insert(3, point);
    grid.insert(4, Rect{});  // empty: meets nothing, but can be erased
    EXPECT_EQ(grid.size(), 4u);
    std::vector<std::uint32_t> ids;
    grid.query(Rect{{0.9, 0.9}, {1.0, 1.0}}, ids);  // the corner cell holds `outside`, which
    EXPECT_EQ(ids, std::vector<std::uint32_t>{1});  // does not meet this box
    ids.clear();
    grid.query(Rect{{3.2, 3.0}, {3.3, 3.05}}, ids);
    EXPECT_EQ(ids, (std::vector<std::uint32_t>{2}));
    ids.clear();
    grid.query(Rect{{0.5, 0.5}, {0.5, 0.5}}, ids);
    EXPECT_EQ(ids, (std::vector<std::uint32_t>{1, 3}));
    ids.clear();
    grid.query(Rect{}, ids);
    EXPECT_TRUE(ids.empty());
    const double nan = std::numeric_limits<double>::quiet_NaN();
    grid.query(Rect{{nan, 0.0}, {1.0, 1.0}}, ids);
    EXPECT_TRUE(ids.empty());

    EXPECT_FALSE(grid.erase(2, point));  // not filed with that box: nothing changes
    EXPECT_FALSE(grid.erase(9, outside));
    EXPECT_EQ(grid.size(), 4u);
    EXPECT_TRUE(grid.erase(4, Rect{}));
    EXPECT_TRUE(grid.erase(1, everywhere));
    EXPECT_FALSE(grid.holds(1, everywhere));
    ids.clear();
    grid.query(Rect{{0.0, 0.0}, {5.0, 5.0}}, ids);
    EXPECT_EQ(ids, (std::vector<std::uint32_t>{2, 3}));
}

TEST(BoxGrid, AnIndexWithoutCellsStillAnswers) {
    BoxGrid none;                                // no extent: everything in the wide list
    BoxGrid flat(Rect{{0.0, 0.0}, {1.0, 0.0}});  // a zero-height extent has no cells either
    for (BoxGrid* g : {&none, &flat}) {
        g->insert(5, Rect{{0.0, 0.0}, {0.1, 0.1}});
        g->insert(6, Rect{{0.5, 0.0}, {0.6, 0.1}});
        std::vector<std::uint32_t> ids;
        g->query(Rect{{0.05, 0.05}, {0.55, 0.06}}, ids);
        EXPECT_EQ(ids, (std::vector<std::uint32_t>{5, 6}));
        EXPECT_TRUE(g->erase(5, Rect{{0.0, 0.0}, {0.1, 0.1}}));
        EXPECT_EQ(g->size(), 1u);
    }
}

}  // namespace
}  // namespace sandtin
