#version 460
#extension GL_GOOGLE_include_directive : require
// resample: adaptive re-tracing (docs/design.md §6.6, Tokuyoshi 2015 §5.4). The pixels the upsample pass could not
// reconstruct (sum of weights < τ) are on a compacted list; this pass, dispatched indirectly with one thread
// per entry, traces each of them at full resolution and overwrites the upsampled result with a fresh sample
// of the weight of a sample traced at its own pixel (EXACT_SAMPLE_WEIGHT, lib/upsample_weights.glsl): it is one.
#include "lib/shared.h"
#include "lib/constants.glsl"
#include "lib/brdf.glsl"
#include "lib/cone.glsl"
#include "lib/gbuffer_read.glsl"
#include "lib/indirect_pack.glsl"
#include "lib/pixel_list.glsl"
#include "lib/upsample_weights.glsl"

layout(local_size_x = VCT_RESAMPLE_GROUP_SIZE) in;

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

void main() {
    const uint index = gl_GlobalInvocationID.x;
    if (index >= resampleList.header.counts.x) return;
    const ivec2 pixel = unpackListedPixel(resampleList.pixels[index]);
    const IndirectSample s = tracePixel(voxels, depthTexture, normalRoughnessTexture, pixel);
    imageStore(indirectImage, pixel,
               packIndirect(vec4(s.diffuse, EXACT_SAMPLE_WEIGHT), vec4(s.specular, EXACT_SAMPLE_WEIGHT)));
}
