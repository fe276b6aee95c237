#include "vk/pipeline.h"

#include <cstddef>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <utility>

#include "core/vertex.h"
#include "vk/binding_check.h"
#include "vk/check.h"

namespace vct::vk {

std::vector<uint32_t> readSpirv(const std::string& name) {
    const char* overrideDir = std::getenv("VCT_SHADER_DIR");
    const std::string dir = overrideDir ? overrideDir : VCT_SHADER_DIR;
    const std::string path = dir + "/" + name + ".spv";
    std::ifstream file(path, std::ios::binary | std::ios::ate);
    if (!file) throw Error("shader '" + path + "' not found (build the vct_shaders target)");
    const auto size = static_cast<size_t>(file.tellg());
    if (size == 0 || size % 4 != 0) throw Error("shader '" + path + "' is not SPIR-V");
    std::vector<uint32_t> code(size / 4);
    file.seekg(0);
    file.read(reinterpret_cast<char*>(code.data()), std::streamsize(size));
    return code;
}

namespace {

VkShaderModule createModule(const Context& context, const std::vector<uint32_t>& code) {
    VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    info.codeSize = code.size() * sizeof(uint32_t);
    info.pCode = code.data();
    VkShaderModule module;
    VK_CHECK(vkCreateShaderModule(context.device(), &info, nullptr, &module));
    return module;
}

// Reads a shader's SPIR-V and adds what it declares to `interfaces`, for checkBindings.
std::vector<uint32_t> readWithInterface(const std::string& owner, const std::string& shader,
                                        VkShaderStageFlagBits stage,
                                        std::vector<ShaderInterface>& interfaces) {
    std::vector<uint32_t> code = readSpirv(shader);
    try {
        interfaces.push_back({stage, shader, reflectBindings(code)});
    } catch (const Error& e) {
        throw Error(owner + ": " + shader + ": " + e.what());
    }
    return code;
}

}  // namespace

VkShaderModule loadShaderModule(const Context& context, const std::string& name) {
    return createModule(context, readSpirv(name));
}

Pipeline& Pipeline::operator=(Pipeline&& other) noexcept {
    if (this != &other) {
        reset();
        device_ = std::exchange(other.device_, VK_NULL_HANDLE);
        setLayout_ = std::exchange(other.setLayout_, VK_NULL_HANDLE);
        layout_ = std::exchange(other.layout_, VK_NULL_HANDLE);
        pipeline_ = std::exchange(other.pipeline_, VK_NULL_HANDLE);
        bindPoint_ = other.bindPoint_;
        pushStages_ = other.pushStages_;
    }
    return *this;
}

void Pipeline::reset() {
    if (!device_) return;
    if (pipeline_) vkDestroyPipeline(device_, pipeline_, nullptr);
    if (layout_) vkDestroyPipelineLayout(device_, layout_, nullptr);
    if (setLayout_) vkDestroyDescriptorSetLayout(device_, setLayout_, nullptr);
    pipeline_ = VK_NULL_HANDLE;
    layout_ = VK_NULL_HANDLE;
    setLayout_ = VK_NULL_HANDLE;
    device_ = VK_NULL_HANDLE;
}

void Pipeline::createLayout(const Context& context, const std::vector<Binding>& bindings,
                            uint32_t pushConstantSize, VkShaderStageFlags pushStages) {
    device_ = context.device();
    std::vector<VkDescriptorSetLayoutBinding> layoutBindings;
    for (const Binding& b : bindings) layoutBindings.push_back({b.binding, b.type, 1, b.stages, nullptr});
    VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    setInfo.flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR;
    setInfo.bindingCount = uint32_t(layoutBindings.size());
    setInfo.pBindings = layoutBindings.data();
    VK_CHECK(vkCreateDescriptorSetLayout(device_, &setInfo, nullptr, &setLayout_));

    pushStages_ = pushConstantSize ? pushStages : 0;
    VkPushConstantRange range{pushStages, 0, pushConstantSize};
    VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layoutInfo.setLayoutCount = 1;
    layoutInfo.pSetLayouts = &setLayout_;
    layoutInfo.pushConstantRangeCount = pushConstantSize ? 1 : 0;
    layoutInfo.pPushConstantRanges = &range;
    VK_CHECK(vkCreatePipelineLayout(device_, &layoutInfo, nullptr, &layout_));
}

Pipeline Pipeline::compute(const Context& context, const std::string& owner, const std::string& shader,
                           const std::vector<Binding>& bindings, uint32_t pushConstantSize,
                           const std::vector<uint32_t>& specialization) {
    std::vector<ShaderInterface> interfaces;
    const std::vector<uint32_t> code =
        readWithInterface(owner, shader, VK_SHADER_STAGE_COMPUTE_BIT, interfaces);
    checkBindings(owner, bindings, interfaces);
    Pipeline pipeline;
    pipeline.bindPoint_ = VK_PIPELINE_BIND_POINT_COMPUTE;
    std::vector<VkSpecializationMapEntry> entries;
    for (uint32_t id = 0; id < specialization.size(); ++id)
        entries.push_back({id, uint32_t(id * sizeof(uint32_t)), sizeof(uint32_t)});
    const VkSpecializationInfo specializationInfo{uint32_t(entries.size()), entries.data(),
                                                  specialization.size() * sizeof(uint32_t),
                                                  specialization.data()};
    pipeline.createLayout(context, bindings, pushConstantSize, VK_SHADER_STAGE_COMPUTE_BIT);
    VkShaderModule module = createModule(context, code);
    VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = module;
    info.stage.pName = "main";
    if (!specialization.empty()) info.stage.pSpecializationInfo = &specializationInfo;
    info.layout = pipeline.layout_;
    VkResult result =
        vkCreateComputePipelines(context.device(), VK_NULL_HANDLE, 1, &info, nullptr, &pipeline.pipeline_);
    vkDestroyShaderModule(context.device(), module, nullptr);
    VK_CHECK(result);
    return pipeline;
}

Pipeline Pipeline::graphics(const Context& context, const GraphicsDesc& desc) {
    std::vector<ShaderInterface> interfaces;
    std::vector<std::vector<uint32_t>> codes;
    codes.push_back(readWithInterface(desc.owner, desc.vertexShader, VK_SHADER_STAGE_VERTEX_BIT, interfaces));
    if (!desc.fragmentShader.empty())
        codes.push_back(
            readWithInterface(desc.owner, desc.fragmentShader, VK_SHADER_STAGE_FRAGMENT_BIT, interfaces));
    checkBindings(desc.owner, desc.bindings, interfaces);

    Pipeline pipeline;
    pipeline.bindPoint_ = VK_PIPELINE_BIND_POINT_GRAPHICS;
    pipeline.createLayout(context, desc.bindings, desc.pushConstantSize,
                          VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT);

    std::vector<VkShaderModule> modules;
    std::vector<VkPipelineShaderStageCreateInfo> stages;
    std::vector<VkSpecializationMapEntry> entries;
    for (uint32_t id = 0; id < desc.specialization.size(); ++id)
        entries.push_back({id, uint32_t(id * sizeof(uint32_t)), sizeof(uint32_t)});
    const VkSpecializationInfo specializationInfo{uint32_t(entries.size()), entries.data(),
                                                  desc.specialization.size() * sizeof(uint32_t),
                                                  desc.specialization.data()};
    auto addStage = [&](VkShaderStageFlagBits stage, const std::vector<uint32_t>& code) {
        modules.push_back(createModule(context, code));
        VkPipelineShaderStageCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
        info.stage = stage;
        info.module = modules.back();
        info.pName = "main";
        if (!desc.specialization.empty()) info.pSpecializationInfo = &specializationInfo;
        stages.push_back(info);
    };
    addStage(VK_SHADER_STAGE_VERTEX_BIT, codes[0]);
    if (!desc.fragmentShader.empty()) addStage(VK_SHADER_STAGE_FRAGMENT_BIT, codes[1]);

    VkVertexInputBindingDescription vertexBinding{0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX};
    VkVertexInputAttributeDescription attributes[] = {
        {0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position)},
        {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, normal)},
        {2, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(Vertex, uv)},
        {3, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(Vertex, tangent)},
        {4, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(Vertex, color)},
    };
    VkPipelineVertexInputStateCreateInfo vertexInput{
        VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    if (desc.vertexInput) {
        vertexInput.vertexBindingDescriptionCount = 1;
        vertexInput.pVertexBindingDescriptions = &vertexBinding;
        vertexInput.vertexAttributeDescriptionCount = desc.positionOnly ? 1 : uint32_t(std::size(attributes));
        vertexInput.pVertexAttributeDescriptions = attributes;
    }
    VkPipelineInputAssemblyStateCreateInfo inputAssembly{
        VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    inputAssembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    viewport.viewportCount = 1;
    viewport.scissorCount = 1;
    VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    raster.polygonMode = VK_POLYGON_MODE_FILL;
    raster.cullMode = VK_CULL_MODE_NONE;
    // glTF front faces are counter-clockwise; the projection's y flip (Vulkan clip space) keeps them so.
    raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    raster.depthBiasEnable = desc.depthBias;
    raster.lineWidth = 1.0f;
    VkPipelineMultisampleStateCreateInfo multisample{
        VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    depth.depthTestEnable = desc.depthFormat != VK_FORMAT_UNDEFINED;
    depth.depthWriteEnable = depth.depthTestEnable && desc.depthWrite;
    depth.depthCompareOp = VK_COMPARE_OP_LESS_OR_EQUAL;
    std::vector<VkPipelineColorBlendAttachmentState> blendAttachments(desc.colorFormats.size());
    for (auto& attachment : blendAttachments) {
        attachment.colorWriteMask = 0xF;
        if (!desc.blendOver) continue;
        attachment.blendEnable = VK_TRUE;
        attachment.srcColorBlendFactor = attachment.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
        attachment.dstColorBlendFactor = attachment.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
        attachment.colorBlendOp = attachment.alphaBlendOp = VK_BLEND_OP_ADD;
    }
    VkPipelineColorBlendStateCreateInfo blend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    blend.attachmentCount = uint32_t(blendAttachments.size());
    blend.pAttachments = blendAttachments.data();
    std::vector<VkDynamicState> dynamicStates = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR,
                                                 VK_DYNAMIC_STATE_CULL_MODE};
    if (desc.depthBias) dynamicStates.push_back(VK_DYNAMIC_STATE_DEPTH_BIAS);
    VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
    dynamic.dynamicStateCount = uint32_t(dynamicStates.size());
    dynamic.pDynamicStates = dynamicStates.data();
    VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
    rendering.colorAttachmentCount = uint32_t(desc.colorFormats.size());
    rendering.pColorAttachmentFormats = desc.colorFormats.data();
    rendering.depthAttachmentFormat = desc.depthFormat;

    VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
    info.pNext = &rendering;
    info.stageCount = uint32_t(stages.size());
    info.pStages = stages.data();
    info.pVertexInputState = &vertexInput;
    info.pInputAssemblyState = &inputAssembly;
    info.pViewportState = &viewport;
    info.pRasterizationState = &raster;
    info.pMultisampleState = &multisample;
    info.pDepthStencilState = &depth;
    info.pColorBlendState = &blend;
    info.pDynamicState = &dynamic;
    info.layout = pipeline.layout_;
    VkResult result =
        vkCreateGraphicsPipelines(context.device(), VK_NULL_HANDLE, 1, &info, nullptr, &pipeline.pipeline_);
    for (VkShaderModule module : modules) vkDestroyShaderModule(context.device(), module, nullptr);
    VK_CHECK(result);
    return pipeline;
}

VkWriteDescriptorSet& DescriptorWriter::next(uint32_t binding, VkDescriptorType type, size_t info) {
    if (writeCount_ == kMax) throw Error("DescriptorWriter: too many bindings");
    info_[writeCount_] = uint8_t(info);
    VkWriteDescriptorSet& write = writes_[writeCount_++];
    write = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.dstBinding = binding;
    write.descriptorCount = 1;
    write.descriptorType = type;
    return write;
}

DescriptorWriter& DescriptorWriter::sampled(uint32_t binding, VkImageView view, VkSampler sampler,
                                            VkImageLayout layout) {
    next(binding, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, imageCount_);
    images_[imageCount_++] = {sampler, view, layout};
    return *this;
}

DescriptorWriter& DescriptorWriter::storage(uint32_t binding, VkImageView view) {
    next(binding, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, imageCount_);
    images_[imageCount_++] = {VK_NULL_HANDLE, view, VK_IMAGE_LAYOUT_GENERAL};
    return *this;
}

DescriptorWriter& DescriptorWriter::uniform(uint32_t binding, VkBuffer buffer, VkDeviceSize size) {
    next(binding, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, bufferCount_);
    buffers_[bufferCount_++] = {buffer, 0, size};
    return *this;
}

DescriptorWriter& DescriptorWriter::storageBuffer(uint32_t binding, VkBuffer buffer, VkDeviceSize size) {
    next(binding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, bufferCount_);
    buffers_[bufferCount_++] = {buffer, 0, size};
    return *this;
}

void DescriptorWriter::push(const Context& context, VkCommandBuffer cmd, const Pipeline& pipeline) {
    for (size_t i = 0; i < writeCount_; ++i) {
        const bool buffer = writes_[i].descriptorType == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER ||
                            writes_[i].descriptorType == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        writes_[i].pImageInfo = buffer ? nullptr : &images_[info_[i]];
        writes_[i].pBufferInfo = buffer ? &buffers_[info_[i]] : nullptr;
    }
    context.cmdPushDescriptorSet(cmd, pipeline.bindPoint(), pipeline.layout(), 0, uint32_t(writeCount_),
                                 writes_);
}

}  // namespace vct::vk
