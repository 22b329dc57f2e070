#include "tin/bulk_removal.hpp"

#include <algorithm>
#include <span>
#include <vector>

#include "util/prepare_for_writing.hpp"

namespace sandtin {

namespace {

/// The vertices offered, with their neighbour lists, and which of them are still in the set.
struct Candidates {
    std::vector<VertexId> ids;
    std::vector<std::uint32_t> first;  ///< CSR offsets into `ring` (size ids + 1)
    std::vector<VertexId> ring;
    std::vector<std::uint8_t> in;        ///< by VertexId::value: 0 out, 1 in, 2 in a patch
    std::vector<std::uint32_t> slot_of;  ///< VertexId::value -> index in ids (valid when `in`)
    std::vector<std::uint8_t> verdict;   ///< by VertexId::value: scratch, all 0 between uses
};

/// Connected components of `part` (alive vertices) over the TIN's current edges.
std::vector<std::vector<VertexId>> components(const Tin& tin, std::vector<VertexId> part) {
    std::sort(part.begin(), part.end());
    std::vector<std::uint8_t> taken(part.size(), 0);
    std::vector<std::vector<VertexId>> out;
    std::vector<VertexId> ring;
    for (std::size_t seed = 0; seed < part.size(); ++seed) {
        if (taken[seed]) continue;
        taken[seed] = 1;
        std::vector<VertexId> group{part[seed]};
        for (std::size_t head = 0; head < group.size(); ++head) {
            tin.neighbours(group[head], ring);
            for (VertexId w : ring) {
                const auto it = std::lower_bound(part.begin(), part.end(), w);
                if (it == part.end() || *it != w) continue;
                const auto k = static_cast<std::size_t>(it - part.begin());
                if (!taken[k]) {
                    taken[k] = 1;
                    group.push_back(w);
                }
            }
        }
        out.push_back(std::move(group));
    }
    return out;
}

/// Removes `patch` in one step; when it does not qualify (typically a ring around vertices
/// that stay: the neighbours of a constrained vertex inside a stamp), halves it across its
/// longer side and tries each connected piece again, a few levels deep. A ring cut in two is
/// two discs.
void remove_or_split(Tin& tin, std::vector<VertexId> patch, EditReport* report, int depth,
                     BulkRemoval& out) {
    std::erase_if(patch, [&](VertexId v) { return !tin.is_alive(v); });
    if (patch.empty()) return;
    if (tin.remove_patch(patch, VolumePolicy::Report, report)) {
        ++out.patches;
        out.removed += patch.size();
        return;
    }
    constexpr int kMaxDepth = 6;
    if (depth >= kMaxDepth || patch.size() < 2) {
        ++out.refused;
        return;
    }
    Vec2 lo = tin.position(patch.front());
    Vec2 hi = lo;
    for (VertexId v : patch) {
        const Vec2 p = tin.position(v);
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
    }
    const bool along_x = hi.x - lo.x >= hi.y - lo.y;
    auto key = [&](VertexId v) { return along_x ? tin.position(v).x : tin.position(v).y; };
    const auto middle = patch.begin() + static_cast<std::ptrdiff_t>(patch.size() / 2);
    std::nth_element(patch.begin(), middle, patch.end(),
                     [&](VertexId a, VertexId b) { return key(a) < key(b); });
    const std::vector<VertexId> first(patch.begin(), middle);
    const std::vector<VertexId> second(middle, patch.end());
    for (const std::vector<VertexId>* half : {&first, &second}) {
        for (std::vector<VertexId>& piece : components(tin, *half))
            remove_or_split(tin, std::move(piece), report, depth + 1, out);
    }
}

}  // namespace

BulkRemoval remove_in_patches(Tin& tin, std::span<const VertexId> vertices, EditReport* report,
                              const std::function<bool(VertexId v, VertexId w)>& may_border) {
    BulkRemoval out;
    out.candidates = vertices.size();
    // Reused between calls: a stamp offers a few hundred vertices of a terrain of millions, and
    // the flag array must not cost O(terrain) per stamp (it is cleared entry by entry below).
    static thread_local Candidates c;
    const std::size_t capacity = tin.vertices().size();
    grow_zero_filled(c.in, capacity);
    grow_zero_filled(c.slot_of, capacity);
    grow_zero_filled(c.verdict, capacity);
    c.ids.clear();
    c.first.assign(1, 0);
    c.ring.clear();
    std::vector<VertexId> around;
    for (VertexId v : vertices) {
        if (!tin.is_alive(v) || c.in[v.value]) continue;
        const Tin::VertexStar star = tin.star(v, around);
        if (star.boundary || star.constrained) continue;
        c.in[v.value] = 1;
        c.slot_of[v.value] = static_cast<std::uint32_t>(c.ids.size());
        c.ids.push_back(v);
        c.ring.insert(c.ring.end(), around.begin(), around.end());
        c.first.push_back(static_cast<std::uint32_t>(c.ring.size()));
    }
    auto in_set = [&](VertexId w) { return w.value < c.in.size() && c.in[w.value] != 0; };

    // A patch is removed with the triangles around it. Two things there would not survive the
    // re-fill: a constrained edge between two vertices left in place (so the neighbours of
    // constrained vertices stay), and a vertex left in place whose every triangle would go
    // (an island: no two consecutive neighbours outside the set; its neighbours stay too).
    // The caller's may_border rule works the same way. Dropping a vertex can make it an island
    // (or break the rule) in turn, hence the loop to a fixed point.
    // In the first pass every vertex outside the set next to it is judged once (constrained,
    // or an island); later passes only look at the vertices dropped in the pass before:
    // dropping shrinks the set, which can turn an island into a non-island but never the
    // other way round, so a vertex that passed keeps passing against its old outside
    // neighbours. The result is that of re-running the full pass until nothing changes.
    std::vector<std::uint32_t> drop;
    std::vector<VertexId> others;
    // `others` holds the neighbours of the vertex whose star is given.
    auto is_island = [&](std::span<const VertexId> ring) {
        for (std::size_t k = 0; k < ring.size(); ++k) {
            if (!in_set(ring[k]) && !in_set(ring[(k + 1) % ring.size()])) return false;
        }
        return true;
    };
    auto ring_of = [&](std::uint32_t i) {
        return std::span<const VertexId>(c.ring.data() + c.first[i], c.first[i + 1] - c.first[i]);
    };
    std::vector<VertexId> judged;  // outside vertices with a verdict (cleared at the end)
    for (std::size_t i = 0; i < c.ids.size(); ++i) {
        for (const VertexId w : ring_of(static_cast<std::uint32_t>(i))) {
            if (in_set(w)) continue;
            std::uint8_t& verdict = c.verdict[w.value];  // 0 unknown, 1 may border, 2 may not
            if (verdict == 0) {
                const Tin::VertexStar star = tin.star(w, others);
                verdict = star.constrained || (!star.boundary && is_island(others)) ? 2 : 1;
                judged.push_back(w);
            }
            if (verdict == 2 || (may_border && !may_border(c.ids[i], w))) {
                drop.push_back(static_cast<std::uint32_t>(i));
                break;
            }
        }
    }
    for (const VertexId w : judged)
        c.verdict[w.value] = 0;
    std::vector<std::uint32_t> dropped;
    while (!drop.empty()) {
        for (std::uint32_t i : drop)
            c.in[c.ids[i].value] = 0;
        dropped.swap(drop);
        drop.clear();
        for (std::uint32_t d : dropped) {
            const std::span<const VertexId> ring = ring_of(d);
            const bool island = is_island(ring);
            for (const VertexId w : ring) {
                if (!in_set(w)) continue;
                const std::uint32_t i = c.slot_of[w.value];
                if (c.verdict[w.value] != 0) continue;  // already dropped in this pass
                if (island || (may_border && !may_border(w, c.ids[d]))) {
                    c.verdict[w.value] = 1;
                    drop.push_back(i);
                }
            }
        }
        for (std::uint32_t i : drop)
            c.verdict[c.ids[i].value] = 0;
    }

    // Connected patches, by breadth-first search within the set.
    std::vector<VertexId> patch;
    for (std::size_t seed = 0; seed < c.ids.size(); ++seed) {
        if (c.in[c.ids[seed].value] != 1) continue;
        c.in[c.ids[seed].value] = 2;  // 2: in the set and taken by a patch
        patch.assign(1, c.ids[seed]);
        for (std::size_t head = 0; head < patch.size(); ++head) {
            const std::uint32_t i = c.slot_of[patch[head].value];
            for (std::uint32_t k = c.first[i]; k < c.first[i + 1]; ++k) {
                const VertexId w = c.ring[k];
                if (w.value < c.in.size() && c.in[w.value] == 1) {
                    c.in[w.value] = 2;
                    patch.push_back(w);
                }
            }
        }
        remove_or_split(tin, patch, report, 0, out);
    }
    for (VertexId v : c.ids)  // dropped ones included: ids keeps every vertex taken in
        c.in[v.value] = 0;
    return out;
}

}  // namespace sandtin
