#include "gpu/render/terrain_renderer.hpp"

#include <cstddef>
#include <cstring>
#include <vector>

#include "gpu/gpu_error.hpp"
#include "lines_frag.spv.h"
#include "lines_vert.spv.h"
#include "terrain_frag.spv.h"
#include "terrain_vert.spv.h"
#include "water_frag.spv.h"
#include "water_vert.spv.h"

namespace sandtin::render {

namespace {

struct LinesPush {
    float view_projection[16];
    float colour[4];
};

/// Push constants of water.vert / water.frag.
struct WaterPush {
    float view_projection[16];
    float light_dir[4];  ///< xyz towards the light
    float eye[4];        ///< xyz the camera, metres, domain-centre relative
    float overlays[4];   ///< x: TerrainPush::overlays' bits
    float unused[4];
};
static_assert(sizeof(WaterPush) == 128);

/// RenderVertex attributes by shader location.
constexpr std::uint32_t kPosition = 1u << 0, kTerrainAttributes = 0x1f, kWaterAttributes = 0x1e1;

gpu::UniqueShaderModule make_module(VkDevice device, const std::uint32_t* code, std::size_t bytes) {
    VkShaderModuleCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
    info.codeSize = bytes;
    info.pCode = code;
    VkShaderModule module = VK_NULL_HANDLE;
    gpu::check(vkCreateShaderModule(device, &info, nullptr, &module), "vkCreateShaderModule");
    return gpu::UniqueShaderModule(device, module);
}

gpu::UniquePipelineLayout make_layout(VkDevice device, std::uint32_t push_bytes,
                                      VkDescriptorSetLayout set = VK_NULL_HANDLE) {
    VkPushConstantRange range{VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                              push_bytes};
    VkPipelineLayoutCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
    info.setLayoutCount = set != VK_NULL_HANDLE ? 1 : 0;
    info.pSetLayouts = &set;
    info.pushConstantRangeCount = 1;
    info.pPushConstantRanges = &range;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    gpu::check(vkCreatePipelineLayout(device, &info, nullptr, &layout), "vkCreatePipelineLayout");
    return gpu::UniquePipelineLayout(device, layout);
}

struct PipelineDesc {
    std::span<const std::uint32_t> vert;
    std::span<const std::uint32_t> frag;
    std::uint32_t attribute_mask;  ///< RenderVertex attributes the shader reads, by location
    VkPrimitiveTopology topology;
    /// LINE draws the edges of triangles (the wireframe from the triangles' own index buffer).
    VkPolygonMode polygon_mode = VK_POLYGON_MODE_FILL;
    /// Blended over what is drawn (premultiplied alpha), without writing depth.
    bool translucent = false;
};

gpu::UniquePipeline make_pipeline(VkDevice device, VkRenderPass pass, VkPipelineLayout layout,
                                  const PipelineDesc& d) {
    const gpu::UniqueShaderModule vert = make_module(device, d.vert.data(), d.vert.size_bytes());
    const gpu::UniqueShaderModule frag = make_module(device, d.frag.data(), d.frag.size_bytes());
    VkPipelineShaderStageCreateInfo stages[2]{};
    for (int i = 0; i < 2; ++i) {
        stages[i].sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
        stages[i].stage = i == 0 ? VK_SHADER_STAGE_VERTEX_BIT : VK_SHADER_STAGE_FRAGMENT_BIT;
        stages[i].module = i == 0 ? vert.get() : frag.get();
        stages[i].pName = "main";
    }
    VkVertexInputBindingDescription binding{0, sizeof(RenderVertex), VK_VERTEX_INPUT_RATE_VERTEX};
    const VkVertexInputAttributeDescription all_attributes[] = {
        {0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(RenderVertex, position)},
        {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(RenderVertex, normal)},
        {2, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(RenderVertex, albedo)},
        {3, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(RenderVertex, overlay)},
        {4, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(RenderVertex, slide)},
        {5, 0, VK_FORMAT_R32_SFLOAT, offsetof(RenderVertex, water)},
        {6, 0, VK_FORMAT_R32_SFLOAT, offsetof(RenderVertex, speed)},
        {7, 0, VK_FORMAT_R32_SFLOAT, offsetof(RenderVertex, sediment)},
        {8, 0, VK_FORMAT_R32_SFLOAT, offsetof(RenderVertex, surface)},
    };
    std::vector<VkVertexInputAttributeDescription> attributes;
    for (const VkVertexInputAttributeDescription& a : all_attributes)
        if (d.attribute_mask & (1u << a.location)) attributes.push_back(a);
    VkPipelineVertexInputStateCreateInfo input{};
    input.sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO;
    input.vertexBindingDescriptionCount = 1;
    input.pVertexBindingDescriptions = &binding;
    input.vertexAttributeDescriptionCount = static_cast<std::uint32_t>(attributes.size());
    input.pVertexAttributeDescriptions = attributes.data();
    VkPipelineInputAssemblyStateCreateInfo assembly{};
    assembly.sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO;
    assembly.topology = d.topology;
    VkPipelineViewportStateCreateInfo viewport{};
    viewport.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO;
    viewport.viewportCount = 1;
    viewport.scissorCount = 1;
    VkPipelineRasterizationStateCreateInfo raster{};
    raster.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO;
    raster.polygonMode = d.polygon_mode;
    raster.cullMode = VK_CULL_MODE_NONE;  // the camera may look from below the domain's edge
    raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    raster.lineWidth = 1.0f;
    VkPipelineMultisampleStateCreateInfo multisample{};
    multisample.sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO;
    multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    VkPipelineDepthStencilStateCreateInfo depth{};
    depth.sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO;
    depth.depthTestEnable = VK_TRUE;
    depth.depthWriteEnable = d.topology == VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST &&
                             d.polygon_mode == VK_POLYGON_MODE_FILL && !d.translucent;
    depth.depthCompareOp = VK_COMPARE_OP_LESS_OR_EQUAL;
    VkPipelineColorBlendAttachmentState blend_attachment{};
    blend_attachment.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                                      VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
    if (d.translucent) {
        blend_attachment.blendEnable = VK_TRUE;
        blend_attachment.srcColorBlendFactor = VK_BLEND_FACTOR_ONE;
        blend_attachment.dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
        blend_attachment.colorBlendOp = VK_BLEND_OP_ADD;
        blend_attachment.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
        blend_attachment.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
        blend_attachment.alphaBlendOp = VK_BLEND_OP_ADD;
    }
    VkPipelineColorBlendStateCreateInfo blend{};
    blend.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO;
    blend.attachmentCount = 1;
    blend.pAttachments = &blend_attachment;
    const VkDynamicState dynamic_states[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    VkPipelineDynamicStateCreateInfo dynamic{};
    dynamic.sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO;
    dynamic.dynamicStateCount = 2;
    dynamic.pDynamicStates = dynamic_states;

    VkGraphicsPipelineCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO;
    info.stageCount = 2;
    info.pStages = stages;
    info.pVertexInputState = &input;
    info.pInputAssemblyState = &assembly;
    info.pViewportState = &viewport;
    info.pRasterizationState = &raster;
    info.pMultisampleState = &multisample;
    info.pDepthStencilState = &depth;
    info.pColorBlendState = &blend;
    info.pDynamicState = &dynamic;
    info.layout = layout;
    info.renderPass = pass;
    VkPipeline pipeline = VK_NULL_HANDLE;
    gpu::check(vkCreateGraphicsPipelines(device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline),
               "vkCreateGraphicsPipelines");
    return gpu::UniquePipeline(device, pipeline);
}

template <std::size_t N>
std::span<const std::uint32_t> spirv(const std::uint32_t (&code)[N]) {
    return {code, N};
}

}  // namespace

TerrainRenderer::TerrainRenderer(const gpu::VulkanContext& context, VkRenderPass render_pass)
    : context_(context), placeholder_(context) {
    const VkDevice device = context.device();
    // Set 0, binding 0: the baked normal map.
    VkDescriptorSetLayoutBinding binding{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1,
                                         VK_SHADER_STAGE_FRAGMENT_BIT, nullptr};
    VkDescriptorSetLayoutCreateInfo sli{};
    sli.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
    sli.bindingCount = 1;
    sli.pBindings = &binding;
    VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
    gpu::check(vkCreateDescriptorSetLayout(device, &sli, nullptr, &set_layout),
               "vkCreateDescriptorSetLayout");
    set_layout_ = gpu::UniqueDescriptorSetLayout(device, set_layout);
    VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1};
    VkDescriptorPoolCreateInfo pi{};
    pi.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
    pi.maxSets = 1;
    pi.poolSizeCount = 1;
    pi.pPoolSizes = &size;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    gpu::check(vkCreateDescriptorPool(device, &pi, nullptr, &pool), "vkCreateDescriptorPool");
    pool_ = gpu::UniqueDescriptorPool(device, pool);
    VkDescriptorSetAllocateInfo ai{};
    ai.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
    ai.descriptorPool = pool;
    ai.descriptorSetCount = 1;
    ai.pSetLayouts = &set_layout;
    gpu::check(vkAllocateDescriptorSets(device, &ai, &set_), "vkAllocateDescriptorSets");
    use_vertex_normals();  // until a baked map is set
    terrain_layout_ = make_layout(device, sizeof(TerrainPush), set_layout);
    terrain_pipeline_ = make_pipeline(device, render_pass, terrain_layout_.get(),
                                      {spirv(kSpv_terrain_vert), spirv(kSpv_terrain_frag),
                                       kTerrainAttributes, VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST});
    water_layout_ = make_layout(device, sizeof(WaterPush));
    water_pipeline_ =
        make_pipeline(device, render_pass, water_layout_.get(),
                      {spirv(kSpv_water_vert), spirv(kSpv_water_frag), kWaterAttributes,
                       VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, VK_POLYGON_MODE_FILL, true});
    lines_layout_ = make_layout(device, sizeof(LinesPush));
    lines_pipeline_ = make_pipeline(device, render_pass, lines_layout_.get(),
                                    {spirv(kSpv_lines_vert), spirv(kSpv_lines_frag), kPosition,
                                     VK_PRIMITIVE_TOPOLOGY_LINE_LIST});
    // The wireframe as the triangles' outlines, from the index buffer the surface is drawn
    // from: nothing to build on the CPU (a list of every edge took 0.9 s at 10^6 vertices, each
    // time the triangles changed). Each inner edge is drawn twice, on the same pixels.
    if (context.features().fill_mode_non_solid) {
        wire_pipeline_ = make_pipeline(device, render_pass, lines_layout_.get(),
                                       {spirv(kSpv_lines_vert), spirv(kSpv_lines_frag), kPosition,
                                        VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, VK_POLYGON_MODE_LINE});
    }
}

void TerrainRenderer::ensure(gpu::Buffer& buffer, VkDeviceSize bytes, VkBufferUsageFlags usage) {
    ensure_mesh_buffer(context_, buffer, bytes, usage);
}

void TerrainRenderer::upload(const TerrainMesh& mesh, const MeshUpdate& update) {
    const auto& v = mesh.vertices();
    const auto& idx = mesh.indices();
    if (v.empty() || idx.empty()) return;
    const VkDeviceSize vbytes = v.size() * sizeof(RenderVertex);
    const VkDeviceSize ibytes = idx.size() * sizeof(std::uint32_t);
    const bool fits = mesh_.vertices && mesh_.vertices.size() >= vbytes && mesh_.indices &&
                      mesh_.indices.size() >= ibytes;
    // A rebuilt mesh may be another object whose versions restarted: the water list is
    // copied again at the next draw.
    if (update.resized || update.water_changed) water_version_ = ~std::uint64_t{0};
    if (!fits || update.resized) {
        bytes_uploaded_ += write_whole_mesh(context_, mesh, mesh_);
        wire_stale_ = true;
        return;
    }
    auto* vdst = static_cast<std::uint8_t*>(mesh_.vertices.mapped());
    auto* idst = static_cast<std::uint8_t*>(mesh_.indices.mapped());
    for (const IdRange& r : update.vertices) {
        const std::size_t at = std::size_t{r.begin} * sizeof(RenderVertex);
        std::memcpy(vdst + at, v.data() + r.begin, std::size_t{r.size()} * sizeof(RenderVertex));
    }
    for (const IdRange& r : update.slots) {
        const std::size_t at = std::size_t{r.begin} * 3 * sizeof(std::uint32_t);
        std::memcpy(idst + at, idx.data() + std::size_t{r.begin} * 3,
                    std::size_t{r.size()} * 3 * sizeof(std::uint32_t));
    }
    bytes_uploaded_ += update.bytes();
    mesh_.vertices.flush(context_);
    mesh_.indices.flush(context_);
    mesh_.index_count = static_cast<std::uint32_t>(idx.size());
    mesh_.vertex_bytes = static_cast<std::size_t>(vbytes);
    if (update.edges_changed) bytes_uploaded_ += write_constrained_edges(context_, mesh, mesh_);
    if (!update.slots.empty()) wire_stale_ = true;
}

void TerrainRenderer::adopt(MeshBuffers buffers, const TerrainMesh& mesh) {
    if (buffers.index_count != mesh.indices().size() ||
        buffers.vertex_bytes != mesh.vertices().size() * sizeof(RenderVertex))
        throw gpu::GpuError("TerrainRenderer::adopt: the buffers do not hold that mesh");
    bytes_uploaded_ += buffers.vertex_bytes + std::uint64_t{buffers.index_count} * 4 +
                       std::uint64_t{buffers.constrained_count} * 4;
    mesh_ = std::move(buffers);
    wire_ = gpu::Buffer();
    wire_count_ = 0;
    wire_stale_ = true;
    water_version_ = ~std::uint64_t{0};  // another mesh: its versions say nothing of ours
}

void TerrainRenderer::set_normal_map(VkImageView view, VkSampler sampler) {
    VkDescriptorImageInfo image{sampler, view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    VkWriteDescriptorSet w{};
    w.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    w.dstSet = set_;
    w.dstBinding = 0;
    w.descriptorCount = 1;
    w.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    w.pImageInfo = &image;
    vkUpdateDescriptorSets(context_.device(), 1, &w, 0, nullptr);
}

void TerrainRenderer::use_vertex_normals() {
    set_normal_map(placeholder_.view(), placeholder_.sampler());
}

void TerrainRenderer::drop_mesh() {
    mesh_ = MeshBuffers{};
    water_ = gpu::Buffer();
    water_count_ = 0;
    water_version_ = ~std::uint64_t{0};
    wire_ = gpu::Buffer();
    wire_count_ = 0;
    wire_stale_ = true;
}

std::span<const std::byte> TerrainRenderer::drawn_vertex_bytes() const {
    if (!mesh_.vertices) return {};
    return {static_cast<const std::byte*>(mesh_.vertices.mapped()), mesh_.vertex_bytes};
}

std::span<const std::byte> TerrainRenderer::drawn_index_bytes() const {
    if (!mesh_.indices) return {};
    return {static_cast<const std::byte*>(mesh_.indices.mapped()),
            std::size_t{mesh_.index_count} * sizeof(std::uint32_t)};
}

void TerrainRenderer::draw(VkCommandBuffer cb, const TerrainPush& push, const float eye[3],
                           VkExtent2D extent, const TerrainMesh& mesh) {
    water_drawn_ = 0;
    if (mesh_.index_count == 0) return;
    VkViewport viewport{
        0.0f, 0.0f, static_cast<float>(extent.width), static_cast<float>(extent.height),
        0.0f, 1.0f};
    VkRect2D scissor{{0, 0}, extent};
    vkCmdSetViewport(cb, 0, 1, &viewport);
    vkCmdSetScissor(cb, 0, 1, &scissor);
    const VkBuffer vb = mesh_.vertices.get();
    const VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(cb, 0, 1, &vb, &offset);
    vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, terrain_pipeline_.get());
    vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, terrain_layout_.get(), 0, 1, &set_,
                            0, nullptr);
    vkCmdPushConstants(cb, terrain_layout_.get(),
                       VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                       sizeof(TerrainPush), &push);
    vkCmdBindIndexBuffer(cb, mesh_.indices.get(), 0, VK_INDEX_TYPE_UINT32);
    vkCmdDrawIndexed(cb, mesh_.index_count, 1, 0, 0, 0);
    draw_water(cb, push, eye, mesh);

    // The wireframe passes cost nothing when off.
    if (!has_overlay_bit(push.overlays[0], kOverlayWireframe)) return;
    if (wire_pipeline_) {
        wire_count_ = 0;  // the edge list is for devices without line polygons
    } else if (wire_stale_) {
        const std::vector<std::uint32_t> edges = mesh.all_edges();
        wire_count_ = static_cast<std::uint32_t>(edges.size());
        if (!edges.empty()) {
            // Rebuilt between frames: the caller waited for the previous frame in upload().
            ensure(wire_, edges.size() * sizeof(std::uint32_t), VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
            std::memcpy(wire_.mapped(), edges.data(), edges.size() * sizeof(std::uint32_t));
            wire_.flush(context_);
        }
        wire_stale_ = false;
    }
    LinesPush lp{};
    std::memcpy(lp.view_projection, push.view_projection, sizeof(lp.view_projection));
    if (wire_pipeline_) {
        lp.colour[0] = lp.colour[1] = lp.colour[2] = 0.08f;
        lp.colour[3] = 1.0f;
        vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, wire_pipeline_.get());
        vkCmdPushConstants(cb, lines_layout_.get(),
                           VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                           sizeof(LinesPush), &lp);
        vkCmdBindIndexBuffer(cb, mesh_.indices.get(), 0, VK_INDEX_TYPE_UINT32);
        vkCmdDrawIndexed(cb, mesh_.index_count, 1, 0, 0, 0);
    }
    vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, lines_pipeline_.get());
    if (wire_count_ > 0) {
        lp.colour[0] = lp.colour[1] = lp.colour[2] = 0.08f;
        lp.colour[3] = 1.0f;
        vkCmdPushConstants(cb, lines_layout_.get(),
                           VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                           sizeof(LinesPush), &lp);
        vkCmdBindIndexBuffer(cb, wire_.get(), 0, VK_INDEX_TYPE_UINT32);
        vkCmdDrawIndexed(cb, wire_count_, 1, 0, 0, 0);
    }
    if (mesh_.constrained_count > 0) {
        lp.colour[0] = 1.0f;
        lp.colour[1] = 0.1f;
        lp.colour[2] = 0.6f;
        vkCmdPushConstants(cb, lines_layout_.get(),
                           VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                           sizeof(LinesPush), &lp);
        vkCmdBindIndexBuffer(cb, mesh_.constrained.get(), 0, VK_INDEX_TYPE_UINT32);
        vkCmdDrawIndexed(cb, mesh_.constrained_count, 1, 0, 0, 0);
    }
}

void TerrainRenderer::draw_water(VkCommandBuffer cb, const TerrainPush& push, const float eye[3],
                                 const TerrainMesh& mesh) {
    if (water_version_ != mesh.water_version()) {
        // Copied between frames, as the wireframe's edges are: the caller waited for the
        // previous frame in upload(). O(wet triangles), and only when the wet set changed.
        const std::vector<std::uint32_t>& wet = mesh.water_indices();
        water_count_ = static_cast<std::uint32_t>(wet.size());
        if (!wet.empty()) {
            ensure(water_, wet.size() * sizeof(std::uint32_t), VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
            std::memcpy(water_.mapped(), wet.data(), wet.size() * sizeof(std::uint32_t));
            water_.flush(context_);
            bytes_uploaded_ += wet.size() * sizeof(std::uint32_t);
        }
        water_version_ = mesh.water_version();
    }
    if (water_count_ == 0) return;  // a dry terrain records no water pass
    WaterPush wp{};
    std::memcpy(wp.view_projection, push.view_projection, sizeof(wp.view_projection));
    std::memcpy(wp.light_dir, push.light_dir, sizeof(wp.light_dir));
    for (int k = 0; k < 3; ++k)
        wp.eye[k] = eye[k];
    wp.overlays[0] = push.overlays[0];
    vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, water_pipeline_.get());
    vkCmdPushConstants(cb, water_layout_.get(),
                       VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                       sizeof(WaterPush), &wp);
    vkCmdBindIndexBuffer(cb, water_.get(), 0, VK_INDEX_TYPE_UINT32);
    vkCmdDrawIndexed(cb, water_count_, 1, 0, 0, 0);
    water_drawn_ = water_count_ / 3;
}

void TerrainRenderer::draw_outline(VkCommandBuffer cb, const float view_projection[16],
                                   std::span<const std::array<float, 3>> loop,
                                   const float colour[4]) {
    if (loop.size() < 2) return;
    const std::size_t count = loop.size() * 2;  // line list: each segment's two ends
    ensure(outline_, count * sizeof(RenderVertex), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    auto* v = static_cast<RenderVertex*>(outline_.mapped());
    for (std::size_t i = 0; i < loop.size(); ++i) {
        const auto& a = loop[i];
        const auto& b = loop[(i + 1) % loop.size()];
        v[2 * i] = RenderVertex{{a[0], a[1], a[2]}, {}, {}, {}, {}, 0.0f, 0.0f, 0.0f, a[2]};
        v[2 * i + 1] = RenderVertex{{b[0], b[1], b[2]}, {}, {}, {}, {}, 0.0f, 0.0f, 0.0f, b[2]};
    }
    outline_.flush(context_);
    LinesPush lp{};
    std::memcpy(lp.view_projection, view_projection, sizeof(lp.view_projection));
    std::memcpy(lp.colour, colour, sizeof(lp.colour));
    vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, lines_pipeline_.get());
    vkCmdPushConstants(cb, lines_layout_.get(),
                       VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                       sizeof(LinesPush), &lp);
    const VkBuffer buffer = outline_.get();
    const VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(cb, 0, 1, &buffer, &offset);
    vkCmdDraw(cb, static_cast<std::uint32_t>(count), 1, 0, 0);
}

}  // namespace sandtin::render
