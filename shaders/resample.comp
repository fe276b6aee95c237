#version 460
#extension GL_GOOGLE_include_directive : require
// resample: adaptive re-tracing (docs/design.md §6.6, Tokuyoshi 2015 §5.4). The pixels the upsample pass could not
// reconstruct (sum of weights < τ) are on a compacted list; this pass, dispatched indirectly with one thread
// per entry (8 in the cone layout, one per cone), traces each of them at full resolution and overwrites the
// upsampled result with a fresh sample of the weight of a sample traced at its own pixel (EXACT_SAMPLE_WEIGHT,
// lib/upsample_weights.glsl): it is one.
#include "lib/shared.h"
#include "lib/constants.glsl"
#include "lib/brdf.glsl"
#include "lib/cone.glsl"
#include "lib/gbuffer_read.glsl"
#include "lib/indirect_pack.glsl"
#include "lib/pixel_list.glsl"
#include "lib/upsample_weights.glsl"

// z: the invocations per entry, 1 (a pixel's cones one after the other) or CONE_LANES_PER_PIXEL (one cone each;
// RenderSettings::TraceLayout, lib/cone_trace.glsl).
layout(local_size_x = VCT_RESAMPLE_GROUP_SIZE, local_size_z_id = VCT_SPEC_CONE_LANES) in;

// Resources: bound by engine/passes/resample_pass.cpp (checked against these bindings when the pipeline is
// made); 1–4 are the trace's numbers, for the shared cone-tracing code.
layout(set = 0, binding = VCT_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform sampler2D depthTexture;
layout(set = 0, binding = 2) uniform sampler2D normalRoughnessTexture;
layout(set = 0, binding = 3) uniform sampler3D voxels;
layout(set = 0, binding = 4, rgba32ui) uniform writeonly uimage2D
    indirectImage;  // the upsample output, overwritten at the listed pixels
layout(set = 0, binding = 6, std430) readonly buffer ResampleList {
    ResampleListHeader header;
    uint pixels[];
}
resampleList;

// The environment: what a cone that leaves the grid sees (lib/environment_sample.glsl).
layout(set = 0, binding = 9) uniform sampler2D environmentMap;

#include "lib/cone_trace.glsl"

// The cone layout's radiances, per cone and entry of the workgroup.
const bool CONE_LANES = gl_WorkGroupSize.z > 1;
shared vec3 coneRadiance[CONE_LANES_PER_PIXEL][VCT_RESAMPLE_GROUP_SIZE];

void writeSample(ivec2 pixel, IndirectSample s) {
    imageStore(indirectImage, pixel,
               packIndirect(vec4(s.diffuse, EXACT_SAMPLE_WEIGHT), vec4(s.specular, EXACT_SAMPLE_WEIGHT)));
}

void main() {
    const uint entry = gl_LocalInvocationID.x;
    const uint index = gl_WorkGroupID.x * VCT_RESAMPLE_GROUP_SIZE + entry;
    const bool listed = index < resampleList.header.counts.x;
    if (!CONE_LANES) {
        if (!listed) return;
        const ivec2 pixel = unpackListedPixel(resampleList.pixels[index]);
        writeSample(pixel, tracePixel(voxels, depthTexture, normalRoughnessTexture, pixel));
        return;
    }
    // The cone layout: every invocation reaches the barrier.
    const ivec2 pixel = listed ? unpackListedPixel(resampleList.pixels[index]) : ivec2(0);
    const PixelSurface surface = pixelSurface(depthTexture, normalRoughnessTexture, pixel);
    const int cone = int(gl_LocalInvocationID.z);
    if (listed && surface.lit && cone < SURFACE_CONE_COUNT)
        coneRadiance[cone][entry] = traceSurfaceCone(voxels, surface.p, surface.n, surface.v,
                                                     surface.perceptualRoughness, surface.set, cone);
    barrier();
    if (cone != 0 || !listed) return;
    IndirectSample s = IndirectSample(vec3(0.0), vec3(0.0));
    if (surface.lit) {
        vec3 radiance[SURFACE_CONE_COUNT];
        for (int i = 0; i < SURFACE_CONE_COUNT; ++i) radiance[i] = coneRadiance[i][entry];
        s = surfaceFromCones(surface.n, surface.v, surface.perceptualRoughness, surface.set, radiance);
    }
    writeSample(pixel, s);
}
