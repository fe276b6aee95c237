// What a SPIR-V module declares in its descriptor sets, read from the module itself (a small parser of the
// few instructions that say it: OpDecorate Binding / DescriptorSet, OpVariable and the types under it).
// Pipeline creation compares this with what the pass declared (vk/pipeline.h), so that a pass table and its
// shader cannot drift apart silently.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>
#include <vector>

namespace vct::vk {

// The numeric type images hold, as seen by a shader (sampler2D / usampler2D / isampler2D, image2D / uimage2D
// …).
enum class TexelClass : uint8_t { Float, Uint, Sint };

struct ShaderBinding {
    uint32_t set = 0;
    uint32_t binding = 0;
    VkDescriptorType type = VK_DESCRIPTOR_TYPE_MAX_ENUM;
    std::string name;  // the variable's (or its block's) name, when the module keeps names
    // Images only (sampled or storage):
    VkImageViewType dimension = VK_IMAGE_VIEW_TYPE_MAX_ENUM;  // 2D, 3D, cube …
    TexelClass texel = TexelClass::Float;
    bool depthCompare = false;  // a shadow sampler (sampler2DShadow)
    VkFormat format =
        VK_FORMAT_UNDEFINED;  // a storage image's layout(rgba16f …) format; undefined: none given
};

// Every descriptor a module declares (uniform and storage buffers, samplers, images), in declaration order.
// Throws vct::Error when the words are not SPIR-V or a declaration is of a kind vct does not bind.
std::vector<ShaderBinding> reflectBindings(const std::vector<uint32_t>& spirv);

// For messages: "storage image", "combined image sampler" …; "rgba16f", "rgba32ui" … (GLSL's spelling).
std::string descriptorTypeName(VkDescriptorType type);
std::string glslFormatName(VkFormat format);

}  // namespace vct::vk
