#pragma once
// Mean curvature of a terrain's surface at a vertex, from the cotangent Laplacian of the
// triangles around it (Meyer, Desbrun, Schröder & Barr 2003): the Laplace–Beltrami operator
// of the position, K = (1 / 2A) sum_j (cot a_ij + cot b_ij) (x_j - x_i), is twice the mean
// curvature times the normal. Seed 001 (§9.1) uses Rusinkiewicz's estimator and says any
// estimator serves; this one needs only the vertex's star, which the TIN walks anyway.
//
// Sign: a hill (convex, the neighbours below the tangent plane) has H > 0, a valley H < 0, a
// plane 0 to rounding. A sphere of radius R has H = 1/R, a cylinder 1/(2R). Units: 1/m.
// A is the vertex's dual (circumcentric) cell, the Voronoi cell on a Delaunay star: with it
// the estimate is exact on a regular star of any valence over a paraboloid, and unbiased on
// random Delaunay TINs (measured on a sphere cap: mean within 1 %). The usual alternatives
// are biased there: a barycentric third gives -1.5 a / cos²(pi/n) on the paraboloid (right
// only for n = 6), and Meyer et al.'s mixed area read 7 % high on a random TIN, whose
// triangles are often obtuse. A star far from Delaunay (a dual cell under half its
// barycentric third, beside constraints) takes the third. The normal is the
// star's area-weighted normal, pointing up.

#include <span>

#include "geom/vec3.hpp"

namespace sandtin {

/// Mean curvature (1/m) at `centre`, whose neighbours `ring` (x, y, z in metres) go round it
/// counter-clockwise seen from above and close: the last and the first span a triangle with
/// it, as every interior vertex of a triangulation has. 0 for fewer than three neighbours or
/// a star without area.
double mean_curvature_of_star(const Vec3& centre, std::span<const Vec3> ring);

}  // namespace sandtin
