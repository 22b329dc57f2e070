#include "gpu/gpu_relaxation.hpp"

#include <algorithm>
#include <array>
#include <cstring>

#include "gpu/gpu_error.hpp"
#include "gpu/shaders.hpp"
#include "gpu/vulkan_context.hpp"

namespace sandtin::gpu {

namespace {

// Must match shaders/talus_common.glsl.
constexpr uint32_t kControlWords = 32;
constexpr uint32_t C_ACTIVE = 0, C_CHANGED = 3, C_SPLIT = 4, C_PARITY = 5, C_TOUCHED = 6,
                   C_PROCESSED_LO = 7, C_CHANGED_TOTAL_LO = 9;
constexpr VkDeviceSize kArgsActive = 16 * 4, kArgsReceivers = 20 * 4, kArgsChanged = 24 * 4;
constexpr uint32_t kRegions = 6;  // active A, active B, receivers, changed, split, touched
constexpr uint32_t R_CHANGED = 3, R_SPLIT = 4, R_TOUCHED = 5;
constexpr uint32_t kStateBytes = 36;   // shaders/talus_common.glsl VertexState
constexpr uint32_t kPackedBytes = 24;  // PackedVertex
static_assert(sizeof(TouchedVertex) == kPackedBytes);
constexpr uint32_t kBindings = 19;
constexpr uint32_t kTimedPairs = 4096;

constexpr VkBufferUsageFlags kStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                        VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                                        VK_BUFFER_USAGE_TRANSFER_DST_BIT;

void compute_barrier(VkCommandBuffer cb) {
    memory_barrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                   VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT,
                   VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT |
                       VK_PIPELINE_STAGE_TRANSFER_BIT,
                   VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
                       VK_ACCESS_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT |
                       VK_ACCESS_TRANSFER_WRITE_BIT);
}

uint64_t word64(const std::vector<uint32_t>& c, uint32_t lo) {
    return uint64_t{c[lo]} | (uint64_t{c[lo + 1]} << 32);
}

}  // namespace

GpuRelaxation::GpuRelaxation(TinMirror& mirror, GpuRelaxationSettings settings)
    : context_(mirror.context()),
      mirror_(mirror),
      settings_(settings),
      outflow_(context_, "talus_outflow", shaders::talus_outflow(), kBindings, sizeof(Push)),
      face_outflow_(context_, "talus_face_outflow", shaders::talus_face_outflow(), kBindings,
                    sizeof(Push)),
      gather_(context_, "talus_gather", shaders::talus_gather(), kBindings, sizeof(Push)),
      age_(context_, "talus_age", shaders::talus_age(), kBindings, sizeof(Push)),
      activate_(context_, "talus_activate", shaders::talus_activate(), kBindings, sizeof(Push)),
      control_(context_, "talus_control", shaders::talus_control(), kBindings, sizeof(Push)),
      pack_(context_, "talus_pack", shaders::talus_pack(), kBindings, sizeof(Push)),
      timer_(std::make_unique<KernelTimer>(context_, kTimedPairs)) {
    if (!(settings_.parameters.damping > 0.0) || settings_.parameters.damping > 1.0) {
        throw GpuError("GpuRelaxation: damping must be in (0, 1]");
    }
    if (settings_.quiet_iterations < 1) {
        throw GpuError("GpuRelaxation: quiet_iterations must be >= 1");
    }
    control_buf_ = Buffer(context_, kControlWords * 4,
                          kStorage | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT, MemoryUse::Device);
    control_host_ =
        Buffer(context_, kControlWords * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::Readback);
    context_.submit_and_wait(
        [&](VkCommandBuffer cb) { vkCmdFillBuffer(cb, control_buf_.get(), 0, VK_WHOLE_SIZE, 0); });
    std::memset(control_host_.mapped(), 0, kControlWords * 4);
}

GpuRelaxation::~GpuRelaxation() = default;

GpuRelaxation::Push GpuRelaxation::push(uint32_t mode) const {
    const TalusParameters& p = settings_.parameters;
    Push pc{};
    pc.iter = iteration_;
    pc.capacity = capacity_;
    pc.mode = mode;
    pc.quiet_limit = static_cast<uint32_t>(settings_.quiet_iterations);
    pc.damping = static_cast<float>(p.damping);
    pc.rest_tolerance = static_cast<float>(p.rest_tolerance);
    pc.r_limit =
        p.relocation_radius > 0.0 ? static_cast<float>(p.relocation_radius * (1.0 + 1e-6)) : 1e30f;
    pc.slide_gain = static_cast<float>(std::max(0.0, settings_.slide_gain));
    pc.seed_lo = static_cast<uint32_t>(settings_.seed);
    pc.seed_hi = static_cast<uint32_t>(settings_.seed >> 32);
    pc.randomness = static_cast<float>(std::clamp(settings_.randomness, 0.0, 0.99));
    pc.settle_margin = static_cast<float>(p.settle_margin);
    pc.split_batch = split_batch_;
    return pc;
}

void GpuRelaxation::ensure_buffers() {
    const uint32_t vcap = mirror_.vertex_capacity();
    const uint32_t ecap = mirror_.edge_capacity();
    if (vcap == 0)
        throw GpuError("GpuRelaxation: the mirror is empty (call TinMirror::sync first)");
    if (vcap != capacity_) {
        Buffer state(context_, VkDeviceSize{vcap} * kStateBytes, kStorage, MemoryUse::Device);
        Buffer lists(context_, VkDeviceSize{vcap} * kRegions * 4, kStorage, MemoryUse::Device);
        const uint32_t old = capacity_;
        context_.submit_and_wait([&](VkCommandBuffer cb) {
            vkCmdFillBuffer(cb, state.get(), 0, VK_WHOLE_SIZE, 0);
            vkCmdFillBuffer(cb, lists.get(), 0, VK_WHOLE_SIZE, 0);
            if (old > 0) {
                memory_barrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                               VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
                VkBufferCopy s{0, 0, VkDeviceSize{old} * kStateBytes};
                vkCmdCopyBuffer(cb, state_.get(), state.get(), 1, &s);
                // Regions are laid out by capacity: move each to its new place.
                std::array<VkBufferCopy, kRegions> r{};
                for (uint32_t i = 0; i < kRegions; ++i) {
                    r[i] = {VkDeviceSize{i} * old * 4, VkDeviceSize{i} * vcap * 4,
                            VkDeviceSize{old} * 4};
                }
                vkCmdCopyBuffer(cb, lists_.get(), lists.get(), kRegions, r.data());
            }
        });
        state_ = std::move(state);
        lists_ = std::move(lists);
        out_ = Buffer(context_, VkDeviceSize{vcap} * 4, kStorage, MemoryUse::Device);
        packed_ = Buffer(context_, VkDeviceSize{vcap} * kPackedBytes, kStorage, MemoryUse::Device);
        readback_ = Buffer(context_, VkDeviceSize{vcap} * kPackedBytes,
                           VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::Readback);
        seed_upload_ = Buffer(context_, VkDeviceSize{vcap} * 4, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                              MemoryUse::Upload);
        capacity_ = vcap;
    }
    if (ecap != edge_capacity_) {
        // q is scratch within an iteration: no contents to keep.
        q_ = Buffer(context_, VkDeviceSize{ecap} * 4, kStorage, MemoryUse::Device);
        edge_capacity_ = ecap;
        bound_generation_ = UINT64_MAX;
    }
}

void GpuRelaxation::bind_all() {
    const std::array<VkBuffer, kBindings> b = {control_buf_.get(),
                                               mirror_.vertex_buffer(VertexBuffer::Height),
                                               mirror_.vertex_buffer(VertexBuffer::Area),
                                               mirror_.vertex_buffer(VertexBuffer::Bedrock),
                                               mirror_.vertex_buffer(VertexBuffer::TanAlpha),
                                               mirror_.vertex_buffer(VertexBuffer::RowOffset),
                                               mirror_.vertex_buffer(VertexBuffer::RowDegree),
                                               mirror_.edge_buffer(EdgeBuffer::Target),
                                               mirror_.edge_buffer(EdgeBuffer::Reverse),
                                               mirror_.edge_buffer(EdgeBuffer::Length),
                                               mirror_.vertex_buffer(VertexBuffer::Longest),
                                               q_.get(),
                                               out_.get(),
                                               state_.get(),
                                               lists_.get(),
                                               mirror_.vertex_buffer(VertexBuffer::Position),
                                               mirror_.vertex_buffer(VertexBuffer::Slide),
                                               packed_.get(),
                                               mirror_.edge_buffer(EdgeBuffer::Across)};
    for (ComputeKernel* k :
         {&outflow_, &face_outflow_, &gather_, &age_, &activate_, &control_, &pack_})
        k->bind(b);
}

void GpuRelaxation::activate(std::span<const uint32_t> vertices) {
    pending_.insert(pending_.end(), vertices.begin(), vertices.end());
}

void GpuRelaxation::read_control(std::vector<uint32_t>& out) const {
    out.resize(kControlWords);
    control_host_.invalidate(context_);
    std::memcpy(out.data(), control_host_.mapped(), kControlWords * 4);
}

GpuRunStats GpuRelaxation::run(int iterations) {
    GpuRunStats stats;
    if (iterations <= 0 || (known_active_ == 0 && pending_.empty())) return stats;
    ensure_buffers();
    const bool rebind =
        bound_generation_ != mirror_.generation() || bound_generation_ == UINT64_MAX;
    if (rebind) {
        bind_all();
        bound_generation_ = mirror_.generation();
    }
    // Pending activations: ids beyond the capacity are dropped (their vertices do not exist).
    std::vector<uint32_t> seeds;
    seeds.reserve(pending_.size());
    for (uint32_t v : pending_)
        if (v < capacity_) seeds.push_back(v);
    pending_.clear();
    std::sort(seeds.begin(), seeds.end());
    seeds.erase(std::unique(seeds.begin(), seeds.end()), seeds.end());
    if (!seeds.empty()) std::memcpy(seed_upload_.mapped(), seeds.data(), seeds.size() * 4);
    seed_upload_.flush(context_);

    const uint64_t before_dispatches = dispatches_total_;
    const bool profile = settings_.profile && timer_->enabled();
    std::vector<uint32_t> before;
    read_control(before);  // totals before this run (host copy is current after every run)

    // The rule picks phase 1's kernel; the other phases are the same for both.
    ComputeKernel& outflow =
        settings_.parameters.rule == SlopeRule::Face ? face_outflow_ : outflow_;
    context_.submit_and_wait([&](VkCommandBuffer cb) {
        if (profile) timer_->reset(cb);
        compute_barrier(cb);  // uploads of the mirror (earlier submissions) -> shaders
        auto timed = [&](const ComputeKernel& k, auto&& record) {
            const uint32_t pair = profile ? timer_->begin(cb, k.name()) : UINT32_MAX;
            record();
            if (profile) timer_->end(cb, pair);
            ++dispatches_total_;
            compute_barrier(cb);
        };
        if (!seeds.empty()) {
            ++iteration_;
            if (iteration_ == 0) iteration_ = 1;
            const auto n = static_cast<uint32_t>(seeds.size());
            VkBufferCopy c{0, VkDeviceSize{R_CHANGED} * capacity_ * 4, VkDeviceSize{n} * 4};
            vkCmdCopyBuffer(cb, seed_upload_.get(), lists_.get(), 1, &c);
            vkCmdUpdateBuffer(cb, control_buf_.get(), C_CHANGED * 4, 4, &n);
            compute_barrier(cb);
            const Push seed = push(1);
            timed(activate_, [&] { activate_.dispatch(cb, n, &seed); });
            const Push ctl = push(3);
            timed(control_, [&] { control_.dispatch(cb, 1, &ctl); });
        }
        for (int it = 0; it < iterations; ++it) {
            ++iteration_;
            if (iteration_ == 0) iteration_ = 1;  // 0 means "never" in the stamps
            const Push p0 = push(0), p1 = push(1), p2 = push(2);
            timed(outflow,
                  [&] { outflow.dispatch_indirect(cb, control_buf_.get(), kArgsActive, &p0); });
            timed(control_, [&] { control_.dispatch(cb, 1, &p0); });
            timed(gather_,
                  [&] { gather_.dispatch_indirect(cb, control_buf_.get(), kArgsReceivers, &p0); });
            timed(control_, [&] { control_.dispatch(cb, 1, &p1); });
            timed(age_, [&] { age_.dispatch_indirect(cb, control_buf_.get(), kArgsActive, &p0); });
            timed(activate_,
                  [&] { activate_.dispatch_indirect(cb, control_buf_.get(), kArgsChanged, &p0); });
            timed(control_, [&] { control_.dispatch(cb, 1, &p2); });
        }
        VkBufferCopy c{0, 0, kControlWords * 4};
        vkCmdCopyBuffer(cb, control_buf_.get(), control_host_.get(), 1, &c);
        host_read_barrier(cb);
    });
    if (profile) timer_->collect();

    std::vector<uint32_t> after;
    read_control(after);
    known_active_ = after[C_ACTIVE];
    stats.iterations = iterations;
    stats.dispatches = dispatches_total_ - before_dispatches;
    stats.active_after = known_active_;
    stats.vertex_updates = word64(after, C_PROCESSED_LO) - word64(before, C_PROCESSED_LO);
    stats.changed = word64(after, C_CHANGED_TOTAL_LO) - word64(before, C_CHANGED_TOTAL_LO);
    return stats;
}

std::vector<TouchedVertex> GpuRelaxation::read_back() {
    if (capacity_ == 0) return {};
    std::vector<uint32_t> ctl;
    read_control(ctl);
    const uint32_t n = std::min(ctl[C_TOUCHED], capacity_);
    if (n == 0) return {};
    const Push pk = push(0), clear = push(4);
    context_.submit_and_wait([&](VkCommandBuffer cb) {
        compute_barrier(cb);
        pack_.dispatch(cb, n, &pk);
        compute_barrier(cb);
        control_.dispatch(cb, 1, &clear);
        compute_barrier(cb);
        VkBufferCopy c{0, 0, VkDeviceSize{n} * kPackedBytes};
        vkCmdCopyBuffer(cb, packed_.get(), readback_.get(), 1, &c);
        VkBufferCopy cc{0, 0, kControlWords * 4};
        vkCmdCopyBuffer(cb, control_buf_.get(), control_host_.get(), 1, &cc);
        host_read_barrier(cb);
    });
    dispatches_total_ += 2;
    readback_.invalidate(context_);
    std::vector<TouchedVertex> out(n);
    std::memcpy(out.data(), readback_.mapped(), VkDeviceSize{n} * kPackedBytes);
    return out;
}

std::vector<uint32_t> GpuRelaxation::take_split_requests() {
    if (capacity_ == 0) return {};
    std::vector<uint32_t> ctl;
    read_control(ctl);
    const uint32_t n = std::min(ctl[C_SPLIT], capacity_);
    if (n == 0) return {};
    std::vector<uint32_t> out(n);
    Buffer host(context_, VkDeviceSize{n} * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                MemoryUse::Readback);
    const uint32_t zero = 0;
    context_.submit_and_wait([&](VkCommandBuffer cb) {
        compute_barrier(cb);
        VkBufferCopy c{VkDeviceSize{R_SPLIT} * capacity_ * 4, 0, VkDeviceSize{n} * 4};
        vkCmdCopyBuffer(cb, lists_.get(), host.get(), 1, &c);
        vkCmdUpdateBuffer(cb, control_buf_.get(), C_SPLIT * 4, 4, &zero);
        compute_barrier(cb);
        VkBufferCopy cc{0, 0, kControlWords * 4};
        vkCmdCopyBuffer(cb, control_buf_.get(), control_host_.get(), 1, &cc);
        host_read_barrier(cb);
    });
    host.invalidate(context_);
    std::memcpy(out.data(), host.mapped(), VkDeviceSize{n} * 4);
    if (++split_batch_ == 0) split_batch_ = 1;  // the list is empty again: a new batch
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

std::vector<float> GpuRelaxation::read_heights() const {
    std::vector<float> h = read_buffer_floats(context_, mirror_.vertex_buffer(VertexBuffer::Height),
                                              VkDeviceSize{mirror_.vertex_capacity()} * 4);
    const double origin = mirror_.height_origin();
    for (float& z : h)
        z = static_cast<float>(static_cast<double>(z) + origin);
    return h;
}

std::vector<float> GpuRelaxation::read_slides() const {
    return read_buffer_floats(context_, mirror_.vertex_buffer(VertexBuffer::Slide),
                              VkDeviceSize{mirror_.vertex_capacity()} * 8);
}

}  // namespace sandtin::gpu
