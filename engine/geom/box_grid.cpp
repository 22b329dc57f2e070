#include "geom/box_grid.hpp"

#include "geom/grid_cell.hpp"

#include <algorithm>
#include <cmath>

namespace sandtin {

namespace {

/// A box covering more cells than this goes into the wide list: filing it cell by cell would
/// cost more than every query reading it once. A tool's rim segment covers one to four.
constexpr std::size_t kMaxCellsPerBox = 64;

}  // namespace

BoxGrid::BoxGrid(const Rect& extent, std::uint32_t target_cells) {
    const double w = extent.width();
    const double h = extent.height();
    if (extent.empty() || !(w > 0.0) || !(h > 0.0) || !std::isfinite(w) || !std::isfinite(h) ||
        target_cells == 0) {
        return;  // no cells: every box is wide
    }
    const double target = static_cast<double>(target_cells);
    const double columns = std::clamp(std::round(std::sqrt(target * w / h)), 1.0, target);
    const double rows = std::clamp(std::round(target / columns), 1.0, target);
    extent_ = extent;
    columns_ = static_cast<std::uint32_t>(columns);
    rows_ = static_cast<std::uint32_t>(rows);
    columns_per_metre_ = columns / w;
    rows_per_metre_ = rows / h;
    cells_.resize(static_cast<std::size_t>(columns_) * rows_);
}

BoxGrid::CellSpan BoxGrid::span_of(const Rect& box) const {
    return {grid_cell(box.min.x, extent_.min.x, columns_per_metre_, columns_),
            grid_cell(box.max.x, extent_.min.x, columns_per_metre_, columns_),
            grid_cell(box.min.y, extent_.min.y, rows_per_metre_, rows_),
            grid_cell(box.max.y, extent_.min.y, rows_per_metre_, rows_)};
}

bool BoxGrid::is_wide(const Rect& box) const {
    return columns_ == 0 || box.empty() || span_of(box).count() > kMaxCellsPerBox;
}

void BoxGrid::insert(std::uint32_t id, const Rect& box) {
    ++size_;
    if (is_wide(box)) {
        wide_.push_back({id, box});
        return;
    }
    const CellSpan s = span_of(box);
    for (std::uint32_t y = s.y0; y <= s.y1; ++y) {
        for (std::uint32_t x = s.x0; x <= s.x1; ++x)
            cell(x, y).push_back({id, box});
    }
}

bool BoxGrid::erase(std::uint32_t id, const Rect& box) {
    // Order within a list does not matter (queries sort), so an entry leaves by swap and pop.
    const auto take = [&](std::vector<Entry>& list) {
        const auto it = std::find_if(list.begin(), list.end(),
                                     [&](const Entry& e) { return e.id == id && e.box == box; });
        if (it == list.end()) return false;
        *it = list.back();
        list.pop_back();
        return true;
    };
    if (is_wide(box)) {
        if (!take(wide_)) return false;
        --size_;
        return true;
    }
    if (!holds(id, box)) return false;
    const CellSpan s = span_of(box);
    for (std::uint32_t y = s.y0; y <= s.y1; ++y) {
        for (std::uint32_t x = s.x0; x <= s.x1; ++x)
            take(cell(x, y));
    }
    --size_;
    return true;
}

void BoxGrid::query(const Rect& query, std::vector<std::uint32_t>& out) const {
    if (query.empty()) return;
    const std::size_t first = out.size();
    for (const Entry& e : wide_) {
        if (e.box.intersects(query)) out.push_back(e.id);
    }
    if (columns_ != 0) {
        const CellSpan s = span_of(query);
        for (std::uint32_t y = s.y0; y <= s.y1; ++y) {
            for (std::uint32_t x = s.x0; x <= s.x1; ++x) {
                for (const Entry& e : cell(x, y)) {
                    if (e.box.intersects(query)) out.push_back(e.id);
                }
            }
        }
    }
    // A box spanning several of the query's cells was found in each of them.
    std::sort(out.begin() + static_cast<std::ptrdiff_t>(first), out.end());
    out.erase(std::unique(out.begin() + static_cast<std::ptrdiff_t>(first), out.end()), out.end());
}

bool BoxGrid::holds(std::uint32_t id, const Rect& box) const {
    const auto has = [&](const std::vector<Entry>& list) {
        return std::any_of(list.begin(), list.end(),
                           [&](const Entry& e) { return e.id == id && e.box == box; });
    };
    if (is_wide(box)) return has(wide_);
    const CellSpan s = span_of(box);
    for (std::uint32_t y = s.y0; y <= s.y1; ++y) {
        for (std::uint32_t x = s.x0; x <= s.x1; ++x) {
            if (!has(cell(x, y))) return false;
        }
    }
    return true;
}

}  // namespace sandtin
