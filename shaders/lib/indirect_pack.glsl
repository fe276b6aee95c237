// The indirect light of one pixel (or one low-res sample) in one RGBA32_UINT texel: demodulated diffuse and
// specular radiance, each with its accumulated weight A (DESIGN §3.5), as eight halves. One texel instead of
// two RGBA16F images: the upsample stores once and reads its history once per pixel, composite reads once
// (measured: ~10 % of the upsample's time at 640×360 on lavapipe, which scatters every image access per
// lane). Same precision as the RGBA16F images it replaces. Shared by GLSL and C++ (CPU readback, tests).
#ifndef VCT_INDIRECT_PACK_GLSL
#define VCT_INDIRECT_PACK_GLSL

#include "lib/constants.glsl"

// diffuse, specular: rgb radiance, a: weight.
VCT_INLINE uvec4 packIndirect(vec4 diffuse, vec4 specular) {
    return uvec4(packHalf2x16(vec2(diffuse.r, diffuse.g)), packHalf2x16(vec2(diffuse.b, diffuse.a)),
                 packHalf2x16(vec2(specular.r, specular.g)), packHalf2x16(vec2(specular.b, specular.a)));
}

VCT_INLINE vec4 unpackIndirectDiffuse(uvec4 texel) {
    return vec4(unpackHalf2x16(texel.x), unpackHalf2x16(texel.y));
}

VCT_INLINE vec4 unpackIndirectSpecular(uvec4 texel) {
    return vec4(unpackHalf2x16(texel.z), unpackHalf2x16(texel.w));
}

#endif  // VCT_INDIRECT_PACK_GLSL
