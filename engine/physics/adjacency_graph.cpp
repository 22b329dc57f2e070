#include "physics/adjacency_graph.hpp"

#include "util/prepare_for_writing.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace sandtin {

namespace {

constexpr std::uint32_t kNone = 0xFFFFFFFFu;

/// Room for a few more neighbours than now, rounded to 4 slots; or exactly the degree.
std::uint32_t row_capacity(std::uint32_t degree, RowSlack slack) {
    return slack == RowSlack::Some ? (degree + 2 + 3) & ~3u : degree;
}

std::uint32_t tin_of(const VertexNumbering* numbering, std::uint32_t v) {
    return numbering != nullptr ? numbering->tin_id(v) : v;
}

/// Local id of live TIN vertex t.
std::uint32_t local_of(const VertexNumbering* numbering, std::uint32_t t) {
    if (numbering == nullptr) return t;
    const std::uint32_t v = numbering->local(t);
    if (v == VertexNumbering::kNone)
        throw std::logic_error("adjacency graph: live vertex " + std::to_string(t) +
                               " is not numbered");
    return v;
}

/// The across() value of the pair (a, b) of consecutive neighbours around p: |ab| when
/// p, a, b turn counter-clockwise (a face), else 0 (the outside of a border vertex).
double across_length(Vec2 p, Vec2 a, Vec2 b) {
    return cross(a - p, b - p) > 0.0 ? distance(a, b) : 0.0;
}

}  // namespace

void AdjacencyGraph::refresh_row_summary(std::uint32_t v) {
    double m = 0.0;
    std::uint32_t lo = v, hi = v;
    const std::uint32_t begin = offset_[v], end = offset_[v] + degree_[v];
    if (keep_shapes_ && corners_.size() < across_.size()) corners_.resize(across_.size());
    for (std::uint32_t k = begin; k < end; ++k) {
        m = std::max(m, length_[k]);
        lo = std::min(lo, target_[k]);
        hi = std::max(hi, target_[k]);
        if (keep_shapes_)
            corners_[k] =
                face_corner(length_[k], length_[k + 1 == end ? begin : k + 1], across_[k]);
    }
    longest_[v] = m;
    row_words_[v] = {lo >> 6, (hi >> 6) + 1};
}

void AdjacencyGraph::ensure_vertices(std::uint32_t n) {
    if (offset_.size() >= n) return;
    longest_.resize(n, 0.0);
    row_words_.resize(n);
    offset_.resize(n, 0);
    degree_.resize(n, 0);
    capacity_.resize(n, 0);
    dirty_flag_.resize(n, 0);
    mark_.resize(n, 0);
}

void AdjacencyGraph::rebuild(const Tin& tin, const VertexNumbering* numbering) {
    const std::uint32_t n = numbering != nullptr ? numbering->size() : tin.vertex_capacity();
    // Tens of megabytes at 10⁶ vertices, filled now: prepared (util/prepare_for_writing.hpp), so
    // filling them takes no page fault per page. (Whether they sit on huge pages made no
    // measurable difference to the kernels' scattered reads.)
    reserve_for_writing(offset_, n);
    reserve_for_writing(degree_, n);
    reserve_for_writing(capacity_, n);
    reserve_for_writing(longest_, n);
    reserve_for_writing(row_words_, n);
    offset_.assign(n, 0);
    degree_.assign(n, 0);
    capacity_.assign(n, 0);
    longest_.assign(n, 0.0);
    row_words_.assign(n, RowWords{});
    target_.clear();
    reverse_.clear();
    length_.clear();
    across_.clear();
    corners_.clear();
    slack_ = 0;
    // A planar triangulation's mean degree is under 6; rows with slack round up to a multiple
    // of 4 with 2 spare. Reserving that once spares the pool's repeated growth (its copies and
    // fresh pages): a 10^6-vertex rebuild went from 2.0 s to 1.3 s.
    const std::size_t live = tin.vertex_count();
    const std::size_t per_row = slack_policy_ == RowSlack::Some ? 10 : 6;
    // An eighth more room than the rows take: a row that outgrows its slots moves to the end of
    // the pool, and without room the first such row doubled it (at 10⁶ vertices a 240 MB copy:
    // the first stamp's erosion took 0.7 s). Only the rows' part is prepared; the room is
    // mapped as rows move into it.
    const std::size_t slots = live * per_row + 64;
    const std::size_t room = slots + slots / 8;
    auto reserve = [&](auto& pool) {
        if (pool.capacity() < room) pool.reserve(room);
        prepare_for_writing(pool.data(), slots * sizeof(pool[0]));
    };
    reserve(target_);
    reserve(length_);
    reserve(across_);
    if (keep_shapes_) reserve(corners_);
    reserve(reverse_);
    std::vector<VertexId> ring;
    const VertexArrays& va = tin.vertices();
    for (std::uint32_t v = 0; v < n; ++v) {
        const std::uint32_t t = tin_of(numbering, v);
        if (t >= va.size() || !va.alive[t]) continue;
        tin.neighbours(VertexId{t}, ring);
        offset_[v] = static_cast<std::uint32_t>(target_.size());
        degree_[v] = static_cast<std::uint32_t>(ring.size());
        capacity_[v] = row_capacity(degree_[v], slack_policy_);
        for (std::size_t k = 0; k < ring.size(); ++k) {
            const VertexId w = ring[k];
            target_.push_back(local_of(numbering, w.value));
            length_.push_back(distance(va.position[t], va.position[w.value]));
            across_.push_back(across_length(va.position[t], va.position[w.value],
                                            va.position[ring[(k + 1) % ring.size()].value]));
        }
        target_.resize(offset_[v] + capacity_[v], kNone);
        length_.resize(offset_[v] + capacity_[v], 0.0);
        across_.resize(offset_[v] + capacity_[v], 0.0);
        slack_ += capacity_[v] - degree_[v];
        refresh_row_summary(v);
    }
    reverse_.assign(target_.size(), kNone);
    for (std::uint32_t v = 0; v < n; ++v) {
        if (degree_[v] > 0) fix_reverse(v);
    }
    dirty_rows_.clear();
    dirty_flag_.assign(n, 0);
    for (std::uint32_t v = 0; v < n; ++v) {
        if (degree_[v] > 0) {
            dirty_flag_[v] = 1;
            dirty_rows_.push_back(v);
        }
    }
}

void AdjacencyGraph::grow_pool(std::uint32_t slots) {
    const std::size_t n = target_.size() + slots;
    if (n <= target_.capacity()) return;
    // The pool doubles (as push_back would), into prepared memory: the copy then takes no page
    // fault per page (growing the 27 MB pool of a 10⁵-vertex groove: 74 -> 42 ms).
    reserve_for_writing(target_, n);
    reserve_for_writing(length_, n);
    reserve_for_writing(across_, n);
    if (keep_shapes_) reserve_for_writing(corners_, n);
    reserve_for_writing(reverse_, n);
}

void AdjacencyGraph::write_row(const Tin& tin, const VertexNumbering* numbering, std::uint32_t v,
                               std::vector<VertexId>& ring) {
    const VertexArrays& va = tin.vertices();
    const std::uint32_t t = tin_of(numbering, v);
    if (t >= va.size() || !va.alive[t]) {
        slack_ += degree_[v];
        degree_[v] = 0;
        refresh_row_summary(v);
        return;
    }
    tin.neighbours(VertexId{t}, ring);
    const auto deg = static_cast<std::uint32_t>(ring.size());
    if (deg > capacity_[v]) {
        grow_pool(row_capacity(deg, RowSlack::Some));
        slack_ += capacity_[v];
        offset_[v] = static_cast<std::uint32_t>(target_.size());
        capacity_[v] = row_capacity(deg, RowSlack::Some);  // it grew: it may grow again
        target_.resize(target_.size() + capacity_[v], kNone);
        length_.resize(length_.size() + capacity_[v], 0.0);
        across_.resize(across_.size() + capacity_[v], 0.0);
        reverse_.resize(reverse_.size() + capacity_[v], kNone);
    } else {
        slack_ -= capacity_[v] - degree_[v];
    }
    degree_[v] = deg;
    slack_ += capacity_[v] - deg;
    for (std::uint32_t k = 0; k < deg; ++k) {
        target_[offset_[v] + k] = local_of(numbering, ring[k].value);
        length_[offset_[v] + k] = distance(va.position[t], va.position[ring[k].value]);
        across_[offset_[v] + k] = across_length(va.position[t], va.position[ring[k].value],
                                                va.position[ring[(k + 1) % deg].value]);
    }
    refresh_row_summary(v);
}

void AdjacencyGraph::fix_reverse(std::uint32_t v) {
    for (std::uint32_t k = offset_[v]; k < offset_[v] + degree_[v]; ++k) {
        const std::uint32_t w = target_[k];
        std::uint32_t found = kNone;
        for (std::uint32_t m = offset_[w]; m < offset_[w] + degree_[w]; ++m) {
            if (target_[m] == v) {
                found = m;
                break;
            }
        }
        reverse_[k] = found;
    }
}

void AdjacencyGraph::update(const Tin& tin, std::span<const VertexId> changed,
                            const VertexNumbering* numbering) {
    if (changed.empty()) return;
    ensure_vertices(numbering != nullptr ? numbering->size() : tin.vertex_capacity());
    std::vector<VertexId> ring;
    std::vector<std::uint32_t> touched;
    if (mark_.size() < offset_.size()) mark_.resize(offset_.size(), 0);
    std::vector<std::uint8_t>& seen = mark_;
    for (VertexId c : changed) {
        // A vertex born and dead between two updates was never numbered: it has no row.
        const std::uint32_t v = numbering != nullptr ? numbering->local(c.value) : c.value;
        if (v >= offset_.size() || seen[v]) continue;
        seen[v] = 1;
        write_row(tin, numbering, v, ring);
        touched.push_back(v);
    }
    // Rows next to rewritten ones hold reverse slots into them.
    const std::size_t direct = touched.size();
    for (std::size_t t = 0; t < direct; ++t) {
        const std::uint32_t v = touched[t];
        for (std::uint32_t k = offset_[v]; k < offset_[v] + degree_[v]; ++k) {
            const std::uint32_t w = target_[k];
            if (!seen[w]) {
                seen[w] = 1;
                touched.push_back(w);
            }
        }
    }
    for (std::uint32_t v : touched)
        seen[v] = 0;
    if (slack_ * 2 > target_.size() && target_.size() > 4096) {
        rebuild(tin, numbering);
        return;
    }
    for (std::uint32_t v : touched) {
        fix_reverse(v);
        if (!dirty_flag_[v]) {
            dirty_flag_[v] = 1;
            dirty_rows_.push_back(v);
        }
    }
}

void AdjacencyGraph::assign(const std::vector<std::vector<std::uint32_t>>& rows,
                            const std::vector<std::vector<double>>& lengths,
                            const std::vector<std::vector<double>>* across) {
    const auto n = static_cast<std::uint32_t>(rows.size());
    if (lengths.size() != n || (across != nullptr && across->size() != n))
        throw std::invalid_argument(
            "adjacency graph: one row of lengths (and of across lengths) per row of neighbours");
    for (std::uint32_t v = 0; v < n; ++v) {
        if (lengths[v].size() != rows[v].size() ||
            (across != nullptr && (*across)[v].size() != rows[v].size()))
            throw std::invalid_argument("adjacency graph: row " + std::to_string(v) +
                                        " has a different number of neighbours and lengths");
        if (across != nullptr) {
            for (double c : (*across)[v]) {
                if (!(c >= 0.0) || !std::isfinite(c))
                    throw std::invalid_argument("adjacency graph: row " + std::to_string(v) +
                                                " has an across length that is negative or "
                                                "not finite");
            }
        }
        for (std::uint32_t w : rows[v]) {
            if (w >= n || w == v)
                throw std::invalid_argument("adjacency graph: row " + std::to_string(v) +
                                            " lists an invalid neighbour " + std::to_string(w));
        }
    }
    offset_.assign(n, 0);
    degree_.assign(n, 0);
    capacity_.assign(n, 0);
    longest_.assign(n, 0.0);
    row_words_.assign(n, RowWords{});
    target_.clear();
    length_.clear();
    slack_ = 0;
    for (std::uint32_t v = 0; v < n; ++v) {
        offset_[v] = static_cast<std::uint32_t>(target_.size());
        degree_[v] = static_cast<std::uint32_t>(rows[v].size());
        capacity_[v] = degree_[v];
        target_.insert(target_.end(), rows[v].begin(), rows[v].end());
        length_.insert(length_.end(), lengths[v].begin(), lengths[v].end());
    }
    across_.assign(target_.size(), 0.0);
    if (across != nullptr) {
        for (std::uint32_t v = 0; v < n; ++v)
            std::copy((*across)[v].begin(), (*across)[v].end(), across_.begin() + offset_[v]);
    }
    if (keep_shapes_) corners_.assign(target_.size(), FaceCorner{});
    for (std::uint32_t v = 0; v < n; ++v)
        refresh_row_summary(v);
    reverse_.assign(target_.size(), kNone);
    for (std::uint32_t v = 0; v < n; ++v)
        fix_reverse(v);
    for (std::uint32_t v = 0; v < n; ++v) {
        for (std::uint32_t k = offset_[v]; k < offset_[v] + degree_[v]; ++k) {
            if (reverse_[k] == kNone || !(length_[reverse_[k]] == length_[k]))
                throw std::invalid_argument(
                    "adjacency graph: edge " + std::to_string(v) + " -> " +
                    std::to_string(target_[k]) +
                    (reverse_[k] == kNone ? " has no opposite edge" : " has another length back"));
        }
    }
    dirty_flag_.assign(n, 0);
    dirty_rows_.clear();
}

std::vector<std::uint32_t> AdjacencyGraph::take_dirty_rows() {
    for (std::uint32_t v : dirty_rows_)
        dirty_flag_[v] = 0;
    std::vector<std::uint32_t> out;
    out.swap(dirty_rows_);
    return out;
}

bool AdjacencyGraph::matches(const Tin& tin, const VertexNumbering* numbering) const {
    const VertexArrays& va = tin.vertices();
    std::vector<VertexId> ring;
    auto local = [&](std::uint32_t t) { return numbering != nullptr ? numbering->local(t) : t; };
    if (numbering != nullptr) {
        for (std::uint32_t v = 0; v < numbering->size(); ++v) {
            const std::uint32_t t = numbering->tin_id(v);
            if (numbering->local(t) != v) return false;
            if ((t >= va.size() || !va.alive[t]) && v < degree_.size() && degree_[v] != 0)
                return false;
        }
    }
    for (std::uint32_t t = 0; t < va.size(); ++t) {
        const std::uint32_t v = local(t);
        if (!va.alive[t]) {
            if (numbering == nullptr && v < degree_.size() && degree_[v] != 0) return false;
            continue;
        }
        if (v >= degree_.size()) return false;
        tin.neighbours(VertexId{t}, ring);
        if (ring.size() != degree_[v]) return false;
        // The row's word range covers v and every neighbour (a kernel marks any of them).
        const auto covers = [&](std::uint32_t u) {
            return row_words_[v].lo <= (u >> 6) && (u >> 6) < row_words_[v].hi;
        };
        if (!covers(v)) return false;
        for (std::uint32_t k = 0; k < degree_[v]; ++k) {
            const std::uint32_t slot = offset_[v] + k;
            if (target_[slot] != local(ring[k].value) || !covers(target_[slot])) return false;
            const std::uint32_t r = reverse_[slot];
            if (r == kNone || target_[r] != v || !(length_[r] == length_[slot])) return false;
            if (std::abs(length_[slot] - distance(va.position[t], va.position[ring[k].value])) >
                0.0)
                return false;
            const Vec2 next = va.position[ring[(k + 1) % ring.size()].value];
            if (!(across_[slot] == across_length(va.position[t], va.position[ring[k].value], next)))
                return false;
            // The corner's shape, bit for bit what the kernel would work out from the lengths.
            if (keep_shapes_) {
                const std::uint32_t after = offset_[v] + (k + 1) % degree_[v];
                const FaceCorner want = face_corner(length_[slot], length_[after], across_[slot]);
                if (!(corners_[slot].foot == want.foot && corners_[slot].altitude == want.altitude))
                    return false;
            }
        }
    }
    return true;
}

}  // namespace sandtin
