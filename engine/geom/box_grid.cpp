#include "geom/box_grid.hpp"

#include <algorithm>

namespace sandtin {

namespace {

/// A box covering more cells than this goes into the wide list: filing it cell by cell would
/// cost more than every query reading it once. A tool's rim segment covers one to four.
constexpr std::size_t kMaxCellsPerBox = 64;

}  // namespace

BoxGrid::BoxGrid(const Rect& extent, std::uint32_t target_cells)
    : grid_(UniformGrid::with_cell_count(extent, target_cells)), cells_(grid_.cell_count()) {}

bool BoxGrid::is_wide(const Rect& box) const {
    return !grid_.has_cells() || box.empty() || grid_.span_of(box).count() > kMaxCellsPerBox;
}

void BoxGrid::insert(std::uint32_t id, const Rect& box) {
    ++size_;
    if (is_wide(box)) {
        wide_.push_back({id, box});
        return;
    }
    grid_.for_each_cell(grid_.span_of(box), [&](std::size_t c) { cells_[c].push_back({id, box}); });
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
    grid_.for_each_cell(grid_.span_of(box), [&](std::size_t c) { take(cells_[c]); });
    --size_;
    return true;
}

void BoxGrid::query(const Rect& query, std::vector<std::uint32_t>& out) const {
    if (query.empty()) return;
    const std::size_t first = out.size();
    for (const Entry& e : wide_) {
        if (e.box.intersects(query)) out.push_back(e.id);
    }
    if (grid_.has_cells()) {
        grid_.for_each_cell(grid_.span_of(query), [&](std::size_t c) {
            for (const Entry& e : cells_[c]) {
                if (e.box.intersects(query)) out.push_back(e.id);
            }
        });
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
    return !grid_.any_cell(grid_.span_of(box), [&](std::size_t c) { return !has(cells_[c]); });
}

}  // namespace sandtin
