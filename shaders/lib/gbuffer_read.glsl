// Reading the G-buffer back in screen-space compute passes: pixel → UV → world position.
#ifndef VCT_GBUFFER_READ_GLSL
#define VCT_GBUFFER_READ_GLSL

// World position of a pixel centre from its depth (Vulkan depth range [0, 1]).
vec3 worldFromDepth(mat4 invViewProj, vec2 uv, float depth) {
    const vec4 clip = vec4(uv * 2.0 - 1.0, depth, 1.0);
    const vec4 world = invViewProj * clip;
    return world.xyz / world.w;
}

bool isBackground(float depth) { return depth >= 1.0; }

// A reconstructed position that cannot be shaded: not finite (NaN compares false), or so far out that it is
// (w ≈ 0: a depth at the last steps below 1 when the near plane is tiny against the far one, e.g. 1e-5 to
// 100 m, where the projection's depth resolution runs out). Such pixels get no indirect light, as the background.
bool isDegeneratePosition(vec3 p) { return !all(lessThan(abs(p), vec3(1e18))); }

// The unit shading normal stored in a normalRoughness texel; straight up where it is degenerate (zero length,
// not finite). gbuffer.frag writes unit normals (the geometric normal where the mesh's are zero), so this only
// guards data that did not come from it.
vec3 gbufferNormal(vec4 normalRoughness) {
    const float len = length(normalRoughness.xyz);
    return len > 1e-6 && len < 1e30 ? normalRoughness.xyz / len : vec3(0.0, 1.0, 0.0);  // NaN compares false
}

#endif
