#pragma once
// A sculpting tool: its footprint (inner and outer contour), its underside profile and the
// parameters of how it is stamped. Built once from a ToolSpec; stamping only reads it.

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "geom/vec2.hpp"
#include "tools/tool_profile.hpp"
#include "tools/tool_shape.hpp"

namespace sandtin {

enum class ContourKind : std::uint8_t { Circle, Rectangle, Polygon };
enum class ProfileKind : std::uint8_t { Flat, HalfSphere, Heightfield, Mesh };

/// How the inner part changes the heights it covers.
enum class ImprintMode : std::uint8_t {
    Dig,    ///< press down only: h = min(h, tool)  (sand is never lifted by a pressing tool)
    Level,  ///< set exactly: h = tool  (a trowel that also fills)
};

struct ToolSpec {
    std::string name = "circle";
    ContourKind contour = ContourKind::Circle;
    double radius = 0.04;       ///< circle radius (m)
    double width = 0.08;        ///< rectangle extent across the forward axis (m)
    double length = 0.08;       ///< rectangle extent along the forward axis (m)
    std::vector<Vec2> polygon;  ///< polygon contour (m, before `scale`), any orientation
    double scale = 1.0;         ///< uniform scale of polygon contours and mesh/heightfield profiles

    ProfileKind profile = ProfileKind::Flat;
    double sphere_radius = 0.0;  ///< half-sphere radius (m); 0 = the contour's bounding radius
    std::filesystem::path profile_file;  ///< PNG heightfield or OBJ mesh
    double relief = 0.02;                ///< heightfield: metres between black and white
    bool contour_from_mesh = false;      ///< contour = the mesh's boundary loop seen from below

    int control_points = 12;     ///< circle: number of vertices of the inner contour
    double gap = 0.0;            ///< distance from I to O (m); 0 = 2.5 % of the tool's radius
    double rim_spacing = 0.0;    ///< longest contour edge (m); 0 = perimeter / control points
    double rim_tolerance = 0.0;  ///< how closely O follows the terrain (m); 0 = 1 % of the radius
    ImprintMode mode = ImprintMode::Dig;
    bool extrude = false;          ///< push the displaced volume into a ridge around the tool
    double extrusion_width = 0.0;  ///< ridge width (m); 0 = the tool's radius
};

/// The same tool `factor` times larger: every length of the spec (contour, profile, relief,
/// gap, rim spacing and tolerance, ridge width) times `factor`, so the tool built from it is
/// similar to the original's, with every depth `factor` times deeper. Lengths left at 0 stay 0
/// (they are already relative to the tool). Throws std::invalid_argument unless factor is
/// positive and finite.
ToolSpec scaled_tool_spec(ToolSpec spec, double factor);

/// Where a stamp goes: the centre in the plane, the heading (radians, counter-clockwise from
/// +x) and the height of the tool's lowest point (m).
struct ToolPlacement {
    Vec2 centre;
    double angle = 0.0;
    double bottom = 0.0;
};

class Tool {
  public:
    /// Throws std::invalid_argument (or std::runtime_error for unreadable profile files) with
    /// a message naming the bad parameter.
    static Tool build(const ToolSpec& spec);

    const ToolSpec& spec() const { return spec_; }
    const ToolShape& shape() const { return shape_; }
    const ToolProfile& profile() const { return profile_; }
    double radius() const { return radius_; }  ///< bounding radius of the inner contour (m)
    double rim_spacing() const { return rim_spacing_; }
    double rim_tolerance() const { return rim_tolerance_; }
    double extrusion_width() const { return extrusion_width_; }
    /// The longest spacing (m) at which a stroke of this tool leaves continuous furrows: half
    /// its profile's shortest tip along the forward axis (ToolProfile::tip_length), so that
    /// consecutive stamps overlap every tip by half its length and cover its flanks too, where
    /// a round tip is shorter. The rake's tines are 18 mm long: 9 mm, where a quarter of its
    /// radius (15 mm) left their flanks scalloped. +infinity for flat and half-sphere profiles,
    /// whose one tip is the whole footprint. Stroke and apply_stroke keep to it.
    double max_stroke_spacing() const { return max_stroke_spacing_; }

    /// One-off mappings; a loop over many points uses a ToolFrame (one sine and cosine).
    Vec2 to_world(const ToolPlacement& at, Vec2 local) const {
        return at.centre + rotate(local, at.angle);
    }
    Vec2 to_local(const ToolPlacement& at, Vec2 world) const {
        return rotate(world - at.centre, -at.angle);
    }
    /// Height of the tool's underside above world point p (m); +infinity where it has no contact.
    double underside(const ToolPlacement& at, Vec2 world) const;

    /// The most interior samples a curved profile may need; Tool::build rejects a larger
    /// lattice (the shipped foot needs a few thousand).
    static constexpr double kMaxInteriorSamples = 4e6;
    /// Where a stamp samples a curved profile inside I: a lattice in tool coordinates (m),
    /// interior_lattice() of the subdivided inner contour at `spacing` (the profile's sample
    /// spacing, at most the rim spacing), with the profile's offset at each point (m above the
    /// lowest point; +infinity: no contact). Empty for a flat profile. Made once when the tool
    /// is built, so a stamp only maps it to the world.
    struct InteriorSamples {
        double spacing = 0.0;  ///< m
        std::vector<Vec2> local;
        std::vector<double> offset;
    };
    const InteriorSamples& interior_samples() const { return interior_samples_; }

  private:
    ToolSpec spec_;
    ToolShape shape_;
    ToolProfile profile_;
    double radius_ = 0.0;
    double rim_spacing_ = 0.0;
    double rim_tolerance_ = 0.0;
    double extrusion_width_ = 0.0;
    double max_stroke_spacing_ = 0.0;
    InteriorSamples interior_samples_;
};

/// A tool at one placement, with the heading's cosine and sine evaluated once: a stamp maps
/// every contour point and asks the underside at every vertex under the tool. Refers to the
/// tool, which must outlive it.
class ToolFrame {
  public:
    ToolFrame(const Tool& tool, const ToolPlacement& at)
        : tool_(&tool), at_(at), cos_(std::cos(at.angle)), sin_(std::sin(at.angle)) {}

    Vec2 to_world(Vec2 local) const {
        return at_.centre + Vec2{cos_ * local.x - sin_ * local.y, sin_ * local.x + cos_ * local.y};
    }
    Vec2 to_local(Vec2 world) const {
        const Vec2 d = world - at_.centre;
        return {cos_ * d.x + sin_ * d.y, -sin_ * d.x + cos_ * d.y};
    }
    /// Height of the underside above world point p (m); +infinity where it has no contact.
    double underside(Vec2 world) const {
        const ToolProfile& profile = tool_->profile();
        // A flat profile needs no local coordinates.
        return at_.bottom + profile.offset(profile.is_flat() ? Vec2{} : to_local(world));
    }

  private:
    const Tool* tool_;
    ToolPlacement at_;
    double cos_;
    double sin_;
};

inline double Tool::underside(const ToolPlacement& at, Vec2 world) const {
    return ToolFrame(*this, at).underside(world);
}

/// The boundary loop of a mesh seen from below (x, y of its open border), centred and scaled
/// like ToolProfile::mesh_imprint. Throws std::invalid_argument when the mesh has no border.
std::vector<Vec2> mesh_outline(const TriangleMesh& mesh, double scale);

}  // namespace sandtin
