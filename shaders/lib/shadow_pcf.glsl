// Percentage-closer filtering of the main light's shadow map (direct.comp). Shared by GLSL and C++
// (lib/cpp_glsl.h): tests/shadow_pcf_test.cpp checks the tap placement against the 3×3 sum it stands for.
#ifndef VCT_SHADOW_PCF_GLSL
#define VCT_SHADOW_PCF_GLSL

#include "lib/constants.glsl"

// The 3×3 PCF: nine bilinear depth-compare taps one texel apart around a position t (in texel-centre units:
// texel i's centre at t = i) weigh the 4×4 texels from floor(t) − 1 on by (1 − f, 1, 1, f) per axis, f the
// fraction of t. Four bilinear taps give the same weights: per axis, one over the first texel pair placed
// 1/(2 − f) past its first texel and weighted 2 − f, one over the last pair placed f/(1 + f) past its first
// texel and weighted 1 + f. The weights sum to 3 per axis, 9 in all. 16 depth compares instead of 36, on every
// device (on lavapipe the nine taps were about three quarters of the direct pass: benchmarks/README.md, issue
// 19); the result differs from the nine taps only by the sampler's filter rounding.
struct PcfTaps {
    vec2 first;  // tap positions, texel-centre units
    vec2 last;
    vec2 firstWeight;
    vec2 lastWeight;
};

VCT_INLINE PcfTaps pcfTaps(vec2 t) {
    PcfTaps taps;
    const vec2 base = floor(t);
    const vec2 f = t - base;
    taps.firstWeight = 2.0f - f;
    taps.lastWeight = 1.0f + f;
    taps.first = base - 1.0f + 1.0f / taps.firstWeight;
    taps.last = base + 1.0f + f / taps.lastWeight;
    return taps;
}

#endif  // VCT_SHADOW_PCF_GLSL
