#include "gpu/tin_mirror.hpp"

#include <algorithm>
#include <cmath>

#include "gpu/gpu_error.hpp"
#include "gpu/vulkan_context.hpp"

namespace sandtin::gpu {

namespace {

// Ranges closer than this many elements are uploaded as one (a few clean bytes for fewer copy
// regions).
constexpr uint32_t kMergeGap = 16;
// At most this many vertex ranges and as many slot ranges per sync: beyond it the ranges across
// the smallest gaps are joined. Each range is a copy region per buffer (nine vertex buffers).
constexpr std::size_t kMaxRanges = 256;

constexpr VkBufferUsageFlags kUsage =
    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
    VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_VERTEX_BUFFER_BIT |
    VK_BUFFER_USAGE_INDEX_BUFFER_BIT;

// New capacity for `need` elements: 1/8 headroom over the need (so the first edits after a
// load do not reallocate) and at least x1.5 of the old capacity (amortised growth).
uint32_t grown(uint32_t have, uint32_t need) {
    if (need <= have) return have;
    const uint64_t g =
        std::max<uint64_t>({uint64_t{need} + need / 8, uint64_t{have} + have / 2, 64});
    return static_cast<uint32_t>(std::min<uint64_t>(g, 0xFFFFFFFFu));
}

// Buffers being replaced by larger ones in one submission: each old buffer's contents are
// copied on the GPU, and the rest is zeroed from `fill_from` on (bytes; what the same sync
// uploads anyway need not be zeroed first).
class Regrowth {
  public:
    explicit Regrowth(const VulkanContext& ctx) : ctx_(ctx) {}
    void add(Buffer& buffer, VkDeviceSize bytes, VkDeviceSize fill_from) {
        const VkDeviceSize old = buffer ? buffer.size() : 0;
        parts_.push_back({&buffer, Buffer(ctx_, bytes, kUsage, MemoryUse::Device), old,
                          std::min(std::max(old, fill_from), bytes)});
    }
    // One submission for all of them (one wait, not one per buffer), then the swap.
    void run() {
        if (parts_.empty()) return;
        ctx_.submit_and_wait([&](VkCommandBuffer cb) {
            for (Part& p : parts_) {
                if (p.old > 0) {
                    VkBufferCopy c{0, 0, p.old};
                    vkCmdCopyBuffer(cb, p.buffer->get(), p.fresh.get(), 1, &c);
                }
                // Fill sizes must be multiples of 4; all element sizes are.
                if (p.fill_from < p.fresh.size())
                    vkCmdFillBuffer(cb, p.fresh.get(), p.fill_from, p.fresh.size() - p.fill_from,
                                    0);
            }
        });
        for (Part& p : parts_)
            *p.buffer = std::move(p.fresh);
        parts_.clear();
    }

  private:
    struct Part {
        Buffer* buffer;
        Buffer fresh;
        VkDeviceSize old;
        VkDeviceSize fill_from;
    };
    const VulkanContext& ctx_;
    std::vector<Part> parts_;
};

}  // namespace

uint32_t element_size(VertexBuffer b) {
    switch (b) {
        case VertexBuffer::Position:
        case VertexBuffer::Slide:
            return 8;
        default:
            return 4;
    }
}
uint32_t element_size(SlotBuffer b) {
    return b == SlotBuffer::Triangles ? 12 : 4;
}
uint32_t element_size(EdgeBuffer) {
    return 4;
}

TinMirror::TinMirror(VulkanContext& context, Tin& tin, MaterialTable materials,
                     VkDeviceSize staging_bytes)
    : context_(context),
      changes_(std::make_unique<ChangeReader>(tin)),
      materials_(std::move(materials)),
      ring_(context, staging_bytes) {
    if (materials_.size() == 0) throw GpuError("TinMirror: the material table is empty");
}

TinMirror::TinMirror(VulkanContext& context, MirrorSeed seed, MaterialTable materials,
                     VkDeviceSize staging_bytes)
    : context_(context),
      changes_(std::move(seed.changes)),
      seed_(std::move(seed)),
      materials_(std::move(materials)),
      ring_(context, staging_bytes) {
    if (!changes_) throw GpuError("TinMirror: the seed has no reader of the TIN's journal");
    if (materials_.size() == 0) throw GpuError("TinMirror: the material table is empty");
}

TinMirror::~TinMirror() {
    ring_.wait_idle();
}

void TinMirror::set_materials(MaterialTable materials) {
    if (materials.size() == 0) throw GpuError("TinMirror: the material table is empty");
    materials_ = std::move(materials);
    materials_dirty_ = true;
}

VkBuffer TinMirror::vertex_buffer(VertexBuffer b) const {
    return vertex_[static_cast<size_t>(b)].get();
}
VkBuffer TinMirror::slot_buffer(SlotBuffer b) const {
    return slot_[static_cast<size_t>(b)].get();
}
VkBuffer TinMirror::edge_buffer(EdgeBuffer b) const {
    return edge_[static_cast<size_t>(b)].get();
}

uint64_t TinMirror::mirrored_bytes() const {
    uint64_t total = 0;
    for (const Buffer& b : vertex_)
        total += b ? b.size() : 0;
    for (const Buffer& b : slot_)
        total += b ? b.size() : 0;
    for (const Buffer& b : edge_)
        total += b ? b.size() : 0;
    return total;
}

void TinMirror::grow(uint32_t vertices, uint32_t slots, uint32_t edges, const Uploaded& uploaded,
                     SyncStats& stats) {
    const uint32_t nv = grown(vertex_capacity_, std::max(vertices, 1u));
    const uint32_t ns = grown(slot_capacity_, std::max(slots, 1u));
    const uint32_t ne = grown(edge_capacity_, std::max(edges, 1u));
    if (nv == vertex_capacity_ && ns == slot_capacity_ && ne == edge_capacity_) return;
    // Queued copies target the old buffers: land them first.
    ring_.flush();
    ring_.wait_idle();
    // What this sync uploads from 0 on (the first sync: every id, slot and pool entry) is not
    // zeroed first: every byte of it would be written twice.
    const auto covered = [](uint32_t count, uint32_t element) {
        return VkDeviceSize{count} * element;
    };
    Regrowth regrowth(context_);
    if (nv != vertex_capacity_) {
        for (uint32_t i = 0; i < static_cast<uint32_t>(VertexBuffer::Count); ++i) {
            const uint32_t e = element_size(static_cast<VertexBuffer>(i));
            regrowth.add(vertex_[i], VkDeviceSize{nv} * e, covered(uploaded.vertices, e));
        }
        vertex_capacity_ = nv;
        tan_alpha_cpu_.resize(nv, 0.0f);
    }
    if (ns != slot_capacity_) {
        for (uint32_t i = 0; i < static_cast<uint32_t>(SlotBuffer::Count); ++i) {
            const uint32_t e = element_size(static_cast<SlotBuffer>(i));
            regrowth.add(slot_[i], VkDeviceSize{ns} * e, covered(uploaded.slots, e));
        }
        slot_capacity_ = ns;
    }
    if (ne != edge_capacity_) {
        for (uint32_t i = 0; i < static_cast<uint32_t>(EdgeBuffer::Count); ++i) {
            const uint32_t e = element_size(static_cast<EdgeBuffer>(i));
            regrowth.add(edge_[i], VkDeviceSize{ne} * e, covered(uploaded.edges, e));
        }
        edge_capacity_ = ne;
    }
    regrowth.run();
    ++generation_;
    stats.reallocated = true;
}

void TinMirror::upload_vertex_range(const Tin& tin, IdRange r) {
    const VertexArrays& va = tin.vertices();
    const uint32_t n = r.size();
    auto put = [&](VertexBuffer b, const void* data, uint32_t elem) {
        ring_.upload(vertex_[static_cast<size_t>(b)].get(), VkDeviceSize{r.begin} * elem, data,
                     VkDeviceSize{n} * elem);
    };
    f2_.resize(2 * size_t{n});
    for (uint32_t i = 0; i < n; ++i) {
        const Vec2 p = va.position[r.begin + i];
        f2_[2 * i] = static_cast<float>(p.x - origin_.x);
        f2_[2 * i + 1] = static_cast<float>(p.y - origin_.y);
    }
    put(VertexBuffer::Position, f2_.data(), 8);
    f_.resize(n);
    auto floats = [&](VertexBuffer b, const std::vector<double>& src, double origin) {
        for (uint32_t i = 0; i < n; ++i)
            f_[i] = static_cast<float>(src[r.begin + i] - origin);
        put(b, f_.data(), 4);
    };
    floats(VertexBuffer::Height, va.height, height_origin_);
    // The bedrock rounds up, so the float floor the shaders drain to is never below the
    // double one (a float below it would let the GPU take sand the TIN does not have).
    for (uint32_t i = 0; i < n; ++i) {
        const double b = va.bedrock[r.begin + i] - height_origin_;
        f_[i] = static_cast<float>(b);
        if (static_cast<double>(f_[i]) < b) f_[i] = std::nextafter(f_[i], HUGE_VALF);
    }
    put(VertexBuffer::Bedrock, f_.data(), 4);
    floats(VertexBuffer::Area, va.lumped_area, 0.0);
    upload_tan_alpha(tin, r);
    u_.resize(n);
    for (uint32_t i = 0; i < n; ++i)
        u_[i] = va.material[r.begin + i];
    put(VertexBuffer::Material, u_.data(), 4);
    put(VertexBuffer::Moisture, va.moisture.data() + r.begin, 4);
    static_assert(sizeof(Vec2f) == 8);
    put(VertexBuffer::Slide, va.slide.data() + r.begin, 8);
    for (uint32_t i = 0; i < n; ++i)
        f_[i] = static_cast<float>(va.water_depth[r.begin + i]);
    put(VertexBuffer::WaterDepth, f_.data(), 4);
}

void TinMirror::upload_tan_alpha(const Tin& tin, IdRange r) {
    const VertexArrays& va = tin.vertices();
    for (uint32_t v = r.begin; v < r.end; ++v) {
        tan_alpha_cpu_[v] =
            va.alive[v]
                ? static_cast<float>(materials_.at(va.material[v]).talus_slope(va.moisture[v]))
                : 0.0f;
    }
    ring_.upload(vertex_buffer(VertexBuffer::TanAlpha), VkDeviceSize{r.begin} * 4,
                 tan_alpha_cpu_.data() + r.begin, VkDeviceSize{r.size()} * 4);
}

void TinMirror::upload_rows(const Tin& tin, const std::vector<uint32_t>& rows,
                            const std::vector<uint32_t>* flags) {
    if (rows.empty()) return;
    // Per-vertex row data, by id ranges (small gaps merged: fewer copy regions).
    for (const IdRange r : merge_into_ranges(rows, kMergeGap)) {
        const uint32_t n = r.size();
        u_.resize(n);
        for (uint32_t i = 0; i < n; ++i)
            u_[i] = graph_.offset(r.begin + i);
        ring_.upload(vertex_buffer(VertexBuffer::RowOffset), VkDeviceSize{r.begin} * 4, u_.data(),
                     VkDeviceSize{n} * 4);
        for (uint32_t i = 0; i < n; ++i)
            u_[i] = graph_.degree(r.begin + i);
        ring_.upload(vertex_buffer(VertexBuffer::RowDegree), VkDeviceSize{r.begin} * 4, u_.data(),
                     VkDeviceSize{n} * 4);
        f_.resize(n);
        for (uint32_t i = 0; i < n; ++i)
            f_[i] = static_cast<float>(graph_.longest_edge(r.begin + i));
        ring_.upload(vertex_buffer(VertexBuffer::Longest), VkDeviceSize{r.begin} * 4, f_.data(),
                     VkDeviceSize{n} * 4);
    }
    // The rows' edge slots in pool order, merged into ranges across small gaps (slack slots in
    // a gap are copied too; nothing reads them).
    std::vector<uint32_t> order;
    for (uint32_t v : rows)
        if (graph_.degree(v) > 0) order.push_back(v);
    std::sort(order.begin(), order.end(),
              [&](uint32_t a, uint32_t b) { return graph_.offset(a) < graph_.offset(b); });
    size_t i = 0;
    while (i < order.size()) {
        const uint32_t begin = graph_.offset(order[i]);
        uint32_t end = begin + graph_.degree(order[i]);
        size_t j = i + 1;
        while (j < order.size() && graph_.offset(order[j]) <= end + kMergeGap) {
            end = std::max(end, graph_.offset(order[j]) + graph_.degree(order[j]));
            ++j;
        }
        const uint32_t n = end - begin;
        ring_.upload(edge_buffer(EdgeBuffer::Target), VkDeviceSize{begin} * 4,
                     graph_.targets().data() + begin, VkDeviceSize{n} * 4);
        ring_.upload(edge_buffer(EdgeBuffer::Reverse), VkDeviceSize{begin} * 4,
                     graph_.reverses().data() + begin, VkDeviceSize{n} * 4);
        f_.resize(n);
        for (uint32_t k = 0; k < n; ++k)
            f_[k] = static_cast<float>(graph_.lengths()[begin + k]);
        ring_.upload(edge_buffer(EdgeBuffer::Length), VkDeviceSize{begin} * 4, f_.data(),
                     VkDeviceSize{n} * 4);
        for (uint32_t k = 0; k < n; ++k)
            f_[k] = static_cast<float>(graph_.across()[begin + k]);
        ring_.upload(edge_buffer(EdgeBuffer::Across), VkDeviceSize{begin} * 4, f_.data(),
                     VkDeviceSize{n} * 4);
        // Constrained flags of the rows in this range (gap slots: 0).
        u_.assign(n, 0u);
        for (size_t r = i; r < j; ++r) {
            const uint32_t v = order[r];
            const uint32_t b = graph_.offset(v);
            for (uint32_t k = 0; k < graph_.degree(v); ++k) {
                const VertexId w{graph_.targets()[b + k]};
                u_[b - begin + k] = flags != nullptr                          ? (*flags)[b + k]
                                    : tin.is_constrained_edge(VertexId{v}, w) ? 1u
                                                                              : 0u;
            }
        }
        ring_.upload(edge_buffer(EdgeBuffer::EdgeFlags), VkDeviceSize{begin} * 4, u_.data(),
                     VkDeviceSize{n} * 4);
        i = j;
    }
}

void TinMirror::update_graph(const Tin& tin, const ChangeSet& changes) {
    // Vertices whose star changed: corners of dirty slots (every re-triangulated star has a new
    // triangle) and vertices that died.
    std::vector<VertexId> star;
    for (const IdRange r : changes.triangles) {
        for (uint32_t s = r.begin; s < r.end; ++s) {
            for (VertexId c : tin.slot_triangle(s))
                if (c.valid()) star.push_back(c);
        }
    }
    for (const IdRange r : changes.vertices) {
        for (uint32_t v = r.begin; v < r.end; ++v)
            if (!tin.is_alive(VertexId{v})) star.push_back(VertexId{v});
    }
    graph_.update(tin, star);
}

void TinMirror::adopt_seed(Tin& tin, const ChangeSet& changes) {
    // A prepared seed's reader reports only what changed after it was built; a mirror without
    // one builds it now, after its reader's first take (which reported everything).
    const bool prepared = seed_.has_value();
    if (!prepared) {
        seed_.emplace();
        build_mirror_seed(tin, *seed_);
    }
    origin_ = seed_->origin;
    height_origin_ = seed_->height_origin;
    graph_ = std::move(seed_->graph);
    if (prepared && !changes.empty()) {
        update_graph(tin, changes);
        seed_->edge_flags.clear();  // rows moved: the flags are read from the TIN again
    }
}

SyncStats TinMirror::sync() {
    Tin& tin = changes_->tin();
    ChangeSet changes = changes_->take();
    SyncStats stats;
    std::vector<uint32_t> rows;
    const std::vector<uint32_t>* seed_flags = nullptr;
    if (first_sync_) {
        adopt_seed(tin, changes);
        rows = graph_.take_dirty_rows();
        if (!seed_->edge_flags.empty()) seed_flags = &seed_->edge_flags;
        // The first sync uploads everything, whatever the reader reported.
        changes.vertices = {IdRange{0, static_cast<uint32_t>(tin.vertices().size())}};
        changes.triangles = {IdRange{0, tin.slot_capacity()}};
    } else if (!changes.empty()) {
        update_graph(tin, changes);
        rows = graph_.take_dirty_rows();
    }
    const uint32_t edges = static_cast<uint32_t>(graph_.slot_count());
    const uint32_t vertex_count = static_cast<uint32_t>(tin.vertices().size());
    // The first sync uploads everything below these counts (the rows' pool up to its last
    // row's slack, which nothing reads).
    const Uploaded uploaded =
        first_sync_ ? Uploaded{vertex_count, tin.slot_capacity(), edges} : Uploaded{};
    grow(std::max(changes.vertex_capacity, vertex_count),
         std::max(changes.slot_capacity, tin.slot_capacity()), edges, uploaded, stats);

    const VertexArrays& va = tin.vertices();
    // Scattered edits (erosion moves sand on thousands of vertices a frame) give thousands of
    // short ranges, each a copy region per buffer: 31 450 regions in one flush after a stroke
    // settled, which the validation layer took most of the editor's CPU time to check. Short
    // gaps, and beyond kMaxRanges the smallest ones, are copied too (their data is current).
    std::vector<IdRange> vranges = coalesce_ranges(changes.vertices, kMergeGap, kMaxRanges);
    std::vector<IdRange> sranges = coalesce_ranges(changes.triangles, kMergeGap, kMaxRanges);
    if (materials_dirty_) {
        // Only tan(repose) depends on the table: one buffer, not all nine (a material edit at
        // 10^6 vertices re-uploaded 36 MB).
        upload_tan_alpha(tin, IdRange{0, static_cast<uint32_t>(va.size())});
        materials_dirty_ = false;
    }
    for (const IdRange r : vranges) {
        if (r.size() == 0) continue;
        upload_vertex_range(tin, r);
        ++stats.vertex_ranges;
    }
    for (const IdRange r : sranges) {
        const uint32_t n = r.size();
        if (n == 0) continue;
        u_.resize(3 * size_t{n});
        std::vector<uint32_t> flags(n);
        for (uint32_t i = 0; i < n; ++i) {
            const auto t = tin.slot_triangle(r.begin + i);
            const bool live = t[0].valid();
            for (int c = 0; c < 3; ++c)
                u_[3 * i + static_cast<uint32_t>(c)] = live ? t[c].value : 0u;
            flags[i] = live ? (tin.slot_constraint_mask(r.begin + i) & 7u) | 8u : 0u;
        }
        ring_.upload(slot_buffer(SlotBuffer::Triangles), VkDeviceSize{r.begin} * 12, u_.data(),
                     VkDeviceSize{n} * 12);
        ring_.upload(slot_buffer(SlotBuffer::SlotFlags), VkDeviceSize{r.begin} * 4, flags.data(),
                     VkDeviceSize{n} * 4);
        ++stats.slot_ranges;
    }
    upload_rows(tin, rows, seed_flags);
    stats.rows = static_cast<uint32_t>(rows.size());
    ring_.flush();
    first_sync_ = false;
    seed_.reset();

    stats.bytes = ring_.take_frame_bytes();
    stats.copy_regions = ring_.take_frame_regions();
    return stats;
}

}  // namespace sandtin::gpu
