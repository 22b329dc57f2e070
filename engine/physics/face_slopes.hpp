#pragma once
// How steep a terrain's triangles stand against the angle of repose of their sand: the rest
// criterion of the piecewise-linear surface itself, |∇h| <= tan(alpha) on every face (Prigozhin's
// critical-slope model; issue 39). The relaxation tests slopes along edges, and a triangle's
// steepest direction is rarely along one of its edges: on a thin triangle its slope exceeds all
// three edge slopes by far. This is the yardstick that shows it, for the benches, the reports
// and the tests; the editor's Slope overlay shows the same per-face quantity on screen.
//
// A face's tan(alpha) is the mean of its corners' (each from its material and moisture, as the
// relaxation takes it). Faces whose three corners carry no sand above the bedrock are rock and
// are not judged. Faces with less than `min_area_fraction` of the measured area are skipped
// (slivers between constraints a hair apart, whose gradient is rounding noise) and counted.

#include <cstddef>
#include <optional>
#include <span>

#include "geom/rect.hpp"
#include "geom/vec2.hpp"
#include "geom/vec3.hpp"
#include "physics/material.hpp"
#include "tin/tin.hpp"

namespace sandtin {

/// |∇h| (m/m) of the plane through three points given by (x, y, z) in metres; +infinity for a
/// face with no area in the plane.
double face_gradient(const Vec3& a, const Vec3& b, const Vec3& c);

struct FaceSlopeOptions {
    /// A face is steep when |∇h| > tan(alpha) (1 + tolerance).
    double tolerance = 1e-3;
    /// A face is part of a slope (a pile's flank, not the flat around it) when
    /// |∇h| > sloped_fraction tan(alpha).
    double sloped_fraction = 0.1;
    /// Faces with less than this fraction of the measured faces' total area are skipped.
    double min_area_fraction = 1e-9;
    /// Only the faces whose centroid lies inside (metres); none: every face.
    std::optional<Rect> region;
};

struct FaceSlopeReport {
    std::size_t faces = 0;          ///< judged: sand faces in the region, not skipped
    std::size_t rock_faces = 0;     ///< no sand above the bedrock at any corner
    std::size_t skipped_faces = 0;  ///< below min_area_fraction of the area
    std::size_t steep_faces = 0;
    double area = 0.0;         ///< m², of the judged faces (in the plane)
    double sloped_area = 0.0;  ///< m², |∇h| > sloped_fraction tan(alpha)
    double steep_area = 0.0;   ///< m², |∇h| > tan(alpha) (1 + tolerance)
    /// Largest |∇h| / tan(alpha) over the judged faces (0 with none), and that face's centroid.
    double max_ratio = 0.0;
    Vec2 steepest_at;

    /// steep_area / sloped_area: the share of the slopes steeper than repose (0 with no slope).
    double steep_share_of_slopes() const {
        return sloped_area > 0.0 ? steep_area / sloped_area : 0.0;
    }
};

/// One triangle to judge: its corners (x, y, z in metres), its tan(alpha), and whether any
/// corner carries sand above the bedrock (rock faces are counted, not judged).
struct SlopeFace {
    Vec3 a, b, c;
    double tan_alpha = 0.0;
    bool sand = true;
};

/// Measures the given faces (those whose centroid is in `options.region` when given): the
/// same yardstick for surfaces that are not a Tin (the regular-grid baseline).
FaceSlopeReport measure_face_slopes(std::span<const SlopeFace> faces,
                                    const FaceSlopeOptions& options = {});

/// Measures every finite face of `tin` (in `options.region` when given). `materials` must
/// hold every material index the vertices use. Throws std::invalid_argument on a negative
/// tolerance or fraction.
FaceSlopeReport measure_face_slopes(const Tin& tin, const MaterialTable& materials,
                                    const FaceSlopeOptions& options = {});

}  // namespace sandtin
