#include "gpu/gpu_sediment.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "gpu/gpu_error.hpp"
#include "gpu/shaders.hpp"
#include "gpu/vulkan_context.hpp"

namespace sandtin::gpu {

namespace {

constexpr uint32_t kSedimentBindings = 18;
constexpr VkBufferUsageFlags kSedimentStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                                VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                                                VK_BUFFER_USAGE_TRANSFER_DST_BIT;

bool rate(double r) {
    return r >= 0.0 && std::isfinite(r);
}

}  // namespace

GpuSediment::GpuSediment(GpuWater& water, SedimentOptions options)
    : context_(water.mirror().context()),
      water_(water),
      mirror_(water.mirror()),
      options_(options),
      changes_(water.mirror().tin()),
      capacity_(context_, "sediment_capacity", shaders::sediment_capacity(), kSedimentBindings,
                sizeof(Push)),
      exchange_(context_, "sediment_exchange", shaders::sediment_exchange(), kSedimentBindings,
                sizeof(Push)),
      carry_(context_, "sediment_carry", shaders::sediment_carry(), kSedimentBindings,
             sizeof(Push)),
      settle_(context_, "sediment_settle", shaders::sediment_settle(), kSedimentBindings,
              sizeof(Push)),
      kind_of_material_(65536, 0) {
    if (!rate(options_.capacity) || !rate(options_.pick_up_rate) || !rate(options_.drop_rate) ||
        !rate(options_.least_slope) || !rate(options_.max_concentration) ||
        options_.max_concentration > 1.0)
        throw GpuError(
            "GpuSediment: every constant must be finite and >= 0, max_concentration at most 1");
    const VertexArrays& va = mirror_.tin().vertices();
    for (std::size_t v = 0; v < va.size(); ++v)
        if (va.alive[v]) palette_.push_back(va.material[v]);
    std::sort(palette_.begin(), palette_.end());
    palette_.erase(std::unique(palette_.begin(), palette_.end()), palette_.end());
    if (palette_.empty()) palette_.push_back(0);
    if (palette_.size() > kMaxKinds)
        throw GpuError("GpuSediment: the terrain holds " + std::to_string(palette_.size()) +
                       " materials; the GPU sediment carries at most " + std::to_string(kMaxKinds));
    for (std::size_t k = 0; k < palette_.size(); ++k)
        kind_of_material_[palette_[k]] = static_cast<uint32_t>(k + 1);
    changes_.take();  // everything: ensure_buffers uploads every vertex's bed kind
    ensure_buffers();
}

GpuSediment::~GpuSediment() = default;

GpuSediment::Push GpuSediment::push(uint32_t parity, double dt) const {
    Push pc{};
    pc.vertex_count = static_cast<uint32_t>(mirror_.tin().vertices().size());
    pc.edge_capacity = water_.edge_capacity();
    pc.parity = parity;
    pc.half = half_;
    pc.kinds = static_cast<uint32_t>(palette_.size());
    pc.stride = vertex_capacity_;
    pc.dt = static_cast<float>(dt);
    pc.capacity_k = static_cast<float>(options_.capacity);
    pc.pick_up = static_cast<float>(options_.pick_up_rate);
    pc.drop_rate = static_cast<float>(options_.drop_rate);
    pc.least_slope = static_cast<float>(options_.least_slope);
    pc.max_concentration = static_cast<float>(options_.max_concentration);
    return pc;
}

void GpuSediment::ensure_buffers() {
    const uint32_t vcap = mirror_.vertex_capacity();
    const auto kinds = static_cast<uint32_t>(palette_.size());
    const VertexArrays& va = mirror_.tin().vertices();
    std::vector<IdRange> kinds_to_upload;
    if (vcap != vertex_capacity_) {
        // Suspension, drops and bed residuals are sand: carried over into the new layout
        // (each half of held and kind starts at its own stride).
        const VkDeviceSize n = vcap;
        Buffer held(context_, 2 * n * 4, kSedimentStorage, MemoryUse::Device);
        Buffer kind(context_, 2 * n * kinds * 4, kSedimentStorage, MemoryUse::Device);
        Buffer dropped(context_, n * kinds * 4, kSedimentStorage, MemoryUse::Device);
        Buffer residual(context_, n * 4, kSedimentStorage, MemoryUse::Device);
        const VkDeviceSize old = std::min(vertex_capacity_, vcap);
        context_.submit_and_wait([&](VkCommandBuffer cb) {
            for (Buffer* b : {&held, &kind, &dropped, &residual})
                vkCmdFillBuffer(cb, b->get(), 0, VK_WHOLE_SIZE, 0);
            if (old == 0) return;
            memory_barrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                           VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
            const VkBufferCopy current_held{VkDeviceSize{half_} * vertex_capacity_ * 4, 0, old * 4};
            vkCmdCopyBuffer(cb, held_.get(), held.get(), 1, &current_held);
            const VkBufferCopy current_kind{VkDeviceSize{half_} * vertex_capacity_ * kinds * 4, 0,
                                            old * kinds * 4};
            vkCmdCopyBuffer(cb, kind_.get(), kind.get(), 1, &current_kind);
            const VkBufferCopy drops{0, 0, old * kinds * 4};
            vkCmdCopyBuffer(cb, dropped_.get(), dropped.get(), 1, &drops);
            const VkBufferCopy rest{0, 0, old * 4};
            vkCmdCopyBuffer(cb, bed_residual_.get(), residual.get(), 1, &rest);
        });
        held_ = std::move(held);
        kind_ = std::move(kind);
        dropped_ = std::move(dropped);
        bed_residual_ = std::move(residual);
        half_ = 0;
        capacity_buffer_ = Buffer(context_, n * 4, kSedimentStorage, MemoryUse::Device);
        scale_ = Buffer(context_, n * 4, kSedimentStorage, MemoryUse::Device);
        bed_kind_ = Buffer(context_, n * 4, kSedimentStorage, MemoryUse::Device);
        vertex_capacity_ = vcap;
        kinds_to_upload.push_back(
            {0, static_cast<uint32_t>(std::min<std::size_t>(va.size(), vcap))});
    }
    if (bound_generation_ != mirror_.generation() || !kinds_to_upload.empty()) {
        const std::array<VkBuffer, kSedimentBindings> buffers{
            mirror_.vertex_buffer(VertexBuffer::Position),
            mirror_.vertex_buffer(VertexBuffer::Height),
            mirror_.vertex_buffer(VertexBuffer::Bedrock),
            mirror_.vertex_buffer(VertexBuffer::Area),
            mirror_.vertex_buffer(VertexBuffer::WaterDepth),
            mirror_.vertex_buffer(VertexBuffer::RowOffset),
            mirror_.vertex_buffer(VertexBuffer::RowDegree),
            mirror_.edge_buffer(EdgeBuffer::Target),
            mirror_.edge_buffer(EdgeBuffer::Reverse),
            mirror_.edge_buffer(EdgeBuffer::Length),
            water_.flux_buffer(),
            capacity_buffer_.get(),
            held_.get(),
            kind_.get(),
            dropped_.get(),
            scale_.get(),
            bed_kind_.get(),
            bed_residual_.get()};
        for (ComputeKernel* k : {&capacity_, &exchange_, &carry_, &settle_})
            k->bind(buffers);
        bound_generation_ = mirror_.generation();
    }
    // Vertices the terrain changed: their bed is the terrain's again (the mirror uploaded it),
    // so their bed residual goes, and their material may be new.
    const ChangeSet changes = changes_.take();
    for (const IdRange r : changes.vertices)
        kinds_to_upload.push_back({r.begin, std::min<uint32_t>(r.end, vertex_capacity_)});
    if (kinds_to_upload.empty()) return;
    std::vector<uint32_t> bed_kinds;
    StagingRing& ring = mirror_.staging();
    for (const IdRange r : kinds_to_upload) {
        if (r.end <= r.begin) continue;
        bed_kinds.assign(r.end - r.begin, 0);
        for (uint32_t v = r.begin; v < r.end; ++v) {
            if (v >= va.size() || !va.alive[v]) continue;
            const uint32_t k = kind_of_material_[va.material[v]];
            if (k == 0)
                throw GpuError("GpuSediment: material " + std::to_string(va.material[v]) +
                               " appeared on the terrain after the sediment started; make a "
                               "new GpuSediment for it");
            bed_kinds[v - r.begin] = k - 1;
        }
        ring.upload(bed_kind_.get(), VkDeviceSize{r.begin} * 4, bed_kinds.data(),
                    VkDeviceSize{r.end - r.begin} * 4);
    }
    ring.flush();
    if (changes.vertices.empty()) return;
    // Suspension at a vertex that died is lost: counted, and cleared with the residuals. (Read
    // back only when a vertex died.)
    bool died = false;
    for (const IdRange r : changes.vertices) {
        for (uint32_t v = r.begin; v < std::min(r.end, vertex_capacity_) && !died; ++v)
            died = v >= va.size() || !va.alive[v];
    }
    const std::vector<float> held =
        died ? read(held_, vertex_capacity_, VkDeviceSize{half_} * vertex_capacity_)
             : std::vector<float>();
    context_.submit_and_wait([&](VkCommandBuffer cb) {
        for (const IdRange r : changes.vertices) {
            const uint32_t end = std::min(r.end, vertex_capacity_);
            if (end <= r.begin) continue;
            vkCmdFillBuffer(cb, bed_residual_.get(), VkDeviceSize{r.begin} * 4,
                            VkDeviceSize{end - r.begin} * 4, 0);
            for (uint32_t v = r.begin; v < end && died; ++v) {
                if ((v < va.size() && va.alive[v]) || !(held[v] > 0.0f)) continue;
                lost_ += static_cast<double>(held[v]);
                vkCmdFillBuffer(cb, held_.get(), (VkDeviceSize{half_} * vertex_capacity_ + v) * 4,
                                4, 0);
            }
        }
    });
}

void GpuSediment::prepare() {
    ensure_buffers();
}

void GpuSediment::record_step(VkCommandBuffer cb, uint32_t parity, double dt) {
    const Push pc = push(parity, dt);
    capacity_.dispatch(cb, pc.vertex_count, &pc);
    compute_transfer_barrier(cb);
    exchange_.dispatch(cb, pc.vertex_count, &pc);
    compute_transfer_barrier(cb);
    carry_.dispatch(cb, pc.vertex_count, &pc);
    half_ = 1 - half_;  // carry wrote the other half: it is the current one now
}

void GpuSediment::settle_all() {
    mirror_.sync();
    ensure_buffers();
    const Push pc = push(0, 0.0);
    context_.submit_and_wait(
        [&](VkCommandBuffer cb) { settle_.dispatch(cb, pc.vertex_count, &pc); });
}

std::vector<float> GpuSediment::read(const Buffer& b, VkDeviceSize floats,
                                     VkDeviceSize offset) const {
    if (offset == 0) return read_buffer_floats(context_, b.get(), floats * 4);
    const std::vector<float> all = read_buffer_floats(context_, b.get(), (offset + floats) * 4);
    return std::vector<float>(all.begin() + static_cast<std::ptrdiff_t>(offset), all.end());
}

double GpuSediment::suspended() const {
    const std::vector<float> held =
        read(held_, vertex_capacity_, VkDeviceSize{half_} * vertex_capacity_);
    double sum = 0.0;
    for (const float h : held)
        sum += static_cast<double>(h);
    return sum;
}

double GpuSediment::sand_volume() const {
    const uint32_t n = static_cast<uint32_t>(mirror_.tin().vertices().size());
    const std::vector<float> height = read_buffer_floats(
        context_, mirror_.vertex_buffer(VertexBuffer::Height), VkDeviceSize{n} * 4);
    const std::vector<float> area = read_buffer_floats(
        context_, mirror_.vertex_buffer(VertexBuffer::Area), VkDeviceSize{n} * 4);
    const std::vector<float> residual = read(bed_residual_, n);
    const VertexArrays& va = mirror_.tin().vertices();
    double sum = suspended();
    for (uint32_t v = 0; v < n; ++v) {
        if (!va.alive[v] || !(area[v] > 0.0f)) continue;
        sum += static_cast<double>(area[v]) * static_cast<double>(height[v]) +
               static_cast<double>(residual[v]);
    }
    return sum;
}

std::vector<double> GpuSediment::read_beds() const {
    const VkDeviceSize n = vertex_capacity_;
    const std::vector<float> height =
        read_buffer_floats(context_, mirror_.vertex_buffer(VertexBuffer::Height), n * 4);
    const std::vector<float> area =
        read_buffer_floats(context_, mirror_.vertex_buffer(VertexBuffer::Area), n * 4);
    const std::vector<float> residual = read(bed_residual_, n);
    std::vector<double> beds(height.size());
    for (std::size_t v = 0; v < height.size(); ++v) {
        // The residual is sand the float height could not take: in double it can.
        const double rest =
            area[v] > 0.0f ? static_cast<double>(residual[v]) / static_cast<double>(area[v]) : 0.0;
        beds[v] = static_cast<double>(height[v]) + mirror_.height_origin() + rest;
    }
    return beds;
}

std::size_t GpuSediment::copy_beds_into(Tin& tin) const {
    const std::vector<double> beds = read_beds();
    const VertexArrays& va = tin.vertices();
    const std::size_t n = std::min(va.size(), beds.size());
    std::size_t written = 0;
    for (std::size_t v = 0; v < n; ++v) {
        if (!va.alive[v] || beds[v] == va.height[v]) continue;
        // The mirror's float of the terrain's height reads back as another double: only a
        // change the float can tell apart is the GPU's.
        const auto mirrored = static_cast<float>(va.height[v] - mirror_.height_origin());
        if (static_cast<double>(mirrored) + mirror_.height_origin() == beds[v]) continue;
        tin.set_height(VertexId{static_cast<std::uint32_t>(v)}, beds[v]);
        ++written;
    }
    return written;
}

std::vector<double> GpuSediment::dropped() const {
    const auto kinds = palette_.size();
    const std::vector<float> d = read(dropped_, VkDeviceSize{vertex_capacity_} * kinds);
    std::vector<double> out(vertex_capacity_, 0.0);
    for (std::size_t v = 0; v < out.size(); ++v)
        for (std::size_t k = 0; k < kinds; ++k)
            out[v] += static_cast<double>(d[v * kinds + k]);
    return out;
}

std::vector<std::uint16_t> GpuSediment::deposited_materials() const {
    const auto kinds = palette_.size();
    const std::vector<float> d = read(dropped_, VkDeviceSize{vertex_capacity_} * kinds);
    const VertexArrays& va = mirror_.tin().vertices();
    std::vector<std::uint16_t> out(vertex_capacity_, 0);
    for (std::size_t v = 0; v < out.size() && v < va.size(); ++v) {
        if (!va.alive[v]) continue;
        std::size_t best = kind_of_material_[va.material[v]] - 1;
        for (std::size_t k = 0; k < kinds; ++k)
            if (d[v * kinds + k] > d[v * kinds + best]) best = k;
        out[v] = palette_[best];
    }
    return out;
}

}  // namespace sandtin::gpu
