// Colour: sRGB transfer functions, luminance and the display tone map.
// Shared by GLSL and C++ (lib/cpp_glsl.h).
// All colours are linear Rec.709/sRGB primaries unless a name says otherwise.
#ifndef VCT_COLOR_GLSL
#define VCT_COLOR_GLSL

#include "lib/constants.glsl"

// sRGB electro-optical transfer function pieces (IEC 61966-2-1). Negative input is clamped to 0 (pow of a
// negative is NaN); input above 1 is encoded as extended sRGB, not clipped.
VCT_INLINE float linearToSrgb(float c) {
    c = max(c, 0.0f);
    return c <= 0.0031308f ? 12.92f * c : 1.055f * pow(c, 1.0f / 2.4f) - 0.055f;
}
VCT_INLINE float srgbToLinear(float c) {
    c = max(c, 0.0f);
    return c <= 0.04045f ? c / 12.92f : pow((c + 0.055f) / 1.055f, 2.4f);
}
VCT_INLINE vec3 linearToSrgb(vec3 c) { return vec3(linearToSrgb(c.r), linearToSrgb(c.g), linearToSrgb(c.b)); }
VCT_INLINE vec3 srgbToLinear(vec3 c) { return vec3(srgbToLinear(c.r), srgbToLinear(c.g), srgbToLinear(c.b)); }

// Relative luminance Y of linear Rec.709 primaries (ITU-R BT.709).
VCT_INLINE float luminance(vec3 c) { return dot(c, vec3(0.2126f, 0.7152f, 0.0722f)); }

// Tone map: Narkowicz 2015, "ACES Filmic Tone Mapping Curve", a rational fit of the ACES RRT+ODT, applied per
// channel. Chosen over Reinhard-on-luminance because it needs no extra clamp for saturated colours (each
// channel maps [0, ∞) monotonically onto [0, 1]; highlights desaturate towards white) and keeps more mid-tone
// contrast. `exposure` is a linear scale applied first (1 = none; Narkowicz's fit matches ACES at 0.6).
// Output is linear display light in [0, 1]: encode with linearToSrgb (or an sRGB target) afterwards.
VCT_INLINE vec3 toneMapAces(vec3 hdr, float exposure) {
    // The curve reaches 1 at x ≈ 7.24 and is clipped there, so the upper clamp changes nothing; it keeps x²
    // finite for Inf or huge input.
    vec3 x = clamp(hdr * exposure, vec3(0.0f), vec3(64.0f));
    const float a = 2.51f;
    const float b = 0.03f;
    const float c = 2.43f;
    const float d = 0.59f;
    const float e = 0.14f;
    return saturate((x * (a * x + b)) / (x * (c * x + d) + e));
}

#endif  // VCT_COLOR_GLSL
