#version 460
#extension GL_GOOGLE_include_directive : require
// direct: one thread per pixel; sums every punctual light (the main one shadowed), emission and, with GI off, the
// environment's light; the background is the environment.
#include "lib/shared.h"
#include "lib/constants.glsl"
#include "lib/brdf.glsl"
#include "lib/gbuffer_read.glsl"
#include "lib/lights.glsl"
#include "lib/pixel_list.glsl"
#include "lib/cone.glsl"
#include "lib/shadow_pcf.glsl"

layout(local_size_x = VCT_TILE_SIZE, local_size_y = VCT_TILE_SIZE) in;
layout(constant_id = VCT_DIRECT_SPEC_GI) const bool GI = true;  // --gi (VCT_FLAG_GI), as a constant: shared.h
// The scene's materials emit / have occlusion (GpuScene::hasEmission, hasOcclusion): else the G-buffer holds no
// emission and occlusion 1, and is not read for them (shared.h).
layout(constant_id = VCT_DIRECT_SPEC_EMISSION) const bool EMISSION = true;
layout(constant_id = VCT_DIRECT_SPEC_OCCLUSION) const bool OCCLUSION = true;
// Only the pixels direct_select.comp listed (a partial run, an indirect dispatch of VCT_TILE_SIZE² per group).
layout(constant_id = VCT_DIRECT_SPEC_LIST) const bool LIST = false;

// Resources: bound by engine/passes/direct_pass.cpp (its resource table gives these binding numbers and is checked
// against them when the pipeline is made).
layout(set = 0, binding = VCT_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = 1) readonly buffer Lights { GpuLight lights[]; };
layout(set = 0, binding = 2) uniform sampler2D depthTexture;
layout(set = 0, binding = 3) uniform sampler2D normalRoughnessTexture;
layout(set = 0, binding = 4) uniform sampler2D baseColorMetallicTexture;
layout(set = 0, binding = 5) uniform sampler2D emissiveOcclusionTexture;
layout(set = 0, binding = 6) uniform sampler2DShadow shadowMap;
layout(set = 0, binding = 7, rgba16f) uniform writeonly image2D outputImage;
layout(set = 0, binding = 8) uniform sampler2D environmentMap;  // lib/environment_sample.glsl
// clang-format off
layout(set = 0, binding = 10, std430) readonly buffer DirectList {
    ResampleListHeader header;
    uint pixels[];
} directList;
// clang-format on

#include "lib/environment_sample.glsl"

#include "lib/shadow_lookup.glsl"

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (LIST) {
        const uint index = gl_WorkGroupID.x * uint(VCT_TILE_SIZE * VCT_TILE_SIZE) + gl_LocalInvocationIndex;
        if (index >= directList.header.counts.x) return;
        pixel = unpackListedPixel(directList.pixels[index]);
    }
    const ivec2 size = ivec2(frame.imageSize);
    if (any(greaterThanEqual(pixel, size))) return;
    const vec2 uv = (vec2(pixel) + 0.5) * frame.texelSize;
    const float depth = texelFetch(depthTexture, pixel, 0).r;
    if (isBackground(depth)) {
        const vec3 farPoint = worldFromDepth(frame.invViewProj, uv, 1.0);
        imageStore(outputImage, pixel,
                   vec4(environmentRadiance(normalize(farPoint - frame.cameraPosition)), 1.0));
        return;
    }
    const vec4 normalRoughness = texelFetch(normalRoughnessTexture, pixel, 0);
    const vec3 p = worldFromDepth(frame.invViewProj, uv, depth);
    const vec3 n = gbufferNormal(normalRoughness);  // never NaN: a zero-length normal reads as +y
    const vec4 baseColorMetallic = texelFetch(baseColorMetallicTexture, pixel, 0);
    // Occlusion is read only with GI off (composite applies it to the indirect light).
    const vec4 emissiveOcclusion = EMISSION || (OCCLUSION && !GI)
                                       ? texelFetch(emissiveOcclusionTexture, pixel, 0)
                                       : vec4(0.0, 0.0, 0.0, 1.0);
    const vec3 v = viewDirection(frame.cameraPosition - p, n);

    vec3 radiance = emissiveOcclusion.rgb;
    const int lightCount = int(frame.lighting.lightCount);
    const int shadowLight = frame.lighting.shadowLight;
    for (int i = 0; i < lightCount; ++i) {
        const IncidentLight light = incidentLight(lights[i], p);
        vec3 reflected = light.radiance * evalBrdfCosine(n, v, light.towardsLight, baseColorMetallic.rgb,
                                                         baseColorMetallic.a, normalRoughness.w);
        if (i == shadowLight && any(greaterThan(reflected, vec3(0.0)))) reflected *= shadowVisibility(p, n);
        radiance += reflected;
    }
    // The environment, only with GI off (with GI on, composite adds the cone-traced indirect light instead),
    // unoccluded but for the material's occlusion: its cosine-weighted mean radiance (what the six diffuse
    // cones read of an open sky) × the diffuse albedo, plus what the specular cone would read × F0. A uniform
    // environment L gives L·(albedo + F0), the constant ambient term this replaced.
    if (!GI) {
        radiance +=
            environmentReflected(n, v, baseColorMetallic.rgb, baseColorMetallic.a, normalRoughness.w) *
            emissiveOcclusion.a;
    }
    imageStore(outputImage, pixel, vec4(radiance, 1.0));
}
