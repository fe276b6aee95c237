#include "vk/binding_check.h"

#include "core/error.h"

namespace vct::vk {

namespace {

TexelClass texelClassOf(VkFormat format) {
    switch (format) {
        case VK_FORMAT_R8_UINT:
        case VK_FORMAT_R8G8_UINT:
        case VK_FORMAT_R8G8B8A8_UINT:
        case VK_FORMAT_R16_UINT:
        case VK_FORMAT_R16G16_UINT:
        case VK_FORMAT_R16G16B16A16_UINT:
        case VK_FORMAT_R32_UINT:
        case VK_FORMAT_R32G32_UINT:
        case VK_FORMAT_R32G32B32A32_UINT:
        case VK_FORMAT_A2B10G10R10_UINT_PACK32:
        case VK_FORMAT_R64_UINT:
            return TexelClass::Uint;
        case VK_FORMAT_R8_SINT:
        case VK_FORMAT_R8G8_SINT:
        case VK_FORMAT_R8G8B8A8_SINT:
        case VK_FORMAT_R16_SINT:
        case VK_FORMAT_R16G16_SINT:
        case VK_FORMAT_R16G16B16A16_SINT:
        case VK_FORMAT_R32_SINT:
        case VK_FORMAT_R32G32_SINT:
        case VK_FORMAT_R32G32B32A32_SINT:
        case VK_FORMAT_R64_SINT:
            return TexelClass::Sint;
        default:
            return TexelClass::Float;  // float, unorm, snorm and depth formats all read as float
    }
}

const char* texelName(TexelClass texel) {
    return texel == TexelClass::Uint ? "uint" : texel == TexelClass::Sint ? "int" : "float";
}

std::string dimensionName(VkImageViewType dimension) {
    switch (dimension) {
        case VK_IMAGE_VIEW_TYPE_1D:
            return "1D";
        case VK_IMAGE_VIEW_TYPE_2D:
            return "2D";
        case VK_IMAGE_VIEW_TYPE_3D:
            return "3D";
        case VK_IMAGE_VIEW_TYPE_CUBE:
            return "cube";
        default:
            return "arrayed";
    }
}

bool isImage(VkDescriptorType type) {
    return type == VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER || type == VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE ||
           type == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
}

// "a storage image rgba16f", "a combined image sampler" …
std::string describe(VkDescriptorType type, VkFormat format) {
    std::string text = "a " + descriptorTypeName(type);
    if (type == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE) text += " " + glslFormatName(format);
    return text;
}

}  // namespace

void checkBindings(const std::string& owner, const std::vector<Binding>& declared,
                   const std::vector<ShaderInterface>& shaders) {
    VkShaderStageFlags pipelineStages = 0;
    for (const ShaderInterface& shader : shaders) pipelineStages |= shader.stage;
    auto fail = [&](uint32_t binding, const std::string& name, const std::string& what) {
        throw Error(owner + ": binding " + std::to_string(binding) + (name.empty() ? "" : " (" + name + ")") +
                    ": " + what);
    };

    std::vector<bool> used(declared.size(), false);
    for (const ShaderInterface& shader : shaders) {
        for (const ShaderBinding& s : shader.bindings) {
            const std::string theirs =
                shader.shader + " declares " + describe(s.type, s.format) + " ('" + s.name + "')";
            if (s.set != 0)
                fail(s.binding, "",
                     shader.shader + " declares it in set " + std::to_string(s.set) +
                         "; passes bind set 0 only");
            size_t index = 0;
            while (index < declared.size() && declared[index].binding != s.binding) ++index;
            if (index == declared.size()) fail(s.binding, "", theirs + ", which the pass does not bind");
            const Binding& d = declared[index];
            used[index] = true;
            if (d.type != s.type)
                fail(s.binding, d.name, "the pass binds " + describe(d.type, d.format) + ", " + theirs);
            if (!(d.stages & shader.stage))
                fail(s.binding, d.name, "the pass binds it for other stages than " + shader.shader + "'s");
            if (!isImage(s.type) || d.format == VK_FORMAT_UNDEFINED) continue;
            if (s.type == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE && s.format != VK_FORMAT_UNDEFINED &&
                s.format != d.format)
                fail(s.binding, d.name, "the pass binds " + describe(d.type, d.format) + ", " + theirs);
            if (d.dimension != VK_IMAGE_VIEW_TYPE_MAX_ENUM && s.dimension != d.dimension)
                fail(s.binding, d.name,
                     "the pass binds a " + dimensionName(d.dimension) + " image, " + shader.shader +
                         " declares a " + dimensionName(s.dimension) + " one ('" + s.name + "')");
            if (texelClassOf(d.format) != s.texel)
                fail(s.binding, d.name,
                     "the pass binds an image of " + std::string(texelName(texelClassOf(d.format))) +
                         " texels (" + glslFormatName(d.format) + "), " + shader.shader + " reads " +
                         texelName(s.texel) + " ones ('" + s.name + "')");
            if (s.type == VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER && s.depthCompare != d.depthCompare)
                fail(s.binding, d.name,
                     std::string("the pass binds it ") + (d.depthCompare ? "with" : "without") +
                         " a depth-comparison sampler, " + shader.shader + " declares " +
                         (s.depthCompare ? "a shadow sampler" : "a plain sampler") + " ('" + s.name + "')");
        }
    }
    for (size_t i = 0; i < declared.size(); ++i)
        if (!used[i] && (declared[i].stages & pipelineStages))
            fail(declared[i].binding, declared[i].name,
                 "the pass binds " + describe(declared[i].type, declared[i].format) +
                     " that no shader of the pipeline declares");
}

}  // namespace vct::vk
