#pragma once
// Per-vertex attributes as structure-of-arrays, indexed by VertexId. The layout maps 1:1 onto
// the GPU vertex buffers. Entries of dead ids keep their last values and alive == 0.

#include <cstdint>
#include <vector>

#include "geom/vec2.hpp"
#include "util/prepare_for_writing.hpp"

namespace sandtin {

struct Vec2f {
    float x = 0.0f;
    float y = 0.0f;
    friend constexpr bool operator==(Vec2f, Vec2f) = default;
};

/// Bedrock height meaning "no bedrock": finite (so it survives float GPU buffers and the
/// finiteness checks) but far below any terrain.
inline constexpr double kNoBedrock = -1.0e30;

struct VertexArrays {
    std::vector<Vec2> position;           ///< metres, fixed for the life of the vertex
    std::vector<double> height;           ///< metres, surface z = f(x, y)
    std::vector<double> bedrock;          ///< metres, non-erodible lower surface (<= height)
    std::vector<std::uint16_t> material;  ///< index into the material table
    std::vector<float> moisture;          ///< saturation in [0, 1]
    std::vector<Vec2f> slide;  ///< texture slide offset in texture units, wrapped to [0, 1)
    /// metres of water standing on the vertex, >= 0 (engine/water): kept between water
    /// operations, saved with the session and undone with the terrain. Double, so that a water
    /// volume carried from one operation to the next stays exact to rounding.
    std::vector<double> water_depth;
    std::vector<double> lumped_area;  ///< m²: one third of the areas of the incident triangles
    std::vector<std::uint8_t> alive;  ///< 1 for live ids

    VertexArrays() = default;
    /// Copies prepare their storage for writing (util/prepare_for_writing.hpp): a terrain's
    /// arrays run to tens of MB, and a plain vector copy took its fresh pages one fault at a
    /// time (a 10^6-vertex snapshot 267 ms, 51 ms prepared).
    VertexArrays(const VertexArrays& other) { *this = other; }
    VertexArrays& operator=(const VertexArrays& other) {
        if (this == &other) return *this;
        copy_array(other.position, position);
        copy_array(other.height, height);
        copy_array(other.bedrock, bedrock);
        copy_array(other.material, material);
        copy_array(other.moisture, moisture);
        copy_array(other.slide, slide);
        copy_array(other.water_depth, water_depth);
        copy_array(other.lumped_area, lumped_area);
        copy_array(other.alive, alive);
        return *this;
    }
    VertexArrays(VertexArrays&&) noexcept = default;
    VertexArrays& operator=(VertexArrays&&) noexcept = default;
    ~VertexArrays() = default;

    std::size_t size() const { return height.size(); }
    void resize(std::size_t n) {
        if (n > size()) reserve_for_writing(n);
        position.resize(n);
        height.resize(n, 0.0);
        bedrock.resize(n, kNoBedrock);
        material.resize(n, 0);
        moisture.resize(n, 0.0f);
        slide.resize(n);
        water_depth.resize(n, 0.0);
        lumped_area.resize(n, 0.0);
        alive.resize(n, 0);
    }

  private:
    template <class T>
    static void copy_array(const std::vector<T>& from, std::vector<T>& to) {
        if (to.capacity() < from.size()) {
            to.clear();  // nothing to carry over when it grows
            sandtin::reserve_for_writing(to, from.size());
        }
        to.assign(from.begin(), from.end());
    }
    void reserve_for_writing(std::size_t n) {
        sandtin::reserve_for_writing(position, n);
        sandtin::reserve_for_writing(height, n);
        sandtin::reserve_for_writing(bedrock, n);
        sandtin::reserve_for_writing(material, n);
        sandtin::reserve_for_writing(moisture, n);
        sandtin::reserve_for_writing(slide, n);
        sandtin::reserve_for_writing(water_depth, n);
        sandtin::reserve_for_writing(lumped_area, n);
        sandtin::reserve_for_writing(alive, n);
    }
};

/// Whether some live vertex holds water at least `min_depth` (m) deep (and some at all).
inline bool holds_water(const VertexArrays& va, double min_depth = 0.0) {
    for (std::size_t v = 0; v < va.size(); ++v)
        if (va.alive[v] && va.water_depth[v] > 0.0 && va.water_depth[v] >= min_depth) return true;
    return false;
}

}  // namespace sandtin
