#version 460
#extension GL_GOOGLE_include_directive : require
// gbuffer: material evaluation (glTF metallic-roughness) and normal mapping.
#include "lib/shared.h"
#include "lib/brdf.glsl"
#include "lib/toksvig.glsl"

// Toksvig variant (docs/design.md §4.1): 0 the small-angle α² + 2σ², 1 the exact-in-power form. Chosen by the
// supersampling measurement in tests/toksvig_test.cpp (exact: MSE 6.16 vs 6.34 against a 16× reference).
#define TOKSVIG_EXACT 1
// 8-bit normal maps quantise each component to 1/127.5: level-0 texels of a unit normal measure |n| from
// about 0.998 to 1.001. Lengths within this much of 1 are read as 1, so unfiltered texels add no roughness.
const float NORMAL_LENGTH_TOLERANCE = 0.003;

// Resources: bound by engine/passes/../render/scene_draw.cpp (its resource table gives these binding numbers and is checked
// against them when the pipeline is made).
layout(set = 0, binding = 2) readonly buffer Materials { GpuMaterial materials[]; };
layout(set = 0, binding = 3) uniform sampler2D baseColorTexture;
layout(set = 0, binding = 4) uniform sampler2D metallicRoughnessTexture;
layout(set = 0, binding = 5) uniform sampler2D normalTexture;
layout(set = 0, binding = 6) uniform sampler2D emissiveTexture;
layout(set = 0, binding = 7) uniform sampler2D occlusionTexture;
layout(set = 0, binding = VCT_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(push_constant) uniform Push { DrawPushConstants draw; };

layout(location = 0) in vec3 inNormal;
layout(location = 1) in vec4 inTangent;
layout(location = 2) in vec2 inUv;
layout(location = 3) in vec4 inClip;
layout(location = 4) in vec4 inPrevClip;
layout(location = 5) in vec3 inWorld;
layout(location = 6) in vec4 inColor;

layout(location = 0) out vec4 outNormalRoughness;
layout(location = 1) out vec4 outBaseColorMetallic;
layout(location = 2) out vec4 outEmissiveOcclusion;
layout(location = 3) out vec2 outMotion;

// Unit vector or, when v is degenerate (zero or not finite), the fallback.
vec3 safeNormalize(vec3 v, vec3 fallback) {
    const float len2 = dot(v, v);
    return (len2 > 1e-20 && !isinf(len2) && !isnan(len2)) ? v * inversesqrt(len2) : fallback;
}

// A material texture: mip-mapped (and anisotropic where the sampler is), or level 0 only when
// VCT_FLAG_TEXTURE_LOD0 is set, so that a supersampled, box-filtered render shows the unfiltered material: the
// ground truth that mip filtering and Toksvig approximate (tests/toksvig_test.cpp). The condition is uniform.
vec4 materialTexture(sampler2D map, vec2 uv) {
    return (frame.flags & VCT_FLAG_TEXTURE_LOD0) != 0u ? textureLod(map, uv, 0.0) : texture(map, uv);
}

void main() {
    // The triangle's geometric normal, towards the camera (the front face's normal on a front face, the back
    // face's on a back face): the fallback where the mesh's normals are zero or not finite (a glTF NORMAL of
    // zeros, or opposite normals averaging to nothing), so such a mesh shades as flat, not as a fixed axis.
    // Taken before the discard below, while the whole quad still runs.
    const vec3 faceCross = cross(dFdx(inWorld), dFdy(inWorld));
    const vec3 towardsCamera = frame.cameraPosition - inWorld;
    const vec3 faceNormal = safeNormalize(dot(faceCross, towardsCamera) < 0.0 ? -faceCross : faceCross,
                                          safeNormalize(towardsCamera, vec3(0.0, 0.0, 1.0)));
    const GpuMaterial material = materials[draw.indices.y];
    vec4 baseColor = material.baseColorFactor * materialTexture(baseColorTexture, inUv);
    // glTF COLOR_0 multiplies the base colour (alpha too). Only where the primitive has one: the
    // interpolated white of the others need not be exactly 1, and their images stay bit-identical.
    if (draw.indices.w != 0u) baseColor *= inColor;
    if (material.flags.x == VCT_ALPHA_MASK && baseColor.a < material.metallicRoughnessCutoffAo.z) discard;

    // Geometric frame; back faces of double-sided surfaces see the flipped normal.
    vec3 normal = safeNormalize(inNormal, gl_FrontFacing ? faceNormal : -faceNormal);
    vec3 tangent = inTangent.xyz - normal * dot(normal, inTangent.xyz);
    tangent = safeNormalize(tangent, abs(normal.x) < 0.9 ? normalize(cross(normal, vec3(1, 0, 0)))
                                                         : normalize(cross(normal, vec3(0, 1, 0))));
    const float handedness = inTangent.w < 0.0 ? -1.0 : 1.0;
    if (!gl_FrontFacing) normal = -normal;
    const vec3 bitangent = cross(normal, tangent) * handedness;

    // Tangent-space normal (glTF: scaled in x, y). The texel's length is kept until here: mips of a normal
    // map average unit normals, and |N̄| < 1 tells how much they disagreed (Toksvig, below).
    const vec3 mapped = materialTexture(normalTexture, inUv).xyz * 2.0 - 1.0;
    const float normalScale = material.emissiveNormalScale.w;
    const vec3 scaled = vec3(mapped.xy * normalScale, mapped.z);
    const vec3 shadingNormal =
        safeNormalize(tangent * scaled.x + bitangent * scaled.y + normal * scaled.z, normal);

    const vec4 mr = materialTexture(metallicRoughnessTexture, inUv);
    const float metallic = clamp(material.metallicRoughnessCutoffAo.x * mr.b, 0.0, 1.0);
    const float perceptualRoughness = clamp(material.metallicRoughnessCutoffAo.y * mr.g, 0.0, 1.0);
    const vec3 emissive = material.emissiveNormalScale.rgb * materialTexture(emissiveTexture, inUv).rgb;
    const float occlusion =
        1.0 + material.metallicRoughnessCutoffAo.w * (materialTexture(occlusionTexture, inUv).r - 1.0);

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
    const float roughness = sqrt(sqrt(saturate(alpha2)));

    outNormalRoughness = vec4(shadingNormal, roughness);
    outBaseColorMetallic = vec4(clamp(baseColor.rgb, 0.0, 1.0), metallic);
    outEmissiveOcclusion = vec4(emissive, occlusion);
    // Motion in UV units (y down, like the image): uv_previous = uv_current - motion.
    const vec2 ndc = inClip.xy / inClip.w;
    const vec2 prevNdc = inPrevClip.xy / inPrevClip.w;
    outMotion = (ndc - prevNdc) * 0.5;
}
