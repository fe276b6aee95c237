// The images one frame renders into, declared once in a table (VCT_FRAME_TARGETS below): each row gives the
// image's name, format, size, usage and when it exists; a history row names the image whose last-frame copy
// it is. Creation, usage flags and the history swap follow from the table; the passes name these images by
// `Target` in their resource tables (render/pass_resources.h), which take the formats from here and check
// them against the shaders' declarations (docs/design.md §2.2).
#pragma once

#include <array>
#include <cstdint>

#include "vk/buffer.h"
#include "vk/context.h"
#include "vk/image.h"

namespace vct {

// Sizes: Frame = the output size W×H; Trace = the low-res trace size ⌈W/s⌉×⌈H/s⌉ (a 1×1 stand-in at trace
// scale 1, where nothing is traced at low resolution but the trace's pipeline still binds them); Shadow = the
// shadow map's own square size.
enum class TargetSize : uint8_t { Frame, Trace, Shadow };
// Usage: Depth = depth attachment, Color = colour attachment, Storage = storage image; every target can also
// be sampled and copied to the host (aux images, tests).
enum class TargetUsage : uint8_t { Depth, Color, Storage };
// Exists: Always; WithGi = only with GI (fixed for a renderer's life); StandInWithoutGi = 1×1 without GI
// (a pass that runs in both modes binds it, its shader skips it); StandInWithoutBlend = 1×1 in a scene without
// blended surfaces (composite binds it and does not read it).
enum class TargetExists : uint8_t { Always, WithGi, StandInWithoutGi, StandInWithoutBlend };
// When a history pair swaps at the start of a frame (FrameTargets::swapHistory): every frame, or only when
// the G-buffer is redrawn (a frame that reuses it keeps both copies, render/renderer.cpp).
enum class HistorySwap : uint8_t { None, EveryFrame, WithGBuffer };

// clang-format off
// T(name, format, size, usage, exists)   one image
// H(name, of, exists, swap)               last frame's `of`: same format, size and usage, swapped with it
//
// shadowMap          light-space depth of the main light
// depth              camera depth (0 near, 1 far / background)
// normalRoughness    world shading normal (xyz), effective perceptual roughness (w)
// baseColorMetallic  base colour (rgb), metallic (a)
// emissiveOcclusion  emitted radiance (rgb), ambient occlusion (a)
// motion             screen-space motion in UV units: uv_previous = uv - motion
// direct             direct light + emission (linear HDR)
// indirectLow        demodulated indirect light, diffuse and specular packed in one texel with their weights
//                    (lib/cone.glsl, lib/indirect_pack.glsl): the trace's low-res output
// indirect           the same at full resolution: the upsample output (weights: accumulated A, docs/design.md §6.5)
// guidePosition      per low-res sample, what the upsample weights compare (lib/upsample_guide.glsl):
//                    world position, w: 1 (0 background)
// guideNormal        unit normal, w: smoothed specular lobe sharpness
// guideAxis          specular lobe axis
// weightSum          upsample: sum of weights, r diffuse, g specular; b: 1 where re-traced
// transparent        the blend pass's layer of blended surfaces, premultiplied: rgb radiance·alpha summed "over"
//                    back to front, a its coverage (composite: hdr = rgb + (1 − a)·opaque)
// hdr, ldr           the final linear HDR (final.exr; written only on demand, Renderer::readFinalHdr) and
//                    tone-mapped sRGB (final.png, the window; every frame)
// the H rows         last frame's upsample output and G-buffer: the temporal history
#define VCT_FRAME_TARGETS(T, H)                                                               \
    T(shadowMap,         VK_FORMAT_D32_SFLOAT,          Shadow, Depth,   Always)              \
    T(depth,             VK_FORMAT_D32_SFLOAT,          Frame,  Depth,   Always)              \
    T(normalRoughness,   VK_FORMAT_R16G16B16A16_SFLOAT, Frame,  Color,   Always)              \
    T(baseColorMetallic, VK_FORMAT_R8G8B8A8_UNORM,      Frame,  Color,   Always)              \
    T(emissiveOcclusion, VK_FORMAT_R16G16B16A16_SFLOAT, Frame,  Color,   Always)              \
    T(motion,            VK_FORMAT_R16G16_SFLOAT,       Frame,  Color,   Always)              \
    T(direct,            VK_FORMAT_R16G16B16A16_SFLOAT, Frame,  Storage, Always)              \
    T(indirectLow,       VK_FORMAT_R32G32B32A32_UINT,   Trace,  Storage, WithGi)              \
    T(indirect,          VK_FORMAT_R32G32B32A32_UINT,   Frame,  Storage, StandInWithoutGi)    \
    T(guidePosition,     VK_FORMAT_R32G32B32A32_SFLOAT, Trace,  Storage, WithGi)              \
    T(guideNormal,       VK_FORMAT_R16G16B16A16_SFLOAT, Trace,  Storage, WithGi)              \
    T(guideAxis,         VK_FORMAT_R16G16B16A16_SFLOAT, Trace,  Storage, WithGi)              \
    T(weightSum,         VK_FORMAT_R16G16B16A16_SFLOAT, Frame,  Storage, WithGi)              \
    T(transparent,       VK_FORMAT_R16G16B16A16_SFLOAT, Frame,  Color,   StandInWithoutBlend) \
    T(hdr,               VK_FORMAT_R32G32B32A32_SFLOAT, Frame,  Storage, Always)              \
    T(ldr,               VK_FORMAT_R8G8B8A8_UNORM,      Frame,  Storage, Always)              \
    H(indirectHistory,     indirect,        WithGi, EveryFrame)                               \
    H(prevDepth,           depth,           WithGi, WithGBuffer)                              \
    H(prevNormalRoughness, normalRoughness, WithGi, WithGBuffer)
// clang-format on

#define VCT_TARGET_ENUMERATOR(name, ...) name,
enum class Target : uint8_t { VCT_FRAME_TARGETS(VCT_TARGET_ENUMERATOR, VCT_TARGET_ENUMERATOR) count };
#undef VCT_TARGET_ENUMERATOR
constexpr size_t kTargetCount = size_t(Target::count);

struct TargetDesc {
    const char* name;
    VkFormat format;
    TargetSize size;
    TargetUsage usage;
    TargetExists exists;
    Target historyOf = Target::count;  // count: not a history
    HistorySwap swap = HistorySwap::None;
};

// The table's rows, indexed by Target; a history row carries its partner's format, size and usage.
inline constexpr std::array<TargetDesc, kTargetCount> kTargets = [] {
#define VCT_TARGET_ROW(name, format, size, usage, exists) \
    TargetDesc{#name, format, TargetSize::size, TargetUsage::usage, TargetExists::exists},
#define VCT_HISTORY_ROW(name, of, exists, swap)                                                         \
    TargetDesc{                                                                                         \
        #name,      VK_FORMAT_UNDEFINED, TargetSize::Frame, TargetUsage::Storage, TargetExists::exists, \
        Target::of, HistorySwap::swap},
    std::array<TargetDesc, kTargetCount> rows = {VCT_FRAME_TARGETS(VCT_TARGET_ROW, VCT_HISTORY_ROW)};
#undef VCT_TARGET_ROW
#undef VCT_HISTORY_ROW
    for (TargetDesc& row : rows) {
        if (row.historyOf == Target::count) continue;
        const TargetDesc& of = rows[size_t(row.historyOf)];
        row.format = of.format;
        row.size = of.size;
        row.usage = of.usage;
    }
    return rows;
}();

constexpr const TargetDesc& targetDesc(Target target) {
    return kTargets[size_t(target)];
}

struct FrameTargets {
#define VCT_TARGET_MEMBER(name, ...) vk::Image name;
    VCT_FRAME_TARGETS(VCT_TARGET_MEMBER, VCT_TARGET_MEMBER)
#undef VCT_TARGET_MEMBER

    // Pixels to re-trace (lib/shared.h ResampleListHeader + one packed pixel per entry), written by upsample,
    // read by resample's indirect dispatch; and the entry count of the last frame, copied back to the host.
    // With GI only.
    vk::Buffer resampleList;
    vk::Buffer resampleCount;
    // Pixels a partial run of direct recomputes (the same header + packed pixels), written by its selection,
    // read by its indirect dispatch (docs/design.md §5.8).
    vk::Buffer directList;

    uint32_t width = 0, height = 0;
    uint32_t traceScale = 1;
    // Whether the indirect-light targets exist (the table's WithGi rows and the buffers above; readers check
    // this flag).
    bool gi = true;
    // Whether the blend pass runs (the scene has blended surfaces): the transparent layer at full size.
    bool blend = false;

    vk::Image& image(Target target);
    const vk::Image& image(Target target) const;

    void create(const vk::Context& context, uint32_t width, uint32_t height, uint32_t shadowMapSize,
                uint32_t traceScale = 1, bool gi = true, bool blend = false);
    // Start of a frame: this frame's outputs and G-buffer become last frame's (no copies, the images swap),
    // for every history pair that exists (none without GI). gbuffer false: the G-buffer is kept (a frame that
    // reuses it, render/renderer.cpp), both copies hold it.
    void swapHistory(bool gbuffer = true);
};

}  // namespace vct
