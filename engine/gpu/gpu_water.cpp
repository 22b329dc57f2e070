#include "gpu/gpu_water.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

#include "gpu/gpu_error.hpp"
#include "gpu/shaders.hpp"
#include "gpu/vulkan_context.hpp"

namespace sandtin::gpu {

namespace {

// Must match shaders/water_common.glsl.
constexpr uint32_t kLimitWord = 0, kWetWord = 1, kFlowingWord = 2, kLimitedWord = 3,
                   kDeepestWord = 4;
constexpr uint32_t kWaterBindings = 15;
constexpr uint32_t kPositiveInfinityBits = 0x7f800000u;

constexpr VkBufferUsageFlags kWaterStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                             VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                                             VK_BUFFER_USAGE_TRANSFER_DST_BIT;

std::vector<float> read_floats(const VulkanContext& context, VkBuffer buffer, uint32_t count) {
    return read_buffer_floats(context, buffer, VkDeviceSize{count} * 4);
}

}  // namespace

GpuWater::GpuWater(TinMirror& mirror, GpuWaterSettings settings)
    : context_(mirror.context()),
      mirror_(mirror),
      settings_(settings),
      changes_(mirror.tin()),
      flux_(context_, "water_flux", shaders::water_flux(), kWaterBindings, sizeof(Push)),
      depth_(context_, "water_depth", shaders::water_depth(), kWaterBindings, sizeof(Push)),
      measure_(context_, "water_measure", shaders::water_measure(), kWaterBindings, sizeof(Push)) {
    if (!(settings_.gravity > 0.0) || !std::isfinite(settings_.gravity) ||
        !(settings_.friction >= 0.0) || !std::isfinite(settings_.friction) ||
        !(settings_.courant > 0.0) || !(settings_.courant <= 1.0))
        throw GpuError("GpuWater: gravity must be > 0, friction >= 0 and courant in (0, 1]");
    control_ = Buffer(context_, kControlWords * 4, kWaterStorage, MemoryUse::Device);
    control_host_ =
        Buffer(context_, kControlWords * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::Readback);
    follow_mirror();  // the buffers exist from here on: read_depths() and volume() work at once
}

GpuWater::~GpuWater() = default;

void GpuWater::set_outflow_widths(std::span<const double> metres_per_vertex) {
    for (const double w : metres_per_vertex) {
        if (!(w >= 0.0) || !std::isfinite(w))
            throw GpuError("GpuWater: an outflow width must be finite and >= 0");
    }
    border_widths_.assign(std::max<std::size_t>(border_widths_.size(), metres_per_vertex.size()),
                          0.0f);
    std::transform(metres_per_vertex.begin(), metres_per_vertex.end(), border_widths_.begin(),
                   [](double w) { return static_cast<float>(w); });
    border_dirty_ = true;
    measured_ = false;
}

GpuWater::Push GpuWater::push(double dt) const {
    Push pc{};
    pc.vertex_count = static_cast<uint32_t>(mirror_.tin().vertices().size());
    pc.edge_capacity = edge_capacity_;
    pc.parity = parity_;
    pc.dt = static_cast<float>(dt);
    pc.gravity = static_cast<float>(settings_.gravity);
    pc.damping = static_cast<float>(1.0 / (1.0 + dt * settings_.friction));
    return pc;
}

void GpuWater::ensure_buffers() {
    const uint32_t vcap = mirror_.vertex_capacity();
    const uint32_t ecap = mirror_.edge_capacity();
    if (vcap == 0) throw GpuError("GpuWater: the mirror is empty");
    bool rebind = bound_generation_ != mirror_.generation();
    if (vcap != vertex_capacity_) {
        // The residual and the border's outflow are volume: carried over. The scale K is
        // rewritten by every step.
        Buffer residual(context_, VkDeviceSize{vcap} * 4, kWaterStorage, MemoryUse::Device);
        Buffer left(context_, VkDeviceSize{vcap} * 4, kWaterStorage, MemoryUse::Device);
        const uint32_t old = std::min(vertex_capacity_, vcap);
        context_.submit_and_wait([&](VkCommandBuffer cb) {
            vkCmdFillBuffer(cb, residual.get(), 0, VK_WHOLE_SIZE, 0);
            vkCmdFillBuffer(cb, left.get(), 0, VK_WHOLE_SIZE, 0);
            if (old == 0) return;
            memory_barrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                           VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
            const VkBufferCopy region{0, 0, VkDeviceSize{old} * 4};
            vkCmdCopyBuffer(cb, residual_.get(), residual.get(), 1, &region);
            vkCmdCopyBuffer(cb, left_.get(), left.get(), 1, &region);
        });
        residual_ = std::move(residual);
        left_ = std::move(left);
        keep_ = Buffer(context_, VkDeviceSize{vcap} * 4, kWaterStorage, MemoryUse::Device);
        border_ = Buffer(context_, VkDeviceSize{vcap} * 4, kWaterStorage, MemoryUse::Device);
        border_widths_.resize(vcap, 0.0f);
        border_dirty_ = true;
        vertex_capacity_ = vcap;
        rebind = true;
    }
    if (ecap != edge_capacity_) {
        // The pool grew: its slots moved, so the fluxes start from rest (as after any
        // re-triangulation).
        q_ = Buffer(context_, VkDeviceSize{ecap} * 8, kWaterStorage, MemoryUse::Device);
        context_.submit_and_wait(
            [&](VkCommandBuffer cb) { vkCmdFillBuffer(cb, q_.get(), 0, VK_WHOLE_SIZE, 0); });
        edge_capacity_ = ecap;
        rebind = true;
    }
    if (rebind) {
        const std::array<VkBuffer, kWaterBindings> buffers{
            control_.get(),
            mirror_.vertex_buffer(VertexBuffer::Position),
            mirror_.vertex_buffer(VertexBuffer::Height),
            mirror_.vertex_buffer(VertexBuffer::Area),
            mirror_.vertex_buffer(VertexBuffer::WaterDepth),
            mirror_.vertex_buffer(VertexBuffer::RowOffset),
            mirror_.vertex_buffer(VertexBuffer::RowDegree),
            mirror_.edge_buffer(EdgeBuffer::Target),
            mirror_.edge_buffer(EdgeBuffer::Reverse),
            mirror_.edge_buffer(EdgeBuffer::Across),
            q_.get(),
            keep_.get(),
            border_.get(),
            residual_.get(),
            left_.get()};
        for (ComputeKernel* k : {&flux_, &depth_, &measure_})
            k->bind(buffers);
        bound_generation_ = mirror_.generation();
    }
}

void GpuWater::follow_mirror() {
    mirror_.sync();
    ensure_buffers();
    if (border_dirty_) {
        StagingRing& ring = mirror_.staging();
        ring.upload(border_.get(), 0, border_widths_.data(), VkDeviceSize{vertex_capacity_} * 4);
        ring.flush();
        border_dirty_ = false;
    }
    const ChangeSet changes = changes_.take();
    if (changes.empty()) return;
    const VertexArrays& va = mirror_.tin().vertices();
    const uint32_t count =
        static_cast<uint32_t>(std::min<std::size_t>(va.size(), vertex_capacity_));
    // Vertices the terrain changed: their depth is the terrain's again (the mirror uploaded
    // it), so a residual kept for the GPU's old depth would be volume twice. Ranges a few ids
    // apart are cleared as one (their residuals are below a float's resolution of the depth).
    const std::vector<IdRange> ranges = coalesce_ranges(changes.vertices, 16, 256);
    for (const IdRange r : ranges) {
        for (uint32_t v = r.begin; v < std::min(r.end, count) && !active_; ++v)
            active_ = va.alive[v] && va.water_depth[v] > 0.0;  // water from the CPU wakes it
    }
    context_.submit_and_wait([&](VkCommandBuffer cb) {
        for (const IdRange r : ranges) {
            const uint32_t end = std::min(r.end, count);
            if (end > r.begin)
                vkCmdFillBuffer(cb, residual_.get(), VkDeviceSize{r.begin} * 4,
                                VkDeviceSize{end - r.begin} * 4, 0);
        }
        // Edges changed: the pipes restart from rest (their slots may now be other edges).
        if (!changes.triangles.empty()) vkCmdFillBuffer(cb, q_.get(), 0, VK_WHOLE_SIZE, 0);
    });
    measured_ = false;  // depths or edges changed: the limit too
}

void GpuWater::record_measure(VkCommandBuffer cb, const Push& pc) {
    measure_.dispatch(cb, pc.vertex_count, &pc);
    ++dispatches_total_;
    memory_barrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                   VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
    const VkBufferCopy all{0, 0, kControlWords * 4};
    vkCmdCopyBuffer(cb, control_.get(), control_host_.get(), 1, &all);
    host_read_barrier(cb);
}

std::array<uint32_t, GpuWater::kControlWords> GpuWater::take_measure() {
    control_host_.invalidate(context_);
    std::array<uint32_t, kControlWords> words{};
    std::memcpy(words.data(), control_host_.mapped(), sizeof(words));
    limit_ = static_cast<double>(std::bit_cast<float>(words[kLimitWord]));
    deepest_ = static_cast<double>(std::bit_cast<float>(words[kDeepestWord]));
    active_ = words[kWetWord] > 0 || words[kFlowingWord] > 0;
    measured_ = true;
    return words;
}

double GpuWater::stable_time_step() {
    follow_mirror();
    if (!measured_) {
        const Push pc = push(1.0);
        context_.submit_and_wait([&](VkCommandBuffer cb) {
            vkCmdFillBuffer(cb, control_.get(), 0, VK_WHOLE_SIZE, 0);
            vkCmdFillBuffer(cb, control_.get(), kLimitWord * 4, 4, kPositiveInfinityBits);
            compute_transfer_barrier(cb);
            record_measure(cb, pc);
        });
        take_measure();
    }
    return settings_.courant * limit_;
}

GpuWaterRun GpuWater::run(int steps, double dt, WaterStepHook* hook) {
    if (steps < 0) throw GpuError("GpuWater: the number of steps must be >= 0");
    if (!(dt > 0.0) || !std::isfinite(dt))
        throw GpuError("GpuWater: a time step must be finite and > 0");
    follow_mirror();
    GpuWaterRun run;
    if (!active_ || steps == 0) return run;  // dry and still: the GPU is not touched
    if (hook) hook->prepare();
    context_.submit_and_wait([&](VkCommandBuffer cb) {
        vkCmdFillBuffer(cb, control_.get(), 0, VK_WHOLE_SIZE, 0);
        vkCmdFillBuffer(cb, control_.get(), kLimitWord * 4, 4, kPositiveInfinityBits);
        compute_transfer_barrier(cb);
        for (int i = 0; i < steps; ++i) {
            parity_ = 1 - parity_;
            const Push pc = push(dt);
            flux_.dispatch(cb, pc.vertex_count, &pc);
            compute_transfer_barrier(cb);
            depth_.dispatch(cb, pc.vertex_count, &pc);
            compute_transfer_barrier(cb);
            if (hook) {
                hook->record_step(cb, parity_, dt);
                compute_transfer_barrier(cb);
            }
        }
        record_measure(cb, push(dt));
    });
    dispatches_total_ += 2 * static_cast<uint64_t>(steps);
    const std::array<uint32_t, kControlWords> words = take_measure();
    run.steps = steps;
    run.dispatches = 2 * static_cast<uint64_t>(steps) + 1;
    run.wet = words[kWetWord];
    run.flowing = words[kFlowingWord];
    run.outflows_limited = words[kLimitedWord];
    return run;
}

std::vector<float> GpuWater::read_depths() const {
    return read_floats(context_, mirror_.vertex_buffer(VertexBuffer::WaterDepth),
                       mirror_.vertex_capacity());
}

double GpuWater::volume() const {
    const uint32_t n = static_cast<uint32_t>(mirror_.tin().vertices().size());
    if (n == 0 || vertex_capacity_ == 0) return 0.0;
    const std::vector<float> depth = read_depths();
    const std::vector<float> area =
        read_floats(context_, mirror_.vertex_buffer(VertexBuffer::Area), n);
    const std::vector<float> residual = read_floats(context_, residual_.get(), n);
    const VertexArrays& va = mirror_.tin().vertices();
    double sum = 0.0;
    for (uint32_t v = 0; v < n; ++v) {
        if (!va.alive[v] || !(area[v] > 0.0f)) continue;
        sum += static_cast<double>(area[v]) * static_cast<double>(depth[v]) +
               static_cast<double>(residual[v]);
    }
    return sum;
}

double GpuWater::volume_left() const {
    if (vertex_capacity_ == 0) return 0.0;
    const std::vector<float> left = read_floats(context_, left_.get(), vertex_capacity_);
    double sum = 0.0;
    for (const float x : left)
        sum += static_cast<double>(x);
    return sum;
}

std::size_t GpuWater::copy_depths_into(Tin& tin) const {
    const std::vector<float> depth = read_depths();
    const VertexArrays& va = tin.vertices();
    const std::size_t n = std::min(va.size(), depth.size());
    std::size_t written = 0;
    for (std::size_t v = 0; v < n; ++v) {
        if (!va.alive[v]) continue;
        const double d = static_cast<double>(depth[v]);
        if (d == va.water_depth[v]) continue;
        tin.set_water_depth(VertexId{static_cast<std::uint32_t>(v)}, d);
        ++written;
    }
    return written;
}

}  // namespace sandtin::gpu
