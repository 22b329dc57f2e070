// Tool undersides: the analytic half-sphere, the imprint of a mesh seen from below, bitmap
// heightfields, and the shipped foot and rake assets. Oracles: the sphere formula, the lower
// envelope of a generated mesh found by brute force over its triangles (with the rigorous
// bound of bilinear interpolation between grid samples), exact linear ramps.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "support/tin_oracles.hpp"
#include "support/tool_oracles.hpp"
#include "tin/tin.hpp"
#include "tools/stamp.hpp"
#include "tools/tool.hpp"
#include "tools/tool_json.hpp"
#include "tools/tool_profile.hpp"

namespace sandtin {
namespace {

using test::inside_polygon;
using test::live_ids;
using test::mesh_is_sound;

TEST(ToolProfile, FlatIsZeroEverywhere) {
    const ToolProfile p = ToolProfile::flat();
    EXPECT_TRUE(p.is_flat());
    for (Vec2 q : test::random_points_in(Rect{{-1, -1}, {1, 1}}, 100, 1))
        EXPECT_EQ(p.offset(q), 0.0);
}

TEST(ToolProfile, HalfSphereIsTheLowerHemisphere) {
    const double r = 0.05;
    const ToolProfile p = ToolProfile::half_sphere(r);
    EXPECT_EQ(p.kind(), ToolProfile::Kind::HalfSphere);
    EXPECT_EQ(p.offset({0, 0}), 0.0);
    for (Vec2 q : test::random_points_in(Rect{{-0.07, -0.07}, {0.07, 0.07}}, 2000, 2)) {
        const double d2 = q.x * q.x + q.y * q.y;
        const double expected = d2 < r * r ? r - std::sqrt(r * r - d2) : r;
        EXPECT_NEAR(p.offset(q), expected, 1e-16);
        EXPECT_GE(p.offset(q), 0.0);
    }
    // On the equator the surface is vertical: offset r.
    EXPECT_NEAR(p.offset({r, 0}), r, 1e-16);
    EXPECT_NEAR(p.offset(rotate({r * 0.6, 0}, 1.0)), r - r * 0.8, 1e-16);
    EXPECT_THROW(ToolProfile::half_sphere(0.0), std::invalid_argument);
    EXPECT_THROW(ToolProfile::half_sphere(-1.0), std::invalid_argument);
}

// ToolFrame evaluates the heading once; against the analytic rotation and the ball's formula.
TEST(ToolFrame, MapsLikeTheRotationAndGivesTheBallsUnderside) {
    ToolSpec spec;
    spec.radius = 0.04;
    spec.profile = ProfileKind::HalfSphere;
    spec.sphere_radius = 0.05;
    const Tool tool = Tool::build(spec);
    const ToolPlacement at{{0.3, 0.7}, std::numbers::pi / 2.0, -0.01};
    const ToolFrame frame(tool, at);
    // A quarter turn counter-clockwise takes local +x to world +y.
    const Vec2 w = frame.to_world({0.02, 0.0});
    EXPECT_NEAR(w.x, 0.3, 1e-17);
    EXPECT_NEAR(w.y, 0.72, 1e-16);
    for (Vec2 q : test::random_points_in(Rect{{0.2, 0.6}, {0.4, 0.8}}, 500, 9)) {
        const Vec2 local = frame.to_local(q);
        const Vec2 back = frame.to_world(local);
        EXPECT_NEAR(back.x, q.x, 1e-15);
        EXPECT_NEAR(back.y, q.y, 1e-15);
        // Distance from the centre is kept, so the ball's offset depends on it alone.
        const double d2 = (q.x - 0.3) * (q.x - 0.3) + (q.y - 0.7) * (q.y - 0.7);
        const double r = 0.05;
        const double expected = at.bottom + (d2 < r * r ? r - std::sqrt(r * r - d2) : r);
        EXPECT_NEAR(frame.underside(q), expected, 1e-15);
        // The one-off mapping (through rotate()) agrees bit for bit.
        const Vec2 one_off = tool.to_local(at, q);
        EXPECT_EQ(one_off.x, local.x);
        EXPECT_EQ(one_off.y, local.y);
    }
}

// A spherical cap (the bottom of a ball of radius R, out to rho_max) as a triangle mesh, moved
// to `centre` and lifted by `lift`, with a flat lid above it that the imprint must ignore.
struct Dome {
    double R = 0.05;
    double rho_max = 0.04;
    Vec2 centre{0.3, -0.2};
    double lift = 1.0;
    int rings = 40;
    int segments = 96;

    double cap(double rho) const { return R - std::sqrt(R * R - rho * rho); }
    TriangleMesh mesh(bool with_lid) const {
        TriangleMesh m;
        auto add = [&](Vec2 p, double z) {
            m.vertices.push_back({p.x + centre.x, p.y + centre.y, z + lift});
            return static_cast<std::uint32_t>(m.vertices.size() - 1);
        };
        auto ring_vertex = [&](int k, int s) -> std::uint32_t {
            return static_cast<std::uint32_t>(1 + (k - 1) * segments + (s % segments));
        };
        add({0, 0}, 0.0);
        for (int k = 1; k <= rings; ++k) {
            const double rho = rho_max * k / rings;
            for (int s = 0; s < segments; ++s) {
                const double a = 2.0 * std::numbers::pi * s / segments;
                add({rho * std::cos(a), rho * std::sin(a)}, cap(rho));
            }
        }
        for (int s = 0; s < segments; ++s)
            m.triangles.push_back({0, ring_vertex(1, s), ring_vertex(1, s + 1)});
        for (int k = 1; k < rings; ++k) {
            for (int s = 0; s < segments; ++s) {
                const auto a = ring_vertex(k, s), b = ring_vertex(k, s + 1);
                const auto c = ring_vertex(k + 1, s), d = ring_vertex(k + 1, s + 1);
                m.triangles.push_back({a, c, d});
                m.triangles.push_back({a, d, b});
            }
        }
        if (with_lid) {
            const std::uint32_t hub = add({0, 0}, 0.1);
            const std::uint32_t first = hub + 1;
            for (int s = 0; s < segments; ++s) {
                const double a = 2.0 * std::numbers::pi * s / segments;
                add({rho_max * std::cos(a), rho_max * std::sin(a)}, 0.1);
            }
            for (int s = 0; s < segments; ++s) {
                m.triangles.push_back({hub, first + static_cast<std::uint32_t>(s),
                                       first + static_cast<std::uint32_t>((s + 1) % segments)});
            }
        }
        return m;
    }
};

/// Lowest z of the mesh above (x, y), by brute force over all triangles; +inf when none.
double lower_envelope(const TriangleMesh& m, Vec2 p) {
    double best = std::numeric_limits<double>::infinity();
    for (const auto& t : m.triangles) {
        const Vec2 a{m.vertices[t[0]][0], m.vertices[t[0]][1]};
        const Vec2 b{m.vertices[t[1]][0], m.vertices[t[1]][1]};
        const Vec2 c{m.vertices[t[2]][0], m.vertices[t[2]][1]};
        if (test::orient2(a, b, c) == 0.0L) continue;
        const auto w = test::barycentric(p, a, b, c);
        if (w[0] < -1e-12L || w[1] < -1e-12L || w[2] < -1e-12L) continue;
        best = std::min(
            best, static_cast<double>(w[0] * m.vertices[t[0]][2] + w[1] * m.vertices[t[1]][2] +
                                      w[2] * m.vertices[t[2]][2]));
    }
    return best;
}

TEST(ToolProfile, MeshImprintIsTheLowerEnvelopeWithinGridResolution) {
    const Dome dome;
    const TriangleMesh mesh = dome.mesh(/*with_lid=*/true);
    const double scale = 2.0;
    const int resolution = 256;
    const ToolProfile p = ToolProfile::mesh_imprint(mesh, scale, resolution);
    EXPECT_EQ(p.kind(), ToolProfile::Kind::Grid);
    // The grid spans the mesh's bounding box (2 rho_max square) times the scale.
    const double cell = 2.0 * dome.rho_max * scale / (resolution - 1);
    const double diag = cell * std::sqrt(2.0);
    std::size_t compared = 0;
    for (Vec2 q : test::random_points_in(Rect{{-0.06, -0.06}, {0.06, 0.06}}, 1500, 3)) {
        const double rho = length(q) / scale;  // mesh units
        if (rho > 0.7 * dome.rho_max) continue;
        ++compared;
        // Oracle 1: the mesh itself. Bilinear interpolation returns a convex combination of
        // the four surrounding grid samples, each the envelope at a point within one cell
        // diagonal of q, so the error is at most the envelope's slope times that diagonal.
        const double rho_far = rho + diag / scale;
        const double slope = rho_far / std::sqrt(dome.R * dome.R - rho_far * rho_far);
        const double envelope = scale * (lower_envelope(mesh, q / scale + dome.centre) - dome.lift);
        EXPECT_NEAR(p.offset(q), envelope, slope * diag + 1e-12) << q.x << ", " << q.y;
        // Oracle 2: the analytic sphere (the mesh is a faceted sphere, which adds its chordal
        // error: under 2e-5 m for these rings and segments, times the scale).
        EXPECT_NEAR(p.offset(q), scale * dome.cap(rho), slope * diag + scale * 2e-5);
    }
    EXPECT_GT(compared, 500u);
    // The lowest point is the origin of the tool.
    EXPECT_NEAR(p.offset({0, 0}), 0.0, 1e-12);
    // Where the mesh does not reach (the corners of its bounding box) the tool has no contact.
    const double corner = 0.95 * dome.rho_max * scale;
    for (Vec2 q : {Vec2{corner, corner}, Vec2{-corner, corner}, Vec2{corner, -corner}})
        EXPECT_EQ(p.offset(q), std::numeric_limits<double>::infinity());
}

// A tool whose contour is its mesh's outline (the shipped foot) stamps its inner contour on
// that outline, so the underside must have contact there, and everywhere along it. The grid
// samples the mesh at its nodes, and a point on the outline often lies in a cell whose nodes
// are all, or nearest, outside the sole: the foot read "no contact" at 39 of its 72 outline
// points, and extrusion, weighting the ridge by the cut at each of them, heaped the sand in
// radial stripes. Oracle: the mesh's lower envelope by brute force over its triangles, with
// the bound of bilinear interpolation (every sample that enters lies within a cell diagonal of
// the point, on the mesh or within that diagonal of it, so the error is at most the mesh's
// steepest slope times two diagonals).
TEST(ToolProfile, MeshImprintHasContactAlongTheWholeOutline) {
    const ToolSpec spec = load_tool_asset("foot");
    ASSERT_TRUE(spec.contour_from_mesh);
    const Tool tool = Tool::build(spec);
    const TriangleMesh mesh = read_obj(spec.profile_file);
    Rect box;
    double lowest = std::numeric_limits<double>::infinity();
    for (const auto& v : mesh.vertices) {
        box.expand(Vec2{v[0], v[1]});
        lowest = std::min(lowest, v[2]);
    }
    const Vec2 centre = box.centre();
    double steepest = 0.0;
    for (const auto& t : mesh.triangles) {
        const auto& a = mesh.vertices[t[0]];
        const auto& b = mesh.vertices[t[1]];
        const auto& c = mesh.vertices[t[2]];
        const double ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2];
        const double vx = c[0] - a[0], vy = c[1] - a[1], vz = c[2] - a[2];
        const double nz = ux * vy - uy * vx;
        if (std::abs(nz) < 1e-300) continue;
        const double nx = uy * vz - uz * vy, ny = uz * vx - ux * vz;
        steepest = std::max(steepest, std::hypot(nx, ny) / std::abs(nz));
    }
    const double diag = std::hypot(box.width(), box.height()) / (256 - 1);
    const std::vector<Vec2>& outline = tool.shape().inner;
    std::size_t without_contact = 0;
    double worst = 0.0;
    for (std::size_t i = 0; i < outline.size(); ++i) {
        const Vec2 a = outline[i];
        const Vec2 b = outline[(i + 1) % outline.size()];
        for (int k = 0; k < 8; ++k) {
            const Vec2 q = lerp(a, b, k / 8.0);
            const double offset = tool.profile().offset(q);
            if (!std::isfinite(offset)) {
                ++without_contact;
                continue;
            }
            // The envelope just inside the outline (on it, rounding may miss every triangle).
            const Vec2 inward = q + (Vec2{} - q) * 1e-9;
            const double envelope = lower_envelope(mesh, inward + centre) - lowest;
            ASSERT_TRUE(std::isfinite(envelope)) << q.x << ", " << q.y;
            worst = std::max(worst, std::abs(offset - envelope));
        }
    }
    EXPECT_EQ(without_contact, 0u) << "of " << 8 * outline.size() << " points on the outline";
    EXPECT_LE(worst, 2.0 * steepest * diag) << "steepest slope " << steepest;
}

TEST(ToolProfile, MeshOutlineIsTheBorderRingCentredAndScaled) {
    const Dome dome;
    const TriangleMesh mesh = dome.mesh(/*with_lid=*/false);
    const double scale = 0.5;
    const std::vector<Vec2> outline = mesh_outline(mesh, scale);
    ASSERT_EQ(outline.size(), static_cast<std::size_t>(dome.segments));
    for (Vec2 p : outline)
        EXPECT_NEAR(length(p), dome.rho_max * scale, 1e-15);
    EXPECT_NEAR(std::abs(static_cast<double>(test::signed_area_ld(outline))),
                0.5 * dome.segments * std::pow(dome.rho_max * scale, 2) *
                    std::sin(2.0 * std::numbers::pi / dome.segments),
                1e-15);
    // A closed mesh (the dome with its lid shares no border... here: a tetrahedron) has none.
    TriangleMesh tetra;
    tetra.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    tetra.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
    EXPECT_THROW(mesh_outline(tetra, 1.0), std::invalid_argument);
}

PngImage ramp_image(int channels, int bit_depth) {
    PngImage img;
    img.width = 11;
    img.height = 5;
    img.channels = channels;
    img.bit_depth = bit_depth;
    const std::uint16_t unit = bit_depth == 16 ? 257 : 1;  // 65535 / 255
    for (std::uint32_t row = 0; row < img.height; ++row) {
        for (std::uint32_t x = 0; x < img.width; ++x) {
            // Brighter (higher) to the right and towards the top row.
            const auto v =
                static_cast<std::uint16_t>((10 * x + 30 * (img.height - 1 - row)) * unit);
            for (int c = 0; c < channels; ++c)
                img.samples.push_back(v);
        }
    }
    return img;
}

TEST(ToolProfile, HeightfieldOfARampIsLinear) {
    const Rect extent{{-0.05, -0.02}, {0.05, 0.02}};
    const double relief = 0.01;
    for (const auto& [channels, depth] : {std::pair{1, 8}, std::pair{3, 8}, std::pair{1, 16}}) {
        SCOPED_TRACE(std::to_string(channels) + " channels, " + std::to_string(depth) + " bits");
        const ToolProfile p = ToolProfile::heightfield(ramp_image(channels, depth), extent, relief);
        auto expected = [&](Vec2 q) {
            const double fx = std::clamp((q.x - extent.min.x) / extent.width(), 0.0, 1.0) * 10.0;
            const double fy = std::clamp((q.y - extent.min.y) / extent.height(), 0.0, 1.0) * 4.0;
            return relief / 255.0 * (10.0 * fx + 30.0 * fy);
        };
        for (Vec2 q : test::random_points_in(extent, 500, 5))
            EXPECT_NEAR(p.offset(q), expected(q), 1e-15);
        // Corners: black at (min.x, min.y) (the bottom row), brightest at (max.x, max.y).
        EXPECT_NEAR(p.offset(extent.min), 0.0, 1e-15);
        EXPECT_NEAR(p.offset(extent.max), relief * 220.0 / 255.0, 1e-15);
        EXPECT_NEAR(p.offset({extent.min.x, extent.max.y}), relief * 120.0 / 255.0, 1e-15);
        // Outside the extent the edge values continue.
        EXPECT_NEAR(p.offset({1.0, 1.0}), relief * 220.0 / 255.0, 1e-15);
    }
    PngImage tiny = ramp_image(1, 8);
    tiny.width = 1;
    tiny.samples.resize(5);
    EXPECT_THROW(ToolProfile::heightfield(tiny, extent, relief), std::invalid_argument);
    EXPECT_THROW(ToolProfile::heightfield(ramp_image(1, 8), Rect{}, relief), std::invalid_argument);
    EXPECT_THROW(ToolProfile::heightfield(ramp_image(1, 8), extent, -1.0), std::invalid_argument);
}

// A stroke keeps its spacing under half the length of the tool's shortest tip along the motion
// (Tool::max_stroke_spacing), so a rake's tines leave furrows, not studs. Oracles: a bitmap
// with two tips of known lengths (runs of black pixels along x); the rake's generator (its
// tines' black core is 14 pixels along a tine's middle row: peg < 0.35 at d = 0.026, so
// |2x - 23| < 13.2); and no limit for flat and round tools, whose one tip is the whole tool.
TEST(ToolProfile, TipLengthIsTheShortestTipAlongTheForwardAxis) {
    PngImage img;
    img.width = 20;
    img.height = 6;
    img.channels = 1;
    img.bit_depth = 8;
    img.samples.assign(120, 255);
    auto black = [&](std::uint32_t x, std::uint32_t row) { img.samples[row * 20 + x] = 0; };
    for (std::uint32_t x = 2; x <= 4; ++x)  // a tip 3 pixels long
        black(x, 1);
    for (std::uint32_t x = 8; x <= 14; ++x)  // a tip 7 pixels long, with a shorter row on it
        black(x, 4);
    black(9, 3);
    black(10, 3);
    img.samples[2 * 20 + 17] = 20;  // within a tenth of the relief: a tip 1 pixel long...
    img.samples[2 * 20 + 18] = 40;  // ...whose neighbour is not
    const Rect extent{{0.0, 0.0}, {0.019, 0.005}};  // 1 mm between samples along x
    ToolProfile p = ToolProfile::heightfield(img, extent, 0.01);
    EXPECT_NEAR(p.tip_length(), 0.001, 1e-15);
    img.samples[2 * 20 + 17] = 255;
    p = ToolProfile::heightfield(img, extent, 0.01);
    EXPECT_NEAR(p.tip_length(), 0.003, 1e-15);

    const Tool rake = Tool::build(load_tool_asset("rake"));
    EXPECT_NEAR(rake.max_stroke_spacing(), 0.5 * 14.0 * 0.03 / 23.0, 1e-12);
    EXPECT_LT(rake.max_stroke_spacing(), 0.25 * rake.radius());  // the editor's spacing
    for (const char* name : {"circle", "ball", "box", "lambda"}) {
        EXPECT_EQ(Tool::build(load_tool_asset(name)).max_stroke_spacing(),
                  std::numeric_limits<double>::infinity())
            << name;
    }
}

/// Stamps an asset tool on rolling sand and checks the imprint against the tool's own
/// underside: nothing inside I above the pre-stamp sand or (beyond the simplifier's
/// tolerance, which may shift heights to conserve volume) above the tool.
void stamp_asset(const std::string& name) {
    SCOPED_TRACE(name);
    const Tool tool = Tool::build(load_tool_asset(name));
    EXPECT_TRUE(test::is_simple(tool.shape().outer));
    for (Vec2 p : tool.shape().inner)
        EXPECT_TRUE(inside_polygon(p, tool.shape().outer));
    Tin tin = Tin::random_points(Rect::from_size(1.0, 1.0), 20000, 71, test::rolling_sand);
    SculptContext context(tin.domain());
    const Tin before = Tin::from_snapshot(tin.snapshot());
    ToolPlacement at{{0.5, 0.5}, 0.6, 0.0};
    at.bottom = *tin.height_at(at.centre) - 0.01;
    const StampReport r = stamp(tin, tool, at, context, Vec2{1.0, 0.0});
    ASSERT_TRUE(r.applied);
    EXPECT_TRUE(mesh_is_sound(tin));
    EXPECT_GT(r.displaced_volume, 0.0);
    const std::vector<Vec2> inner = test::rotate_all(tool.shape().inner, at.centre, at.angle);
    const double tol = context.settings.simplify.tolerance;
    std::size_t below = 0, checked = 0;
    LocateHint hint;
    for (VertexId v : live_ids(tin)) {
        const Vec2 p = tin.position(v);
        if (!test::inside_by(p, inner, 1e-9)) continue;
        ++checked;
        const double h = tin.height(v);
        const double sand = *before.height_at(p, &hint);
        EXPECT_LE(h, sand + tol) << p.x << ", " << p.y;
        const double u = tool.underside(at, p);
        if (std::isfinite(u)) {
            EXPECT_LE(h, u + tol) << p.x << ", " << p.y;
        }
        below += h < sand - 1e-3 ? 1 : 0;
    }
    EXPECT_GT(checked, 10u);
    EXPECT_GT(below, 10u) << "the tool should have pressed into the sand";
}

// After one stamp of a smooth curved tool, the surface inside I (away from I's outline, where
// the profile drops to the rim) follows the imprint, min(sand, underside), within twice the
// simplification tolerance d_m: lattice points go in where the surface strays by more than
// d_m / 2, and the simplifier may take up to d_m. Sampled between the vertices too, which is
// what an artist sees. (The rake is left out: its tines are steps, which a lattice of any
// spacing only brackets.)
// Also with the tool partly outside the domain, where the samples come from the clipped
// contour instead of the tool's own lattice, up to the border: the terrain has vertices along
// the border as inside (test::smooth_terrain), so the sand before the stamp is as smooth there
// as anywhere. (Tin::random_points has only the corners on the border: its surface falls
// steeply from the border's long edges to the interior's, and any vertex the stamp adds there
// re-shapes that slope; CurvedStampAtTheBorderFollowsTheImprintUpToTheBorder covers such a
// terrain, on planar sand.)
TEST(ToolProfile, CurvedStampFollowsTheImprintWithinTwiceTheSimplifyTolerance) {
    for (const auto& [name, centre] :
         {std::pair{"foot", Vec2{0.5, 0.5}}, std::pair{"ball", Vec2{0.5, 0.5}},
          std::pair{"foot", Vec2{0.5, 0.97}}, std::pair{"ball", Vec2{0.02, 0.45}}}) {
        SCOPED_TRACE(std::string(name) + " at " + std::to_string(centre.x) + ", " +
                     std::to_string(centre.y));
        const Tool tool = Tool::build(load_tool_asset(name));
        Tin tin =
            test::smooth_terrain(Rect::from_size(1.0, 1.0), 20000, 71, test::rolling_sand, 0.007);
        SculptContext context(tin.domain());
        const Tin before = Tin::from_snapshot(tin.snapshot());
        ToolPlacement at{centre, 0.6, 0.0};
        at.bottom = *tin.height_at(at.centre) - 0.01;
        ASSERT_TRUE(stamp(tin, tool, at, context, Vec2{1.0, 0.0}).applied);
        const std::vector<Vec2> inner = test::rotate_all(tool.shape().inner, at.centre, at.angle);
        const double d_m = context.settings.simplify.tolerance;
        LocateHint hint_before, hint_after;
        std::size_t checked = 0;
        double worst = 0.0;
        const Rect around{{std::max(0.0, centre.x - 0.2), std::max(0.0, centre.y - 0.2)},
                          {std::min(1.0, centre.x + 0.2), std::min(1.0, centre.y + 0.2)}};
        for (Vec2 p : test::random_points_in(around, 60000, 5)) {
            if (!test::inside_by(p, inner, 0.004)) continue;
            const double under = tool.underside(at, p);
            if (!std::isfinite(under)) continue;
            const double want = std::min(*before.height_at(p, &hint_before), under);
            worst = std::max(worst, std::abs(*tin.height_at(p, &hint_after) - want));
            ++checked;
        }
        EXPECT_GT(checked, 500u);
        EXPECT_LE(worst, 2.0 * d_m);
        EXPECT_TRUE(mesh_is_sound(tin));
    }
}

// At the domain's border a clipped I runs straight along it, with the profile in the middle of
// the tool there, not dropping to the rim as along the tool's outline. On tilted planar sand
// (every triangulation of it is the same plane, so the sand before the stamp is known exactly
// up to the border, even with no vertices along it: Tin::random_points has only the corners
// there) the surface inside I follows the imprint within 2 d_m everywhere, on the border line
// and in the strip beside it too. (Before the border was sampled, it only interpolated I's two
// corners there: 5 to 14 mm off on the border line.) The imprint alone, without the ball's
// extrusion ridge: where O is not constrained (a ball's outline stands above the sand, so
// nothing there is enforced), triangles cross O and the ridge's slope reaches a few mm inside
// it; in a corner, where the whole volume goes into the short stretch of band left, that added
// 0.4 mm at 4.4 mm inside I.
TEST(ToolProfile, CurvedStampAtTheBorderFollowsTheImprintUpToTheBorder) {
    auto plane = [](Vec2 p) { return 0.1 + 0.05 * p.x + 0.03 * p.y; };
    for (const auto& [name, centre] :
         {std::pair{"foot", Vec2{0.5, 0.97}}, std::pair{"ball", Vec2{0.02, 0.45}},
          std::pair{"foot", Vec2{0.03, 0.5}}, std::pair{"ball", Vec2{0.5, 0.985}},
          std::pair{"ball", Vec2{0.985, 0.015}}}) {
        SCOPED_TRACE(std::string(name) + " at " + std::to_string(centre.x) + ", " +
                     std::to_string(centre.y));
        ToolSpec spec = load_tool_asset(name);
        spec.extrude = false;
        const Tool tool = Tool::build(spec);
        Tin tin = Tin::random_points(Rect::from_size(1.0, 1.0), 20000, 71, plane);
        SculptContext context(tin.domain());
        ToolPlacement at{centre, 0.6, 0.0};
        at.bottom = plane(centre) - 0.01;
        ASSERT_TRUE(stamp(tin, tool, at, context, Vec2{1.0, 0.0}).applied);
        EXPECT_TRUE(mesh_is_sound(tin));
        const std::vector<Vec2> inner = test::rotate_all(tool.shape().inner, at.centre, at.angle);
        const double d_m = context.settings.simplify.tolerance;
        LocateHint hint;
        // The imprint where the tool reaches the sand, the untouched plane elsewhere.
        auto error_at = [&](Vec2 p) {
            const double under = tool.underside(at, p);
            if (!test::inside_by(p, inner, 0.004) || !std::isfinite(under)) return -1.0;
            return std::abs(*tin.height_at(p, &hint) - std::min(plane(p), under));
        };
        const Rect around{{std::max(0.0, centre.x - 0.1), std::max(0.0, centre.y - 0.1)},
                          {std::min(1.0, centre.x + 0.1), std::min(1.0, centre.y + 0.1)}};
        double worst = 0.0, worst_strip = 0.0, worst_on_border = 0.0;
        std::size_t checked = 0, in_strip = 0, on_border = 0;
        for (Vec2 p : test::random_points_in(around, 60000, 5)) {
            const double e = error_at(p);
            if (e < 0.0) continue;
            const bool strip = std::min({p.x, p.y, 1.0 - p.x, 1.0 - p.y}) < 0.002;
            (strip ? worst_strip : worst) = std::max(strip ? worst_strip : worst, e);
            ++(strip ? in_strip : checked);
        }
        // The border line, every 0.05 mm along the sides within reach of the tool.
        for (int k = 0; k <= 4000; ++k) {
            const double x = around.min.x + (around.max.x - around.min.x) * k / 4000.0;
            const double y = around.min.y + (around.max.y - around.min.y) * k / 4000.0;
            for (Vec2 p : {Vec2{0.0, y}, Vec2{1.0, y}, Vec2{x, 0.0}, Vec2{x, 1.0}}) {
                const double e = error_at(p);
                if (e < 0.0) continue;
                worst_on_border = std::max(worst_on_border, e);
                ++on_border;
            }
        }
        EXPECT_GT(checked, 500u);
        EXPECT_GT(in_strip, 50u);
        EXPECT_GT(on_border, 200u);
        EXPECT_LE(worst, 2.0 * d_m);
        EXPECT_LE(worst_strip, 2.0 * d_m);
        EXPECT_LE(worst_on_border, 2.0 * d_m);
    }
}

TEST(ToolProfile, ShippedFootAndRakeBuildAndStamp) {
    stamp_asset("foot");
    stamp_asset("rake");
    stamp_asset("ball");
}

// Oracle: similarity. A tool scaled by k must be the same tool k times larger: contours,
// radius, rim spacing and tolerance, ridge width, and the underside's depth at corresponding
// points all k times the original's, for every shipped asset (each contour and profile kind).
TEST(ToolSpecScale, AScaledToolIsSimilarToTheOriginal) {
    constexpr double k = 37.5;
    for (const char* name : {"circle", "ball", "box", "rake", "lambda", "foot"}) {
        SCOPED_TRACE(name);
        const ToolSpec spec = load_tool_asset(name);
        const Tool a = Tool::build(spec);
        const Tool b = Tool::build(scaled_tool_spec(spec, k));
        const double eps = 1e-12 * k * a.radius();
        ASSERT_EQ(a.shape().inner.size(), b.shape().inner.size());
        ASSERT_EQ(a.shape().outer.size(), b.shape().outer.size());
        for (std::size_t i = 0; i < a.shape().inner.size(); ++i)
            EXPECT_LE(distance(a.shape().inner[i] * k, b.shape().inner[i]), eps);
        for (std::size_t i = 0; i < a.shape().outer.size(); ++i)
            EXPECT_LE(distance(a.shape().outer[i] * k, b.shape().outer[i]), eps);
        EXPECT_NEAR(b.radius(), k * a.radius(), eps);
        EXPECT_NEAR(b.shape().gap, k * a.shape().gap, eps);
        EXPECT_NEAR(b.rim_spacing(), k * a.rim_spacing(), eps);
        EXPECT_NEAR(b.rim_tolerance(), k * a.rim_tolerance(), eps);
        EXPECT_NEAR(b.extrusion_width(), k * a.extrusion_width(), eps);
        // The underside on a 41 x 41 grid over the tool, placed turned and raised.
        const ToolPlacement at_a{{0.3, -0.2}, 0.7, 0.05};
        const ToolPlacement at_b{at_a.centre * k, at_a.angle, at_a.bottom * k};
        std::size_t contact = 0;
        for (int i = 0; i <= 40; ++i) {
            for (int j = 0; j <= 40; ++j) {
                const Vec2 local{a.radius() * (i / 20.0 - 1.0), a.radius() * (j / 20.0 - 1.0)};
                const double ua = a.underside(at_a, a.to_world(at_a, local));
                const double ub = b.underside(at_b, b.to_world(at_b, local * k));
                if (!std::isfinite(ua)) {
                    EXPECT_FALSE(std::isfinite(ub)) << local.x << ", " << local.y;
                    continue;
                }
                ++contact;
                EXPECT_NEAR(ub, k * ua, 1e-9 * k) << local.x << ", " << local.y;
            }
        }
        EXPECT_GT(contact, 100u);
    }
    EXPECT_THROW(scaled_tool_spec(ToolSpec{}, 0.0), std::invalid_argument);
    EXPECT_THROW(scaled_tool_spec(ToolSpec{}, -2.0), std::invalid_argument);
    EXPECT_THROW(scaled_tool_spec(ToolSpec{}, std::numeric_limits<double>::quiet_NaN()),
                 std::invalid_argument);
}

}  // namespace
}  // namespace sandtin
