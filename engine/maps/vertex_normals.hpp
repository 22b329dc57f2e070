#pragma once
// Per-vertex normals of the TIN surface: the area-weighted mean of the incident triangles'
// normals (sum of their unnormalised cross products), unit length, pointing up (z > 0).

#include <vector>

#include "geom/vec3.hpp"
#include "tin/tin.hpp"

namespace sandtin {

/// Indexed by VertexId (size vertex_capacity(); dead ids get (0, 0, 1)). `z_scale`
/// exaggerates heights before the normals are taken.
std::vector<Vec3> vertex_normals(const Tin& tin, double z_scale = 1.0);

/// Unit normal of the triangle (a, b, c), counter-clockwise seen from above.
Vec3 face_normal(Vec3 a, Vec3 b, Vec3 c);

/// The tangent the mesh exports give a vertex with unit normal `n`: east (1, 0, 0) made
/// perpendicular to n, or n x up where n faces due east or west. With the bitangent N x T
/// (north on level ground) it is the frame a tangent-space normal map is read in. `up` is the
/// up axis of n's frame: (0, 0, 1) in the terrain's, (0, 1, 0) in a Y-up export's (whose x is
/// still east), so both give the same tangent.
Vec3 surface_tangent(Vec3 n, Vec3 up);

}  // namespace sandtin
