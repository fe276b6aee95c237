// The indirect light of one pixel (or one low-res sample) in one RGBA32_UINT texel: demodulated diffuse and
// specular radiance, each with its accumulated weight A (docs/design.md §6.5), as eight bfloat16 values (a float's
// upper 16 bits, rounded to nearest even). One texel instead of two RGBA16F images: the upsample stores once and
// reads its history once per pixel, composite reads once. bfloat16, not half: packing is three integer
// operations (packHalf2x16 measured 3 ms of 20 in the upsample at 640×360 on lavapipe), and it keeps float's
// range, so bright emitters cannot overflow to inf as they could in fp16; its 8-bit significand (relative
// rounding error ≤ 2⁻⁸ = 0.4 %, 0.1 % RMS) is far below the upsampling error it stores (benchmarks/README.md).
// Shared by GLSL and C++ (CPU readback, tests).
#ifndef VCT_INDIRECT_PACK_GLSL
#define VCT_INDIRECT_PACK_GLSL

#include "lib/constants.glsl"

// The bfloat16 of x (round to nearest, ties to even; NaN and ±inf stay NaN and ±inf) in the low 16 bits.
VCT_INLINE uint bfloat16Bits(float x) {
    const uint bits = floatBitsToUint(x);
    return (bits + 0x7FFFu + ((bits >> 16) & 1u)) >> 16;
}

VCT_INLINE uint packBfloat16x2(float low, float high) {
    return bfloat16Bits(low) | (bfloat16Bits(high) << 16);
}

VCT_INLINE vec2 unpackBfloat16x2(uint packed) {
    return vec2(uintBitsToFloat(packed << 16), uintBitsToFloat(packed & 0xFFFF0000u));
}

// diffuse, specular: rgb radiance, a: weight.
VCT_INLINE uvec4 packIndirect(vec4 diffuse, vec4 specular) {
    return uvec4(packBfloat16x2(diffuse.r, diffuse.g), packBfloat16x2(diffuse.b, diffuse.a),
                 packBfloat16x2(specular.r, specular.g), packBfloat16x2(specular.b, specular.a));
}

VCT_INLINE vec4 unpackIndirectDiffuse(uvec4 texel) {
    return vec4(unpackBfloat16x2(texel.x), unpackBfloat16x2(texel.y));
}

VCT_INLINE vec4 unpackIndirectSpecular(uvec4 texel) {
    return vec4(unpackBfloat16x2(texel.z), unpackBfloat16x2(texel.w));
}

#endif  // VCT_INDIRECT_PACK_GLSL
