#version 460
#extension GL_GOOGLE_include_directive : require
// composite: linear HDR result, then exposure, tone map and sRGB encoding for display.
#include "lib/shared.h"
#include "lib/constants.glsl"
#include "lib/color.glsl"

layout(local_size_x = VCT_TILE_SIZE, local_size_y = VCT_TILE_SIZE) in;

layout(set = 0, binding = VCT_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = VCT_COMPOSITE_BINDING_DIRECT, rgba16f) uniform readonly image2D directImage;
layout(set = 0, binding = VCT_COMPOSITE_BINDING_HDR, rgba32f) uniform writeonly image2D hdrImage;
layout(set = 0, binding = VCT_COMPOSITE_BINDING_LDR, rgba8) uniform writeonly image2D ldrImage;

void main() {
    const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, ivec2(frame.imageSize.xy)))) return;
    const vec3 hdr = imageLoad(directImage, pixel).rgb;
    imageStore(hdrImage, pixel, vec4(hdr, 1.0));
    imageStore(ldrImage, pixel, vec4(linearToSrgb(toneMapAces(hdr, frame.ambient.w)), 1.0));
}
