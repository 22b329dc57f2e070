#include "gpu/gpu_moisture.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

#include "gpu/gpu_error.hpp"
#include "gpu/shaders.hpp"
#include "gpu/vulkan_context.hpp"

namespace sandtin::gpu {

namespace {

// Must match shaders/moisture_common.glsl.
constexpr uint32_t kWetWord = 0, kWettestWord = 1, kSlowedWord = 2;
constexpr uint32_t kMoistureBindings = 12;

constexpr VkBufferUsageFlags kMoistureStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                                VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                                                VK_BUFFER_USAGE_TRANSFER_DST_BIT;

}  // namespace

GpuMoisture::GpuMoisture(TinMirror& mirror, MoistureSettings settings)
    : context_(mirror.context()),
      mirror_(mirror),
      settings_(settings),
      changes_(mirror.tin()),
      weights_(context_, "moisture_weights", shaders::moisture_weights(), kMoistureBindings,
               sizeof(Push)),
      wet_(context_, "moisture_wet", shaders::moisture_wet(), kMoistureBindings, sizeof(Push)),
      spread_(context_, "moisture_spread", shaders::moisture_spread(), kMoistureBindings,
              sizeof(Push)),
      finish_(context_, "moisture_finish", shaders::moisture_finish(), kMoistureBindings,
              sizeof(Push)) {
    if (!(settings_.diffusivity >= 0.0) || !std::isfinite(settings_.diffusivity))
        throw GpuError("GpuMoisture: diffusivity must be a finite number >= 0 (m²/s)");
    if (!(settings_.drying_half_life > 0.0))
        throw GpuError("GpuMoisture: drying_half_life must be > 0 (s; infinity: no drying)");
    control_ = Buffer(context_, kControlWords * 4, kMoistureStorage, MemoryUse::Device);
    control_host_ =
        Buffer(context_, kControlWords * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::Readback);
    follow_mirror();
    // Whatever moisture the terrain holds now is the GPU's to spread (and water, to wet it).
    const VertexArrays& va = mirror_.tin().vertices();
    for (std::size_t v = 0; v < va.size() && !active_; ++v)
        active_ = va.alive[v] && (va.moisture[v] > 0.0f || va.water_depth[v] > 0.0);
}

GpuMoisture::~GpuMoisture() = default;

GpuMoisture::Push GpuMoisture::push() const {
    Push pc{};
    pc.vertex_count = static_cast<uint32_t>(mirror_.tin().vertices().size());
    pc.drying = std::isfinite(settings_.drying_half_life) ? 1u : 0u;
    pc.decay = 1.0f;
    pc.threshold = static_cast<float>(kNegligibleMoisture);
    return pc;
}

void GpuMoisture::ensure_buffers() {
    const uint32_t vcap = mirror_.vertex_capacity();
    if (vcap == 0) throw GpuError("GpuMoisture: the mirror is empty");
    bool rebind = bound_generation_ != mirror_.generation();
    if (vcap != vertex_capacity_) {
        scratch_ = Buffer(context_, VkDeviceSize{vcap} * 4, kMoistureStorage, MemoryUse::Device);
        weight_sum_ = Buffer(context_, VkDeviceSize{vcap} * 4, kMoistureStorage, MemoryUse::Device);
        ratio_ = Buffer(context_, VkDeviceSize{vcap} * 4, kMoistureStorage, MemoryUse::Device);
        vertex_capacity_ = vcap;
        weights_stale_ = true;
        rebind = true;
    }
    if (rebind) {
        const std::array<VkBuffer, kMoistureBindings> buffers{
            control_.get(),
            mirror_.vertex_buffer(VertexBuffer::Position),
            mirror_.vertex_buffer(VertexBuffer::Area),
            mirror_.vertex_buffer(VertexBuffer::Moisture),
            scratch_.get(),
            mirror_.vertex_buffer(VertexBuffer::RowOffset),
            mirror_.vertex_buffer(VertexBuffer::RowDegree),
            mirror_.edge_buffer(EdgeBuffer::Target),
            mirror_.edge_buffer(EdgeBuffer::Across),
            weight_sum_.get(),
            ratio_.get(),
            mirror_.vertex_buffer(VertexBuffer::WaterDepth)};
        for (ComputeKernel* k : {&weights_, &wet_, &spread_, &finish_})
            k->bind(buffers);
        bound_generation_ = mirror_.generation();
        weights_stale_ = true;
    }
}

void GpuMoisture::follow_mirror() {
    mirror_.sync();
    ensure_buffers();
    const ChangeSet changes = changes_.take();
    if (!changes.triangles.empty()) weights_stale_ = true;  // re-triangulated: new weights
    const VertexArrays& va = mirror_.tin().vertices();
    for (const IdRange r : changes.vertices) {
        if (!changes.triangles.empty()) break;  // positions and areas may have moved
        for (uint32_t v = r.begin; v < std::min<std::size_t>(r.end, va.size()); ++v) {
            if (!va.alive[v]) weights_stale_ = true;  // a vertex died
        }
    }
    for (const IdRange r : changes.vertices) {
        for (uint32_t v = r.begin; v < std::min<std::size_t>(r.end, va.size()) && !active_; ++v)
            active_ = va.alive[v] && (va.moisture[v] > 0.0f || va.water_depth[v] > 0.0);
    }
}

void GpuMoisture::measure_weights() {
    if (!weights_stale_) return;
    const Push pc = push();
    context_.submit_and_wait([&](VkCommandBuffer cb) {
        weights_.dispatch(cb, pc.vertex_count, &pc);
        memory_barrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                       VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT);
    });
    ++dispatches_total_;
    std::vector<float> ratios =
        read_buffer_floats(context_, ratio_.get(), VkDeviceSize{pc.vertex_count} * 4);
    const VertexArrays& va = mirror_.tin().vertices();
    std::vector<double> finite;
    finite.reserve(ratios.size());
    for (std::size_t v = 0; v < ratios.size(); ++v)
        if (va.alive[v] && std::isfinite(ratios[v])) finite.push_back(ratios[v]);
    bound_ratio_ = moisture_step_ratio(finite);
    weights_stale_ = false;
}

double GpuMoisture::sub_step() {
    follow_mirror();
    measure_weights();
    if (!(settings_.diffusivity > 0.0)) return std::numeric_limits<double>::infinity();
    return 0.5 * bound_ratio_ / settings_.diffusivity;
}

GpuMoistureRun GpuMoisture::run(double seconds, const WettingByWater* wetting) {
    if (!(seconds >= 0.0) || !std::isfinite(seconds))
        throw GpuError("GpuMoisture: seconds must be a finite number >= 0");
    if (wetting && (!(wetting->depth > 0.0) || !std::isfinite(wetting->depth) ||
                    !(wetting->moisture >= 0.0f) || !(wetting->moisture <= 1.0f)))
        throw GpuError("GpuMoisture: the wetting depth must be > 0 and its moisture in [0, 1]");
    follow_mirror();
    GpuMoistureRun run;
    const bool drying = std::isfinite(settings_.drying_half_life);
    const bool changing = seconds > 0.0 && (settings_.diffusivity > 0.0 || drying);
    // Nothing wet (and no water to wet it): the GPU is not touched.
    if (!active_ || (!changing && !wetting)) return run;
    measure_weights();
    const double bound = settings_.diffusivity > 0.0 ? 0.5 * bound_ratio_ / settings_.diffusivity
                                                     : std::numeric_limits<double>::infinity();
    // Equal sub-steps within the bound (one when the bound is infinite).
    const double count = !changing              ? 0.0
                         : std::isfinite(bound) ? std::max(1.0, std::ceil(seconds / bound))
                                                : 1.0;
    const double dt = count > 0.0 ? seconds / count : 0.0;
    run.sub_steps = static_cast<std::size_t>(count);
    Push pc = push();
    pc.d_dt = static_cast<float>(settings_.diffusivity * dt);
    pc.decay = drying ? static_cast<float>(std::exp2(-dt / settings_.drying_half_life)) : 1.0f;
    if (wetting) {
        pc.wet_depth = static_cast<float>(wetting->depth);
        pc.wet_moisture = wetting->moisture;
    }
    context_.submit_and_wait([&](VkCommandBuffer cb) {
        vkCmdFillBuffer(cb, control_.get(), 0, VK_WHOLE_SIZE, 0);
        compute_transfer_barrier(cb);
        if (wetting) {
            wet_.dispatch(cb, pc.vertex_count, &pc);
            compute_transfer_barrier(cb);
            ++run.dispatches;
        }
        for (std::size_t i = 0; i < run.sub_steps; ++i) {
            pc.parity = static_cast<uint32_t>(i % 2);
            spread_.dispatch(cb, pc.vertex_count, &pc);
            compute_transfer_barrier(cb);
            ++run.dispatches;
        }
        if (run.sub_steps % 2 == 1) {
            // The last sub-step wrote the scratch half: the result belongs in the mirror's.
            const VkBufferCopy all{0, 0, VkDeviceSize{pc.vertex_count} * 4};
            vkCmdCopyBuffer(cb, scratch_.get(), mirror_.vertex_buffer(VertexBuffer::Moisture), 1,
                            &all);
            compute_transfer_barrier(cb);
        }
        finish_.dispatch(cb, pc.vertex_count, &pc);
        ++run.dispatches;
        memory_barrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                       VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
        const VkBufferCopy words{0, 0, kControlWords * 4};
        vkCmdCopyBuffer(cb, control_.get(), control_host_.get(), 1, &words);
        host_read_barrier(cb);
    });
    dispatches_total_ += run.dispatches;
    control_host_.invalidate(context_);
    std::array<uint32_t, kControlWords> w{};
    std::memcpy(w.data(), control_host_.mapped(), sizeof(w));
    run.wet = w[kWetWord];
    run.wettest = std::bit_cast<float>(w[kWettestWord]);
    run.vertices_slowed = w[kSlowedWord];
    // Still wet, or water that may wet it again at the next run.
    active_ = run.wet > 0 || (wetting != nullptr && any_water());
    return run;
}

bool GpuMoisture::any_water() const {
    const VertexArrays& va = mirror_.tin().vertices();
    for (std::size_t v = 0; v < va.size(); ++v)
        if (va.alive[v] && va.water_depth[v] > 0.0) return true;
    return false;
}

std::vector<float> GpuMoisture::read_moisture() const {
    return read_buffer_floats(context_, mirror_.vertex_buffer(VertexBuffer::Moisture),
                              VkDeviceSize{mirror_.vertex_capacity()} * 4);
}

double GpuMoisture::total() const {
    const uint32_t n = static_cast<uint32_t>(mirror_.tin().vertices().size());
    if (n == 0) return 0.0;
    const std::vector<float> m = read_moisture();
    const std::vector<float> area = read_buffer_floats(
        context_, mirror_.vertex_buffer(VertexBuffer::Area), VkDeviceSize{n} * 4);
    const VertexArrays& va = mirror_.tin().vertices();
    double sum = 0.0;
    for (uint32_t v = 0; v < n; ++v)
        if (va.alive[v] && area[v] > 0.0f)
            sum += static_cast<double>(area[v]) * static_cast<double>(m[v]);
    return sum;
}

std::size_t GpuMoisture::copy_moisture_into(Tin& tin) const {
    const std::vector<float> m = read_moisture();
    const VertexArrays& va = tin.vertices();
    const std::size_t n = std::min(va.size(), m.size());
    std::size_t written = 0;
    for (std::size_t v = 0; v < n; ++v) {
        if (!va.alive[v] || m[v] == va.moisture[v]) continue;
        tin.set_moisture(VertexId{static_cast<std::uint32_t>(v)}, m[v]);
        ++written;
    }
    return written;
}

}  // namespace sandtin::gpu
