#version 460
#extension GL_GOOGLE_include_directive : require
// skin: deforms one skinned and/or morphed primitive of one instance, one invocation per vertex: its morph
// targets' deltas times this frame's weights, then its (up to 8) joint influences, with the math of
// lib/deform.glsl that the CPU twin (engine/scene/deform.cpp) runs too. Writes whole vertices (the Vertex
// layout: the draws take them as vertex input) into the deformed buffer, and on a cut into the previous one
// as well (no motion).
#include "lib/shared.h"
#include "lib/deform.glsl"

layout(local_size_x = VCT_SKIN_GROUP_SIZE) in;

// Resources: bound by engine/passes/skin_pass.cpp (its resource table gives these binding numbers and is checked
// against them when the pipeline is made).
// The Vertex struct (VCT_FLOATS_PER_VERTEX floats: position, normal, uv, tangent, color) read and written as
// floats: std430 would pad its vec3s. The colour passes through unchanged.
layout(set = 0, binding = 0) readonly buffer Rest { float restData[]; };
struct SkinVertex {
    uvec4 joints0;
    uvec4 joints1;
    vec4 weights0;
    vec4 weights1;
};
layout(set = 0, binding = 1) readonly buffer Skins { SkinVertex skinVertices[]; };
// MorphDelta: position, normal, tangent deltas (xyz) per vertex and target.
layout(set = 0, binding = 2) readonly buffer Morphs { vec4 morphDeltas[]; };
layout(set = 0, binding = 3) readonly buffer Joints { mat4 jointMatrices[]; };
layout(set = 0, binding = 4) readonly buffer Weights { float morphWeights[]; };
layout(set = 0, binding = 5) writeonly buffer Deformed { float deformedData[]; };
layout(set = 0, binding = 6) writeonly buffer Previous { float previousData[]; };

layout(push_constant) uniform Push { SkinPushConstants push; };

const uint kFloatsPerVertex = VCT_FLOATS_PER_VERTEX;

void main() {
    const uint v = gl_GlobalInvocationID.x;
    const uint count = push.vertices.y;
    if (v >= count) return;
    const uint rest = (push.vertices.x + v) * kFloatsPerVertex;
    float data[VCT_FLOATS_PER_VERTEX];
    for (uint i = 0; i < kFloatsPerVertex; ++i) data[i] = restData[rest + i];

    // Targets in order, then the influences in order: the order deform.cpp sums in.
    vec3 dp = vec3(0.0), dn = vec3(0.0), dt = vec3(0.0);
    for (uint t = 0; t < push.morph.y; ++t) {
        const float w = morphWeights[push.morph.z + t];
        if (w == 0.0) continue;
        const uint d = (push.morph.x + t * count + v) * 3;
        dp = morphInfluence(dp, morphDeltas[d].xyz, w);
        dn = morphInfluence(dn, morphDeltas[d + 1].xyz, w);
        dt = morphInfluence(dt, morphDeltas[d + 2].xyz, w);
    }
    mat4 skin = mat4(0.0);
    bool weighted = false;
    if (push.vertices.w != VCT_SKIN_NONE) {
        const SkinVertex s = skinVertices[push.vertices.w + v];
        for (int k = 0; k < 8; ++k) {
            const float w = k < 4 ? s.weights0[k] : s.weights1[k - 4];
            const uint j = k < 4 ? s.joints0[k] : s.joints1[k - 4];
            if (!(w > 0.0) || j >= push.flags.y) continue;
            skin = skinInfluence(skin, jointMatrices[push.morph.w + j], w);
            weighted = true;
        }
    }
    const DeformedVertex d =
        deformVertex(vec3(data[0], data[1], data[2]), vec3(data[3], data[4], data[5]),
                     vec4(data[8], data[9], data[10], data[11]), dp, dn, dt, skin, weighted);
    data[0] = d.position.x;
    data[1] = d.position.y;
    data[2] = d.position.z;
    data[3] = d.normal.x;
    data[4] = d.normal.y;
    data[5] = d.normal.z;
    data[8] = d.tangent.x;
    data[9] = d.tangent.y;
    data[10] = d.tangent.z;
    const uint dst = (push.vertices.z + v) * kFloatsPerVertex;
    for (uint i = 0; i < kFloatsPerVertex; ++i) deformedData[dst + i] = data[i];
    if (push.flags.x != 0)
        for (uint i = 0; i < kFloatsPerVertex; ++i) previousData[dst + i] = data[i];
}
