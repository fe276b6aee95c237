// The main light's shadow at a surface point: 3×3 PCF on its shadow map (lib/shadow_pcf.glsl's four bilinear
// compare taps). Shared by direct.comp (opaque pixels) and blend.frag (blended fragments). GLSL only.
// Expects before inclusion: `frame` (FrameUniforms), `shadowMap` (sampler2DShadow), lib/shadow_pcf; with
// VCT_SHADOW_COORDINATES_ONLY defined (direct_select.comp, which reads no texel), `frame` alone.
#ifndef VCT_SHADOW_LOOKUP_GLSL
#define VCT_SHADOW_LOOKUP_GLSL

// Where a surface point looks the shadow map up: texel-centre coordinates t (texel i's centre at t = i) and the
// depth compared, or `reads` false outside the light's frustum (lit, no texel read). The position is pushed along
// the normal by a texel or so, which removes acne on surfaces at grazing light angles without detaching shadows.
struct ShadowCoordinate {
    bool reads;
    vec2 t;
    float depth;
};

ShadowCoordinate shadowCoordinate(vec3 worldPosition, vec3 normal) {
    ShadowCoordinate c = ShadowCoordinate(false, vec2(0.0), 0.0);
    const vec3 offsetPosition = worldPosition + normal * frame.lighting.shadowNormalOffset * 1.5;
    const vec4 clip = frame.lightViewProj * vec4(offsetPosition, 1.0);
    if (clip.w <= 0.0) return c;
    const vec3 ndc = clip.xyz / clip.w;
    const vec2 uv = ndc.xy * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))) || ndc.z >= 1.0) return c;
    c.reads = true;
    c.t = uv / frame.lighting.shadowTexelSize - 0.5;
    c.depth = ndc.z;
    return c;
}

#ifndef VCT_SHADOW_COORDINATES_ONLY
float shadowVisibility(vec3 worldPosition, vec3 normal) {
    const ShadowCoordinate c = shadowCoordinate(worldPosition, normal);
    if (!c.reads) return 1.0;
    const float texelSize = frame.lighting.shadowTexelSize;
    const PcfTaps taps = pcfTaps(c.t);
    const vec2 first = (taps.first + 0.5) * texelSize, last = (taps.last + 0.5) * texelSize;
    const float visible =
        taps.firstWeight.x * taps.firstWeight.y * texture(shadowMap, vec3(first, c.depth)) +
        taps.lastWeight.x * taps.firstWeight.y * texture(shadowMap, vec3(last.x, first.y, c.depth)) +
        taps.firstWeight.x * taps.lastWeight.y * texture(shadowMap, vec3(first.x, last.y, c.depth)) +
        taps.lastWeight.x * taps.lastWeight.y * texture(shadowMap, vec3(last, c.depth));
    return visible / 9.0;
}
#endif

// Whether shadowVisibility at this point reads a texel of `rect` ([xy, zw)): the 3×3 PCF's taps read the 4×4
// texels from floor(t) − 1 on (lib/shadow_pcf.glsl).
bool shadowLookupReads(vec3 worldPosition, vec3 normal, ivec4 rect) {
    const ShadowCoordinate c = shadowCoordinate(worldPosition, normal);
    if (!c.reads) return false;
    const ivec2 first = ivec2(floor(c.t)) - 1, last = first + 3;
    return all(lessThan(first, rect.zw)) && all(greaterThanEqual(last, rect.xy));
}

#endif  // VCT_SHADOW_LOOKUP_GLSL
