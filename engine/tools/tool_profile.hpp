#pragma once
// The underside of a tool: how far above its lowest point the tool surface is at each point of
// its footprint (metres, tool-local coordinates). Flat and half-sphere profiles are analytic;
// bitmap heightfields and the imprint of a triangle mesh seen from below are sampled on a grid
// and interpolated bilinearly.

#include <cstdint>
#include <limits>
#include <vector>

#include "formats/obj_mesh.hpp"
#include "formats/png_image.hpp"
#include "geom/rect.hpp"
#include "geom/vec2.hpp"

namespace sandtin {

class ToolProfile {
  public:
    enum class Kind : std::uint8_t { Flat, HalfSphere, Grid };

    /// A flat underside: the tool levels its whole footprint to one height.
    static ToolProfile flat();
    /// A ball of `radius` metres: offset = r - sqrt(r² - |q|²) (the seed prints the root with
    /// the wrong sign; this is the lower hemisphere). Outside the ball's rim the offset is r.
    static ToolProfile half_sphere(double radius);
    /// A grayscale image covering `extent` in tool coordinates: black (0) is the lowest point of
    /// the tool, white is `relief` metres above it. Row 0 of the image is at extent.max.y.
    static ToolProfile heightfield(const PngImage& image, const Rect& extent, double relief);
    /// The lower envelope of a triangle mesh (x, y horizontal, z up; units metres times
    /// `scale`, centred on the mesh's xy bounding box). Points the mesh does not cover are
    /// "no contact" (+infinity), but for a skirt one grid cell's diagonal wide around its
    /// outline, which takes the height of the mesh's nearest point: the underside has contact
    /// everywhere on the mesh, up to its outline (the contour of a contour_from_mesh tool).
    /// Sampled on a `resolution` x `resolution` grid; in a cell where some samples have no
    /// contact, offset() blends those that do.
    static ToolProfile mesh_imprint(const TriangleMesh& mesh, double scale, int resolution = 256);

    Kind kind() const { return kind_; }
    bool is_flat() const { return kind_ == Kind::Flat; }
    /// Height of the underside above the tool's lowest point at local point q (metres, >= 0);
    /// +infinity where the tool does not touch.
    double offset(Vec2 q) const;
    /// A spacing (metres) fine enough to represent the profile's curvature; 0 for flat tools.
    double sample_spacing() const { return sample_spacing_; }
    /// The length of the profile's shortest tip along the tool's forward axis (local +x), in
    /// metres: of each tip (a connected region of samples within kTipBand of the relief above
    /// the lowest point: a rake's tines, a sole's pads), the longest run of samples along x
    /// (their count times the sample spacing), and the shortest of those. +infinity for flat
    /// and half-sphere profiles, whose one tip is the whole footprint.
    double tip_length() const;
    /// The band above the lowest point that makes a tip, as a share of the relief (the highest
    /// contact sample above the lowest).
    static constexpr double kTipBand = 0.1;

  private:
    Kind kind_ = Kind::Flat;
    double radius_ = 0.0;
    double sample_spacing_ = 0.0;
    Rect extent_;
    int nx_ = 0;
    int ny_ = 0;
    std::vector<double> grid_;  ///< row-major, row 0 at extent_.min.y; NaN = no contact
};

}  // namespace sandtin
