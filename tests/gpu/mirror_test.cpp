// The GPU mirror of the TIN: contents equal the TIN after edits and growth; uploads are the
// dirty ranges only (counted).

#include <array>
#include <cmath>
#include <random>
#include <thread>

#include "gpu/mirror_seed.hpp"
#include "gpu/tin_mirror.hpp"
#include "gpu_fixture.hpp"
#include "gpu_scenes.hpp"
#include "tools/stamp.hpp"
#include "tools/tool.hpp"

namespace sandtin::gpu {
namespace {

using testing::GpuTest;
using testing::kUnitSquare;
using testing::read_as;

// Reads every mirrored buffer back and compares it with the TIN and the mirror's graph.
void expect_mirror_equals_tin(const VulkanContext& ctx, const TinMirror& m, const Tin& tin) {
    const VertexArrays& va = tin.vertices();
    const uint32_t n = static_cast<uint32_t>(va.size());
    ASSERT_GE(m.vertex_capacity(), n);
    const auto pos = read_as<float>(ctx, m.vertex_buffer(VertexBuffer::Position), 2 * size_t{n});
    const auto h = read_as<float>(ctx, m.vertex_buffer(VertexBuffer::Height), n);
    const auto area = read_as<float>(ctx, m.vertex_buffer(VertexBuffer::Area), n);
    const auto off = read_as<uint32_t>(ctx, m.vertex_buffer(VertexBuffer::RowOffset), n);
    const auto deg = read_as<uint32_t>(ctx, m.vertex_buffer(VertexBuffer::RowDegree), n);
    const AdjacencyGraph& g = m.graph();
    const auto target = read_as<uint32_t>(ctx, m.edge_buffer(EdgeBuffer::Target), g.slot_count());
    const auto reverse = read_as<uint32_t>(ctx, m.edge_buffer(EdgeBuffer::Reverse), g.slot_count());
    const auto eflags =
        read_as<uint32_t>(ctx, m.edge_buffer(EdgeBuffer::EdgeFlags), g.slot_count());
    const auto across = read_as<float>(ctx, m.edge_buffer(EdgeBuffer::Across), g.slot_count());
    EXPECT_TRUE(g.matches(tin));
    std::vector<VertexId> ring;
    int bad = 0;
    for (uint32_t v = 0; v < n && bad < 5; ++v) {
        if (!va.alive[v]) continue;
        const Vec2 o = m.origin();
        if (pos[2 * v] != static_cast<float>(va.position[v].x - o.x) ||
            pos[2 * v + 1] != static_cast<float>(va.position[v].y - o.y) ||
            h[v] != static_cast<float>(va.height[v] - m.height_origin()) ||
            area[v] != static_cast<float>(va.lumped_area[v])) {
            ADD_FAILURE() << "vertex " << v << " attributes differ";
            ++bad;
            continue;
        }
        tin.neighbours(VertexId{v}, ring);
        if (deg[v] != ring.size() || off[v] != g.offset(v)) {
            ADD_FAILURE() << "row " << v << " differs";
            ++bad;
            continue;
        }
        for (uint32_t k = 0; k < deg[v]; ++k) {
            const uint32_t slot = off[v] + k;
            const uint32_t w = target[slot];
            const bool constrained = tin.is_constrained_edge(VertexId{v}, VertexId{w});
            // The face rule's across: the graph's, and where there is a face, the distance
            // between this slot's target and the next one's (from the TIN's positions).
            const uint32_t next = target[off[v] + (k + 1 == deg[v] ? 0 : k + 1)];
            const double far_edge = distance(va.position[w], va.position[next]);
            const bool across_ok =
                across[slot] == static_cast<float>(g.across()[slot]) &&
                (across[slot] == 0.0f ||
                 std::abs(static_cast<double>(across[slot]) - far_edge) <= 1e-6 * far_edge);
            if (w != g.targets()[slot] || target[reverse[slot]] != v ||
                (eflags[slot] & 1u) != (constrained ? 1u : 0u) || !across_ok) {
                ADD_FAILURE() << "edge slot " << slot << " of row " << v << " differs";
                ++bad;
                break;
            }
        }
    }
    const uint32_t slots = tin.slot_capacity();
    const auto tri =
        read_as<uint32_t>(ctx, m.slot_buffer(SlotBuffer::Triangles), 3 * size_t{slots});
    const auto sflags = read_as<uint32_t>(ctx, m.slot_buffer(SlotBuffer::SlotFlags), slots);
    for (uint32_t s = 0; s < slots && bad < 10; ++s) {
        const auto t = tin.slot_triangle(s);
        const bool live = t[0].valid();
        const uint32_t want_flags = live ? (tin.slot_constraint_mask(s) & 7u) | 8u : 0u;
        if (sflags[s] != want_flags ||
            (live && (tri[3 * s] != t[0].value || tri[3 * s + 1] != t[1].value ||
                      tri[3 * s + 2] != t[2].value))) {
            ADD_FAILURE() << "slot " << s << " differs";
            ++bad;
        }
    }
}

TEST_F(GpuTest, MirrorEqualsTinAfterEditsConstraintsAndGrowth) {
    Tin tin = Tin::random_points(kUnitSquare, 3000, 17,
                                 [](Vec2 p) { return testing::collapsing_cone(p); });
    TinMirror mirror(ctx(), tin, MaterialTable::presets(), 64 << 10);  // small ring: wraps a lot
    const SyncStats first = mirror.sync();
    EXPECT_GT(first.bytes, 0u);
    expect_mirror_equals_tin(ctx(), mirror, tin);
    const uint64_t generation = mirror.generation();

    // Edits: heights, a constrained polyline, a removal, then enough inserts to grow.
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(0.01, 0.99);
    for (int i = 0; i < 50; ++i) {
        const VertexId v = tin.locate({u(rng), u(rng)}).corners[0];
        tin.set_height(v, tin.height(v) + 0.01);
    }
    const VertexId a = tin.insert_point({0.2, 0.2}, 0.3);
    const VertexId b = tin.insert_point({0.7, 0.35}, 0.3);
    const VertexId c = tin.insert_point({0.5, 0.8}, 0.3);
    const std::array<VertexId, 3> poly{a, b, c};
    tin.insert_constraint(poly, true, 1);
    const SyncStats edit = mirror.sync();
    EXPECT_GT(edit.bytes, 0u);
    EXPECT_LT(edit.bytes, first.bytes / 4);
    expect_mirror_equals_tin(ctx(), mirror, tin);

    std::vector<Vec2> pts;
    for (int i = 0; i < 4000; ++i)
        pts.push_back({u(rng), u(rng)});
    tin.insert_points_on_surface(pts);
    for (int i = 0; i < 40; ++i) {
        const VertexId v = tin.locate({u(rng), u(rng)}).corners[1];
        tin.remove_vertex(v);
    }
    const SyncStats grown = mirror.sync();
    EXPECT_TRUE(grown.reallocated);
    EXPECT_GT(mirror.generation(), generation);
    expect_mirror_equals_tin(ctx(), mirror, tin);
    EXPECT_EQ(mirror.total_uploaded_bytes(), first.bytes + edit.bytes + grown.bytes);
}

// Scattered edits (erosion moves sand on thousands of separate vertices a frame) upload in a
// few copy regions, not one per vertex and buffer: the validation layer, and drivers, pay for
// each region (31 450 in one editor frame before ranges were coalesced).
TEST_F(GpuTest, ScatteredEditsUploadInFewCopyRegions) {
    Tin tin = Tin::random_points(kUnitSquare, 20000, 29, [](Vec2 p) { return 0.1 * p.x; });
    TinMirror mirror(ctx(), tin);
    mirror.sync();
    const uint64_t mirrored = mirror.mirrored_bytes();
    // Every 8th live vertex: 2 500 ranges of one id each in the journal.
    std::size_t edited = 0;
    for (uint32_t i = 0; i < tin.vertex_capacity(); i += 8) {
        if (!tin.is_alive(VertexId{i})) continue;
        tin.set_height(VertexId{i}, tin.height(VertexId{i}) + 0.001);
        ++edited;
    }
    ASSERT_GT(edited, 2000u);
    const SyncStats scattered = mirror.sync();
    // One range per vertex would be one region per vertex buffer each: over 20 000.
    EXPECT_LT(scattered.copy_regions, 100u) << scattered.copy_regions;
    EXPECT_LT(scattered.bytes, mirrored) << "the gaps are short, not the whole mirror";
    expect_mirror_equals_tin(ctx(), mirror, tin);

    // Every 40th vertex: 500 ranges with gaps too wide to join for free. The mirror keeps at
    // most 256 vertex ranges a sync (nine buffers each), joining the narrowest gaps.
    for (uint32_t i = 0; i < tin.vertex_capacity(); i += 40) {
        if (tin.is_alive(VertexId{i})) tin.set_height(VertexId{i}, tin.height(VertexId{i}) - 0.001);
    }
    const SyncStats sparse = mirror.sync();
    EXPECT_LE(sparse.copy_regions, 256u * 9u) << sparse.copy_regions;
    EXPECT_LT(sparse.bytes, mirrored);
    expect_mirror_equals_tin(ctx(), mirror, tin);

    // Two edits far apart stay two ranges: the gap is bounded, nothing between is copied.
    tin.set_height(VertexId{0}, tin.height(VertexId{0}) + 0.001);
    const auto last = static_cast<uint32_t>(tin.vertex_capacity() - 1);
    ASSERT_TRUE(tin.is_alive(VertexId{last}));
    tin.set_height(VertexId{last}, tin.height(VertexId{last}) + 0.001);
    const SyncStats two = mirror.sync();
    EXPECT_LT(two.bytes, mirrored / 100) << two.bytes << " of " << mirrored;
    expect_mirror_equals_tin(ctx(), mirror, tin);
}

// A mirror created after another one took the journal's first (complete) report still
// uploads everything.
TEST_F(GpuTest, ASecondMirrorOnTheSameTinStartsComplete) {
    Tin tin = Tin::random_points(kUnitSquare, 2000, 19, [](Vec2 p) { return 0.3 * p.x * p.y; });
    TinMirror first(ctx(), tin);
    first.sync();
    TinMirror second(ctx(), tin);
    const SyncStats s = second.sync();
    EXPECT_GT(s.bytes, second.mirrored_bytes() / 2);
    expect_mirror_equals_tin(ctx(), second, tin);
}

// A material edit re-uploads tan(repose) of every vertex from the new table, and nothing
// else: the rest of the mirror stays as it was.
TEST_F(GpuTest, AMaterialEditUploadsTheNewAnglesOfReposeOnly) {
    Tin tin = Tin::random_points(kUnitSquare, 2000, 23, [](Vec2 p) { return 0.2 * p.x; });
    for (uint32_t v = 0; v < 2000; v += 7)
        if (tin.is_alive(VertexId{v})) tin.set_material(VertexId{v}, 1);
    tin.set_moisture(VertexId{3}, 0.6f);
    TinMirror mirror(ctx(), tin);
    mirror.sync();
    std::vector<Material> all = MaterialTable::presets().all();
    all[1].repose_dry += 0.05;
    all[0].repose_wet += 0.05;
    const MaterialTable table(all);
    mirror.set_materials(table);
    const SyncStats s = mirror.sync();
    const uint32_t n = static_cast<uint32_t>(tin.vertices().size());
    EXPECT_EQ(s.bytes, uint64_t{n} * 4) << "one float per vertex";
    const auto tan_alpha = read_as<float>(ctx(), mirror.vertex_buffer(VertexBuffer::TanAlpha), n);
    const VertexArrays& va = tin.vertices();
    int bad = 0;
    for (uint32_t v = 0; v < n && bad < 5; ++v) {
        const float want =
            va.alive[v] ? static_cast<float>(table.at(va.material[v]).talus_slope(va.moisture[v]))
                        : 0.0f;
        if (tan_alpha[v] != want) {
            ADD_FAILURE() << "vertex " << v << ": " << tan_alpha[v] << " against " << want;
            ++bad;
        }
    }
    expect_mirror_equals_tin(ctx(), mirror, tin);
}

// A mirror seeded on another thread (prepare_mirror_seed, as the editor's worker does when it
// opens a scene) holds what a mirror that built everything itself holds, constrained edges
// included; and a seed the TIN moved on from (edits between the seed and the first sync)
// catches up through its reader instead of uploading a stale graph.
TEST_F(GpuTest, AMirrorFromASeedBuiltOnAnotherThreadEqualsTheTin) {
    Tin tin = Tin::random_points(kUnitSquare, 4000, 23,
                                 [](Vec2 p) { return testing::collapsing_cone(p); });
    const VertexId a = tin.insert_point({0.2, 0.3}, 0.3);
    const VertexId b = tin.insert_point({0.7, 0.4}, 0.3);
    const VertexId c = tin.insert_point({0.45, 0.8}, 0.3);
    const std::array<VertexId, 3> ring{a, b, c};
    tin.insert_constraint(ring, true, 1);
    MirrorSeed seed;
    std::thread worker([&] { seed = prepare_mirror_seed(tin); });
    worker.join();
    std::size_t constrained = 0;
    for (std::uint32_t f : seed.edge_flags)
        constrained += f;
    EXPECT_GE(constrained, 6u) << "the triangle's three edges, both ways";

    TinMirror seeded(ctx(), std::move(seed));
    const SyncStats first = seeded.sync();
    EXPECT_GT(first.bytes, seeded.mirrored_bytes() / 2) << "the first sync uploads everything";
    expect_mirror_equals_tin(ctx(), seeded, tin);
    TinMirror own(ctx(), tin);
    own.sync();
    EXPECT_EQ(seeded.origin().x, own.origin().x);
    EXPECT_EQ(seeded.origin().y, own.origin().y);
    EXPECT_EQ(seeded.height_origin(), own.height_origin());
    EXPECT_EQ(seeded.graph().targets(), own.graph().targets());

    // Edits after the seed was built: a new constrained edge, moved heights, a removal.
    MirrorSeed behind = prepare_mirror_seed(tin);
    const VertexId d = tin.insert_point({0.85, 0.85}, 0.2);
    const std::array<VertexId, 2> edge{c, d};
    tin.insert_constraint(edge, false, 2);
    tin.set_height(a, tin.height(a) + 0.05);
    tin.remove_vertex(tin.locate({0.1, 0.9}).corners[0]);
    TinMirror caught_up(ctx(), std::move(behind));
    caught_up.sync();
    expect_mirror_equals_tin(ctx(), caught_up, tin);
    // And it goes on from there like any mirror.
    tin.set_height(b, tin.height(b) - 0.02);
    caught_up.sync();
    expect_mirror_equals_tin(ctx(), caught_up, tin);
}

// The acceptance figure: one stamp (r = 0.04, 12 control points) on a 10^6-vertex terrain
// uploads less than 1 % of the mirrored bytes.
TEST_F(GpuTest, OneStampOn1e6VerticesUploadsUnderOnePercentOfTheMirror) {
    Tin tin = Tin::random_points(kUnitSquare, 1000000, 23, [](Vec2 p) { return 0.2 + 0.05 * p.x; });
    TinMirror mirror(ctx(), tin);
    const SyncStats first = mirror.sync();
    const uint64_t mirrored = mirror.mirrored_bytes();
    EXPECT_GE(first.bytes, mirrored / 2) << "the first sync uploads the whole terrain";

    SculptContext context(tin.domain());
    ToolSpec spec;
    spec.radius = 0.04;
    spec.control_points = 12;
    const Tool tool = Tool::build(spec);
    const StampReport r = stamp(tin, tool, ToolPlacement{{0.5, 0.5}, 0.0, 0.15}, context);
    ASSERT_TRUE(r.applied);
    const SyncStats after = mirror.sync();
    EXPECT_GT(after.bytes, 0u);
    EXPECT_LT(after.bytes, mirrored / 100) << after.bytes << " of " << mirrored;
    EXPECT_FALSE(after.reallocated);
    RecordProperty("stamp_upload_bytes", std::to_string(after.bytes));
    RecordProperty("mirrored_bytes", std::to_string(mirrored));
    // Nothing changed since: nothing is uploaded.
    EXPECT_EQ(mirror.sync().bytes, 0u);
    expect_mirror_equals_tin(ctx(), mirror, tin);
}

}  // namespace
}  // namespace sandtin::gpu
