#include "gpu/render/normal_map.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "gpu/buffer.hpp"
#include "gpu/gpu_error.hpp"
#include "gpu/vulkan_context.hpp"

namespace sandtin::render {

namespace {

constexpr VkFormat kFormat = VK_FORMAT_R32G32B32A32_SFLOAT;  // the bake's vec4 texels as they are
constexpr VkDeviceSize kTexelBytes = 16;

void grow(std::optional<Rect>& r, Vec2 p) {
    if (!r) {
        r = Rect{p, p};
        return;
    }
    r->min.x = std::min(r->min.x, p.x);
    r->min.y = std::min(r->min.y, p.y);
    r->max.x = std::max(r->max.x, p.x);
    r->max.y = std::max(r->max.y, p.y);
}

}  // namespace

std::optional<Rect> normal_map_dirty_region(const Tin& tin, const AdjacencyGraph& graph,
                                            const ChangeSet& changes) {
    std::vector<std::uint32_t> seeds;
    for (const IdRange r : changes.vertices)
        for (std::uint32_t v = r.begin; v < r.end; ++v)
            if (tin.is_alive(VertexId{v})) seeds.push_back(v);
    for (const IdRange r : changes.triangles) {
        for (std::uint32_t s = r.begin; s < r.end; ++s) {
            for (VertexId c : tin.slot_triangle(s))
                if (c.valid()) seeds.push_back(c.value);
        }
    }
    std::sort(seeds.begin(), seeds.end());
    seeds.erase(std::unique(seeds.begin(), seeds.end()), seeds.end());
    std::optional<Rect> out;
    const VertexArrays& va = tin.vertices();
    auto row = [&](std::uint32_t v, auto&& f) {
        f(v);
        if (v >= graph.vertex_capacity()) return;
        for (std::uint32_t k = graph.offset(v); k < graph.offset(v) + graph.degree(v); ++k)
            f(graph.targets()[k]);
    };
    for (std::uint32_t v : seeds) {
        row(v,
            [&](std::uint32_t w) { row(w, [&](std::uint32_t u) { grow(out, va.position[u]); }); });
    }
    return out;
}

MapGrid normal_map_grid(const Rect& domain, std::uint32_t max_side) {
    const double w = domain.width(), h = domain.height();
    const double scale = static_cast<double>(max_side) / std::max(w, h);
    const auto side = [&](double metres) {
        return std::max<std::uint32_t>(2, static_cast<std::uint32_t>(std::lround(metres * scale)));
    };
    return MapGrid(domain, side(w), side(h), SampleAt::Centres);
}

TerrainNormalMap::TerrainNormalMap(gpu::TinMirror& mirror, const Rect& domain,
                                   std::uint32_t max_side)
    : mirror_(mirror), grid_(normal_map_grid(domain, max_side)), maps_(mirror) {
    const gpu::VulkanContext& ctx = mirror.context();
    const VkDevice device = ctx.device();
    VkFormatProperties props{};
    vkGetPhysicalDeviceFormatProperties(ctx.physical_device(), kFormat, &props);
    const VkFormatFeatureFlags need =
        VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT | VK_FORMAT_FEATURE_TRANSFER_DST_BIT;
    if ((props.optimalTilingFeatures & need) != need)
        throw gpu::GpuError("the device cannot sample RGBA32F images (normal map)");
    const bool linear =
        (props.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT) != 0;

    VkImageCreateInfo ii{};
    ii.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
    ii.imageType = VK_IMAGE_TYPE_2D;
    ii.format = kFormat;
    ii.extent = {grid_.width, grid_.height, 1};
    ii.mipLevels = 1;
    ii.arrayLayers = 1;
    ii.samples = VK_SAMPLE_COUNT_1_BIT;
    ii.tiling = VK_IMAGE_TILING_OPTIMAL;
    ii.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
               VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    ii.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    ii.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkImage image = VK_NULL_HANDLE;
    gpu::check(vkCreateImage(device, &ii, nullptr, &image), "vkCreateImage (normal map)");
    image_ = gpu::UniqueImage(device, image);
    VkMemoryRequirements req{};
    vkGetImageMemoryRequirements(device, image, &req);
    VkMemoryAllocateInfo ai{};
    ai.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
    ai.allocationSize = req.size;
    ai.memoryTypeIndex =
        ctx.memory_type(req.memoryTypeBits, 0, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    VkDeviceMemory memory = VK_NULL_HANDLE;
    gpu::check(vkAllocateMemory(device, &ai, nullptr, &memory), "vkAllocateMemory (normal map)");
    memory_ = gpu::UniqueMemory(device, memory);
    gpu::check(vkBindImageMemory(device, image, memory, 0), "vkBindImageMemory (normal map)");

    VkImageViewCreateInfo vi{};
    vi.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
    vi.image = image;
    vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vi.format = kFormat;
    vi.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkImageView view = VK_NULL_HANDLE;
    gpu::check(vkCreateImageView(device, &vi, nullptr, &view), "vkCreateImageView (normal map)");
    view_ = gpu::UniqueImageView(device, view);

    VkSamplerCreateInfo si{};
    si.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO;
    // Linear where the format allows it: the map is smooth between texels too.
    si.magFilter = si.minFilter = linear ? VK_FILTER_LINEAR : VK_FILTER_NEAREST;
    si.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    si.addressModeU = si.addressModeV = si.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    si.maxLod = 0.0f;
    VkSampler sampler = VK_NULL_HANDLE;
    gpu::check(vkCreateSampler(device, &si, nullptr, &sampler), "vkCreateSampler (normal map)");
    sampler_ = gpu::UniqueSampler(device, sampler);
    bake_all();
}

TerrainNormalMap::~TerrainNormalMap() = default;

void TerrainNormalMap::bake_all() {
    bake(grid_.domain, {0, 0, grid_.width - 1, grid_.height - 1});
}

std::optional<gpu::TexelRect> TerrainNormalMap::rebake(const Tin& tin, const ChangeSet& changes) {
    const std::optional<Rect> region = normal_map_dirty_region(tin, mirror_.graph(), changes);
    if (!region) return std::nullopt;
    // Texel centres inside the region, plus one texel of margin for float rounding.
    const Vec2 lo = grid_.to_grid({region->min.x, region->max.y});
    const Vec2 hi = grid_.to_grid({region->max.x, region->min.y});
    const auto clamp_to = [](double v, std::uint32_t n) {
        return static_cast<std::uint32_t>(std::clamp(v, 0.0, static_cast<double>(n - 1)));
    };
    const gpu::TexelRect t{clamp_to(std::floor(lo.x) - 1.0, grid_.width),
                           clamp_to(std::floor(lo.y) - 1.0, grid_.height),
                           clamp_to(std::ceil(hi.x) + 1.0, grid_.width),
                           clamp_to(std::ceil(hi.y) + 1.0, grid_.height)};
    bake(*region, t);
    return t;
}

void TerrainNormalMap::bake(const Rect& region, gpu::TexelRect t) {
    const VkImage image = image_.get();
    const bool first = !initialised_;
    // One submission: the bake, then the copy of its rectangle into the texture.
    maps_.bake_region(grid_, region, t, gpu::BakeNormals::Smooth, [&](VkCommandBuffer cb) {
        const VkBuffer source = maps_.normal_map();
        // The bake's writes -> the copy; the fragment shader's reads of the last frame -> the
        // copy's writes (one frame in flight: the caller waited for it).
        gpu::memory_barrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                            VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
        VkImageMemoryBarrier b{};
        b.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
        b.srcAccessMask = first ? 0 : VK_ACCESS_SHADER_READ_BIT;
        b.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        b.oldLayout = first ? VK_IMAGE_LAYOUT_UNDEFINED : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
        b.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
        b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        b.image = image;
        b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdPipelineBarrier(
            cb, first ? VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT : VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
            VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr, 1, &b);
        VkBufferImageCopy c{};
        c.bufferOffset = (VkDeviceSize{t.row0} * grid_.width + t.col0) * kTexelBytes;
        c.bufferRowLength = grid_.width;
        c.bufferImageHeight = grid_.height;
        c.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        c.imageOffset = {static_cast<std::int32_t>(t.col0), static_cast<std::int32_t>(t.row0), 0};
        c.imageExtent = {t.width(), t.height(), 1};
        vkCmdCopyBufferToImage(cb, source, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &c);
        b.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        b.dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
        b.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
        b.newLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
        vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT,
                             VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, 0, 0, nullptr, 0, nullptr, 1,
                             &b);
    });
    initialised_ = true;
    texels_baked_ += std::uint64_t{t.width()} * t.height();
}

std::vector<float> TerrainNormalMap::read_back() const {
    const gpu::VulkanContext& ctx = mirror_.context();
    const VkDeviceSize bytes = grid_.size() * kTexelBytes;
    gpu::Buffer staging(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, gpu::MemoryUse::Readback);
    ctx.submit_and_wait([&](VkCommandBuffer cb) {
        VkImageMemoryBarrier b{};
        b.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
        b.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_SHADER_READ_BIT;
        b.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
        b.oldLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
        b.newLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
        b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        b.image = image_.get();
        b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdPipelineBarrier(cb,
                             VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                             VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr, 1, &b);
        VkBufferImageCopy c{};
        c.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        c.imageExtent = {grid_.width, grid_.height, 1};
        vkCmdCopyImageToBuffer(cb, image_.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                               staging.get(), 1, &c);
        b.srcAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
        b.dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
        b.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
        b.newLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
        vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT,
                             VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, 0, 0, nullptr, 0, nullptr, 1,
                             &b);
        gpu::memory_barrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                            VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
    });
    staging.invalidate(ctx);
    std::vector<float> out(grid_.size() * 4);
    std::memcpy(out.data(), staging.mapped(), bytes);
    return out;
}

}  // namespace sandtin::render
