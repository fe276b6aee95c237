// The images one frame renders into, sized from the output size (and the shadow map's own size).
#pragma once

#include "vk/buffer.h"
#include "vk/context.h"
#include "vk/image.h"

namespace vct {

struct FrameTargets {
    static constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
    static constexpr VkFormat kNormalRoughnessFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
    static constexpr VkFormat kBaseColorMetallicFormat = VK_FORMAT_R8G8B8A8_UNORM;
    static constexpr VkFormat kEmissiveOcclusionFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
    static constexpr VkFormat kMotionFormat = VK_FORMAT_R16G16_SFLOAT;
    static constexpr VkFormat kRadianceFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
    static constexpr VkFormat kIndirectFormat = VK_FORMAT_R32G32B32A32_UINT;  // lib/indirect_pack.glsl
    static constexpr VkFormat kHdrFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
    static constexpr VkFormat kLdrFormat = VK_FORMAT_R8G8B8A8_UNORM;

    vk::Image shadowMap;          // light-space depth of the main light
    vk::Image depth;              // camera depth (0 near, 1 far / background)
    vk::Image normalRoughness;    // world shading normal (xyz), perceptual roughness (w)
    vk::Image baseColorMetallic;  // base colour (rgb), metallic (a)
    vk::Image emissiveOcclusion;  // emitted radiance (rgb), ambient occlusion (a)
    vk::Image motion;             // screen-space motion in UV units: uv_previous = uv - motion
    vk::Image direct;             // direct light + emission (linear HDR)
    // Demodulated indirect light (lib/cone.glsl): diffuse = cosine-weighted mean incoming radiance (× albedo
    // in composite), specular = incoming radiance along the specular cone (× DFG in composite); both packed in
    // one texel with their weights (lib/indirect_pack.glsl).
    vk::Image indirectLow;          // trace output, ceil(w/s) × ceil(h/s) for trace scale s > 1
    // Per low-res sample, what the upsample weights compare (written by trace, lib/upsample_guide.glsl).
    vk::Image guidePosition;        // RGBA32F world position, w: 1 (0 background)
    vk::Image guideNormal;          // RGBA16F unit normal, w: smoothed specular lobe sharpness
    vk::Image guideAxis;            // RGBA16F specular lobe axis
    vk::Image indirect;             // upsample output, full res; weights: accumulated A (docs/design.md §6.5)
    // Last frame's upsample output and G-buffer, for the temporal history (swapped in by swapHistory()).
    vk::Image indirectHistory;
    vk::Image prevDepth;
    vk::Image prevNormalRoughness;
    vk::Image weightSum;          // upsample: sum of weights, r diffuse, g specular; b: 1 where re-traced
    // Pixels to re-trace (lib/shared.h ResampleListHeader + one packed pixel per entry), written by upsample,
    // read by resample's indirect dispatch; and the entry count of the last frame, copied back to the host.
    vk::Buffer resampleList;
    vk::Buffer resampleCount;
    vk::Image hdr;                // final linear HDR (what final.exr holds)
    vk::Image ldr;                // final tone-mapped sRGB (what final.png holds and the window shows)

    uint32_t width = 0, height = 0;
    uint32_t traceScale = 1;
    // Whether the indirect-light targets exist: with GI off, indirectLow through resampleCount above are not
    // allocated (empty handles; readers check this flag), except a 1×1 `indirect` for composite's binding.
    bool gi = true;

    void create(const vk::Context& context, uint32_t width, uint32_t height, uint32_t shadowMapSize,
                uint32_t traceScale = 1, bool gi = true);
    // Start of a frame: this frame's outputs and G-buffer become last frame's (no copies, the images swap).
    // Without GI there is no history: nothing to swap.
    // gbuffer false: the G-buffer is kept (a frame that reuses it, render/renderer.cpp), both copies hold it.
    void swapHistory(bool gbuffer = true);
};

}  // namespace vct
