#include "gpu/mirror_seed.hpp"

namespace sandtin::gpu {

void build_mirror_seed(const Tin& tin, MirrorSeed& seed) {
    seed.origin = tin.domain().min;
    const VertexArrays& va = tin.vertices();
    double sum = 0.0;
    std::size_t live = 0;
    for (std::size_t v = 0; v < va.size(); ++v) {
        if (!va.alive[v]) continue;
        sum += va.height[v];
        ++live;
    }
    seed.height_origin = live > 0 ? sum / static_cast<double>(live) : 0.0;
    seed.graph.rebuild(tin);
    const AdjacencyGraph& g = seed.graph;
    seed.edge_flags.assign(g.slot_count(), 0u);
    for (std::uint32_t v = 0; v < g.vertex_capacity(); ++v) {
        // One walk around v says whether any of its edges is constrained; most vertices of a
        // terrain have none (only tool rims and walls are), and their flags stay 0.
        if (g.degree(v) == 0 || !tin.is_on_constraint(VertexId{v})) continue;
        const std::uint32_t b = g.offset(v);
        for (std::uint32_t k = 0; k < g.degree(v); ++k) {
            const VertexId w{g.targets()[b + k]};
            seed.edge_flags[b + k] = tin.is_constrained_edge(VertexId{v}, w) ? 1u : 0u;
        }
    }
}

MirrorSeed prepare_mirror_seed(Tin& tin) {
    MirrorSeed seed;
    seed.changes = std::make_unique<ChangeReader>(tin);
    seed.changes->take();  // "everything": the seed below is everything
    build_mirror_seed(tin, seed);
    return seed;
}

}  // namespace sandtin::gpu
