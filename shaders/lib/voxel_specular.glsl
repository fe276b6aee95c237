// Glossy reflection in the voxels' six direction slabs (docs/design.md §5.11). Shared by GLSL and C++
// (lib/cpp_glsl.h): pure functions, `f` literals. Expects lib/brdf.glsl, lib/cone.glsl, lib/toksvig.glsl and
// lib/voxel.glsl.
//
// A voxel lit by a punctual light sends its diffuse part to every side alike and its specular part into a lobe
// about the mirror direction r = reflect(−l, n). The slabs hold radiance by the direction it leaves in, and a cone
// reads them weighted by ω² per axis (voxelSlabWeights), so they can carry the lobe's broad shape: glossy
// surfaces lighting others (glossy-to-diffuse transport), which a diffuse-only voxel cannot.
//
// The lobe is a von Mises-Fisher distribution (a normalised spherical Gaussian) about r of concentration λ, the
// GGX lobe (as a spherical Gaussian of sharpness 2/α² about n in half-vector space) warped to the outgoing
// directions: λ = 2/α² / (4 n·l) (Wang et al. 2009, "All-frequency rendering of dynamic, spatially-varying
// reflectance"). Slab s (outgoing direction e) takes the share E[(ω·e)₊²] of the lobe: its own reading weight, so
// the six shares sum to 1 and keep the lobe's mean direction within the slabs' resolution. The shares are then
// scaled so that the light the slabs send through the surface, Σ_s value_s·slabExitance(n, s), is the specular
// exitance E·(n·l)·ρ_s (ρ_s the directional albedo, F0·A + B from the split-sum table): what the voxel reflects reaches the other surfaces in total,
// however blurred. (Keeping ∫ radiance dω instead sent 2.3x too much light from walls lit at grazing angles, whose
// narrow grazing lobes the slabs spread towards their normals: measured on cornell against the path tracer.)
#ifndef VCT_VOXEL_SPECULAR_GLSL
#define VCT_VOXEL_SPECULAR_GLSL

// Mean cosine A(λ) = coth λ − 1/λ of a vMF lobe of concentration λ about its axis (E[ω·r]), from 1/λ: 1 − 1/λ for
// a sharp lobe, λ/3 − λ³/45 + 2λ⁵/945 for a broad one.
VCT_INLINE float vmfMeanCosine(float inverseLambda) {
    if (inverseLambda < 1e-4f) return 1.0f - inverseLambda;  // coth λ = 1 to float precision
    if (inverseLambda > 10.0f) {  // λ < 0.1: the series, where coth λ − 1/λ would cancel in float
        float lambda = 1.0f / inverseLambda, l2 = lambda * lambda;
        return lambda * (1.0f / 3.0f - l2 * (1.0f / 45.0f - l2 * (2.0f / 945.0f)));
    }
    // coth λ = (1 + e^−2λ)/(1 − e^−2λ): no overflow for large λ.
    float e = exp(-2.0f / inverseLambda);
    return (1.0f + e) / (1.0f - e) - inverseLambda;
}

// A(λ)/λ, the spread of the second moment: E[ωωᵀ] = (1 − 3A/λ)·r rᵀ + (A/λ)·I. 1/3 for a uniform lobe, → 0 for
// a sharp one.
VCT_INLINE float vmfSpread(float inverseLambda) {
    return clamp(vmfMeanCosine(inverseLambda) * inverseLambda, 0.0f, 1.0f / 3.0f);
}

// E[(ω·e)₊²] for a vMF lobe about unit r with spread vmfSpread(λ) and unit e: the axis part goes to the side r
// points to, the isotropic part half to each side, scaled by `isotropicWeight`. With it 1 the six axis
// directions' values sum to 1; specularSlabShare passes the slab's facing.
VCT_INLINE float vmfSlabShare(vec3 r, float spread, vec3 e, float isotropicWeight) {
    float re = max(dot(r, e), 0.0f);
    return (1.0f - 3.0f * spread) * re * re + isotropicWeight * 0.5f * spread;
}

// The roughness of a voxel's lobe: its surfaces' mean perceptual roughness widened by the spread of their normals
// (Toksvig, lib/toksvig.glsl) read from the averaged normal's length: a curved or bumpy surface within one voxel
// reflects a wider lobe than any one of its points does.
VCT_INLINE float voxelLobeRoughness(float perceptualRoughness, float normalLength) {
    float a = alphaFromPerceptual(perceptualRoughness);
    return sqrt(sqrt(toksvigAlpha2Exact(a * a, toksvigVariance(normalLength))));
}

// What a slab of unit radiance sends through the surface of unit normal n, ∫ (ω·e)₊²·(ω·n)₊ dω = π/8·(1 + n·e)²
// (e its outgoing direction; integrated in closed form, tests/voxel_specular_test.cpp checks it numerically). The
// six values sum to π, the exitance of unit radiance on every side.
VCT_INLINE float slabExitance(vec3 n, int slab) {
    float c = 1.0f - dot(n, voxelSlabDirection(slab));
    return 0.125f * PI * c * c;
}

// The specular lobe of a voxel lit from unit l: its axis r = reflect(−l, n) (xyz) and spread (w, vmfSpread), its
// sharpness the warped GGX lobe's as the cones take it (lib/cone.glsl's specularLobeInverseSharpness, with the
// light's n·l for the view's). n is the voxel's unit normal turned towards the light, NoL = n·l > 0.
VCT_INLINE vec4 specularLobe(vec3 n, vec3 l, float NoL, float perceptualRoughness) {
    float inverseLambda = specularLobeInverseSharpness(alphaFromPerceptual(perceptualRoughness), NoL);
    return vec4(2.0f * NoL * n - l, vmfSpread(inverseLambda));
}

// The share of `lobe` that slab `slab` carries, before normalisation: its reading weight E[(ω·e)₊²]
// (vmfSlabShare), e the slab's outgoing direction; inject.comp scales the shares to the specular exitance with
// slabExitance. `facing` is the slab's voxelFacing (lib/voxel.glsl): it keeps the lobe's isotropic part (half to
// every side) from leaving behind the surface, and leaves the axis part alone.
// The lobe goes where it points, also along the surface: a metal sphere's flank lit from above at a grazing
// angle reflects the light downwards, onto the floor around it.
// - Foreshortening each slab by (n·e)₊ (until issue 18, round 6) gave that flank's downward slab nothing, and its
//   lobe lit the walls sideways instead: cornell's floor got 10 % of its light by glossy bounces where the truth
//   has 32 %. The factor had been there to keep a lit metal plane from lighting itself through the sideways slabs
//   of its own voxels (`plane` 1.77× without it); the jittered cone set's clearance keeps a surface's own voxels
//   out of its cones instead (`plane` 1.06× against the path tracer; docs/design.md §5.6), the fixed set's does
//   not (1.77×, still closer than the 0.27× the factor gave it there).
// - The facing on the axis part (until round 21) did the same wherever the averaged normal n̄ leans away from
//   the slab the reflection leaves by: a flank whose n̄ points up and sideways reflects a grazing light sideways
//   and down, and its downward slab is behind n̄. The reflection r = 2(n·l)n − l is never behind its surface, but
//   its slab components can be. Cornell's floor got 0.77× (64³) and 0.66× (128³) of its true glossy-bounce
//   light with it, 1.14× and 1.03× without (docs/design.md §5.11).
//   Cost: what the axis part sends behind a one-sided oblique surface is seen from behind it, and the exitance
//   normalisation (inject.comp) does not count it (tests/voxel_specular_test.cpp bounds it).
VCT_INLINE float specularSlabShare(vec4 lobe, int slab, float facing) {
    return vmfSlabShare(vec3(lobe), lobe.w, -voxelSlabDirection(slab), facing);
}

// The share of the light arriving from the grid that a voxel sends on (multiple bounces, docs/design.md §5.7).
// The bounce gathers give the cosine-weighted mean incoming radiance without a direction, so the voxel reflects it
// as light arriving at the cosine-weighted hemisphere's mean cosine n·l = 2/3, to every side alike: the specular
// albedo ρ_s = F0·A + B of the split-sum table at (2/3, roughness) (`dfg`), and the diffuse albedo of what the
// specular layer leaves, albedo·(1 − ρ_s). That sum is at most 1 wherever the albedo and ρ_s are, so no furnace
// runs away; the lights' split (albedo·(1 − F(n·l)) + ρ_s) need not be. Until round 17 a voxel reflected bounced
// light by its base colour (no specular layer for a dielectric, a metal's base colour as a diffuse reflectance):
// cornell's every-bounce light rose from 0.911 to 0.928 of the path tracer's (64³). Without glossy voxels, the
// diffuse albedo alone (what `vct reference --secondary diffuse` reflects).
const float BOUNCE_MEAN_COSINE = 2.0f / 3.0f;
VCT_INLINE vec3 bouncedLightReflectance(vec3 baseColor, float metallic, vec2 dfg, bool glossy) {
    const vec3 albedo = diffuseAlbedo(baseColor, metallic);
    if (!glossy) return albedo;
    const vec3 specularAlbedo = f0FromMetallic(baseColor, metallic) * dfg.x + dfg.y;
    return albedo * (1.0f - specularAlbedo) + specularAlbedo;
}

#endif  // VCT_VOXEL_SPECULAR_GLSL
