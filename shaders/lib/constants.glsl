// Constants and tiny helpers for the shared math headers (GLSL and C++, see lib/cpp_glsl.h).
#ifndef VCT_CONSTANTS_GLSL
#define VCT_CONSTANTS_GLSL

// Shared headers define their functions in the header. C++ needs `inline` so that several translation units
// may include them (one-definition rule); GLSL has no such keyword.
#ifndef VCT_INLINE
#ifdef __cplusplus
#define VCT_INLINE inline
#else
#define VCT_INLINE
#endif
#endif

const float PI = 3.14159265358979f;
const float INV_PI = 0.318309886183791f;

// HLSL's saturate, which neither GLSL nor GLM has.
VCT_INLINE float saturate(float x) { return clamp(x, 0.0f, 1.0f); }
VCT_INLINE vec3 saturate(vec3 x) { return clamp(x, vec3(0.0f), vec3(1.0f)); }

VCT_INLINE float pow5(float x) {
    float x2 = x * x;
    return x2 * x2 * x;
}

#endif  // VCT_CONSTANTS_GLSL
