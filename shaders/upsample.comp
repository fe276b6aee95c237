#version 460
#extension GL_GOOGLE_include_directive : require
// upsample: the low-res demodulated indirect light (diffuse, specular) back to full resolution over space and
// time (DESIGN §3.5, seed 004 §5.3). For full-res pixel i:
//   spatial   S = Σ_j f·w_z·w_lobe·I_j over the low-res samples j of a (2r)² window, W_s = Σ_j f·w_z·w_lobe;
//             sample j was traced at full-res pixel s·j + o_k, and the trace stored the geometry and lobe it
//             saw there (the guide images), exact per sample;
//   temporal  the history H (last frame's output, accumulated weight A in alpha) reprojected with the motion
//             vector, bilinear over 4 texels, each validated with the same weights against last frame's
//             G-buffer: T = Σ_t b_t·w_t·A_t·H_t, T_w = Σ_t b_t·w_t·A_t;
//   output    O = (S + γT) / (W_s + γT_w), new A = min(W_s + γT_w, A_max);
//   sum of weights W = W_s + γT_w, kept per pixel; W < τ puts the pixel on the resample list (compacted,
//             with the indirect dispatch of the resample pass counted up as entries are appended).
// Diffuse and specular are weighted separately, each with its own lobe (lib/upsample_weights.glsl). Never a
// division by a zero sum: with no weight at all the pixel takes its nearest valid sample (and is re-traced).
#include "lib/shared.h"
#include "lib/constants.glsl"
#include "lib/brdf.glsl"
#include "lib/gbuffer_read.glsl"
#include "lib/upsample_weights.glsl"
#include "lib/upsample_guide.glsl"

layout(local_size_x = VCT_TILE_SIZE, local_size_y = VCT_TILE_SIZE) in;

layout(set = 0, binding = VCT_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = VCT_UPSAMPLE_BINDING_DIFFUSE_LOW) uniform sampler2D diffuseLow;
layout(set = 0, binding = VCT_UPSAMPLE_BINDING_SPECULAR_LOW) uniform sampler2D specularLow;
layout(set = 0, binding = VCT_UPSAMPLE_BINDING_DEPTH) uniform sampler2D depthTexture;
layout(set = 0, binding = VCT_UPSAMPLE_BINDING_NORMAL_ROUGHNESS) uniform sampler2D normalRoughnessTexture;
layout(set = 0, binding = VCT_UPSAMPLE_BINDING_MOTION) uniform sampler2D motionTexture;
layout(set = 0, binding = VCT_UPSAMPLE_BINDING_PREV_DEPTH) uniform sampler2D prevDepthTexture;
layout(set = 0, binding = VCT_UPSAMPLE_BINDING_PREV_NORMAL_ROUGHNESS) uniform sampler2D prevNormalRoughnessTexture;
layout(set = 0, binding = VCT_UPSAMPLE_BINDING_GUIDE_POSITION) uniform sampler2D guidePositionTexture;
layout(set = 0, binding = VCT_UPSAMPLE_BINDING_GUIDE_NORMAL) uniform sampler2D guideNormalTexture;
layout(set = 0, binding = VCT_UPSAMPLE_BINDING_GUIDE_AXIS) uniform sampler2D guideAxisTexture;
layout(set = 0, binding = VCT_UPSAMPLE_BINDING_DIFFUSE_HISTORY) uniform sampler2D diffuseHistory;
layout(set = 0, binding = VCT_UPSAMPLE_BINDING_SPECULAR_HISTORY) uniform sampler2D specularHistory;
layout(set = 0, binding = VCT_UPSAMPLE_BINDING_DIFFUSE, rgba16f) uniform writeonly image2D diffuseImage;
layout(set = 0, binding = VCT_UPSAMPLE_BINDING_SPECULAR, rgba16f) uniform writeonly image2D specularImage;
layout(set = 0, binding = VCT_UPSAMPLE_BINDING_WEIGHT_SUM, rgba16f) uniform writeonly image2D weightSumImage;
layout(set = 0, binding = VCT_UPSAMPLE_BINDING_RESAMPLE_LIST, std430) buffer ResampleList {
    ResampleListHeader header;
    uint pixels[];
} resampleList;

// (diffuse, specular) weight of sample b seen from pixel a, by the chosen guide. The diffuse lobes share one
// sharpness, so their lobe weight is the angle term alone (lib/upsample_weights.glsl, equal λ̄).
vec2 guideWeights(Guide a, Guide b) {
    const int mode = int(frame.upsampleMode.x);
    if (mode == VCT_WEIGHTS_BILINEAR) return vec2(1.0);
    const float wz = planeWeight(a.n, a.p, b.p, a.cameraDistance);
    if (mode == VCT_WEIGHTS_NORMAL) return vec2(wz * normalWeight(a.n, b.n, frame.upsampleParams.z));
    const float beta = frame.upsampleParams.x;
    const float diffuseSharpness = smoothedSharpness(1.0 / SG_DIFFUSE_SHARPNESS, frame.upsampleParams.y);
    return wz * vec2(lobeWeightSmoothed(a.n, diffuseSharpness, b.n, diffuseSharpness, beta),
                     lobeWeightSmoothed(a.specularAxis, a.specularSharpness, b.specularAxis, b.specularSharpness,
                                        beta));
}

void main() {
    const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    const ivec2 size = ivec2(frame.imageSize.xy);
    if (any(greaterThanEqual(pixel, size))) return;
    const int scale = max(int(frame.voxelParams.w), 1);

    const float depth = texelFetch(depthTexture, pixel, 0).r;
    if (isBackground(depth)) {
        // Nothing to light: no indirect light, never re-traced.
        imageStore(diffuseImage, pixel, vec4(0.0));
        imageStore(specularImage, pixel, vec4(0.0));
        imageStore(weightSumImage, pixel, vec4(0.0));
        return;
    }
    if (scale == 1) {
        // Every pixel traced this frame (the reference): a copy, with the weight of one fresh sample.
        imageStore(diffuseImage, pixel, vec4(texelFetch(diffuseLow, pixel, 0).rgb, 1.0));
        imageStore(specularImage, pixel, vec4(texelFetch(specularLow, pixel, 0).rgb, 1.0));
        imageStore(weightSumImage, pixel, vec4(1.0, 1.0, 0.0, 0.0));
        return;
    }

    const vec2 uv = (vec2(pixel) + 0.5) * frame.imageSize.zw;
    const float kappa = frame.upsampleParams.y;
    const Guide here = guideFromGBuffer(texelFetch(normalRoughnessTexture, pixel, 0),
                                        worldFromDepth(frame.invViewProj, uv, depth), frame.cameraPosition.xyz,
                                        kappa);

    // ---- spatial: the low-res samples around the pixel, each at its own jittered full-res position ----
    const ivec2 lowSize = textureSize(diffuseLow, 0);
    const ivec2 jitter = frame.traceJitter.xy;
    // Tent radius in low-res texels: 1 (bilinear: the 2×2 nearest) without a guide; 2 (4×4) with one, so that
    // the guide has candidates left to choose from where it rejects some.
    const int radius = int(frame.upsampleMode.x) == VCT_WEIGHTS_BILINEAR ? 1 : 2;
    const vec2 lowCoord = vec2(pixel - jitter) / float(scale);  // this pixel in low-res sample units
    const ivec2 base = ivec2(floor(lowCoord));
    vec3 spatialDiffuse = vec3(0.0), spatialSpecular = vec3(0.0);
    vec2 spatialWeight = vec2(0.0);
    // Fallback for a zero sum: the sample nearest the pixel (largest kernel weight) that is not background.
    vec3 nearestDiffuse = vec3(0.0), nearestSpecular = vec3(0.0);
    float nearestKernel = -1.0;
    // A fixed 4×4 window (constant bounds, so the compiler unrolls it); radius 1 leaves the outer ring at f = 0.
    for (int dy = -1; dy <= 2; ++dy) {
        for (int dx = -1; dx <= 2; ++dx) {
            if (radius == 1 && (dx == -1 || dx == 2 || dy == -1 || dy == 2)) continue;
            const int x = base.x + dx, y = base.y + dy;
            const ivec2 low = ivec2(x, y);
            if (any(lessThan(low, ivec2(0))) || any(greaterThanEqual(low, lowSize))) continue;
            const ivec2 at = min(low * scale + jitter, size - 1);  // where trace.comp traced it
            const vec4 position = texelFetch(guidePositionTexture, low, 0);
            if (position.w == 0.0) continue;  // background
            const float f = tentKernel((vec2(pixel) - vec2(at)) / float(scale), float(radius));
            const vec3 diffuseSample = texelFetch(diffuseLow, low, 0).rgb;
            const vec3 specularSample = texelFetch(specularLow, low, 0).rgb;
            if (f > nearestKernel) {
                nearestKernel = f;
                nearestDiffuse = diffuseSample;
                nearestSpecular = specularSample;
            }
            if (f <= 0.0) continue;
            Guide there;
            there.p = position.xyz;
            const vec4 normalSharpness = texelFetch(guideNormalTexture, low, 0);
            there.n = normalSharpness.xyz;
            there.specularSharpness = normalSharpness.w;
            there.specularAxis = texelFetch(guideAxisTexture, low, 0).xyz;
            const vec2 w = f * guideWeights(here, there);
            spatialDiffuse += w.x * diffuseSample;
            spatialSpecular += w.y * specularSample;
            spatialWeight += w;
        }
    }

    // ---- temporal: last frame's output where this surface was, validated against last frame's G-buffer ----
    vec3 historyDiffuse = vec3(0.0), historySpecular = vec3(0.0);
    vec2 historyWeight = vec2(0.0);
    if (frame.upsampleMode.y > 0.5) {
        const vec2 prevUv = uv - texelFetch(motionTexture, pixel, 0).xy;
        const vec2 prevCoord = prevUv * frame.imageSize.xy - 0.5;  // texel-centre coordinates
        const ivec2 prevBase = ivec2(floor(prevCoord));
        const vec2 fraction = prevCoord - vec2(prevBase);
        for (int tap = 0; tap < 4; ++tap) {
            const ivec2 offset = ivec2(tap & 1, tap >> 1);
            const ivec2 texel = prevBase + offset;
            if (any(lessThan(texel, ivec2(0))) || any(greaterThanEqual(texel, size))) continue;
            const float prevDepth = texelFetch(prevDepthTexture, texel, 0).r;
            if (isBackground(prevDepth)) continue;
            const vec2 bilinear = mix(vec2(1.0) - fraction, fraction, vec2(offset));
            const vec2 texelUv = (vec2(texel) + 0.5) * frame.imageSize.zw;
            const Guide then = guideFromGBuffer(texelFetch(prevNormalRoughnessTexture, texel, 0),
                                                worldFromDepth(frame.prevInvViewProj, texelUv, prevDepth),
                                                frame.prevCameraPosition.xyz, kappa);
            const vec4 diffuseTexel = texelFetch(diffuseHistory, texel, 0);
            const vec4 specularTexel = texelFetch(specularHistory, texel, 0);
            // Each tap's weight is its bilinear share × the guide × the weight it had accumulated (alpha).
            const vec2 w = bilinear.x * bilinear.y * guideWeights(here, then) * vec2(diffuseTexel.a, specularTexel.a);
            historyDiffuse += w.x * diffuseTexel.rgb;
            historySpecular += w.y * specularTexel.rgb;
            historyWeight += w;
        }
    }

    const float gamma = frame.upsampleParams.w;
    const vec2 weightSum = spatialWeight + gamma * historyWeight;
    // The smallest sum worth dividing by: fp16 history and underflowing lobe weights leave denormal sums.
    const float minSum = 1e-4;
    const vec3 diffuse = weightSum.x > minSum ? (spatialDiffuse + gamma * historyDiffuse) / weightSum.x
                                              : nearestDiffuse;
    const vec3 specular = weightSum.y > minSum ? (spatialSpecular + gamma * historySpecular) / weightSum.y
                                               : nearestSpecular;
    const float maxWeight = frame.upsampleMode.w;
    const bool resample = min(weightSum.x, weightSum.y) < frame.upsampleMode.z;
    imageStore(diffuseImage, pixel, vec4(diffuse, min(weightSum.x, maxWeight)));
    imageStore(specularImage, pixel, vec4(specular, min(weightSum.y, maxWeight)));
    imageStore(weightSumImage, pixel, vec4(weightSum, resample ? 1.0 : 0.0, 0.0));

    if (resample) {
        const uint index = atomicAdd(resampleList.header.counts.x, 1u);
        resampleList.pixels[index] = uint(pixel.x) | (uint(pixel.y) << 16);
        // One more workgroup of the resample pass for every VCT_RESAMPLE_GROUP_SIZE entries.
        if (index % uint(VCT_RESAMPLE_GROUP_SIZE) == 0u) atomicAdd(resampleList.header.dispatch.x, 1u);
    }
}
