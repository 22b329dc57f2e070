#include "gpu/render/terrain_renderer.hpp"

#include <cstddef>
#include <cstring>

#include "gpu/gpu_error.hpp"
#include "terrain_frag.spv.h"
#include "terrain_vert.spv.h"

namespace sandtin::render {

namespace {

gpu::UniqueShaderModule make_module(VkDevice device, const std::uint32_t* code, std::size_t bytes) {
    VkShaderModuleCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
    info.codeSize = bytes;
    info.pCode = code;
    VkShaderModule module = VK_NULL_HANDLE;
    gpu::check(vkCreateShaderModule(device, &info, nullptr, &module), "vkCreateShaderModule");
    return gpu::UniqueShaderModule(device, module);
}

}  // namespace

TerrainRenderer::TerrainRenderer(const gpu::VulkanContext& context, VkRenderPass render_pass)
    : context_(context) {
    const VkDevice device = context.device();
    VkPushConstantRange range{VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                              sizeof(TerrainPush)};
    VkPipelineLayoutCreateInfo layout_info{};
    layout_info.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
    layout_info.pushConstantRangeCount = 1;
    layout_info.pPushConstantRanges = &range;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    gpu::check(vkCreatePipelineLayout(device, &layout_info, nullptr, &layout),
               "vkCreatePipelineLayout");
    layout_ = gpu::UniquePipelineLayout(device, layout);

    const gpu::UniqueShaderModule vert =
        make_module(device, kSpv_terrain_vert, sizeof(kSpv_terrain_vert));
    const gpu::UniqueShaderModule frag =
        make_module(device, kSpv_terrain_frag, sizeof(kSpv_terrain_frag));
    VkPipelineShaderStageCreateInfo stages[2]{};
    stages[0] = {};
    stages[0].sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
    stages[0].module = vert.get();
    stages[0].pName = "main";
    stages[1] = {};
    stages[1].sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    stages[1].module = frag.get();
    stages[1].pName = "main";

    VkVertexInputBindingDescription binding{0, sizeof(TerrainVertex), VK_VERTEX_INPUT_RATE_VERTEX};
    const VkVertexInputAttributeDescription attributes[] = {
        {0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(TerrainVertex, position)},
        {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(TerrainVertex, normal)},
        {2, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(TerrainVertex, albedo)},
        {3, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(TerrainVertex, barycentric)},
        {4, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(TerrainVertex, overlay)},
        {5, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(TerrainVertex, slide)},
    };
    VkPipelineVertexInputStateCreateInfo input{};
    input.sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO;
    input.vertexBindingDescriptionCount = 1;
    input.pVertexBindingDescriptions = &binding;
    input.vertexAttributeDescriptionCount = 6;
    input.pVertexAttributeDescriptions = attributes;
    VkPipelineInputAssemblyStateCreateInfo assembly{};
    assembly.sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO;
    assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkPipelineViewportStateCreateInfo viewport{};
    viewport.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO;
    viewport.viewportCount = 1;
    viewport.scissorCount = 1;
    VkPipelineRasterizationStateCreateInfo raster{};
    raster.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO;
    raster.polygonMode = VK_POLYGON_MODE_FILL;
    raster.cullMode = VK_CULL_MODE_NONE;  // the camera may look from below the edge of the domain
    raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    raster.lineWidth = 1.0f;
    VkPipelineMultisampleStateCreateInfo multisample{};
    multisample.sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO;
    multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    VkPipelineDepthStencilStateCreateInfo depth{};
    depth.sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO;
    depth.depthTestEnable = VK_TRUE;
    depth.depthWriteEnable = VK_TRUE;
    depth.depthCompareOp = VK_COMPARE_OP_LESS;
    VkPipelineColorBlendAttachmentState blend_attachment{};
    blend_attachment.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                                      VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
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
    info.layout = layout_.get();
    info.renderPass = render_pass;
    VkPipeline pipeline = VK_NULL_HANDLE;
    gpu::check(vkCreateGraphicsPipelines(device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline),
               "vkCreateGraphicsPipelines (terrain)");
    pipeline_ = gpu::UniquePipeline(device, pipeline);
}

void TerrainRenderer::upload(std::span<const TerrainVertex> vertices) {
    const VkDeviceSize bytes = vertices.size_bytes();
    if (bytes == 0) {
        vertex_count_ = 0;
        return;
    }
    if (!vertices_ || vertices_.size() < bytes) {
        // Grow by half again so a terrain that gains vertices does not reallocate every edit.
        vertices_ = gpu::Buffer(context_, bytes + bytes / 2, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT,
                                gpu::MemoryUse::Upload);
    }
    std::memcpy(vertices_.mapped(), vertices.data(), bytes);
    vertices_.flush(context_);
    vertex_count_ = vertices.size();
    bytes_uploaded_ += bytes;
}

void TerrainRenderer::draw(VkCommandBuffer cb, const TerrainPush& push, VkExtent2D extent) const {
    if (vertex_count_ == 0) return;
    VkViewport viewport{
        0.0f, 0.0f, static_cast<float>(extent.width), static_cast<float>(extent.height),
        0.0f, 1.0f};
    VkRect2D scissor{{0, 0}, extent};
    vkCmdSetViewport(cb, 0, 1, &viewport);
    vkCmdSetScissor(cb, 0, 1, &scissor);
    vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_.get());
    vkCmdPushConstants(cb, layout_.get(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT,
                       0, sizeof(TerrainPush), &push);
    const VkBuffer buffer = vertices_.get();
    const VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(cb, 0, 1, &buffer, &offset);
    vkCmdDraw(cb, static_cast<std::uint32_t>(vertex_count_), 1, 0, 0);
}

}  // namespace sandtin::render
