#version 460
#extension GL_GOOGLE_include_directive : require
// composite: linear HDR result, then exposure, tone map and sRGB encoding for display.
// With GI on (GI, VCT_COMPOSITE_SPEC_GI): direct + albedo·diffuse·occlusion + specularDfg(F0, DFG)·specular, where
// diffuse and specular are the demodulated cone-traced incoming radiance (lib/cone.glsl) and DFG the split-sum
// table with multiple-scattering energy compensation (brdf.glsl). With GI off, direct already holds the
// environment's light, unoccluded (direct.comp). Blended surfaces (the blend pass's premultiplied layer) go
// over the result.
#include "lib/shared.h"
#include "lib/constants.glsl"
#include "lib/brdf.glsl"
#include "lib/color.glsl"
#include "lib/gbuffer_read.glsl"
#include "lib/indirect_pack.glsl"

layout(local_size_x = VCT_TILE_SIZE, local_size_y = VCT_TILE_SIZE) in;
layout(constant_id = VCT_COMPOSITE_SPEC_GI) const bool GI = true;         // RenderSettings::gi
layout(constant_id = VCT_COMPOSITE_SPEC_BLEND) const bool BLEND = false;  // the scene has blended surfaces
// The scene's materials have occlusion (GpuScene::hasOcclusion): else the G-buffer holds 1 (shared.h).
layout(constant_id = VCT_COMPOSITE_SPEC_OCCLUSION) const bool OCCLUSION = true;
// Also write the linear HDR image (Renderer::readFinalHdr); the frame writes the tone-mapped one alone.
layout(constant_id = VCT_COMPOSITE_SPEC_HDR) const bool HDR = true;

// Resources: bound by engine/passes/composite_pass.cpp (its resource table gives these binding numbers and is checked
// against them when the pipeline is made).
layout(set = 0, binding = VCT_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = 1, rgba16f) uniform readonly image2D directImage;
layout(set = 0, binding = 2, rgba32f) uniform writeonly image2D hdrImage;
layout(set = 0, binding = 3, rgba8) uniform writeonly image2D ldrImage;
layout(set = 0, binding = 4) uniform sampler2D depthTexture;
layout(set = 0, binding = 5) uniform sampler2D normalRoughnessTexture;
layout(set = 0, binding = 6) uniform sampler2D baseColorMetallicTexture;
layout(set = 0, binding = 7) uniform sampler2D emissiveOcclusionTexture;
// Full-res demodulated indirect light (lib/indirect_pack.glsl).
layout(set = 0, binding = 8, rgba32ui) uniform readonly uimage2D indirectImage;
// Split-sum DFG table, uv = (n·v, perceptual roughness).
layout(set = 0, binding = 10) uniform sampler2D dfgTable;
// Blended surfaces (the blend pass, BLEND): premultiplied radiance, a = their combined coverage.
layout(set = 0, binding = 11) uniform sampler2D transparentTexture;

// Indirect light leaving the surface at `pixel` towards the camera.
vec3 indirect(ivec2 pixel) {
    const float depth = texelFetch(depthTexture, pixel, 0).r;
    if (isBackground(depth)) return vec3(0.0);  // the background's radiance is already in direct
    const vec2 uv = (vec2(pixel) + 0.5) * frame.texelSize;
    const vec4 normalRoughness = texelFetch(normalRoughnessTexture, pixel, 0);
    const vec4 baseColorMetallic = texelFetch(baseColorMetallicTexture, pixel, 0);
    const float occlusion = OCCLUSION ? texelFetch(emissiveOcclusionTexture, pixel, 0).a : 1.0;
    const vec3 p = worldFromDepth(frame.invViewProj, uv, depth);
    const vec3 n = gbufferNormal(normalRoughness);
    const vec3 v = viewDirection(frame.cameraPosition - p, n);
    const float NoV = max(dot(n, v), MIN_N_DOT_V);
    // Table texel centres are at (i + 0.5)/size for both axes, so (n·v, roughness) is the uv directly.
    const vec2 dfg = textureLod(dfgTable, vec2(NoV, saturate(normalRoughness.w)), 0.0).rg;
    const vec3 albedo = diffuseAlbedo(baseColorMetallic.rgb, baseColorMetallic.a);
    const vec3 f0 = f0FromMetallic(baseColorMetallic.rgb, baseColorMetallic.a);
    const uvec4 packed = imageLoad(indirectImage, pixel);
    const vec3 diffuse = unpackIndirectDiffuse(packed).rgb;
    const vec3 specular = unpackIndirectSpecular(packed).rgb;
    return albedo * diffuse * occlusion + specularDfg(f0, dfg) * specular;
}

void main() {
    const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, ivec2(frame.imageSize)))) return;
    vec3 hdr = imageLoad(directImage, pixel).rgb;
    if (GI) hdr += indirect(pixel);
    // The blended surfaces over the opaque frame (Porter-Duff "over", premultiplied). The layer holds them
    // already composited with each other back to front; "over" is associative, so this equals drawing each
    // over the finished opaque frame in turn.
    if (BLEND) {
        const vec4 layer = texelFetch(transparentTexture, pixel, 0);
        hdr = layer.rgb + (1.0 - layer.a) * hdr;
    }
    if (HDR) imageStore(hdrImage, pixel, vec4(hdr, 1.0));
    imageStore(ldrImage, pixel, vec4(linearToSrgb(toneMapAces(hdr, frame.exposure)), 1.0));
}
