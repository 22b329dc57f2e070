#include "physics/vertex_numbering.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace sandtin {

void VertexNumbering::assign_identity(const Tin& tin) {
    identity_ = true;
    appended_ = 0;
    const std::uint32_t n = tin.vertex_capacity();
    to_tin_.resize(n);
    to_local_.resize(n);
    for (std::uint32_t v = 0; v < n; ++v)
        to_tin_[v] = to_local_[v] = v;
}

void VertexNumbering::assign_strips(const Tin& tin) {
    identity_ = false;
    appended_ = 0;
    const VertexArrays& va = tin.vertices();
    const Rect domain = tin.domain();
    const auto live = static_cast<double>(std::max<std::size_t>(tin.vertex_count(), 1));
    const double spacing = std::sqrt(domain.width() * domain.height() / live);
    const double strip = 2.0 * spacing;
    struct Key {
        std::int64_t row;
        double x;
        std::uint32_t id;
    };
    std::vector<Key> keys;
    keys.reserve(tin.vertex_count());
    for (std::uint32_t v = 0; v < va.size(); ++v) {
        if (!va.alive[v]) continue;
        const double y = va.position[v].y - domain.min.y;
        keys.push_back({static_cast<std::int64_t>(std::floor(y / strip)), va.position[v].x, v});
    }
    std::sort(keys.begin(), keys.end(), [](const Key& a, const Key& b) {
        return std::tie(a.row, a.x, a.id) < std::tie(b.row, b.x, b.id);
    });
    to_tin_.resize(keys.size());
    to_local_.assign(va.size(), kNone);
    for (std::uint32_t l = 0; l < keys.size(); ++l) {
        to_tin_[l] = keys[l].id;
        to_local_[keys[l].id] = l;
    }
}

std::uint32_t VertexNumbering::add(std::uint32_t t) {
    if (t < to_local_.size() && to_local_[t] != kNone) return to_local_[t];
    if (identity_) {
        for (auto v = static_cast<std::uint32_t>(to_tin_.size()); v <= t; ++v) {
            to_tin_.push_back(v);
            to_local_.push_back(v);
        }
        return t;
    }
    if (t >= to_local_.size()) to_local_.resize(static_cast<std::size_t>(t) + 1, kNone);
    to_local_[t] = static_cast<std::uint32_t>(to_tin_.size());
    to_tin_.push_back(t);
    ++appended_;
    return to_local_[t];
}

}  // namespace sandtin
