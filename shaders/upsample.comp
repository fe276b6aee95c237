#version 460
#extension GL_GOOGLE_include_directive : require
// upsample: plain bilinear upsample of the low-res demodulated indirect light (diffuse and specular) to full
// resolution. Placeholder for the lobe-aware spatio-temporal upsampling (DESIGN §3.5).
#include "lib/shared.h"

layout(local_size_x = VCT_TILE_SIZE, local_size_y = VCT_TILE_SIZE) in;

layout(set = 0, binding = VCT_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = VCT_UPSAMPLE_BINDING_DIFFUSE_LOW) uniform sampler2D diffuseLow;
layout(set = 0, binding = VCT_UPSAMPLE_BINDING_SPECULAR_LOW) uniform sampler2D specularLow;
layout(set = 0, binding = VCT_UPSAMPLE_BINDING_DIFFUSE, rgba16f) uniform writeonly image2D diffuseImage;
layout(set = 0, binding = VCT_UPSAMPLE_BINDING_SPECULAR, rgba16f) uniform writeonly image2D specularImage;

void main() {
    const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, ivec2(frame.imageSize.xy)))) return;
    // Low-res texel x was traced at full-res pixel s·x, whose centre is s·x + 0.5; so full-res pixel X sits at
    // low-res texel coordinate X/s (+ 0.5 to the texel centre convention of texture()).
    const float scale = max(frame.voxelParams.w, 1.0);
    const vec2 lowUv = (vec2(pixel) / scale + 0.5) / vec2(textureSize(diffuseLow, 0));
    imageStore(diffuseImage, pixel, vec4(textureLod(diffuseLow, lowUv, 0.0).rgb, 1.0));
    imageStore(specularImage, pixel, vec4(textureLod(specularLow, lowUv, 0.0).rgb, 1.0));
}
