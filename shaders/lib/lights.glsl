// Punctual lights (KHR_lights_punctual) as the direct and inject passes and the path-traced reference evaluate
// them. Shared by GLSL and C++ (lib/cpp_glsl.h): pure functions, `f` literals; GpuLight and VCT_LIGHT_* come
// from lib/shared.h.
#ifndef VCT_LIGHTS_GLSL
#define VCT_LIGHTS_GLSL

// Distance reported for a directional light: farther than anything in a scene (shadow rays end there).
const float LIGHT_AT_INFINITY = 3.0e38f;

// What a punctual light delivers at a point.
struct IncidentLight {
    vec3 radiance;      // colour × intensity × falloff: irradiance at normal incidence (a punctual light)
    vec3 towardsLight;  // unit direction from the point towards the light
    float distance;     // to the light's position; LIGHT_AT_INFINITY for a directional light
};

// Light arriving from `light` at p (KHR_lights_punctual: inverse-square falloff, the recommended smooth window to
// zero at the range, the spot's angular attenuation, linear in the cosine between its cones, squared).
VCT_INLINE IncidentLight incidentLight(GpuLight light, vec3 p) {
    IncidentLight result;
    const int type = int(light.directionType.w);
    if (type == VCT_LIGHT_DIRECTIONAL) {
        result.towardsLight = -vec3(light.directionType);
        result.radiance = vec3(light.colorIntensity);
        result.distance = LIGHT_AT_INFINITY;
        return result;
    }
    const vec3 delta = vec3(light.positionRange) - p;
    const float distance2 = max(dot(delta, delta), 1e-8f);
    result.towardsLight = delta * inversesqrt(distance2);
    result.distance = sqrt(distance2);
    float attenuation = 1.0f / distance2;
    const float range = light.positionRange.w;
    if (range > 0.0f) {
        // glTF's recommended smooth window to zero at the range.
        const float ratio = sqrt(distance2) / range;
        attenuation *= clamp(1.0f - ratio * ratio * ratio * ratio, 0.0f, 1.0f);
    }
    if (type == VCT_LIGHT_SPOT) {
        const float cd = dot(vec3(light.directionType), -result.towardsLight);
        const float spot = clamp(cd * light.spotScaleOffset.x + light.spotScaleOffset.y, 0.0f, 1.0f);
        attenuation *= spot * spot;
    }
    result.radiance = vec3(light.colorIntensity) * attenuation;
    return result;
}

#endif  // VCT_LIGHTS_GLSL
