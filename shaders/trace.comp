#version 460
#extension GL_GOOGLE_include_directive : require
// trace: one thread per LOW-res pixel (x, y), traced at the jittered full-res pixel s·(x, y) + o_k
// (docs/design.md §6.1: o_k cycles through the s×s offsets, so s² frames visit every full-res pixel) from the
// full-res G-buffer there: 6 diffuse cones around n and 1 specular cone along reflect(−v, n) through the voxel
// grid. Outputs are demodulated (lib/cone.glsl); the upsample pass knows o_k and reads the same G-buffer texels.
// In the cone layout (GPUs: RenderSettings::TraceLayout) a low-res pixel has 8 invocations, 7 of which march one
// cone each.
#include "lib/shared.h"
#include "lib/constants.glsl"
#include "lib/brdf.glsl"
#include "lib/cone.glsl"
#include "lib/gbuffer_read.glsl"
#include "lib/upsample_weights.glsl"
#include "lib/upsample_guide.glsl"
#include "lib/indirect_pack.glsl"

// z: the invocations per pixel, 1 (the pixel layout: a pixel's cones one after the other) or CONE_LANES_PER_PIXEL
// (the cone layout: one cone each; RenderSettings::TraceLayout, lib/cone_trace.glsl).
layout(local_size_x = VCT_TILE_SIZE, local_size_y = VCT_TILE_SIZE, local_size_z_id = VCT_SPEC_CONE_LANES) in;

// The trace scale s (lib/shared.h, VCT_SPEC_TRACE_SCALE: the one way it reaches the shaders).
layout(constant_id = VCT_SPEC_TRACE_SCALE) const int SCALE = 4;
// Trace scale 1: every pixel traced, written straight into the full-res indirect targets with the weight of
// one fresh sample; no upsample pass runs, so no guides are written (their images are 1×1 stand-ins).
const bool FULL_RESOLUTION = SCALE == 1;

// Resources: bound by engine/passes/trace_pass.cpp (its resource table gives these binding numbers and is checked
// against them when the pipeline is made).
layout(set = 0, binding = VCT_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform sampler2D depthTexture;
layout(set = 0, binding = 2) uniform sampler2D normalRoughnessTexture;
layout(set = 0, binding = 3)
    uniform sampler3D voxels;  // radiance (premultiplied rgb) + opacity, mips 1.. (lib/cone_trace.glsl)
layout(set = 0, binding = 4, rgba32ui) uniform writeonly uimage2D
    indirectImage;  // packed (lib/indirect_pack.glsl); low res (full res at scale 1)
// What the upsample weights compare, per low-res sample (lib/upsample_guide.glsl).
layout(set = 0, binding = 6,
       rgba32f) uniform writeonly image2D guidePositionImage;  // world position, w: 1 (0: background)
layout(set = 0, binding = 7,
       rgba16f) uniform writeonly image2D guideNormalImage;  // unit normal, w: smoothed specular sharpness λ̄
layout(set = 0, binding = 8, rgba16f) uniform writeonly image2D guideAxisImage;  // specular lobe axis

// The environment: what a cone that leaves the grid sees (lib/environment_sample.glsl).
layout(set = 0, binding = 9) uniform sampler2D environmentMap;
// Trace scale 1 only: last frame's output and G-buffer, the history this frame's sample is added to.
layout(set = 0, binding = 10) uniform sampler2D motionTexture;
layout(set = 0, binding = 11) uniform sampler2D prevDepthTexture;
layout(set = 0, binding = 12) uniform sampler2D prevNormalRoughnessTexture;
layout(set = 0, binding = 13) uniform usampler2D indirectHistory;

#include "lib/cone_trace.glsl"

// Trace scale 1: this frame's sample s at full-res `pixel` (guide g) over last frame's output where the surface
// was: the texel nearest to the position reprojected with the motion vector, weighted by its accumulated weight
// A and by the upsample's plane and lobe weights against last frame's G-buffer there (a disocclusion or a
// changed lobe loses it), decayed by γ. O = (s + γ·h·H)/(1 + γ·h), A' = min(1 + γ·h, A_max in own samples).
// With a static camera the samples of successive frames, their cone sets jittered differently
// (coneSetOf), average: the figure the upsample's history reaches at trace scale > 1. Only with the
// jittered cones: a fixed set traces the same value every frame.
uvec4 accumulateHistory(ivec2 pixel, vec2 uv, Guide here, IndirectSample s) {
    vec4 diffuse = vec4(s.diffuse, 1.0);
    vec4 specular = vec4(s.specular, 1.0);
    // With the fixed cone set (--cone-rotation off) trace scale 1 stays the fresh every-pixel trace of each frame,
    // what the upsampling is measured against (docs/design.md §8.3).
    const uint needed = VCT_FLAG_HISTORY | VCT_FLAG_CONE_ROTATION;
    if ((frame.flags & needed) != needed) return packIndirect(diffuse, specular);
    const ivec2 size = ivec2(frame.imageSize);
    const vec2 prevUv = uv - texelFetch(motionTexture, pixel, 0).xy;
    const ivec2 texel = ivec2(floor(prevUv * frame.imageSize));
    const bool inside = all(greaterThanEqual(texel, ivec2(0))) && all(lessThan(texel, size));
    const ivec2 at = clamp(texel, ivec2(0), size - 1);
    const float prevDepth = texelFetch(prevDepthTexture, at, 0).r;
    const vec2 atUv = (vec2(at) + 0.5) * frame.texelSize;
    const Guide then = guideFromGBuffer(texelFetch(prevNormalRoughnessTexture, at, 0),
                                        worldFromDepth(frame.prevInvViewProj, atUv, prevDepth),
                                        frame.prevCameraPosition, frame.upsample.kappa);
    if (!inside || isBackground(prevDepth) || isDegeneratePosition(then.p))
        return packIndirect(diffuse, specular);
    const float beta = frame.upsample.beta;
    const float diffuseSharpness =
        smoothedSharpness(1.0 / frame.upsample.diffuseSharpness, frame.upsample.kappa);
    const float plane = planeLogWeightScaled(scaledTangentPlane(here.n, here.p, here.cameraDistance), then.p);
    const vec2 guide =
        exp(vec2(plane) +
            vec2(equalLobeLogWeight(here.n, then.n, diffuseSharpness, beta),
                 lobeLogWeightPrepared(here.specularAxis, preparedSharpness(here.specularSharpness),
                                       then.specularAxis, preparedSharpness(then.specularSharpness), beta)));
    const uvec4 historyTexel = texelFetch(indirectHistory, at, 0);
    const vec4 diffuseTexel = unpackIndirectDiffuse(historyTexel);
    const vec4 specularTexel = unpackIndirectSpecular(historyTexel);
    const vec2 h = frame.upsample.gamma * guide * vec2(diffuseTexel.a, specularTexel.a);
    const float maxWeight = frame.upsample.maxHistoryWeight / EXACT_SAMPLE_WEIGHT;
    diffuse = vec4((s.diffuse + h.x * diffuseTexel.rgb) / (1.0 + h.x), min(1.0 + h.x, maxWeight));
    specular = vec4((s.specular + h.y * specularTexel.rgb) / (1.0 + h.y), min(1.0 + h.y, maxWeight));
    return packIndirect(diffuse, specular);
}

// The cone layout's radiances, per cone and pixel of the workgroup.
const bool CONE_LANES = gl_WorkGroupSize.z > 1;
shared vec3 coneRadiance[CONE_LANES_PER_PIXEL][VCT_TILE_SIZE * VCT_TILE_SIZE];

// Low-res pixel `lowPixel` has nothing to light: the guide marks the sample as background for the upsample.
void writeBackground(ivec2 lowPixel) {
    imageStore(indirectImage, lowPixel, packIndirect(vec4(0.0, 0.0, 0.0, 1.0), vec4(0.0, 0.0, 0.0, 1.0)));
    if (!FULL_RESOLUTION) imageStore(guidePositionImage, lowPixel, vec4(0.0));
}

// Writes low-res pixel `lowPixel`'s sample s, traced at full-res `pixel` (uv its centre) of surface g.
void writeSample(ivec2 lowPixel, ivec2 pixel, vec2 uv, Guide g, IndirectSample s) {
    if (FULL_RESOLUTION) {
        // Weight 1: one fresh sample, added to the history as the upsample adds a pixel-own sample
        // (docs/design.md §6.5, the same reprojection, validation, decay γ and cap in own samples).
        imageStore(indirectImage, lowPixel, accumulateHistory(pixel, uv, g, s));
        return;
    }
    // Weight 1: one fresh sample (what the upsample weighs by where it was traced).
    imageStore(indirectImage, lowPixel, packIndirect(vec4(s.diffuse, 1.0), vec4(s.specular, 1.0)));
    imageStore(guidePositionImage, lowPixel, vec4(g.p, 1.0));
    imageStore(guideNormalImage, lowPixel, vec4(g.n, g.specularSharpness));
    imageStore(guideAxisImage, lowPixel, vec4(g.specularAxis, 0.0));
}

void main() {
    const ivec2 lowPixel = ivec2(gl_GlobalInvocationID.xy);
    const bool inside = all(lessThan(lowPixel, imageSize(indirectImage)));
    // The cone layout's invocations all reach its barrier.
    if (!CONE_LANES && !inside) return;
    // Clamped at the right and bottom edges (the low-res image rounds up); upsample clamps the same way.
    const ivec2 pixel = min(lowPixel * SCALE + frame.upsample.traceOffset, ivec2(frame.imageSize) - 1);
    const float depth = texelFetch(depthTexture, pixel, 0).r;
    const vec2 uv = (vec2(pixel) + 0.5) * frame.texelSize;
    const bool lit =
        inside && !isBackground(depth) && !isDegeneratePosition(worldFromDepth(frame.invViewProj, uv, depth));
    if (!CONE_LANES && !lit) {
        writeBackground(lowPixel);
        return;
    }
    const vec4 normalRoughness = texelFetch(normalRoughnessTexture, pixel, 0);
    // The sample's guide for the upsample weights, computed once here rather than by every pixel it serves.
    const Guide g = guideFromGBuffer(normalRoughness, worldFromDepth(frame.invViewProj, uv, depth),
                                     frame.cameraPosition, frame.upsample.kappa);
    // No grid yet: no indirect light.
    const bool traced = lit && frame.voxels.voxelSize > 0.0;
    // The turned set's noise is that of the low-res sample (of the pixel at trace scale 1): neighbouring samples,
    // which the upsample combines, then get interleaved gradient noise's far-apart values. Indexed by the traced
    // pixel, s apart, the noise ran along diagonals: hatching on cornell's walls at 1280×720, and 1485 still
    // pixels moving by more than 2 of 255 levels from frame 64 to 65 at 320×180 against 991 (docs/design.md §5.5).
    const ConeSet set = coneSetOf(FULL_RESOLUTION ? pixel : lowPixel, frame.upsample.frameIndex);
    const vec3 v = viewDirection(frame.cameraPosition - g.p, g.n);
    IndirectSample s = IndirectSample(vec3(0.0), vec3(0.0));
    if (!CONE_LANES) {
        if (traced) s = traceSurface(voxels, g.p, g.n, v, normalRoughness.w, set);
        writeSample(lowPixel, pixel, uv, g, s);
        return;
    }
    const int cone = int(gl_LocalInvocationID.z);
    const uint slot = gl_LocalInvocationID.y * VCT_TILE_SIZE + gl_LocalInvocationID.x;
    if (traced && cone < SURFACE_CONE_COUNT)
        coneRadiance[cone][slot] = traceSurfaceCone(voxels, g.p, g.n, v, normalRoughness.w, set, cone);
    barrier();
    if (cone != 0 || !inside) return;
    if (!lit) {
        writeBackground(lowPixel);
        return;
    }
    if (traced) {
        vec3 radiance[SURFACE_CONE_COUNT];
        for (int i = 0; i < SURFACE_CONE_COUNT; ++i) radiance[i] = coneRadiance[i][slot];
        s = surfaceFromCones(g.n, v, normalRoughness.w, set, radiance);
    }
    writeSample(lowPixel, pixel, uv, g, s);
}
