#include "gpu/render/normal_map.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "gpu/buffer.hpp"
#include "gpu/gpu_error.hpp"
#include "gpu/image.hpp"
#include "gpu/vulkan_context.hpp"

namespace sandtin::render {

namespace {

// The bake's vec4 texels land in a staging image as they are, and a blit converts the
// rectangle to the texture: x and y of the unit normal as 16-bit signed normalised values
// (z = sqrt(1 - x^2 - y^2) > 0 in the shader). A quarter of the float texture's bytes: the
// fragment stage samples it for every terrain pixel.
constexpr VkFormat kStagingFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
constexpr VkFormat kTextureFormat = VK_FORMAT_R16G16_SNORM;
constexpr VkDeviceSize kTexelBytes = 16;  // of the bake's buffer

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
                                   std::uint32_t max_side, bool bake_now)
    : mirror_(mirror), grid_(normal_map_grid(domain, max_side)), maps_(mirror) {
    const gpu::VulkanContext& ctx = mirror.context();
    const VkDevice device = ctx.device();
    const auto features = [&](VkFormat f) {
        VkFormatProperties props{};
        vkGetPhysicalDeviceFormatProperties(ctx.physical_device(), f, &props);
        return props.optimalTilingFeatures;
    };
    const VkFormatFeatureFlags staging_need =
        VK_FORMAT_FEATURE_TRANSFER_DST_BIT | VK_FORMAT_FEATURE_BLIT_SRC_BIT;
    const VkFormatFeatureFlags texture_need = VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT |
                                              VK_FORMAT_FEATURE_BLIT_DST_BIT |
                                              VK_FORMAT_FEATURE_TRANSFER_SRC_BIT;
    if ((features(kStagingFormat) & staging_need) != staging_need ||
        (features(kTextureFormat) & texture_need) != texture_need)
        throw gpu::GpuError("the device cannot blit RGBA32F into RG16_SNORM images (normal map)");
    const bool linear =
        (features(kTextureFormat) & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT) != 0;

    staging_ = gpu::Image(ctx, {kStagingFormat,
                                {grid_.width, grid_.height},
                                VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                                "normal map staging"});
    image_ = gpu::Image(ctx, {kTextureFormat,
                              {grid_.width, grid_.height},
                              VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                                  VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                              "normal map"});
    view_ = gpu::create_image_view(device, image_.get(), kTextureFormat, VK_IMAGE_ASPECT_COLOR_BIT,
                                   "normal map");

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
    if (bake_now) bake_all();
}

TerrainNormalMap::~TerrainNormalMap() = default;

void TerrainNormalMap::bake_all() {
    bake(grid_.domain, {0, 0, grid_.width - 1, grid_.height - 1});
    next_row_ = grid_.height;
}

void TerrainNormalMap::bake_rows(std::uint32_t rows) {
    if (complete() || rows == 0) return;
    const std::uint32_t last = std::min(grid_.height, next_row_ + rows) - 1;
    // The first band computes every vertex normal (none is valid yet); the later ones reuse
    // them: an empty region recomputes none.
    bake(next_row_ == 0 ? grid_.domain : Rect{}, {0, next_row_, grid_.width - 1, last});
    next_row_ = last + 1;
}

std::optional<gpu::TexelRect> TerrainNormalMap::rebake(const Tin& tin, const ChangeSet& changes) {
    if (!complete())
        throw std::logic_error("TerrainNormalMap::rebake: the map is still being baked");
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
    const VkImage staging = staging_.get();
    const VkImage texture = image_.get();
    const bool first = !initialised_;
    // One submission: the bake, the copy of its rectangle into the staging image and the blit
    // (format conversion) of that rectangle into the texture.
    maps_.bake_region(grid_, region, t, gpu::BakeNormals::Smooth, [&](VkCommandBuffer cb) {
        // The bake's writes -> the copy. Between bakes the staging image rests as a blit
        // source; the previous blit read it, so the copy waits for that too.
        gpu::memory_barrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                            VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
        gpu::image_barrier(cb, staging, VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                           first ? 0 : VK_ACCESS_TRANSFER_READ_BIT,
                           first ? VK_IMAGE_LAYOUT_UNDEFINED : VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                           VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                           VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        VkBufferImageCopy c{};
        c.bufferOffset = (VkDeviceSize{t.row0} * grid_.width + t.col0) * kTexelBytes;
        c.bufferRowLength = grid_.width;
        c.bufferImageHeight = grid_.height;
        c.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        c.imageOffset = {static_cast<std::int32_t>(t.col0), static_cast<std::int32_t>(t.row0), 0};
        c.imageExtent = {t.width(), t.height(), 1};
        vkCmdCopyBufferToImage(cb, maps_.normal_map(), staging,
                               VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &c);
        gpu::image_barrier(cb, staging, VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                           VK_ACCESS_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                           VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT,
                           VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        // The fragment shader's reads of the last frame -> the blit's writes (one frame in
        // flight: the caller waited for it).
        gpu::image_barrier(
            cb, texture, VK_IMAGE_ASPECT_COLOR_BIT,
            first ? VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT : VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
            first ? 0 : VK_ACCESS_SHADER_READ_BIT,
            first ? VK_IMAGE_LAYOUT_UNDEFINED : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
            VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
            VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        VkImageBlit blit{};
        blit.srcSubresource = blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        blit.srcOffsets[0] = blit.dstOffsets[0] = c.imageOffset;
        blit.srcOffsets[1] = blit.dstOffsets[1] = {static_cast<std::int32_t>(t.col1 + 1),
                                                   static_cast<std::int32_t>(t.row1 + 1), 1};
        vkCmdBlitImage(cb, staging, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, texture,
                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_NEAREST);
        gpu::image_barrier(cb, texture, VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                           VK_ACCESS_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                           VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT,
                           VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    });
    initialised_ = true;
    texels_baked_ += std::uint64_t{t.width()} * t.height();
}

std::vector<float> TerrainNormalMap::read_back() const {
    const gpu::VulkanContext& ctx = mirror_.context();
    const VkDeviceSize bytes = grid_.size() * 4;  // two 16-bit values per texel
    gpu::Buffer host(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, gpu::MemoryUse::Readback);
    const VkImage texture = image_.get();
    ctx.submit_and_wait([&](VkCommandBuffer cb) {
        gpu::image_barrier(cb, texture, VK_IMAGE_ASPECT_COLOR_BIT,
                           VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                           VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT,
                           VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT,
                           VK_ACCESS_TRANSFER_READ_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        VkBufferImageCopy c{};
        c.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        c.imageExtent = {grid_.width, grid_.height, 1};
        vkCmdCopyImageToBuffer(cb, texture, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, host.get(), 1,
                               &c);
        gpu::image_barrier(cb, texture, VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                           VK_ACCESS_TRANSFER_READ_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                           VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT,
                           VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        gpu::host_read_barrier(cb);
    });
    host.invalidate(ctx);
    std::vector<std::int16_t> raw(grid_.size() * 2);
    std::memcpy(raw.data(), host.mapped(), bytes);
    // Decoded as the shader does: snorm -> [-1, 1], z from the unit length.
    std::vector<float> out(grid_.size() * 4, 0.0f);
    for (std::size_t i = 0; i < grid_.size(); ++i) {
        const float x = std::max(static_cast<float>(raw[2 * i]) / 32767.0f, -1.0f);
        const float y = std::max(static_cast<float>(raw[2 * i + 1]) / 32767.0f, -1.0f);
        out[4 * i] = x;
        out[4 * i + 1] = y;
        out[4 * i + 2] = std::sqrt(std::max(1.0f - x * x - y * y, 0.0f));
    }
    return out;
}

}  // namespace sandtin::render
