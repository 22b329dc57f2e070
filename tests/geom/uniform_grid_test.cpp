// UniformGrid and PackedCells: the cell arithmetic and per-cell lists under BoxGrid, PointGrid
// and NearEdgeIndex. The oracles never touch a grid: every box, point or edge is tested against
// every query by brute force, and the grid's answer (the items filed in the cells a query
// reads, filtered by the same exact test) must be the same set. Inputs are random over
// extents from a single point to 100 m, with boxes from points to twice the extent, many
// coordinates snapped exactly onto cell borders, and queries far outside the extent.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <random>
#include <set>
#include <vector>

#include "geom/rect.hpp"
#include "geom/uniform_grid.hpp"
#include "geom/vec2.hpp"

namespace sandtin {
namespace {

/// The grids the tests draw over: extents of every shape, including a single point and lines.
struct UgCase {
    Rect extent;
    double cells_per_metre;  ///< for with_cells_per_metre
};

std::vector<UgCase> ug_cases() {
    return {
        {Rect{{1.0, -1.0}, {5.0, 1.0}}, 4.0},      // 17 x 9 square cells of 1/4 m
        {Rect{{0.0, 0.0}, {1.0, 1.0}}, 10.0},      // 0.1 is not a binary fraction
        {Rect{{-50.0, -3.0}, {50.0, 3.0}}, 0.37},  // long and thin, cells wider than the height
        {Rect{{2.0, 3.0}, {2.0, 3.0}}, 8.0},       // a single point: one cell
        {Rect{{0.0, 0.0}, {0.0, 2.0}}, 3.0},       // a vertical line: one column
        {Rect{{-1e-3, 7.0}, {1e-3, 7.0}}, 1e4},    // a tiny horizontal line
        {Rect{{0.25, 0.25}, {0.75, 0.75}}, 0.0},   // zero density: one cell
    };
}

/// A coordinate around [lo, hi]: anywhere from half the span before it to half after, snapped
/// onto a cell border (a multiple of 1 / per_metre from lo) a third of the time, and now and
/// then far outside.
double ug_coordinate(std::mt19937_64& rng, double lo, double hi, double per_metre) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const double span = std::max(hi - lo, 1e-3);
    const double pick = unit(rng);
    if (pick < 0.05) return unit(rng) < 0.5 ? lo - 1e3 * span : hi + 1e3 * span;
    double c = lo - 0.5 * span + 2.0 * span * unit(rng);
    if (pick < 0.4 && per_metre > 0.0) c = lo + std::round((c - lo) * per_metre) / per_metre;
    return c;
}

/// A random box over `g`: a point a tenth of the time, a segment (zero width or height) a
/// tenth, otherwise sized from 1e-4 of the extent to twice it.
Rect ug_box(std::mt19937_64& rng, const UniformGrid& g, double per_metre) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const Rect& e = g.extent();
    const Vec2 a{ug_coordinate(rng, e.min.x, e.max.x, per_metre),
                 ug_coordinate(rng, e.min.y, e.max.y, per_metre)};
    const double span = std::max({e.width(), e.height(), 1e-3});
    const double scale = span * std::pow(10.0, -4.0 + 4.3 * unit(rng));
    const double pick = unit(rng);
    Vec2 size{scale * unit(rng), scale * unit(rng)};
    if (pick < 0.1)
        size = {0.0, 0.0};
    else if (pick < 0.15)
        size.y = 0.0;
    else if (pick < 0.2)
        size.x = 0.0;
    return Rect{a, a + size};
}

std::vector<std::size_t> ug_cells_of(const UniformGrid& g, const CellSpan& s) {
    std::vector<std::size_t> cells;
    g.for_each_cell(s, [&](std::size_t c) { cells.push_back(c); });
    return cells;
}

TEST(UniformGrid, SizesCoverTheExtentAndRefuseUnusableInput) {
    // with_cells_per_metre: floor(side * density) + 1 cells a side, the extent's min corner in
    // cell 0 and its max corner in the last.
    for (const UgCase& gc : ug_cases()) {
        const UniformGrid g = UniformGrid::with_cells_per_metre(gc.extent, gc.cells_per_metre);
        ASSERT_TRUE(g.has_cells());
        EXPECT_EQ(g.columns(),
                  static_cast<std::uint32_t>(gc.extent.width() * gc.cells_per_metre) + 1);
        EXPECT_EQ(g.rows(),
                  static_cast<std::uint32_t>(gc.extent.height() * gc.cells_per_metre) + 1);
        EXPECT_EQ(g.cell_count(), std::size_t{g.columns()} * g.rows());
        EXPECT_EQ(g.cell_of(gc.extent.min), 0u);
        EXPECT_EQ(g.column_of(gc.extent.max.x),
                  static_cast<std::uint32_t>(gc.extent.width() * gc.cells_per_metre));
        EXPECT_EQ(g.extent(), gc.extent);
    }
    // with_cell_count: close to the target, nearly square, tiling the extent exactly.
    const Rect wide{{1.0, -1.0}, {5.0, 1.0}};
    const UniformGrid g = UniformGrid::with_cell_count(wide, 128);
    EXPECT_EQ(g.columns(), 16u);
    EXPECT_EQ(g.rows(), 8u);
    EXPECT_EQ(g.column_of(1.25), 1u);                       // a border belongs to the cell after
    EXPECT_EQ(g.column_of(std::nextafter(1.25, 0.0)), 0u);  // it
    EXPECT_EQ(g.column_of(5.0), 15u);
    EXPECT_EQ(g.row_of(1.0), 7u);
    const UniformGrid tall = UniformGrid::with_cell_count(Rect{{0.0, 0.0}, {1.0, 1000.0}}, 16);
    EXPECT_EQ(tall.columns(), 1u);  // at least one column
    EXPECT_EQ(tall.rows(), 16u);

    // Beyond the extent, and NaN, map to border cells.
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    EXPECT_EQ(g.column_of(-1e300), 0u);
    EXPECT_EQ(g.column_of(1e300), 15u);
    EXPECT_EQ(g.column_of(inf), 15u);
    EXPECT_EQ(g.column_of(-inf), 0u);
    EXPECT_EQ(g.column_of(nan), 0u);

    // No cells.
    const Rect unit{{0.0, 0.0}, {1.0, 1.0}};
    EXPECT_FALSE(UniformGrid().has_cells());
    EXPECT_EQ(UniformGrid().cell_count(), 0u);
    EXPECT_FALSE(UniformGrid::with_cells_per_metre(Rect{}, 1.0).has_cells());
    EXPECT_FALSE(UniformGrid::with_cells_per_metre(unit, -1.0).has_cells());
    EXPECT_FALSE(UniformGrid::with_cells_per_metre(unit, inf).has_cells());
    EXPECT_FALSE(UniformGrid::with_cells_per_metre(unit, nan).has_cells());
    EXPECT_FALSE(UniformGrid::with_cells_per_metre(Rect{{-inf, 0.0}, {1.0, 1.0}}, 1.0).has_cells());
    EXPECT_FALSE(UniformGrid::with_cell_count(unit, 0).has_cells());
    EXPECT_FALSE(UniformGrid::with_cell_count(Rect{{0.0, 0.0}, {1.0, 0.0}}, 16).has_cells());
    EXPECT_FALSE(UniformGrid::with_cell_count(Rect{{0.0, 0.0}, {inf, 1.0}}, 16).has_cells());
    EXPECT_FALSE(UniformGrid::with_cell_count(Rect{}, 16).has_cells());
    // An infinite extent at zero density is one cell; at a positive density the side is capped.
    const UniformGrid one = UniformGrid::with_cells_per_metre(Rect{{0.0, 0.0}, {inf, inf}}, 0.0);
    EXPECT_EQ(one.cell_count(), 1u);
    EXPECT_EQ(one.cell_of({1e300, 5.0}), 0u);
    const UniformGrid capped =
        UniformGrid::with_cells_per_metre(Rect{{0.0, 0.0}, {1e12, 1.0}}, 1.0);
    EXPECT_EQ(capped.columns(), 65536u);
    EXPECT_EQ(capped.rows(), 2u);
}

TEST(UniformGrid, SpansVisitTheirCellsInOrderAndGrowWithinTheGrid) {
    const UniformGrid g = UniformGrid::with_cells_per_metre(Rect{{0.0, 0.0}, {1.0, 0.5}}, 4.0);
    ASSERT_EQ(g.columns(), 5u);
    ASSERT_EQ(g.rows(), 3u);
    const CellSpan s = g.span_of(Rect{{0.3, 0.1}, {0.6, 0.3}});  // columns 1-2, rows 0-1
    EXPECT_EQ(s.count(), 4u);
    EXPECT_EQ(ug_cells_of(g, s), (std::vector<std::size_t>{1, 2, 6, 7}));
    EXPECT_EQ(ug_cells_of(g, g.grown(s, 1)),
              (std::vector<std::size_t>{0, 1, 2, 3, 5, 6, 7, 8, 10, 11, 12, 13}));
    EXPECT_EQ(g.grown(s, 100).count(), g.cell_count());
    EXPECT_EQ(g.grown(g.span_of(Vec2{1.0, 0.5}), 0).count(), 1u);
    const CellSpan corner = g.grown(g.span_of(Vec2{-5.0, 9.0}), 1);
    EXPECT_EQ(ug_cells_of(g, corner), (std::vector<std::size_t>{5, 6, 10, 11}));
    // any_cell stops at the first cell that answers yes.
    std::vector<std::size_t> visited;
    EXPECT_TRUE(g.any_cell(s, [&](std::size_t c) {
        visited.push_back(c);
        return c == 6;
    }));
    EXPECT_EQ(visited, (std::vector<std::size_t>{1, 2, 6}));
    EXPECT_FALSE(g.any_cell(s, [](std::size_t) { return false; }));
    // A one-cell grid grows into itself.
    const UniformGrid single = UniformGrid::with_cells_per_metre(Rect{{2.0, 3.0}, {2.0, 3.0}}, 8.0);
    EXPECT_EQ(single.grown(single.span_of(Vec2{2.0, 3.0}), 1).count(), 1u);
}

/// Boxes filed by the cells they cover, as BoxGrid and NearEdgeIndex file theirs: a query
/// reading the cells its box covers finds every box that meets it, and each cell lists its
/// boxes in filing order.
TEST(UniformGrid, BoxesFiledByTheirSpansAreFoundAsByABruteForceScan) {
    std::mt19937_64 rng(20260311);
    std::size_t hits = 0;
    std::size_t multi_cell = 0;
    std::size_t queries = 0;
    const auto check = [&](const UniformGrid& g, double per_metre, const char* what) {
        ASSERT_TRUE(g.has_cells()) << what;
        std::vector<Rect> boxes;
        for (int i = 0; i < 300; ++i)
            boxes.push_back(ug_box(rng, g, per_metre));
        const PackedCells<std::uint32_t> cells(g.cell_count(), [&](auto&& file) {
            for (std::uint32_t i = 0; i < boxes.size(); ++i)
                g.for_each_cell(g.span_of(boxes[i]), [&](std::size_t c) { file(c, i); });
        });
        ASSERT_EQ(cells.cell_count(), g.cell_count());
        for (std::size_t c = 0; c < g.cell_count(); ++c)
            ASSERT_TRUE(std::is_sorted(cells[c].begin(), cells[c].end())) << what;
        for (int k = 0; k < 1000; ++k) {
            const Rect q = ug_box(rng, g, per_metre);
            std::set<std::uint32_t> got;
            g.for_each_cell(g.span_of(q), [&](std::size_t c) {
                for (const std::uint32_t i : cells[c]) {
                    if (boxes[i].intersects(q)) got.insert(i);
                }
            });
            std::set<std::uint32_t> want;
            for (std::uint32_t i = 0; i < boxes.size(); ++i) {
                if (boxes[i].intersects(q)) want.insert(i);
            }
            ASSERT_EQ(got, want) << what << ", query " << k;
            // Every corner and the centre of the query lie in its span.
            const CellSpan s = g.span_of(q);
            for (const Vec2 p : {q.min, q.max, Vec2{q.min.x, q.max.y}, q.centre()}) {
                const std::uint32_t x = g.column_of(p.x);
                const std::uint32_t y = g.row_of(p.y);
                ASSERT_TRUE(x >= s.x0 && x <= s.x1 && y >= s.y0 && y <= s.y1) << what;
            }
            hits += want.size();
            multi_cell += s.count() > 1;
            ++queries;
        }
    };
    for (const UgCase& gc : ug_cases()) {
        check(UniformGrid::with_cells_per_metre(gc.extent, gc.cells_per_metre), gc.cells_per_metre,
              "with_cells_per_metre");
        if (gc.extent.width() > 0.0 && gc.extent.height() > 0.0) {
            for (const std::uint32_t target : {1u, 7u, 128u, 4096u}) {
                const UniformGrid g = UniformGrid::with_cell_count(gc.extent, target);
                check(g, g.columns() / gc.extent.width(), "with_cell_count");
            }
        }
    }
    // The draw exercised what it is for.
    EXPECT_GT(hits, 100000u);
    EXPECT_GT(multi_cell, queries / 8);
}

/// Points filed by their cell, as PointGrid files them: with cells a hair wider than r, the
/// points nearer than r to a query are all in its cell or the eight around it.
TEST(UniformGrid, NeighbouringCellsHoldEveryPointWithinACellWidth) {
    std::mt19937_64 rng(20260312);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::size_t near = 0;
    std::size_t far = 0;
    for (const double r : {1e-3, 0.05, 0.3, 7.0}) {
        for (const std::size_t count : {std::size_t{1}, std::size_t{2}, std::size_t{400}}) {
            std::vector<Vec2> points;
            const double side = r * (1.0 + 1e-9);
            for (std::size_t i = 0; i < count; ++i) {
                Vec2 p{3.0 * unit(rng) - 1.0, 2.0 * unit(rng)};
                if (i % 3 == 0) p = {std::round(p.x / side) * side, p.y};  // on a column border
                if (count == 2 && i == 1) p = points[0];                   // the same point twice
                points.push_back(p);
            }
            Rect extent;
            for (const Vec2 p : points)
                extent.expand(p);
            const UniformGrid g = UniformGrid::with_cells_per_metre(extent, 1.0 / side);
            const PackedCells<std::uint32_t> cells(g.cell_count(), [&](auto&& file) {
                for (std::uint32_t i = 0; i < points.size(); ++i)
                    file(g.cell_of(points[i]), i);
            });
            for (int k = 0; k < 3000; ++k) {
                Vec2 p;
                const double pick = unit(rng);
                if (pick < 0.5) {
                    const double a = 6.283185307179586 * unit(rng);  // about r from a point
                    p = points[k % count] + Vec2{std::cos(a), std::sin(a)} * (r * 2.0 * unit(rng));
                } else if (pick < 0.9) {
                    p = {5.0 * unit(rng) - 2.0, 4.0 * unit(rng) - 1.0};
                } else {
                    p = {1e6 * (unit(rng) - 0.5), 1e6 * (unit(rng) - 0.5)};
                }
                std::set<std::uint32_t> got;
                g.for_each_cell(g.grown(g.span_of(p), 1), [&](std::size_t c) {
                    for (const std::uint32_t i : cells[c]) {
                        if (length_squared(points[i] - p) < r * r) got.insert(i);
                    }
                });
                std::set<std::uint32_t> want;
                for (std::uint32_t i = 0; i < points.size(); ++i) {
                    if (length_squared(points[i] - p) < r * r) want.insert(i);
                }
                ASSERT_EQ(got, want) << "r " << r << ", " << count << " points, query " << k;
                (want.empty() ? far : near) += 1;
            }
        }
    }
    EXPECT_GT(near, 5000u);
    EXPECT_GT(far, 5000u);
}

/// Segments filed in the cells of their box grown by a reach, as NearEdgeIndex files a
/// polygon's edges: the cell a point falls in lists every segment nearer than the reach.
TEST(UniformGrid, ACellListsEverySegmentWithinTheReachOfIt) {
    std::mt19937_64 rng(20260313);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const auto segment_distance = [](Vec2 p, Vec2 a, Vec2 b) {
        const Vec2 ab = b - a;
        const double l2 = length_squared(ab);
        const double t = l2 > 0.0 ? std::clamp(dot(p - a, ab) / l2, 0.0, 1.0) : 0.0;
        return distance(p, a + ab * t);
    };
    std::size_t near = 0;
    for (const double reach : {0.002, 0.04, 0.5}) {
        std::vector<Vec2> v;  // a closed random walk, with a repeated vertex (a point segment)
        Vec2 at{0.0, 0.0};
        for (int i = 0; i < 200; ++i) {
            v.push_back(at);
            if (i == 50) v.push_back(at);
            at = at + Vec2{0.1 * (unit(rng) - 0.5), 0.1 * (unit(rng) - 0.5)};
        }
        const std::size_t n = v.size();
        Rect box;
        for (const Vec2 p : v)
            box.expand(p);
        const double margin = reach * (1.0 + 1e-9);
        const UniformGrid g = UniformGrid::with_cells_per_metre(box.inflated(margin), 2.0 / reach);
        const PackedCells<std::uint32_t> cells(g.cell_count(), [&](auto&& file) {
            for (std::uint32_t i = 0; i < n; ++i) {
                Rect e;
                e.expand(v[i]);
                e.expand(v[(i + 1) % n]);
                g.for_each_cell(g.span_of(e.inflated(margin)), [&](std::size_t c) { file(c, i); });
            }
        });
        for (int k = 0; k < 5000; ++k) {
            const std::size_t i = k % n;
            const Vec2 on = lerp(v[i], v[(i + 1) % n], unit(rng));
            const double a = 6.283185307179586 * unit(rng);
            const Vec2 p = on + Vec2{std::cos(a), std::sin(a)} * (reach * 1.5 * unit(rng));
            const auto listed = cells[g.cell_of(p)];
            for (std::uint32_t e = 0; e < n; ++e) {
                if (segment_distance(p, v[e], v[(e + 1) % n]) < reach) {
                    ASSERT_TRUE(std::find(listed.begin(), listed.end(), e) != listed.end())
                        << "reach " << reach << ", query " << k << ", segment " << e;
                    ++near;
                }
            }
        }
    }
    EXPECT_GT(near, 10000u);
}

TEST(PackedCells, KeepsFilingOrderAndEmptyCells) {
    const PackedCells<int> cells(4, [](auto&& file) {
        file(2, 30);
        file(0, 10);
        file(2, 31);
        file(2, 29);
    });
    EXPECT_EQ(cells.cell_count(), 4u);
    EXPECT_EQ(std::vector<int>(cells[0].begin(), cells[0].end()), std::vector<int>{10});
    EXPECT_TRUE(cells[1].empty());
    EXPECT_EQ(std::vector<int>(cells[2].begin(), cells[2].end()), (std::vector<int>{30, 31, 29}));
    EXPECT_TRUE(cells[3].empty());
    EXPECT_EQ(PackedCells<int>().cell_count(), 0u);
    const PackedCells<int> nothing(3, [](auto&&) {});
    EXPECT_EQ(nothing.cell_count(), 3u);
    EXPECT_TRUE(nothing[2].empty());
}

TEST(PackedCells, ACountingSortOfOneCellItemsFilesAsTheVisitorDoes) {
    std::mt19937_64 rng(20260314);
    for (const std::size_t cell_count : {std::size_t{1}, std::size_t{5}, std::size_t{300}}) {
        for (const std::size_t n : {std::size_t{0}, std::size_t{1}, std::size_t{1000}}) {
            std::vector<std::uint32_t> cell(n);
            std::vector<int> item(n);
            std::uniform_int_distribution<std::uint32_t> pick(
                0, static_cast<std::uint32_t>(cell_count - 1));
            for (std::size_t i = 0; i < n; ++i) {
                cell[i] = pick(rng);
                item[i] = static_cast<int>(i);
            }
            const PackedCells<int> sorted(cell_count, cell, item);
            const PackedCells<int> visited(cell_count, [&](auto&& file) {
                for (std::size_t i = 0; i < n; ++i)
                    file(cell[i], item[i]);
            });
            ASSERT_EQ(sorted.cell_count(), cell_count);
            for (std::size_t c = 0; c < cell_count; ++c) {
                std::vector<int> want;  // the items of cell c, in input order
                for (std::size_t i = 0; i < n; ++i) {
                    if (cell[i] == c) want.push_back(item[i]);
                }
                EXPECT_EQ(std::vector<int>(sorted[c].begin(), sorted[c].end()), want);
                EXPECT_EQ(std::vector<int>(visited[c].begin(), visited[c].end()), want);
            }
        }
    }
}

}  // namespace
}  // namespace sandtin
