// Normal-map filtering (docs/design.md §4): Toksvig's roughness from the length of an averaged normal, and
// geometric specular anti-aliasing from screen-space normal derivatives (Kaplanyan et al. 2016, in the
// average-normal isotropic form: docs/design.md §4.2).
// Shared by GLSL and C++ (lib/cpp_glsl.h): pure functions, `f` literals. All work on α² (α = perceptual²,
// the GGX width) and return α'² in [0, 1]; every finite input, r = 0 and infinite derivatives included,
// gives a finite result.
#ifndef VCT_TOKSVIG_GLSL
#define VCT_TOKSVIG_GLSL

#include "lib/constants.glsl"

// Shortest averaged-normal length used: r → 0 (normals that cancel) would give σ² → ∞.
const float TOKSVIG_MIN_LENGTH = 1e-3f;

// Pixel filter of the specular AA: a Gaussian of variance 0.25 pixel² (docs/design.md §4.2).
const float SPECULAR_AA_KERNEL_VARIANCE = 0.25f;
// Largest roughness (α²) the specular AA may add: keeps the bias bounded where derivatives explode
// (silhouettes, grazing angles).
const float SPECULAR_AA_THRESHOLD = 0.18f;

// Slope variance of the normals whose average has length r (Toksvig 2005): σ² = (1 − r) / r.
// r is clamped to [TOKSVIG_MIN_LENGTH, 1]; r ≥ 1 (a unit normal) gives 0.
VCT_INLINE float toksvigVariance(float r) {
    float len = clamp(r, TOKSVIG_MIN_LENGTH, 1.0f);
    return (1.0f - len) / len;
}

// Small-angle form: the NDF's slope variance α²/2 plus the normals' σ², i.e. α'² = α² + 2σ², clamped to 1.
VCT_INLINE float toksvigAlpha2(float alpha2, float sigma2) {
    return clamp(alpha2 + 2.0f * max(sigma2, 0.0f), 0.0f, 1.0f);
}

// Exact-in-power form: α'² = (α² + 2σ²(1 − α²)) / (1 + 2σ²(1 − α²)). Agrees with the small-angle form to
// first order in σ², saturates smoothly towards 1 instead of being clipped.
VCT_INLINE float toksvigAlpha2Exact(float alpha2, float sigma2) {
    float a2 = saturate(alpha2);
    float t = 2.0f * max(sigma2, 0.0f) * (1.0f - a2);
    return saturate((a2 + t) / (1.0f + t));
}

// Screen-space variance of the normal for the pixel filter: σ_k² (|∂n/∂x|² + |∂n/∂y|²), where the
// arguments are the squared lengths of the derivatives of the (average) normal across one pixel. This is the
// trace of the covariance, an upper bound of its largest eigenvalue (the isotropic form, docs/design.md §4.2).
VCT_INLINE float specularAAVariance(float dndx2, float dndy2) {
    return SPECULAR_AA_KERNEL_VARIANCE * (max(dndx2, 0.0f) + max(dndy2, 0.0f));
}

// Geometric specular AA (Kaplanyan et al. 2016; Tokuyoshi): α'² = clamp(α² + min(2·var, threshold), 0, 1).
VCT_INLINE float specularAAAlpha2(float alpha2, float variance, float threshold) {
    float added = min(2.0f * max(variance, 0.0f), threshold);
    return saturate(alpha2 + added);
}

#endif  // VCT_TOKSVIG_GLSL
