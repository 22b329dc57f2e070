#include "geom/box_grid.hpp"

#include <algorithm>
#include <cmath>

namespace sandtin {

namespace {

/// A box covering more cells than this goes into the wide list: filing it cell by cell would
/// cost more than every query reading it once. A tool's rim segment covers one to four.
constexpr std::size_t kMaxCellsPerBox = 64;

/// The cell index of coordinate `x` along one axis, clamped into [0, count); monotone in x, so
/// two closed intervals that share a point share that point's cell. NaN maps to cell 0.
std::uint32_t cell_index(double x, double origin, double cell_size, std::uint32_t count) {
    const double f = (x - origin) / cell_size;
    if (!(f > 0.0)) return 0;
    if (!(f < static_cast<double>(count))) return count - 1;
    return std::min(static_cast<std::uint32_t>(f), count - 1);
}

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
    cell_width_ = w / columns;
    cell_height_ = h / rows;
    cells_.resize(static_cast<std::size_t>(columns_) * rows_);
}

BoxGrid::CellSpan BoxGrid::span_of(const Rect& box) const {
    return {cell_index(box.min.x, extent_.min.x, cell_width_, columns_),
            cell_index(box.max.x, extent_.min.x, cell_width_, columns_),
            cell_index(box.min.y, extent_.min.y, cell_height_, rows_),
            cell_index(box.max.y, extent_.min.y, cell_height_, rows_)};
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
