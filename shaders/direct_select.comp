#version 460
#extension GL_GOOGLE_include_directive : require
// direct_select: the pixels a partial run of direct recomputes (docs/design.md §5.8), when only instances moved
// since the last frame: those where the moved bounds project (changedPixels) and those whose shadow lookup reads a
// texel the shadow pass redrew (changedShadowTexels). One thread per pixel of the rectangle dispatched (from
// params.yz); the listed pixels go to direct's indirect dispatch. On a CPU device a pixel that returns still runs
// its batch's code, masked (benchmarks/README.md, round 13): selecting first and shading only the list keeps the
// lighting code off the pixels that keep their value.
#include "lib/shared.h"
#include "lib/constants.glsl"
#include "lib/brdf.glsl"
#include "lib/gbuffer_read.glsl"
#include "lib/pixel_list.glsl"

layout(local_size_x = VCT_TILE_SIZE, local_size_y = VCT_TILE_SIZE) in;

// Resources: bound by engine/passes/direct_pass.cpp (its selection's resource table gives these binding numbers
// and is checked against them when the pipeline is made).
layout(set = 0, binding = VCT_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = 2) uniform sampler2D depthTexture;
layout(set = 0, binding = 3) uniform sampler2D normalRoughnessTexture;
// clang-format off
layout(set = 0, binding = 10, std430) buffer DirectList {
    ResampleListHeader header;
    uint pixels[];
} directList;
// clang-format on
layout(push_constant) uniform Push { DirectPushConstants push; };

#define VCT_SHADOW_COORDINATES_ONLY
#include "lib/shadow_lookup.glsl"

void main() {
    const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy) + ivec2(push.params.yz);
    if (any(greaterThanEqual(pixel, ivec2(frame.imageSize)))) return;
    bool recompute =
        all(greaterThanEqual(pixel, push.changedPixels.xy)) && all(lessThan(pixel, push.changedPixels.zw));
    const float depth = texelFetch(depthTexture, pixel, 0).r;
    // The background outside changedPixels keeps its environment; a surface its light unless its shadow changed.
    if (!recompute && !isBackground(depth)) {
        const vec2 uv = (vec2(pixel) + 0.5) * frame.texelSize;
        const vec3 p = worldFromDepth(frame.invViewProj, uv, depth);
        const vec3 n = gbufferNormal(texelFetch(normalRoughnessTexture, pixel, 0));
        recompute = shadowLookupReads(p, n, push.changedShadowTexels);
    }
    if (!recompute) return;
    // direct runs a workgroup for every VCT_TILE_SIZE² entries.
    APPEND_LISTED_PIXEL(directList, pixel, VCT_TILE_SIZE * VCT_TILE_SIZE)
}
