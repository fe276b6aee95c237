// Microfacet BRDF (docs/design.md §3): GGX NDF, height-correlated Smith visibility, Schlick Fresnel,
// Lambert diffuse, glTF metallic-roughness parameters, and the split-sum DFG term with multiple-scattering
// energy compensation. Shared by GLSL and C++ (lib/cpp_glsl.h): pure functions, `f` literals.
//
// Conventions: n, v, l are unit vectors pointing away from the surface; NoV = dot(n, v) etc.
// evalBrdf returns the BRDF value f(v, l) in 1/sr, WITHOUT the cosine; evalBrdfCosine multiplies by n·l.
#ifndef VCT_BRDF_GLSL
#define VCT_BRDF_GLSL

#include "lib/constants.glsl"

// Smallest n·v (and n·l) used in shading: grazing and back-facing shading normals (normal maps) are shaded as
// almost grazing instead of turning black or NaN (as Filament's MIN_N_DOT_V).
const float MIN_N_DOT_V = 1e-4f;

// Smallest α for punctual lights only: a light of zero solid angle on a perfect mirror (α = 0, D a delta)
// would give 0 or 0/0. 0.002 is Filament's MIN_ROUGHNESS (perceptual 0.045). Lobes and the DFG term take
// α = 0 as it is.
const float MIN_ALPHA_PUNCTUAL = 0.002f;

// Unit view vector v from a surface point p towards the camera, given toCamera = camera − p: normalize(), but the
// shading normal n where p lies at the camera (|camera − p| below 1e-15, e.g. a surface through the camera
// reconstructed from a depth at the near plane, where normalize(0) is NaN), and where toCamera is not finite.
// v = n reads as a head-on view: finite lobes, n·v = 1.
VCT_INLINE vec3 viewDirection(vec3 toCamera, vec3 n) {
    const float len2 = dot(toCamera, toCamera);
    return len2 > 1e-30f && len2 < 3e38f ? toCamera * inversesqrt(len2) : n;  // NaN compares false
}

// ---- material parameters (glTF 2.0 metallic-roughness) ----

// α = perceptualRoughness² (Burley 2012, Karis 2013; glTF spec appendix B). Exact, may be 0 (a mirror).
VCT_INLINE float alphaFromPerceptual(float perceptualRoughness) {
    float r = saturate(perceptualRoughness);
    return r * r;
}

// Reflectance at normal incidence: 4% for dielectrics (IOR 1.5), the base colour for metals
// (glTF appendix B).
VCT_INLINE vec3 f0FromMetallic(vec3 baseColor, float metallic) {
    return mix(vec3(0.04f), baseColor, saturate(metallic));
}

// Diffuse albedo: metals have none (glTF appendix B).
VCT_INLINE vec3 diffuseAlbedo(vec3 baseColor, float metallic) {
    return baseColor * (1.0f - saturate(metallic));
}

// ---- one function per physical term ----

// GGX / Trowbridge-Reitz NDF: Walter et al. 2007, "Microfacet Models for Refraction through Rough
// Surfaces", eq. 33.
// Normalised: ∫ D(h) (n·h) dω_h = 1. Finite for every input (0 at α = 0: a delta cannot be sampled).
VCT_INLINE float D_GGX(float NoH, float alpha) {
    if (NoH <= 0.0f) return 0.0f;  // χ⁺(n·h): no microfacet faces away from the macro surface
    NoH = min(NoH, 1.0f);
    // (n·h)²(α²−1) + 1 written as (1 − (n·h)²) + (n·h)²α²: no cancellation at n·h → 1 for small α.
    float NoH2 = NoH * NoH;
    float k = alpha / max((1.0f - NoH2) + NoH2 * alpha * alpha, 1e-20f);
    return k * k * INV_PI;
}

// Height-correlated Smith visibility V = G₂ / (4 n·l n·v): Heitz 2014, "Understanding the Masking-Shadowing
// Function in Microfacet-Based BRDFs", eq. 99; in the form of Lagarde & de Rousiers 2014 (Frostbite), §3.2.2.
VCT_INLINE float V_SmithGGXCorrelated(float NoV, float NoL, float alpha) {
    NoV = max(NoV, 0.0f);
    NoL = max(NoL, 0.0f);
    float a2 = alpha * alpha;
    float lambdaV = NoL * sqrt(NoV * NoV * (1.0f - a2) + a2);
    float lambdaL = NoV * sqrt(NoL * NoL * (1.0f - a2) + a2);
    // Guard: the sum is 0 when n·v = n·l = 0, or when either is 0 at α = 0. Callers multiply by n·l.
    return 0.5f / max(lambdaV + lambdaL, 1e-8f);
}

// Schlick 1994, "An Inexpensive BRDF Model for Physically-based Rendering", eq. 15.
VCT_INLINE vec3 F_Schlick(vec3 f0, float VoH) { return f0 + (1.0f - f0) * pow5(1.0f - saturate(VoH)); }
VCT_INLINE float F_Schlick(float f0, float VoH) { return f0 + (1.0f - f0) * pow5(1.0f - saturate(VoH)); }

// Lambert diffuse BRDF for unit albedo.
VCT_INLINE float Fd_Lambert() { return INV_PI; }

// ---- the combined BRDF ----

// Single-scattering specular lobe f_s = D·V·F (Cook & Torrance 1982 with V = G / (4 n·l n·v)), in 1/sr.
VCT_INLINE vec3 specularBrdf(float NoV, float NoL, float NoH, float VoH, vec3 f0, float alpha) {
    return D_GGX(NoH, alpha) * V_SmithGGXCorrelated(NoV, NoL, alpha) * F_Schlick(f0, VoH);
}

// Diffuse lobe weighted by the light Fresnel did not reflect, f_d·(1 − F) (docs/design.md §3.2; glTF appendix B).
VCT_INLINE vec3 diffuseBrdf(vec3 albedo, vec3 F) { return (1.0f - F) * albedo * Fd_Lambert(); }

// f(v, l) = f_d·(1 − F) + f_s for a glTF material, in 1/sr, without the cosine. 0 for light below the
// surface (n·l ≤ 0); n·v is clamped to MIN_N_DOT_V (see above). Reciprocal for n·v, n·l ≥ MIN_N_DOT_V.
VCT_INLINE vec3 evalBrdf(vec3 n, vec3 v, vec3 l, vec3 baseColor, float metallic, float perceptualRoughness) {
    float NoL = dot(n, l);
    if (NoL <= 0.0f) return vec3(0.0f);
    NoL = max(NoL, MIN_N_DOT_V);
    float NoV = max(dot(n, v), MIN_N_DOT_V);
    vec3 h = v + l;
    h = h * inversesqrt(max(dot(h, h), 1e-12f));  // v = −l (only with a back-facing v) gives h = 0, not NaN
    float NoH = saturate(dot(n, h));
    float VoH = saturate(dot(v, h));
    float alpha = max(alphaFromPerceptual(perceptualRoughness), MIN_ALPHA_PUNCTUAL);
    vec3 f0 = f0FromMetallic(baseColor, metallic);
    vec3 F = F_Schlick(f0, VoH);
    vec3 specular = D_GGX(NoH, alpha) * V_SmithGGXCorrelated(NoV, NoL, alpha) * F;
    return diffuseBrdf(diffuseAlbedo(baseColor, metallic), F) + specular;
}

// f(v, l)·(n·l): what a punctual light of unit irradiance (at normal incidence) reflects towards v.
VCT_INLINE vec3 evalBrdfCosine(vec3 n, vec3 v, vec3 l, vec3 baseColor, float metallic,
                               float perceptualRoughness) {
    return evalBrdf(n, v, l, baseColor, metallic, perceptualRoughness) * saturate(dot(n, l));
}

// ---- split sum (Karis 2013, "Real Shading in Unreal Engine 4", pp. 5-7) ----

// Van der Corput radical inverse in base 2 (bit reversal), as a float in [0, 1).
VCT_INLINE float radicalInverseVdC(uint bits) {
    bits = (bits << 16u) | (bits >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
    bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
    bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
    bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
    return float(bits) * 2.3283064365386963e-10f;  // / 2³²
}

// Point i of an n-point Hammersley set (Dammertz 2012, "Hammersley Points on the Hemisphere").
VCT_INLINE vec2 hammersley(uint i, uint n) { return vec2(float(i) / float(n), radicalInverseVdC(i)); }

// Half vector with pdf D(h)(n·h), in tangent space (z = n): Karis 2013, p. 4 (Walter et al. 2007, eq. 35-36).
VCT_INLINE vec3 importanceSampleGGX(vec2 xi, float alpha) {
    float phi = 2.0f * PI * xi.x;
    float cosTheta = sqrt((1.0f - xi.y) / max(1.0f + (alpha * alpha - 1.0f) * xi.y, 1e-7f));
    float sinTheta = sqrt(max(1.0f - cosTheta * cosTheta, 0.0f));
    return vec3(sinTheta * cos(phi), sinTheta * sin(phi), cosTheta);
}

// Directional albedo of the specular lobe split by Fresnel, Karis 2013 p. 7: returns (scale, bias) with
// ∫ f_s (n·l) dω_l ≈ F0·scale + bias, from sampleCount GGX-importance-sampled half vectors. E = scale + bias
// is the single-scattering albedo for F0 = 1 (≤ 1: energy lost to multiple scattering; 1 at α = 0).
VCT_INLINE vec2 integrateDFG(float NoV, float alpha, int sampleCount) {
    NoV = saturate(NoV);
    vec3 v = vec3(sqrt(1.0f - NoV * NoV), 0.0f, NoV);
    float scale = 0.0f;
    float bias = 0.0f;
    for (int i = 0; i < sampleCount; i++) {
        vec3 h = importanceSampleGGX(hammersley(uint(i), uint(sampleCount)), alpha);
        float VoH = dot(v, h);
        vec3 l = 2.0f * VoH * h - v;
        float NoL = l.z;
        if (NoL > 0.0f && VoH > 0.0f) {
            // f_s·(n·l) / pdf_l with pdf_l = D (n·h) / (4 v·h): D cancels.
            float weight = V_SmithGGXCorrelated(NoV, NoL, alpha) * 4.0f * NoL * VoH / max(h.z, 1e-8f);
            float Fc = pow5(1.0f - VoH);
            scale += (1.0f - Fc) * weight;
            bias += Fc * weight;
        }
    }
    vec2 dfg = vec2(scale, bias) / float(max(sampleCount, 1));
    // Near a mirror the float estimate can exceed the true E ≤ 1 by ~1e-4; keep the bound exact.
    return dfg / max(dfg.x + dfg.y, 1.0f);
}

// Multiple-scattering energy compensation (docs/design.md §3.3; Filament §4.7.2; Fdez-Agüera 2019):
// scales single-scattering specular by 1 + F0 (1/E − 1), E = scale + bias from integrateDFG. ≥ 1 for E ≤ 1.
VCT_INLINE vec3 specularEnergyCompensation(vec3 f0, vec2 dfg) {
    // E ≥ ~0.4 in practice. The lower guard keeps 1/E finite; the upper one absorbs rounding (fp16 tables,
    // filtering) so that the compensation never darkens.
    float E = clamp(dfg.x + dfg.y, 1e-4f, 1.0f);
    return 1.0f + f0 * (1.0f / E - 1.0f);
}

// Specular colour for prefiltered (cone-traced) radiance: (F0·scale + bias) with energy compensation.
VCT_INLINE vec3 specularDfg(vec3 f0, vec2 dfg) {
    return (f0 * dfg.x + dfg.y) * specularEnergyCompensation(f0, dfg);
}

#endif  // VCT_BRDF_GLSL
