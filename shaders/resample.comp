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
#include "lib/upsample_weights.glsl"

layout(local_size_x = VCT_RESAMPLE_GROUP_SIZE) in;

layout(set = 0, binding = VCT_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = VCT_TRACE_BINDING_DEPTH) uniform sampler2D depthTexture;
layout(set = 0, binding = VCT_TRACE_BINDING_NORMAL_ROUGHNESS) uniform sampler2D normalRoughnessTexture;
layout(set = 0, binding = VCT_TRACE_BINDING_VOXELS) uniform sampler3D voxels;
layout(set = 0, binding = VCT_RESAMPLE_BINDING_INDIRECT, rgba32ui) uniform writeonly uimage2D indirectImage;
layout(set = 0, binding = VCT_RESAMPLE_BINDING_LIST, std430) readonly buffer ResampleList {
    ResampleListHeader header;
    uint pixels[];
} resampleList;

#include "lib/cone_trace.glsl"

void main() {
    const uint index = gl_GlobalInvocationID.x;
    if (index >= resampleList.header.counts.x) return;
    const uint packed = resampleList.pixels[index];
    const ivec2 pixel = ivec2(packed & 0xffffu, packed >> 16);
    const IndirectSample s = tracePixel(voxels, depthTexture, normalRoughnessTexture, pixel);
    imageStore(indirectImage, pixel,
               packIndirect(vec4(s.diffuse, EXACT_SAMPLE_WEIGHT), vec4(s.specular, EXACT_SAMPLE_WEIGHT)));
}
