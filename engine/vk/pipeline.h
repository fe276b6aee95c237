// Shader modules, pipelines and push descriptors. The bindings a pipeline is made with come from its pass's
// resource table (render/pass_resources.h) and are checked against the shaders' own SPIR-V when the pipeline
// is created (vk/binding_check.h); resources are bound with push descriptors (DescriptorWriter), with no
// descriptor pools or sets to manage.
#pragma once

#include <vulkan/vulkan.h>

#include <string>
#include <vector>

#include "vk/context.h"

namespace vct::vk {

// Reads build/shaders/NAME.spv (or $VCT_SHADER_DIR/NAME.spv); a clear error when it is missing.
std::vector<uint32_t> readSpirv(const std::string& name);
VkShaderModule loadShaderModule(const Context& context, const std::string& name);

struct Binding {
    uint32_t binding;
    VkDescriptorType type;
    VkShaderStageFlags stages;
    // What else the shader must declare there, checked against its SPIR-V (vk/binding_check.h):
    std::string name;                       // the resource, for messages
    VkFormat format = VK_FORMAT_UNDEFINED;  // the image's (undefined: not an image, or unknown)
    VkImageViewType dimension = VK_IMAGE_VIEW_TYPE_MAX_ENUM;  // 2D or 3D (max enum: not checked)
    bool depthCompare = false;                                // sampled through a depth-comparison sampler
};

// A pipeline and its layout (one push-descriptor set + optional push constants). Destroys both.
class Pipeline {
  public:
    Pipeline() = default;
    ~Pipeline() { reset(); }
    Pipeline(Pipeline&& other) noexcept { *this = std::move(other); }
    Pipeline& operator=(Pipeline&& other) noexcept;
    Pipeline(const Pipeline&) = delete;
    Pipeline& operator=(const Pipeline&) = delete;

    VkPipeline handle() const { return pipeline_; }
    VkPipelineLayout layout() const { return layout_; }
    VkPipelineBindPoint bindPoint() const { return bindPoint_; }
    VkShaderStageFlags pushConstantStages() const { return pushStages_; }
    void reset();

    // `specialization[i]` is the value of the shader's `layout(constant_id = i)` (32-bit: int, uint or bool).
    // `owner` names the pass in errors (a binding that does not match the shader's).
    static Pipeline compute(const Context& context, const std::string& owner, const std::string& shader,
                            const std::vector<Binding>& bindings, uint32_t pushConstantSize,
                            const std::vector<uint32_t>& specialization = {});

    struct GraphicsDesc {
        std::string owner;
        std::string vertexShader;
        std::string fragmentShader;  // empty: depth only
        std::vector<VkFormat> colorFormats;
        VkFormat depthFormat = VK_FORMAT_UNDEFINED;
        std::vector<Binding> bindings;
        uint32_t pushConstantSize = 0;
        bool vertexInput = true;    // core/vertex.h's Vertex layout in binding 0
        bool positionOnly = false;  // only its position attribute (depth-only passes)
        bool depthBias = false;     // dynamic depth bias (shadow maps)
        bool depthWrite = true;     // false: the depth attachment is tested, not written (blended surfaces)
        // Premultiplied Porter-Duff "over" on every colour attachment: dst = src + (1 − src.a)·dst, alpha alike.
        bool blendOver = false;
        // Specialization constants 0, 1, … (uint32 each), given to every stage.
        std::vector<uint32_t> specialization;
    };
    // Dynamic rendering; viewport, scissor and cull mode are dynamic state.
    static Pipeline graphics(const Context& context, const GraphicsDesc& desc);

    void bind(VkCommandBuffer cmd) const { vkCmdBindPipeline(cmd, bindPoint_, pipeline_); }
    void pushConstants(VkCommandBuffer cmd, const void* data, uint32_t size) const {
        vkCmdPushConstants(cmd, layout_, pushStages_, 0, size, data);
    }

  private:
    void createLayout(const Context& context, const std::vector<Binding>& bindings, uint32_t pushConstantSize,
                      VkShaderStageFlags pushStages);

    VkDevice device_ = VK_NULL_HANDLE;
    VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkPipeline pipeline_ = VK_NULL_HANDLE;
    VkPipelineBindPoint bindPoint_ = VK_PIPELINE_BIND_POINT_COMPUTE;
    VkShaderStageFlags pushStages_ = 0;
};

// Collects the resources of one dispatch or draw and pushes them as set 0. A value: it may be copied (the
// write records point into its own arrays only when pushed).
class DescriptorWriter {
  public:
    DescriptorWriter& sampled(uint32_t binding, VkImageView view, VkSampler sampler,
                              VkImageLayout layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    DescriptorWriter& storage(uint32_t binding, VkImageView view);
    DescriptorWriter& uniform(uint32_t binding, VkBuffer buffer, VkDeviceSize size = VK_WHOLE_SIZE);
    DescriptorWriter& storageBuffer(uint32_t binding, VkBuffer buffer, VkDeviceSize size = VK_WHOLE_SIZE);
    void push(const Context& context, VkCommandBuffer cmd, const Pipeline& pipeline);

  private:
    static constexpr size_t kMax = 24;
    VkDescriptorImageInfo images_[kMax]{};
    VkDescriptorBufferInfo buffers_[kMax]{};
    VkWriteDescriptorSet writes_[kMax]{};
    uint8_t info_[kMax]{};  // writes_[i]'s entry in images_ or buffers_ (by its descriptor type)
    size_t imageCount_ = 0, bufferCount_ = 0, writeCount_ = 0;
    VkWriteDescriptorSet& next(uint32_t binding, VkDescriptorType type, size_t info);
};

}  // namespace vct::vk
