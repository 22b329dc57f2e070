#pragma once
// A uniform grid over a rectangle of the plane, and the per-cell lists that index things by it:
// the cell arithmetic of every grid index in geom (BoxGrid, PointGrid, NearEdgeIndex) lives
// here, so that filing into a grid and reading from it agree by construction.
//
// Units: coordinates and extents in metres, densities in cells per metre.
//
// Invariants of a UniformGrid with cells (has_cells()):
//   - columns() >= 1 and rows() >= 1; cell (x, y) has index y * columns() + x (row-major).
//   - column_of(x) = floor((x - extent().min.x) * cells per metre) clamped into
//     [0, columns()); NaN maps to 0. It is monotone in x, so a closed interval [lo, hi] holds
//     every column from column_of(lo) to column_of(hi), and two closed intervals that share a
//     point share that point's column. Rows likewise.
//   - Coordinates beyond the extent map to its border cells: any point or box may be filed,
//     and the border cells simply reach to infinity.
// A UniformGrid without cells (default-constructed, or built from an unusable extent) answers
// nothing: callers test has_cells() and fall back to a scan of everything.
//
// CellSpan names a rectangle of cells (what a box covers, or a cell and its neighbours);
// PackedCells<T> holds per-cell lists built once, in one array (compressed rows). An index that
// is edited cell by cell keeps a std::vector per cell, indexed by cell_index().

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "geom/rect.hpp"
#include "geom/vec2.hpp"

namespace sandtin {

/// The cells x0..x1 by y0..y1 of a grid, inclusive (x0 <= x1, y0 <= y1).
struct CellSpan {
    std::uint32_t x0 = 0, x1 = 0, y0 = 0, y1 = 0;

    std::size_t count() const {
        return static_cast<std::size_t>(x1 - x0 + 1) * static_cast<std::size_t>(y1 - y0 + 1);
    }
};

class UniformGrid {
  public:
    /// No cells.
    UniformGrid() = default;

    /// Square cells 1 / cells_per_metre wide from extent.min: floor(width * cells_per_metre) + 1
    /// columns (so the cells cover the extent, its max side included) and rows likewise. The
    /// caller keeps that small (the indexes cap their cells per side); beyond 65 536 a side the
    /// count is capped. cells_per_metre = 0 gives one cell, and so does an infinite extent with
    /// it. No cells when the extent is empty, its min is not finite, or cells_per_metre is
    /// negative or not finite.
    static UniformGrid with_cells_per_metre(const Rect& extent, double cells_per_metre);

    /// About `target_cells` nearly square cells tiling `extent` exactly (its max corner in the
    /// last cell): columns = round(sqrt(target * width / height)) and rows = round(target /
    /// columns), each in [1, target]. No cells when the extent has no area, is not finite, or
    /// target_cells is 0.
    static UniformGrid with_cell_count(const Rect& extent, std::uint32_t target_cells);

    bool has_cells() const { return columns_ != 0; }
    std::uint32_t columns() const { return columns_; }
    std::uint32_t rows() const { return rows_; }
    std::size_t cell_count() const { return static_cast<std::size_t>(columns_) * rows_; }
    /// The rectangle the grid was built over (metres). Cells past it on the right or top may
    /// exist (with_cells_per_metre rounds up); coordinates past it still map to border cells.
    const Rect& extent() const { return extent_; }

    // The queries below need has_cells().

    std::uint32_t column_of(double x) const {
        return clamped_cell(x, extent_.min.x, columns_per_metre_, columns_);
    }
    std::uint32_t row_of(double y) const {
        return clamped_cell(y, extent_.min.y, rows_per_metre_, rows_);
    }
    std::size_t cell_index(std::uint32_t column, std::uint32_t row) const {
        return static_cast<std::size_t>(row) * columns_ + column;
    }
    /// The cell p falls in.
    std::size_t cell_of(Vec2 p) const { return cell_index(column_of(p.x), row_of(p.y)); }

    /// The cells a closed box covers: every point of the box lies in one of them, and two boxes
    /// that meet share a cell of their spans. (A box that is empty by NaN maps as its
    /// coordinates do; test Rect::empty() first where that matters.)
    CellSpan span_of(const Rect& box) const {
        return {column_of(box.min.x), column_of(box.max.x), row_of(box.min.y), row_of(box.max.y)};
    }
    /// The single cell p falls in.
    CellSpan span_of(Vec2 p) const {
        const std::uint32_t x = column_of(p.x);
        const std::uint32_t y = row_of(p.y);
        return {x, x, y, y};
    }
    /// `s` grown by `rings` cells on every side, clipped to the grid: with rings = 1 and cells
    /// wider than r (by a hair, against rounding), every point within r of a point of s's cells
    /// is in one of them.
    CellSpan grown(const CellSpan& s, std::uint32_t rings) const {
        const auto down = [rings](std::uint32_t i) { return i > rings ? i - rings : 0; };
        const auto up = [rings](std::uint32_t i, std::uint32_t count) {
            return count - 1 - i > rings ? i + rings : count - 1;
        };
        return {down(s.x0), up(s.x1, columns_), down(s.y0), up(s.y1, rows_)};
    }

    /// Calls f(cell index) for every cell of `s`, row by row, ascending within a row: in
    /// ascending index order.
    template <class F>
    void for_each_cell(const CellSpan& s, F&& f) const {
        for (std::uint32_t y = s.y0; y <= s.y1; ++y) {
            const std::size_t row = static_cast<std::size_t>(y) * columns_;
            for (std::size_t c = row + s.x0; c <= row + s.x1; ++c)
                f(c);
        }
    }
    /// Whether f(cell index) is true for some cell of `s`, visited as by for_each_cell and
    /// stopping at the first.
    template <class F>
    bool any_cell(const CellSpan& s, F&& f) const {
        for (std::uint32_t y = s.y0; y <= s.y1; ++y) {
            const std::size_t row = static_cast<std::size_t>(y) * columns_;
            for (std::size_t c = row + s.x0; c <= row + s.x1; ++c) {
                if (f(c)) return true;
            }
        }
        return false;
    }

  private:
    /// floor((x - origin) * per_metre) clamped into [0, count) (count > 0); NaN maps to 0.
    static std::uint32_t clamped_cell(double x, double origin, double per_metre,
                                      std::uint32_t count) {
        const double f = (x - origin) * per_metre;
        if (!(f > 0.0)) return 0;
        if (!(f < static_cast<double>(count))) return count - 1;
        return std::min(static_cast<std::uint32_t>(f), count - 1);
    }

    Rect extent_;
    double columns_per_metre_ = 0.0;
    double rows_per_metre_ = 0.0;
    std::uint32_t columns_ = 0;
    std::uint32_t rows_ = 0;
};

/// Per-cell lists of T, built once and read many times: every cell's items contiguous in one
/// array, in the order they were filed (compressed rows: no allocation per cell).
template <class T>
class PackedCells {
  public:
    /// No cells.
    PackedCells() = default;

    /// Files items into `cell_count` cells. `visit(file)` must call file(cell, item) for every
    /// filing (an item may be filed in several cells); it is called twice, once to count and
    /// once to fill, and must make the same calls both times.
    template <class Visit>
    PackedCells(std::size_t cell_count, Visit&& visit) {
        start_.assign(cell_count + 1, 0);
        visit([&](std::size_t cell, const T&) { ++start_[cell + 1]; });
        std::vector<std::uint32_t> fill = counted();
        visit([&](std::size_t cell, const T& item) { items_[fill[cell]++] = item; });
    }

    /// Files items[i] in cell cells[i] (< cell_count), one cell each (a stable counting sort);
    /// cells and items have the same length.
    PackedCells(std::size_t cell_count, std::span<const std::uint32_t> cells,
                std::span<const T> items) {
        start_.assign(cell_count + 1, 0);
        for (const std::uint32_t c : cells)
            ++start_[c + 1];
        std::vector<std::uint32_t> fill = counted();
        for (std::size_t i = 0; i < cells.size(); ++i)
            items_[fill[cells[i]]++] = items[i];
    }

    std::size_t cell_count() const { return start_.empty() ? 0 : start_.size() - 1; }
    /// The items filed in `cell`, in filing order.
    std::span<const T> operator[](std::size_t cell) const {
        return {items_.data() + start_[cell], items_.data() + start_[cell + 1]};
    }

  private:
    /// With start_[c + 1] holding cell c's count: turns the counts into starts, sizes items_,
    /// and returns each cell's next free slot.
    std::vector<std::uint32_t> counted() {
        for (std::size_t c = 1; c < start_.size(); ++c)
            start_[c] += start_[c - 1];
        items_.resize(start_.back());
        return {start_.begin(), start_.end() - 1};
    }

    std::vector<std::uint32_t> start_;  ///< cell c holds items_[start_[c] .. start_[c + 1])
    std::vector<T> items_;
};

}  // namespace sandtin
