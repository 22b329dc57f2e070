#pragma once
// The terrain as the renderer draws it: three vertices per triangle (so each corner carries a
// barycentric coordinate for the wireframe and the triangle's constrained-edge mask), with the
// smooth vertex normal, the material albedo, the texture-sliding offset and the overlay values.
// Built on the CPU from the TIN; positions are relative to the domain centre, in metres.

#include <cstdint>
#include <span>
#include <vector>

#include "physics/material.hpp"
#include "tin/tin.hpp"

namespace sandtin::render {

struct TerrainVertex {
    float position[3];  ///< metres, x/y relative to the domain centre, z = height
    float normal[3];
    float albedo[3];  ///< linear RGB
    float barycentric[3];
    /// x: mask of constrained edges (bit i: edge opposite corner i); y: slope of the triangle /
    /// tan(angle of repose); z: sand thickness above bedrock (m, 0 without bedrock); w: 1 when
    /// the vertex is active (eroding).
    float overlay[4];
    float slide[2];
};
static_assert(sizeof(TerrainVertex) == 18 * sizeof(float));

/// `active` (indexed by VertexId, may be shorter than the vertex capacity) flags eroding
/// vertices.
std::vector<TerrainVertex> build_terrain_vertices(const Tin& tin, const MaterialTable& materials,
                                                  std::span<const std::uint8_t> active);

}  // namespace sandtin::render
