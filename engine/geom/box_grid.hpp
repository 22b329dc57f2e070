#pragma once
// An index of axis-aligned boxes by id that answers "which boxes meet this box?" in time
// proportional to the query's neighbourhood, not to the number of boxes. A uniform grid over a
// fixed extent (geom/uniform_grid.hpp) lists in each cell the boxes that meet it; boxes that
// would span many cells (a constraint drawn across the whole terrain) sit in one list that
// every query reads.
// Insertions and erasures are cheap, so the index follows an edited set (the TIN's live
// constraints) rather than being rebuilt.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "geom/rect.hpp"
#include "geom/uniform_grid.hpp"

namespace sandtin {

class BoxGrid {
  public:
    /// An index with no cells: every box goes into the wide list.
    BoxGrid() = default;
    /// Cells tile `extent` (metres), about `target_cells` of them, nearly square. Boxes reaching
    /// beyond the extent are filed in its border cells, so any box may be inserted.
    explicit BoxGrid(const Rect& extent, std::uint32_t target_cells = 4096);

    /// Files `box` under `id`. An id may be inserted once until it is erased.
    void insert(std::uint32_t id, const Rect& box);
    /// Removes `id`; `box` must be the box it was inserted with. Returns false (and changes
    /// nothing) when no such entry exists.
    bool erase(std::uint32_t id, const Rect& box);
    /// Appends to `out` the ids whose boxes meet `query` (closed: touching counts), ascending
    /// and without repeats. An empty box meets nothing.
    void query(const Rect& query, std::vector<std::uint32_t>& out) const;

    /// True when `id` is filed with exactly `box` in every cell the box covers (a check for
    /// validators; costs the cells the box covers).
    bool holds(std::uint32_t id, const Rect& box) const;
    /// Number of ids filed.
    std::size_t size() const { return size_; }

  private:
    struct Entry {
        std::uint32_t id;
        Rect box;
    };
    bool is_wide(const Rect& box) const;

    UniformGrid grid_;
    std::vector<std::vector<Entry>> cells_;  ///< by the grid's cell index
    std::vector<Entry> wide_;  ///< empty boxes, and boxes covering more than a few cells
    std::size_t size_ = 0;
};

}  // namespace sandtin
