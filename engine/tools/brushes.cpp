#include "tools/brushes.hpp"

#include <cmath>
#include <stdexcept>

#include "tools/refine.hpp"

namespace sandtin {

BrushReport apply_brush(Tin& tin, Vec2 centre, const BrushSettings& s, SculptContext& context) {
    if (!is_finite(centre)) throw std::invalid_argument("brush: centre is not finite");
    if (!(s.radius > 0.0) || !std::isfinite(s.radius))
        throw std::invalid_argument("brush: radius must be positive");
    if (!std::isfinite(s.strength) || s.strength < 0.0)
        throw std::invalid_argument("brush: strength must be zero or positive");
    if ((s.kind == BrushKind::Smooth || s.kind == BrushKind::Flatten) && s.strength > 1.0) {
        throw std::invalid_argument("brush: smooth and flatten strength must lie in [0, 1]");
    }
    BrushReport report;
    const Rect d = tin.domain();
    if (!d.inflated(s.radius).contains(centre)) return report;
    const double ledger0 = tin.volume_ledger();
    const std::size_t before = tin.vertex_count();
    if (s.kind != BrushKind::PaintMaterial) {
        const double spacing = s.refine_spacing > 0.0 ? s.refine_spacing : s.radius / 6.0;
        refine_long_edges(tin, centre, s.radius, spacing, &context.hint, 8192);
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
            std::vector<VertexId> ring;
            for (std::size_t i = 0; i < disc.size(); ++i) {
                const VertexId v = disc[i];
                tin.neighbours(v, ring);
                double mean = 0.0;
                for (VertexId w : ring)
                    mean += va.height[w.value];
                mean = ring.empty() ? va.height[v.value] : mean / static_cast<double>(ring.size());
                const double h = va.height[v.value];
                target[i] = h + s.strength * weight[i] * (mean - h);
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
        case BrushKind::PaintMaterial:
            for (std::size_t i = 0; i < disc.size(); ++i) {
                if (weight[i] > 0.0 && va.material[disc[i].value] != s.material) {
                    tin.set_material(disc[i], s.material);
                    ++report.vertices_changed;
                }
            }
            return report;
    }
    for (std::size_t i = 0; i < disc.size(); ++i) {
        if (target[i] != va.height[disc[i].value]) {
            tin.set_height(disc[i], target[i]);
            ++report.vertices_changed;
        }
    }
    context.simplifier.enqueue(disc);
    if (context.settings.simplify_after_edit)
        context.simplifier.run(tin, context.settings.simplify);
    report.volume_change = tin.volume_ledger() - ledger0;
    return report;
}

}  // namespace sandtin
