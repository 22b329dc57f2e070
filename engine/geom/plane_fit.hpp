#pragma once
// The least-squares plane z = a x + b y + c through a set of points, by vertical residuals
// (what decides the volume a removal changes), and how far the points stray from it. The
// simplifier asks it about a vertex and its ring, a planar patch removal about a whole patch.

#include <span>

#include "geom/vec2.hpp"

namespace sandtin {

/// The largest vertical distance (m) of the points (xy in metres, z in metres) from their
/// least-squares plane. Coordinates are taken relative to `origin` and scaled to unit size, so
/// the fit is as well conditioned for a 1 mm star as for a 100 m patch. Returns +infinity when
/// the points do not determine a plane: fewer than three, all on one line, a non-finite value,
/// or spans of different sizes.
double plane_fit_residual(std::span<const Vec2> xy, std::span<const double> z, Vec2 origin);

}  // namespace sandtin
