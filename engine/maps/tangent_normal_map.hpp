#pragma once
// A tangent-space normal map for a mesh export. glTF's normalTexture holds normals in the frame
// a viewer interpolates across each triangle: the tangent T and normal N from the mesh's
// vertices, and the bitangent B = N x T. OBJ importers read map_Bump the same way, with
// MikkTSpace tangents from the texture coordinates (u east, v north: T east, B north). A
// world-space map there makes the viewer tilt every slope a second time (an 80 degree wall
// shaded 80 degrees off).

#include "maps/map_grid.hpp"
#include "tin/tin.hpp"

namespace sandtin {

/// `world`: three channels of unit normals in the terrain frame (x east, y north, z up) on
/// `grid` (bake_normal_map of the terrain whose look is exported). `surface`: the TIN the mesh's
/// top is built from (the terrain itself or its re-mesh), whose vertices carry
/// vertex_normals(surface) and surface_tangent() of those, as the mesh exports write them.
///
/// Returns, per sample, the unit vector v (z > 0 wherever the world normal faces the same way
/// as the interpolated one) with normalise(v.x T + v.y B + v.z N) equal to the world normal,
/// where N and T interpolate the vertex normals and tangents linearly at the sample, each
/// normalised, and B = N x T (MikkTSpace's per-pixel rule). Where `surface` is the terrain and
/// `world` its smooth bake, every sample is (0, 0, 1) to rounding: the mesh already carries the
/// normals, and the map carries only what the mesh lacks (a re-mesh's lost detail, facets).
MapImage bake_tangent_normal_map(const Tin& surface, const MapImage& world, const MapGrid& grid);

}  // namespace sandtin
