// The glTF metallic-roughness material at a rasterized fragment (docs/design.md §3.1, §4): base colour, the
// normal-mapped shading normal and the filtered roughness (Toksvig, specular AA), metallic, emission,
// occlusion. Shared by gbuffer.frag (written to the G-buffer) and blend.frag (shaded in place), so that opaque
// and blended surfaces evaluate their materials the same way. GLSL only (samplers, derivatives).
// Expects before inclusion: `frame` (FrameUniforms), the material's samplers baseColorTexture,
// metallicRoughnessTexture, normalTexture, emissiveTexture, occlusionTexture, lib/brdf and lib/toksvig.
#ifndef VCT_SURFACE_GLSL
#define VCT_SURFACE_GLSL

// Toksvig variant (docs/design.md §4.1): 0 the small-angle α² + 2σ², 1 the exact-in-power form. Chosen by the
// supersampling measurement in tests/toksvig_test.cpp (exact: MSE 6.16 vs 6.34 against a 16× reference).
#define TOKSVIG_EXACT 1
// 8-bit normal maps quantise each component to 1/127.5: level-0 texels of a unit normal measure |n| from
// about 0.998 to 1.001. Lengths within this much of 1 are read as 1, so unfiltered texels add no roughness.
const float NORMAL_LENGTH_TOLERANCE = 0.003;

// Unit vector or, when v is degenerate (zero or not finite), the fallback.
vec3 safeNormalize(vec3 v, vec3 fallback) {
    const float len2 = dot(v, v);
    return (len2 > 1e-20 && !isinf(len2) && !isnan(len2)) ? v * inversesqrt(len2) : fallback;
}

// A material texture: mip-mapped (and anisotropic where the sampler is), or level 0 only with TEXTURE_LOD0
// (VCT_SPEC_TEXTURE_LOD0), so that a supersampled, box-filtered render shows the unfiltered material: the ground
// truth that mip filtering and Toksvig approximate (tests/toksvig_test.cpp).
layout(constant_id = VCT_SPEC_TEXTURE_LOD0) const bool TEXTURE_LOD0 = false;
vec4 materialTexture(sampler2D map, vec2 uv) {
    return TEXTURE_LOD0 ? textureLod(map, uv, 0.0) : texture(map, uv);
}

// The material's texture in `slot` (VCT_TEXTURE_SLOT_*), or `neutral` where it has none: the value that leaves
// the factor alone (white; a flat tangent-space normal). A missing texture is not sampled: on a CPU device the
// pipeline's TEXTURED_SLOTS (VCT_SPEC_TEXTURED_SLOTS) leaves the sample out of the shader; on a GPU the
// material's flags skip it, a condition uniform over a draw, so the samples' derivatives stay defined.
layout(constant_id = VCT_SPEC_TEXTURED_SLOTS) const uint TEXTURED_SLOTS = VCT_EVERY_TEXTURE_SLOT;
vec4 materialTextureOr(GpuMaterial material, int slot, sampler2D map, vec2 uv, vec4 neutral) {
    const uint bit = 1u << uint(slot);
    return (TEXTURED_SLOTS & bit) != 0u && (material.flags.y & bit) != 0u ? materialTexture(map, uv)
                                                                          : neutral;
}

// The triangle's geometric normal, towards the camera (the front face's normal on a front face, the back
// face's on a back face): the fallback where the mesh's normals are zero or not finite (a glTF NORMAL of
// zeros, or opposite normals averaging to nothing), so such a mesh shades as flat, not as a fixed axis.
// Called before any discard, while the whole quad still runs.
vec3 surfaceFaceNormal(vec3 world) {
    const vec3 faceCross = cross(dFdx(world), dFdy(world));
    const vec3 towardsCamera = frame.cameraPosition - world;
    return safeNormalize(dot(faceCross, towardsCamera) < 0.0 ? -faceCross : faceCross,
                         safeNormalize(towardsCamera, vec3(0.0, 0.0, 1.0)));
}

// Base colour (rgb, linear) and alpha: the factor × the texture.
// glTF COLOR_0 multiplies it (alpha too), only where the primitive has one (`hasVertexColor`, the draw's
// indices.w): the interpolated white of the others need not be exactly 1, and their images stay bit-identical.
vec4 surfaceBaseColor(GpuMaterial material, vec2 uv, vec4 vertexColor, bool hasVertexColor) {
    vec4 baseColor = material.baseColorFactor * materialTextureOr(material, VCT_TEXTURE_SLOT_BASE_COLOR,
                                                                  baseColorTexture, uv, vec4(1.0));
    if (hasVertexColor) baseColor *= vertexColor;
    return baseColor;
}

struct Surface {
    vec3 shadingNormal;  // unit, world space, towards the viewer's side on back faces
    float roughness;     // effective perceptual roughness (after Toksvig and specular AA)
    float metallic;
    vec3 emissive;
    float occlusion;
};

// The rest of the material at the fragment: the tangent frame and normal map, roughness filtering, emission.
Surface evaluateSurface(GpuMaterial material, vec3 faceNormal, vec3 inNormal, vec4 inTangent, vec2 uv,
                        bool frontFacing) {
    // Geometric frame; back faces of double-sided surfaces see the flipped normal.
    vec3 normal = safeNormalize(inNormal, frontFacing ? faceNormal : -faceNormal);
    vec3 tangent = inTangent.xyz - normal * dot(normal, inTangent.xyz);
    tangent = safeNormalize(tangent, abs(normal.x) < 0.9 ? normalize(cross(normal, vec3(1, 0, 0)))
                                                         : normalize(cross(normal, vec3(0, 1, 0))));
    const float handedness = inTangent.w < 0.0 ? -1.0 : 1.0;
    if (!frontFacing) normal = -normal;
    const vec3 bitangent = cross(normal, tangent) * handedness;

    // Tangent-space normal (glTF: scaled in x, y). The texel's length is kept until here: mips of a normal
    // map average unit normals, and |N̄| < 1 tells how much they disagreed (Toksvig, below).
    const float flatTexel = float(VCT_FLAT_NORMAL_TEXEL) / 255.0;
    const vec4 normalTexel = materialTextureOr(material, VCT_TEXTURE_SLOT_NORMAL, normalTexture, uv,
                                               vec4(flatTexel, flatTexel, 1.0, 1.0));
    const vec3 mapped = normalTexel.xyz * 2.0 - 1.0;
    const float normalScale = material.emissiveNormalScale.w;
    const vec3 scaled = vec3(mapped.xy * normalScale, mapped.z);
    const vec3 shadingNormal =
        safeNormalize(tangent * scaled.x + bitangent * scaled.y + normal * scaled.z, normal);

    const vec4 mr = materialTextureOr(material, VCT_TEXTURE_SLOT_METALLIC_ROUGHNESS, metallicRoughnessTexture,
                                      uv, vec4(1.0));
    const float metallic = clamp(material.metallicRoughnessCutoffAo.x * mr.b, 0.0, 1.0);
    const float perceptualRoughness = clamp(material.metallicRoughnessCutoffAo.y * mr.g, 0.0, 1.0);
    const vec3 emissive =
        material.emissiveNormalScale.rgb *
        materialTextureOr(material, VCT_TEXTURE_SLOT_EMISSIVE, emissiveTexture, uv, vec4(1.0)).rgb;
    const float occlusion =
        1.0 +
        material.metallicRoughnessCutoffAo.w *
            (materialTextureOr(material, VCT_TEXTURE_SLOT_OCCLUSION, occlusionTexture, uv, vec4(1.0)).r -
             1.0);

    // Normal filtering widens the GGX lobe: α'² from α² (α = perceptual²), written back as perceptual √α'.
    const float alpha = alphaFromPerceptual(perceptualRoughness);
    float alpha2 = alpha * alpha;
    // Derivatives outside the switches (uniform anyway): the shading normal's change across one pixel.
    const vec3 dndx = dFdx(shadingNormal), dndy = dFdy(shadingNormal);
    if ((frame.flags & VCT_FLAG_TOKSVIG) != 0u) {
        // Slopes of the scaled map are normalScale × the texels' slopes, so their variance scales by its square.
        const float r = min(length(mapped) + NORMAL_LENGTH_TOLERANCE, 1.0);
        const float sigma2 = toksvigVariance(r) * normalScale * normalScale;
#if TOKSVIG_EXACT
        alpha2 = toksvigAlpha2Exact(alpha2, sigma2);
#else
        alpha2 = toksvigAlpha2(alpha2, sigma2);
#endif
    }
    if ((frame.flags & VCT_FLAG_SPECULAR_AA) != 0u)
        alpha2 = specularAAAlpha2(alpha2, specularAAVariance(dot(dndx, dndx), dot(dndy, dndy)),
                                  SPECULAR_AA_THRESHOLD);
    Surface s;
    s.shadingNormal = shadingNormal;
    s.roughness = sqrt(sqrt(saturate(alpha2)));
    s.metallic = metallic;
    s.emissive = emissive;
    s.occlusion = occlusion;
    return s;
}

#endif  // VCT_SURFACE_GLSL
