#version 460
#extension GL_GOOGLE_include_directive : require
// upsample: the low-res demodulated indirect light (diffuse, specular) back to full resolution over space and
// time (docs/design.md §6; Herzog et al. 2010, Tokuyoshi 2015 §5.3). For full-res pixel i:
//   spatial   S = Σ_j c_j·f·w_z·w_lobe·I_j over the low-res samples j around the pixel, W_s = Σ_j f·w_z·w_lobe,
//             W_acc = Σ_j c_j·f·w_z·w_lobe; sample j was traced at full-res pixel s·j + o_k, and the trace
//             stored the geometry and lobe it saw there (the guide images), exact per sample; c_j makes the
//             sample traced at pixel i itself count EXACT_SAMPLE_WEIGHT neighbourhoods (1 for the others);
//   temporal  the history H (last frame's output, accumulated weight A in alpha) at the texel nearest to the
//             position reprojected with the motion vector, validated with the same weights against last
//             frame's G-buffer: T = w_t·A·H, T_w = w_t·A (without a guide: bilinear over 4 texels, unvalidated);
//   output    O = (S + γT) / (W_acc + γT_w), new A = min(W_acc + γT_w, A_max);
//   sum of weights W = W_s + γT_w / EXACT_SAMPLE_WEIGHT, kept per pixel; W < τ puts the pixel on the resample
//             list (compacted, with the indirect dispatch of the resample pass counted up as entries are
//             appended).
// Diffuse and specular are weighted separately, each with its own lobe (lib/upsample_weights.glsl). Never a
// division by a zero sum: every valid sample keeps a floor weight of FALLBACK_SHARE × its kernel weight, so
// where the guide rejects them all the pixel takes their kernel-weighted mean (and is re-traced).
//
// How it is made fast (measured on lavapipe, which runs 8 invocations per SIMD instruction, gathers per lane
// from shared memory and images alike, and pays for code under a uniform branch; the same choices save
// bandwidth and divergence on GPUs):
// - Specialization constants fix the trace scale, the weights and temporal per pipeline, so the
//   code of the other configurations is not compiled at all (an early return over dead code measured 21 ms
//   of 56 ms at 640×360).
// - One invocation per low-res cell: the s×s pixels whose windows share a base sample read the same (2r)²
//   samples, so the invocation loads them once into registers (5 texel fetches per sample: 80 per cell,
//   5 per pixel at s = 4, instead of 80 per pixel) and then reconstructs its s×s pixels.
// - The inner loops have no branches: an invalid sample (outside the image, background) gets weight 0, and
//   the weights multiply in the log domain (one exp per sample and lobe: plane × lobe = exp(sum of logs); the
//   SG ratio term, at a whole β/2, is a power made of multiplies instead: lib/upsample_weights.glsl).
#include "lib/shared.h"
#include "lib/constants.glsl"
#include "lib/brdf.glsl"
#include "lib/gbuffer_read.glsl"
#include "lib/upsample_weights.glsl"
#include "lib/upsample_guide.glsl"
#include "lib/indirect_pack.glsl"
#include "lib/pixel_list.glsl"

#extension GL_EXT_control_flow_attributes : require

// One invocation per low-res cell (s×s pixels).
layout(local_size_x = VCT_TILE_SIZE, local_size_y = VCT_TILE_SIZE) in;

// The configuration, fixed per pipeline (engine/passes/upsample_pass.cpp keeps one pipeline per combination).
layout(constant_id = VCT_SPEC_TRACE_SCALE) const int SCALE = 4;  // trace scale s: 2 or 4
layout(constant_id = VCT_UPSAMPLE_SPEC_WEIGHTS) const int WEIGHTS = VCT_WEIGHTS_SG;
layout(constant_id = VCT_UPSAMPLE_SPEC_TEMPORAL) const bool TEMPORAL = true;      // --temporal
layout(constant_id = VCT_UPSAMPLE_SPEC_WEIGHT_SUM) const bool WEIGHT_SUM = true;  // write weightSumImage
// The layout (--upsample-layout): false, one invocation per low-res cell, its samples in registers (CPU devices);
// true, one invocation per pixel, the workgroup's samples in shared memory (GPUs). See main().
layout(constant_id = VCT_UPSAMPLE_SPEC_PER_PIXEL) const bool PER_PIXEL = false;
// sgRatioPower(β) (lib/upsample_weights.glsl): the SG ratio term's power, made of multiplies when β/2 is whole.
layout(constant_id = VCT_UPSAMPLE_SPEC_RATIO_POWER) const int RATIO_POWER = 10;
// The image size is a multiple of s on both axes: no sample is traced at a clamped pixel (REACH), so every pixel's
// kernel reaches exactly the samples the lattice gives it. Fixed per pipeline because lavapipe pays for the code
// under a branch that no invocation takes (the per-cell fallback measured 0.9 ms of 13.5 ms at 640×360).
layout(constant_id = VCT_UPSAMPLE_SPEC_WHOLE_CELLS) const bool WHOLE_CELLS = true;

// Resources: bound by engine/passes/upsample_pass.cpp (its resource table gives these binding numbers and is
// checked against them when the pipeline is made).
layout(set = 0, binding = VCT_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform usampler2D indirectLow;  // the trace's output (lib/indirect_pack.glsl)
layout(set = 0, binding = 5) uniform sampler2D depthTexture;
layout(set = 0, binding = 6) uniform sampler2D normalRoughnessTexture;
layout(set = 0, binding = 7) uniform sampler2D motionTexture;
layout(set = 0, binding = 8) uniform sampler2D prevDepthTexture;
layout(set = 0, binding = 9) uniform sampler2D prevNormalRoughnessTexture;
// The trace's per-sample guides.
layout(set = 0, binding = 14) uniform sampler2D guidePositionTexture;
layout(set = 0, binding = 15) uniform sampler2D guideNormalTexture;
layout(set = 0, binding = 16) uniform sampler2D guideAxisTexture;
layout(set = 0, binding = 10) uniform usampler2D indirectHistory;  // last frame's output
// Diffuse, specular + accumulated weights A.
layout(set = 0, binding = 3, rgba32ui) uniform writeonly uimage2D indirectImage;
// r: sum of weights (diffuse), g: (specular), b: 1 re-traced.
layout(set = 0, binding = 12, rgba16f) uniform writeonly image2D weightSumImage;
// The pixels to re-trace (count, the resample pass's indirect dispatch, pixels). clang-format would put the
// instance name of this GLSL block on a line of its own.
// clang-format off
layout(set = 0, binding = 13, std430) buffer ResampleList {
    ResampleListHeader header;
    uint pixels[];
} resampleList;
// clang-format on

// Tent radius in low-res texels: 1 (bilinear: the 2×2 nearest) without a guide; 2 (4×4) with one, so that the
// guide has candidates left to choose from where it rejects some.
// The floor weight of a valid sample, as a share of its kernel weight: far below any weight the guide keeps
// (and below τ), it only decides the result where the guide rejects every sample (a branch-free fallback).
const float FALLBACK_SHARE = 1e-6;
// The spatial kernel (lib/upsample_weights.glsl): bilinear (no guide) the tent over the 2×2 nearest samples;
// with a guide the quadratic B-spline over the 3×3 nearest, so that the guide has candidates left where it
// rejects some. A cell's pixels reach 4×4 samples in all (the left half of the cell the first three columns,
// the right half the last three); each pixel weighs its 3×3 (REACH), with constant indices into the invocation's
// samples (a variable index, or selects, measured 3.4× slower on lavapipe than the 7 weights it saves).
const int RADIUS = WEIGHTS == VCT_WEIGHTS_BILINEAR ? 1 : 2;
const int WINDOW = 2 * RADIUS;  // samples per axis around a cell
// Arrays of samples have the largest window's size (a size from specialization constants is not valid SPIR-V
// once passed by value); only the first WINDOW² entries are used.
const int MAX_SAMPLES = 16;

// A low-res sample as the trace left it (trace.comp's guide images), with its kernel validity.
struct Sample {
    vec3 p;
    float valid;  // 1, or 0 outside the image and on the background
    vec3 n;
    FoldedLobe specularLobe;  // axis ξ and λ̄, prepared for lobePairWeightFolded (lib/upsample_weights.glsl)
    vec3 diffuse;
    vec3 specular;
    vec2 at;  // the full-res pixel it was traced at
};

// Where the samples live. Per cell: the invocation's own (2r)² samples. Per pixel: the samples of the workgroup's
// cells, a square of REGION² from the first cell's window; a cell's window starts at its place in the group.
Sample cellSamples[MAX_SAMPLES];
const int GROUP_CELLS = VCT_TILE_SIZE / SCALE;  // cells per workgroup and axis, per-pixel layout
const int REGION = GROUP_CELLS + WINDOW - 1;    // ≤ 7: 49 samples for 64 invocations
const int MAX_REGION_SAMPLES = VCT_TILE_SIZE * VCT_TILE_SIZE;
shared Sample groupSamples[MAX_REGION_SAMPLES];

// The samples a pixel weighs, per axis: only the ones its kernel reaches. The B-spline (radius 1.5 low-res texels)
// of a pixel in the first half of its cell reaches window columns 0–2 and gives column 3 an exact 0, and the second
// half's columns 1–3 (rows alike): 9 of the 16 pairs, the same sums, since the 7 left out add exactly 0 (their log
// weights are ≤ 0, so f = 0 multiplies a finite number). Bilinear reaches its whole 2×2 window. Not where a sample
// of the window was traced at a clamped pixel (the last low-res column or row of an image whose size is not a
// multiple of s): it sits nearer than the lattice says, and such a pixel weighs the whole window (per pixel,
// main() gives it to the whole workgroup; per cell, to every pipeline of an image that has such samples,
// WHOLE_CELLS).
const int REACH = WEIGHTS != VCT_WEIGHTS_BILINEAR ? WINDOW - 1 : WINDOW;

// Sample k (0 .. reach² − 1) of the samples a pixel weighs: the sample of its cell's window from `first` (a window
// column and row: 0, or 1 for the second half of the cell) in rows of `reach`. Per cell the index must come out a
// constant (main() reconstructs each quarter of the cell in a call of its own): a variable index into the
// invocation's samples measured 3.4× slower on lavapipe than the weights it saves.
Sample windowSample(int k, ivec2 cellInGroup, ivec2 first, int reach) {
    const ivec2 at = cellInGroup + first + ivec2(k % reach, k / reach);
    if (!PER_PIXEL) return cellSamples[at.y * WINDOW + at.x];
    return groupSamples[at.y * REGION + at.x];
}

// The pixel being reconstructed: its guide, tangent plane and specular lobe prepared for many weights.
struct PixelGuide {
    Guide guide;
    vec4 plane;
    FoldedLobe specularLobe;
};

// The (diffuse, specular) guide weight of a surface with normal nq and specular lobe q seen from pixel `a`,
// times its plane weight exp(logPlane), by the chosen guide; bilinear has no guide (1). The diffuse lobes share
// one sharpness, so their lobe weight is the angle term alone (equalLobeLogWeight). The specular lobes come
// folded (foldedLobe, once per pixel and once per sample), so that a pair costs one division and, at a whole
// β/2, a few multiplies for the ratio term (lobePairWeightFolded). Both exponents are summed first and taken in
// one vec2 exp.
vec2 guideWeights(PixelGuide a, vec3 nq, FoldedLobe q, float logPlane) {
    if (WEIGHTS == VCT_WEIGHTS_BILINEAR) return vec2(1.0);
    if (WEIGHTS == VCT_WEIGHTS_NORMAL)
        return exp(vec2(logPlane + normalLogWeight(a.guide.n, nq, frame.upsample.normalVariance)));
    const float beta = frame.upsample.beta;
    const float diffuseSharpness =
        smoothedSharpness(1.0 / frame.upsample.diffuseSharpness, frame.upsample.kappa);
    const vec2 specular = lobePairWeightFolded(a.specularLobe, q, beta, RATIO_POWER);
    return exp(vec2(logPlane + equalLobeLogWeight(a.guide.n, nq, diffuseSharpness, beta),
                    logPlane + specular.x)) *
           vec2(1.0, specular.y);
}

// The folded specular lobe of a guide (none without the SG weights).
FoldedLobe foldedSpecularLobe(vec3 axis, float sharpness) {
    return WEIGHTS == VCT_WEIGHTS_SG ? foldedLobe(axis, sharpness) : FoldedLobe(vec3(0.0), 0.0, 0.0);
}

// ln of the plane-distance weight of point q against a pixel's scaledTangentPlane (none for bilinear).
float planeLogWeightFrom(vec4 plane, vec3 q) {
    return WEIGHTS == VCT_WEIGHTS_BILINEAR ? 0.0 : planeLogWeightScaled(plane, q);
}

// Sums over the cell's samples (spatial) or over the history (temporal) of weighted diffuse and specular light.
struct WeightedLight {
    vec3 diffuse, specular;
    vec2 weight;              // the sum of weights W_s (spatial) or the history's weight (temporal)
    vec2 accumulationWeight;  // spatial only: the same weights with the pixel-own sample counted more
};

// ---- spatial: the cell's low-res samples, each at its own jittered full-res position ----
// Two sums of the same weights: weight (the sum of weights W_s of docs/design.md §6.5, for τ and the weights
// view) and the accumulation weights, in which a sample traced at this very pixel counts EXACT_SAMPLE_WEIGHT
// (lib/upsample_weights.glsl), as many interpolated neighbourhoods as make it dominate the history.
// `precise` (no fused multiply-add in the sums and in the weights feeding them): the cell and pixel layouts sum
// different numbers of exact zeros, and a GPU compiler fuses a·b + c in one instance of this code and not in the
// other (4–11 pixels of a 160×90 image differed on an NVIDIA H200); so they round alike on every device.
WeightedLight spatialLight(ivec2 pixel, PixelGuide here, ivec2 cellInGroup, ivec2 first, int reach) {
    precise WeightedLight sum = WeightedLight(vec3(0.0), vec3(0.0), vec2(0.0), vec2(0.0));
    [[unroll]] for (int k = 0; k < reach * reach; ++k) {
        const Sample j = windowSample(k, cellInGroup, first, reach);
        // Kernel × validity: 0 outside the image and on the background.
        const vec2 offset = (vec2(pixel) - j.at) / float(SCALE);
        const float f =
            (WEIGHTS == VCT_WEIGHTS_BILINEAR ? tentKernel(offset, 1.0) : bsplineKernel(offset)) * j.valid;
        const vec2 w = f * (guideWeights(here, j.n, j.specularLobe, planeLogWeightFrom(here.plane, j.p)) +
                            FALLBACK_SHARE);
        const float share = WEIGHTS != VCT_WEIGHTS_BILINEAR && all(equal(j.at, vec2(pixel)))
                                ? EXACT_SAMPLE_WEIGHT / BSPLINE_CENTRE
                                : 1.0;
        const vec2 a = share * w;
        sum.diffuse += a.x * j.diffuse;
        sum.specular += a.y * j.specular;
        sum.weight += w;
        sum.accumulationWeight += a;
    }
    return sum;
}

// ---- temporal: last frame's output where this surface was, validated against last frame's G-buffer ----
// With a guide: the nearest texel to the reprojected position, weighted by the guide against last frame's
// G-buffer there × the weight it had accumulated (alpha). Nearest, not bilinear: indirect light is smooth, so the
// sub-texel shift costs little, while bilinear taps blur the history a little more with every moving frame,
// and 4 validated taps cost more than the 1/16-res trace on lavapipe (measured: 3.4 ms of 22 ms at
// 640×360). With a static camera the two are the same (the reprojection lands on texel centres).
// Valid history (not the first frame, not a cut): uniform per frame, set by the renderer.
// Without a guide (bilinear) nothing can validate a tap, so the history is resampled bilinearly over the 4
// texels around the reprojected position (outside the image or on the background: weight 0), the
// guide-free baseline as a whole.
WeightedLight historyLight(ivec2 pixel, vec2 uv, PixelGuide here) {
    const ivec2 size = ivec2(frame.imageSize);
    WeightedLight sum = WeightedLight(vec3(0.0), vec3(0.0), vec2(0.0), vec2(0.0));
    if (WEIGHTS == VCT_WEIGHTS_BILINEAR && TEMPORAL && (frame.flags & VCT_FLAG_HISTORY) != 0u) {
        const vec2 prevCoord = (uv - texelFetch(motionTexture, pixel, 0).xy) * frame.imageSize - 0.5;
        const ivec2 prevBase = ivec2(floor(prevCoord));
        const vec2 fraction = prevCoord - vec2(prevBase);
        [[unroll]] for (int tap = 0; tap < 4; ++tap) {
            const ivec2 offset = ivec2(tap & 1, tap >> 1);
            const ivec2 texel = prevBase + offset;
            const bool inside = all(greaterThanEqual(texel, ivec2(0))) && all(lessThan(texel, size));
            const ivec2 at = clamp(texel, ivec2(0), size - 1);
            const vec2 bilinear = mix(vec2(1.0) - fraction, fraction, vec2(offset));
            const float share = inside && !isBackground(texelFetch(prevDepthTexture, at, 0).r)
                                    ? bilinear.x * bilinear.y
                                    : 0.0;
            const uvec4 historyTexel = texelFetch(indirectHistory, at, 0);
            const vec4 diffuseTexel = unpackIndirectDiffuse(historyTexel);
            const vec4 specularTexel = unpackIndirectSpecular(historyTexel);
            const vec2 w = share * vec2(diffuseTexel.a, specularTexel.a);
            sum.diffuse += w.x * diffuseTexel.rgb;
            sum.specular += w.y * specularTexel.rgb;
            sum.weight += w;
        }
    }
    if (WEIGHTS != VCT_WEIGHTS_BILINEAR && TEMPORAL && (frame.flags & VCT_FLAG_HISTORY) != 0u) {
        const vec2 prevUv = uv - texelFetch(motionTexture, pixel, 0).xy;
        const ivec2 texel = ivec2(floor(prevUv * frame.imageSize));
        const bool inside = all(greaterThanEqual(texel, ivec2(0))) && all(lessThan(texel, size));
        const ivec2 at = clamp(texel, ivec2(0), size - 1);
        const float prevDepth = texelFetch(prevDepthTexture, at, 0).r;
        const vec2 atUv = (vec2(at) + 0.5) * frame.texelSize;
        const Guide then = guideFromGBuffer(texelFetch(prevNormalRoughnessTexture, at, 0),
                                            worldFromDepth(frame.prevInvViewProj, atUv, prevDepth),
                                            frame.prevCameraPosition, frame.upsample.kappa);
        const FoldedLobe thenLobe = foldedSpecularLobe(then.specularAxis, then.specularSharpness);
        const uvec4 historyTexel = texelFetch(indirectHistory, at, 0);
        const vec4 diffuseTexel = unpackIndirectDiffuse(historyTexel);
        const vec4 specularTexel = unpackIndirectSpecular(historyTexel);
        const vec2 guide = guideWeights(here, then.n, thenLobe, planeLogWeightFrom(here.plane, then.p));
        // Outside last frame's image or on its background: no history (the select also keeps the garbage
        // guide of a far-plane position out of the sums).
        sum.weight = inside && !isBackground(prevDepth) && !isDegeneratePosition(then.p)
                         ? guide * vec2(diffuseTexel.a, specularTexel.a)
                         : vec2(0.0);
        sum.diffuse = sum.weight.x * diffuseTexel.rgb;
        sum.specular = sum.weight.y * specularTexel.rgb;
    }
    return sum;
}

// ---- output: the two sums combined, written, and the pixel listed for re-tracing when its weights are low ----
void writePixel(ivec2 pixel, bool background, WeightedLight spatial, WeightedLight history) {
    const float gamma = frame.upsample.gamma;
    const vec2 accumulated = spatial.accumulationWeight + gamma * history.weight;
    // The sum of weights τ tests: this frame's neighbourhood by its kernel weights, plus the history counted
    // in pixel-own samples (EXACT_SAMPLE_WEIGHT each). Where the guide rejects most neighbours (silhouettes,
    // thin features) the pixel is then re-traced unless its own sample is recent, instead of resting on the
    // interpolated light that a history capped in neighbourhood units would keep for good.
    const vec2 weightSum = spatial.weight + gamma * history.weight / EXACT_SAMPLE_WEIGHT;
    // A sum below the floor has no valid sample and no history behind it (its numerator is as small): black.
    const float minSum = 1e-30;
    const vec3 diffuse = (spatial.diffuse + gamma * history.diffuse) / max(accumulated.x, minSum);
    const vec3 specular = (spatial.specular + gamma * history.specular) / max(accumulated.y, minSum);
    const float maxWeight = frame.upsample.maxHistoryWeight;
    // Nothing to light on the background: no indirect light, never re-traced.
    // τ is 0 without adaptive re-tracing (nothing is listed). A uniform, not a specialization constant: the
    // variant without the append measured 25 % slower on lavapipe (LLVM then unrolled the 16-pixel loop).
    const bool resample = !background && min(weightSum.x, weightSum.y) < frame.upsample.tau;
    const vec4 diffuseOut = background ? vec4(0.0) : vec4(diffuse, min(accumulated.x, maxWeight));
    const vec4 specularOut = background ? vec4(0.0) : vec4(specular, min(accumulated.y, maxWeight));
    const vec4 weightOut = background ? vec4(0.0) : vec4(weightSum, resample ? 1.0 : 0.0, 0.0);
    imageStore(indirectImage, pixel, packIndirect(diffuseOut, specularOut));
    if (WEIGHT_SUM) imageStore(weightSumImage, pixel, weightOut);

    // The resample pass runs a workgroup for every VCT_RESAMPLE_GROUP_SIZE entries.
    if (resample) APPEND_LISTED_PIXEL(resampleList, pixel, VCT_RESAMPLE_GROUP_SIZE)
}

// Reconstructs one full-res pixel from its cell's samples and its history; writes it and lists it for
// re-tracing when its sum of weights is low. `first`, `reach`: the samples it weighs (windowSample).
void reconstruct(ivec2 pixel, ivec2 cellInGroup, ivec2 first, int reach) {
    const float depth = texelFetch(depthTexture, pixel, 0).r;
    const vec2 uv = (vec2(pixel) + 0.5) * frame.texelSize;
    const vec3 position = worldFromDepth(frame.invViewProj, uv, depth);
    // A position that cannot be shaded (lib/gbuffer_read.glsl) is treated as the background, as the trace does.
    const bool background = isBackground(depth) || isDegeneratePosition(position);
    // A background pixel's "position" is at the far plane (or infinite): its weights may be garbage, even NaN;
    // its outputs are replaced by zeros at the end, without a branch around the work.
    PixelGuide here;
    here.guide = guideFromGBuffer(texelFetch(normalRoughnessTexture, pixel, 0), position,
                                  frame.cameraPosition, frame.upsample.kappa);
    here.plane = scaledTangentPlane(here.guide.n, here.guide.p, here.guide.cameraDistance);
    here.specularLobe = foldedSpecularLobe(here.guide.specularAxis, here.guide.specularSharpness);
    writePixel(pixel, background, spatialLight(pixel, here, cellInGroup, first, reach),
               historyLight(pixel, uv, here));
}

// Low-res sample `low` as the trace left it (zero weight outside the image and on the background).
Sample loadSample(ivec2 low, ivec2 size, ivec2 lowSize, ivec2 jitter) {
    const bool inside = all(greaterThanEqual(low, ivec2(0))) && all(lessThan(low, lowSize));
    const ivec2 at = clamp(low, ivec2(0), lowSize - 1);
    const vec4 position = texelFetch(guidePositionTexture, at, 0);
    Sample j;
    j.p = position.xyz;
    j.valid = inside ? position.w : 0.0;  // w = 0: background
    const vec4 normalSharpness =
        WEIGHTS != VCT_WEIGHTS_BILINEAR ? texelFetch(guideNormalTexture, at, 0) : vec4(0.0);
    j.n = normalSharpness.xyz;
    const uvec4 light = texelFetch(indirectLow, at, 0);
    j.diffuse = unpackIndirectDiffuse(light).rgb;
    j.specular = unpackIndirectSpecular(light).rgb;
    j.at = vec2(min(low * SCALE + jitter, size - 1));  // where trace.comp traced it
    // An invalid sample is multiplied by a zero kernel weight, and 0 × NaN is NaN: its guide (which the
    // trace does not write on the background, so it may be anything) must be finite. Selects, no branch.
    const bool valid = j.valid > 0.0;
    j.p = valid ? j.p : vec3(0.0);
    j.n = valid ? j.n : vec3(0.0, 0.0, 1.0);
    const vec3 axis = WEIGHTS == VCT_WEIGHTS_SG ? texelFetch(guideAxisTexture, at, 0).xyz : vec3(0.0);
    j.specularLobe = foldedSpecularLobe(valid ? axis : vec3(0.0, 0.0, 1.0), valid ? normalSharpness.w : 1.0);
    j.diffuse = valid ? j.diffuse : vec3(0.0);
    j.specular = valid ? j.specular : vec3(0.0);
    return j;
}

// Per cell: reconstructs the pixels of one quarter of the cell (`quarter`: 0 or 1 per axis, the half of the cell
// along x and y), each from the 3×3 samples its kernel reaches (REACH). `quarter` must be a constant at every call,
// so that the samples' indices are too (windowSample).
void reconstructQuarter(ivec2 first, ivec2 size, const ivec2 quarter) {
    const int HALF = SCALE / 2;
    [[dont_unroll]] for (int i = 0; i < HALF * HALF; ++i) {
        const ivec2 pixel = first + quarter * HALF + ivec2(i % HALF, i / HALF);
        if (all(greaterThanEqual(pixel, ivec2(0))) && all(lessThan(pixel, size)))
            reconstruct(pixel, ivec2(0), quarter, REACH);
    }
}

void main() {
    const ivec2 size = ivec2(frame.imageSize);
    const ivec2 jitter = frame.upsample.traceOffset;
    const ivec2 lowSize = textureSize(indirectLow, 0);
    if (PER_PIXEL) {
        // ---- one invocation per pixel: the workgroup's GROUP_CELLS² cells (from cell −1), their samples loaded
        // once into shared memory, one per invocation. On a GPU the per-cell layout keeps 16 samples in each
        // invocation's registers (spilled) and runs s² times fewer invocations: on an NVIDIA H200 its sg upsample
        // cost 2.0× the trace and 2.0× the normal weights' at 1280×720 (benchmarks/README.md, round 7).
        const ivec2 groupCell = ivec2(gl_WorkGroupID.xy) * GROUP_CELLS - 1;
        const int lane = int(gl_LocalInvocationIndex);
        if (lane < REGION * REGION)
            groupSamples[lane] = loadSample(groupCell - (RADIUS - 1) + ivec2(lane % REGION, lane / REGION),
                                            size, lowSize, jitter);
        barrier();
        const ivec2 local = ivec2(gl_LocalInvocationID.xy);
        const ivec2 pixel = (groupCell + local / SCALE) * SCALE + jitter + local % SCALE;
        // A sample traced at a clamped pixel (REACH) anywhere in the group's region: the whole window, in the same
        // branch for the whole workgroup.
        const ivec2 lastSample = groupCell - (RADIUS - 1) + REGION - 1;
        const bool clamped = any(greaterThan(lastSample * SCALE + jitter, size - 1));
        if (all(greaterThanEqual(pixel, ivec2(0))) && all(lessThan(pixel, size))) {
            if (REACH == WINDOW || clamped)
                reconstruct(pixel, local / SCALE, ivec2(0), WINDOW);
            else
                reconstruct(pixel, local / SCALE, ivec2(greaterThanEqual(local % SCALE, ivec2(SCALE / 2))),
                            REACH);
        }
        return;
    }

    // ---- one invocation per low-res cell (s×s pixels) ----
    // Cell b holds the pixels x with floor((x − o)/s) = b: x ∈ [s·b + o, s·b + o + s). Cells start at −1, where
    // the offset o leaves pixels left of sample 0.
    const ivec2 cell = ivec2(gl_GlobalInvocationID.xy) - 1;
    const ivec2 first = cell * SCALE + jitter;
    if (any(greaterThanEqual(first, size)) || any(lessThan(first + SCALE, ivec2(1)))) return;

    // ---- the (2r)² samples around the cell, from cell − r + 1 ----
    [[unroll]] for (int k = 0; k < WINDOW * WINDOW; ++k) cellSamples[k] =
        loadSample(cell + ivec2(k % WINDOW, k / WINDOW) - (RADIUS - 1), size, lowSize, jitter);

    // ---- the cell's pixels (loops, not unrolled: s² copies of the reconstruction would be all code) ----
    if (REACH < WINDOW && WHOLE_CELLS) {
        // Each quarter from its 3×3 samples: 9 guide weights per pixel instead of 16.
        reconstructQuarter(first, size, ivec2(0, 0));
        reconstructQuarter(first, size, ivec2(1, 0));
        reconstructQuarter(first, size, ivec2(0, 1));
        reconstructQuarter(first, size, ivec2(1, 1));
    } else {
        [[dont_unroll]] for (int i = 0; i < SCALE * SCALE; ++i) {
            const ivec2 pixel = first + ivec2(i % SCALE, i / SCALE);
            if (all(greaterThanEqual(pixel, ivec2(0))) && all(lessThan(pixel, size)))
                reconstruct(pixel, ivec2(0), ivec2(0), WINDOW);
        }
    }
}
