#include "tools/sand.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "tools/refine.hpp"
#include "tools/tool_shape.hpp"

namespace sandtin {

namespace {

struct Kernel {
    std::vector<VertexId> vertices;
    std::vector<double> weight;
    std::vector<VertexId> simplifiable;  ///< simplifiable_after_dab
};

/// Refines the disc and returns the vertices in it with their falloff weights.
Kernel prepare(Tin& tin, Vec2 centre, const PourSettings& s, SculptContext& context,
               PourReport& report) {
    if (!is_finite(centre)) throw std::invalid_argument("pour: centre is not finite");
    if (!(s.radius > 0.0) || !std::isfinite(s.radius))
        throw std::invalid_argument("pour: radius must be positive");
    const Rect d = tin.domain();
    if (!d.inflated(s.radius).contains(centre)) return {};
    const double spacing = s.refine_spacing > 0.0 ? s.refine_spacing : s.radius / 4.0;
    const std::size_t before = tin.vertex_count();
    // The inserted points must not re-shape the surface outside the disc: they are fenced, as
    // a brush's are (tools/refine.hpp).
    const SurfaceFence fence =
        dab_fence(s.radius, context.settings.simplify.tolerance, context.peek_generation());
    const SurfaceFence* guard =
        context.settings.fence_coarse_edges && coarse_for_dab(tin, centre, s.radius, &context.hint)
            ? &fence
            : nullptr;
    if (d.contains(centre)) {
        report.edges_fenced +=
            insert_points_fenced(tin, std::span<const Vec2>(&centre, 1), guard, &context.hint);
    }
    // A ring at half the radius gives the pour a round shape on a coarse terrain.
    std::vector<Vec2> ring;
    for (Vec2 p : circle_contour(0.5 * s.radius, 8)) {
        if (d.contains(centre + p)) ring.push_back(centre + p);
    }
    report.edges_fenced += insert_points_fenced(tin, ring, guard, &context.hint);
    report.edges_fenced +=
        refine_long_edges(tin, centre, s.radius, spacing, &context.hint, 4096, nullptr, guard)
            .fenced;
    report.vertices_inserted = tin.vertex_count() - before;

    Kernel k;
    const VertexArrays& va = tin.vertices();
    for (VertexId v : tin.vertices_in_disc(centre, s.radius, &context.hint)) {
        const double w =
            falloff_weight(s.falloff, distance(va.position[v.value], centre) / s.radius);
        if (w > 0.0) {
            k.vertices.push_back(v);
            k.weight.push_back(w);
        }
    }
    k.simplifiable =
        simplifiable_after_dab(tin, k.vertices, centre, s.radius, spacing, report.edges_fenced > 0);
    return k;
}

}  // namespace

PourReport pour_sand(Tin& tin, Vec2 centre, double volume, const PourSettings& settings,
                     SculptContext& context) {
    if (!(volume >= 0.0) || !std::isfinite(volume))
        throw std::invalid_argument("pour: volume must be zero or positive");
    PourReport report;
    if (volume == 0.0) return report;
    // From before the refinement: where the sand around it lies on the bedrock, its volume
    // compensation cannot take all of what re-triangulating moved (Tin::split_edges).
    const double ledger0 = tin.volume_ledger();
    const Kernel k = prepare(tin, centre, settings, context, report);
    const VertexArrays& va = tin.vertices();
    double denominator = 0.0;
    for (std::size_t i = 0; i < k.vertices.size(); ++i)
        denominator += va.lumped_area[k.vertices[i].value] * k.weight[i];
    if (!(denominator > 0.0)) {
        report.volume = tin.volume_ledger() - ledger0;
        return report;
    }
    const double scale = volume / denominator;
    for (std::size_t i = 0; i < k.vertices.size(); ++i) {
        const VertexId v = k.vertices[i];
        tin.set_height(v, va.height[v.value] + scale * k.weight[i]);
    }
    report.volume = tin.volume_ledger() - ledger0;
    report.vertices_changed = k.vertices.size();
    context.simplifier.enqueue(k.simplifiable);
    return report;
}

PourReport remove_sand(Tin& tin, Vec2 centre, double volume, const PourSettings& settings,
                       SculptContext& context) {
    if (!(volume >= 0.0) || !std::isfinite(volume))
        throw std::invalid_argument("remove: volume must be zero or positive");
    PourReport report;
    if (volume == 0.0) return report;
    const double ledger0 = tin.volume_ledger();  // as pour_sand's
    const Kernel k = prepare(tin, centre, settings, context, report);
    const VertexArrays& va = tin.vertices();
    // Take the volume in rounds: vertices that run out of sand drop out and the rest share
    // what is still owed.
    std::vector<std::uint8_t> exhausted(k.vertices.size(), 0);
    double owed = volume;
    for (int round = 0; round < 16 && owed > volume * 1e-14; ++round) {
        double denominator = 0.0;
        for (std::size_t i = 0; i < k.vertices.size(); ++i) {
            if (!exhausted[i]) denominator += va.lumped_area[k.vertices[i].value] * k.weight[i];
        }
        if (!(denominator > 0.0)) break;
        const double scale = owed / denominator;
        for (std::size_t i = 0; i < k.vertices.size(); ++i) {
            if (exhausted[i]) continue;
            const VertexId v = k.vertices[i];
            const double h = va.height[v.value];
            const double floor = va.bedrock[v.value];
            double target = h - scale * k.weight[i];
            if (target <= floor) {
                target = floor;
                exhausted[i] = 1;
            }
            owed -= va.lumped_area[v.value] * (h - target);
            tin.set_height(v, target);
        }
    }
    report.volume = tin.volume_ledger() - ledger0;
    report.vertices_changed = k.vertices.size();
    context.simplifier.enqueue(k.simplifiable);
    return report;
}

std::optional<std::string> short_pour_warning(bool remove, double asked, double moved) {
    if (!(std::abs(moved) < 0.99 * asked)) return std::nullopt;
    char text[320];
    std::snprintf(text, sizeof text,
                  remove ? "removed %.3g m³ of the %.3g m³ asked: there is no more sand above the "
                           "bedrock there, or the point lies outside the terrain"
                         : "poured %.3g m³ of the %.3g m³ asked: the rest fell outside the terrain",
                  std::abs(moved), asked);
    return std::string(text);
}

}  // namespace sandtin
