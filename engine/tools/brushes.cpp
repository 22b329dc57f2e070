#include "tools/brushes.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "physics/curvature_weathering.hpp"
#include "tools/refine.hpp"

namespace sandtin {

namespace {

/// Height at v of the least-squares plane through its neighbours (the mean when the fit is
/// degenerate, e.g. collinear neighbours on the border).
double neighbour_plane_height(const VertexArrays& va, VertexId v,
                              const std::vector<VertexId>& ring) {
    const Vec2 o = va.position[v.value];
    double sxx = 0, sxy = 0, syy = 0, sx = 0, sy = 0, n = 0, sxz = 0, syz = 0, sz = 0;
    for (VertexId w : ring) {
        const Vec2 p = va.position[w.value] - o;
        const double z = va.height[w.value];
        sxx += p.x * p.x;
        sxy += p.x * p.y;
        syy += p.y * p.y;
        sx += p.x;
        sy += p.y;
        n += 1.0;
        sxz += p.x * z;
        syz += p.y * z;
        sz += z;
    }
    if (n == 0.0) return va.height[v.value];
    const double det =
        sxx * (syy * n - sy * sy) - sxy * (sxy * n - sy * sx) + sx * (sxy * sy - syy * sx);
    const double scale = (sxx + syy + n) * (sxx + syy + n) * (sxx + syy + n);
    if (!(std::abs(det) > 1e-12 * scale)) return sz / n;
    // The plane's value at the vertex itself (local origin) is its constant term c.
    return (sxx * (syy * sz - syz * sy) - sxy * (sxy * sz - syz * sx) +
            sxz * (sxy * sy - syy * sx)) /
           det;
}

}  // namespace

BrushReport apply_brush(Tin& tin, Vec2 centre, const BrushSettings& s, SculptContext& context) {
    if (!is_finite(centre)) throw std::invalid_argument("brush: centre is not finite");
    if (!(s.radius > 0.0) || !std::isfinite(s.radius))
        throw std::invalid_argument("brush: radius must be positive");
    if (!std::isfinite(s.strength) || s.strength < 0.0)
        throw std::invalid_argument("brush: strength must be zero or positive");
    if ((s.kind == BrushKind::Smooth || s.kind == BrushKind::Flatten ||
         s.kind == BrushKind::Weather) &&
        s.strength > 1.0) {
        throw std::invalid_argument(
            "brush: smooth, flatten and weather strength must lie in [0, 1]");
    }
    BrushReport report;
    const Rect d = tin.domain();
    if (!d.inflated(s.radius).contains(centre)) return report;
    const double ledger0 = tin.volume_ledger();
    const std::size_t before = tin.vertex_count();
    const double spacing = s.refine_spacing > 0.0 ? s.refine_spacing : s.radius / 6.0;
    if (s.kind != BrushKind::PaintMaterial) {
        // Refinement must not re-shape the surface outside the dab: its insertions are fenced
        // (on a 2 m elevation grid, a 2 m dab moved the surface 0.28 m up to 5.5 m away).
        const SurfaceFence fence =
            dab_fence(s.radius, context.settings.simplify.tolerance, context.peek_generation());
        report.edges_fenced =
            refine_long_edges(tin, centre, s.radius, spacing, &context.hint, 8192, nullptr,
                              context.settings.fence_coarse_edges &&
                                      coarse_for_dab(tin, centre, s.radius, &context.hint)
                                  ? &fence
                                  : nullptr)
                .fenced;
    }
    report.vertices_inserted = tin.vertex_count() - before;

    const std::vector<VertexId> disc = tin.vertices_in_disc(centre, s.radius, &context.hint);
    const VertexArrays& va = tin.vertices();
    std::vector<double> weight(disc.size());
    for (std::size_t i = 0; i < disc.size(); ++i) {
        weight[i] =
            falloff_weight(s.falloff, distance(va.position[disc[i].value], centre) / s.radius);
    }
    // Targets are computed from the heights before the dab (Jacobi), so the result does not
    // depend on the order the vertices were found in.
    std::vector<double> target(disc.size());
    switch (s.kind) {
        case BrushKind::Raise:
        case BrushKind::Lower: {
            const double sign = s.kind == BrushKind::Raise ? 1.0 : -1.0;
            for (std::size_t i = 0; i < disc.size(); ++i) {
                target[i] = va.height[disc[i].value] + sign * s.strength * weight[i];
            }
            break;
        }
        case BrushKind::Smooth: {
            // Towards the least-squares plane of the neighbours, evaluated at the vertex: a
            // plane is left exactly as it is (a plain neighbour average is not, on an irregular
            // triangulation), and bumps and pits are pulled in.
            std::vector<VertexId> ring;
            for (std::size_t i = 0; i < disc.size(); ++i) {
                const VertexId v = disc[i];
                tin.neighbours(v, ring);
                const double h = va.height[v.value];
                target[i] = h + s.strength * weight[i] * (neighbour_plane_height(va, v, ring) - h);
            }
            break;
        }
        case BrushKind::Flatten: {
            const double level = s.flatten_to
                                     ? *s.flatten_to
                                     : tin.height_at({std::clamp(centre.x, d.min.x, d.max.x),
                                                      std::clamp(centre.y, d.min.y, d.max.y)},
                                                     &context.hint)
                                           .value_or(0.0);
            if (!std::isfinite(level))
                throw std::invalid_argument("brush: flatten height is not finite");
            for (std::size_t i = 0; i < disc.size(); ++i) {
                const double h = va.height[disc[i].value];
                target[i] = h + s.strength * weight[i] * (level - h);
            }
            break;
        }
        case BrushKind::Weather: {
            // Crests in the disc wear and their sand settles downhill, the volume kept; the
            // falloff weighs each vertex's wear. Its own writes, not targets: sand also lands
            // on neighbours just outside the disc.
            WeatheringSettings w;
            w.strength = s.strength;
            // The smooth falloff can round a hair below 0 near the rim; weathering takes
            // weights in [0, 1] only.
            for (double& x : weight)
                x = std::clamp(x, 0.0, 1.0);
            const WeatheringReport r = weather_vertices(tin, disc, weight, w);
            report.vertices_changed = r.vertices_worn + r.vertices_raised;
            for (std::size_t i = 0; i < disc.size(); ++i)
                target[i] = va.height[disc[i].value];
            break;
        }
        case BrushKind::PaintMaterial:
            if (!(s.moisture >= 0.0f && s.moisture <= 1.0f))
                throw std::invalid_argument("brush: paint moisture must lie in [0, 1]");
            for (std::size_t i = 0; i < disc.size(); ++i) {
                const std::uint32_t v = disc[i].value;
                if (!(weight[i] > 0.0) ||
                    (va.material[v] == s.material && va.moisture[v] == s.moisture)) {
                    continue;
                }
                tin.set_material(disc[i], s.material);
                tin.set_moisture(disc[i], s.moisture);
                ++report.vertices_changed;
            }
            return report;
    }
    for (std::size_t i = 0; i < disc.size(); ++i) {
        if (target[i] != va.height[disc[i].value]) {
            tin.set_height(disc[i], target[i]);
            ++report.vertices_changed;
        }
    }
    context.simplifier.enqueue(
        simplifiable_after_dab(tin, disc, centre, s.radius, spacing, report.edges_fenced > 0));
    if (context.settings.simplify_after_edit)
        context.simplifier.run(tin, context.settings.simplify);
    report.volume_change = tin.volume_ledger() - ledger0;
    return report;
}

}  // namespace sandtin
