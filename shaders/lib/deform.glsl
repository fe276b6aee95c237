// Skinning and morph targets (glTF 2.0 §3.7.2.2 and §3.7.3), one vertex at a time: the one implementation of
// the deformation math, run by shaders/skin.comp on the GPU and by engine/scene/deform.cpp on the CPU (the
// path-traced reference, the deformed bounds, the tests). Targets morph the rest shape first, in the mesh's
// space; the skin matrix Σ w_k · J[j_k] (J = joint world × inverse bind) then places it in the world.
// Shared by GLSL and C++ (lib/cpp_glsl.h): pure functions, `f` literals.
#ifndef VCT_DEFORM_GLSL
#define VCT_DEFORM_GLSL

#include "lib/constants.glsl"

struct DeformedVertex {
    vec3 position;
    vec3 normal;
    vec4 tangent;
};

// One influence added to a vertex's skin matrix (each language reads joints and weights its own way; both
// start from mat4(0) and add the influences in the same order, so both sum the same floats).
VCT_INLINE mat4 skinInfluence(mat4 skin, mat4 joint, float weight) { return skin + joint * weight; }

// One target's delta added to a morphed attribute.
VCT_INLINE vec3 morphInfluence(vec3 sum, vec3 delta, float weight) { return sum + delta * weight; }

// Normals transform by the inverse transpose of the linear part. Its direction is the cofactor matrix's
// times the determinant's sign, which also exists where a joint is scaled to 0 (no inverse: NaN).
VCT_INLINE vec3 deformNormalDirection(mat3 m, vec3 n) {
    const vec3 c0 = cross(m[1], m[2]), c1 = cross(m[2], m[0]), c2 = cross(m[0], m[1]);
    const float handedness = dot(m[0], c0) < 0.0f ? -1.0f : 1.0f;
    return (c0 * n.x + c1 * n.y + c2 * n.z) * handedness;
}

// v normalised, or `fallback` where it has no direction (a zero or overflowing length).
VCT_INLINE vec3 deformNormalize(vec3 v, vec3 fallback) {
    const float squared = dot(v, v);
    return squared > 1e-30f && squared < 1e30f ? v * inversesqrt(squared) : fallback;
}

// The deformed vertex. morphPosition/Normal/Tangent: Σ w_i δ_i over the mesh's targets (0 without targets);
// `skinned`: false for a mesh without a skin and for a vertex whose weights are all 0 (it keeps its bind
// pose); `skin`: Σ w_k · J[j_k]. Normals and tangents stay unit length (the rest ones where a deformation
// collapses them); tangent.w (the bitangent sign) is kept.
VCT_INLINE DeformedVertex deformVertex(vec3 position, vec3 normal, vec4 tangent, vec3 morphPosition,
                                       vec3 morphNormal, vec3 morphTangent, mat4 skin, bool skinned) {
    vec3 p = position + morphPosition;
    vec3 n = normal + morphNormal;
    vec3 t = vec3(tangent) + morphTangent;
    if (skinned) {
        p = vec3(skin * vec4(p, 1.0f));
        n = deformNormalDirection(mat3(skin), n);
        t = mat3(skin) * t;
    }
    DeformedVertex v;
    v.position = p;
    v.normal = deformNormalize(n, normal);
    v.tangent = vec4(deformNormalize(t, vec3(tangent)), tangent.w);
    return v;
}

#endif  // VCT_DEFORM_GLSL
