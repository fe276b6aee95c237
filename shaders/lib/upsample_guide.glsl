// What the upsample weights compare at one pixel (docs/design.md §6.2–6.4): its position, camera distance, normal
// and the specular lobe (axis ξ, κ-smoothed sharpness λ̄). The diffuse lobe is the normal with a fixed sharpness.
// trace.comp computes it once per low-res sample and stores it (its guide images); upsample.comp
// computes it for its own pixel and for the history's texels from the G-buffers. GLSL only; expects
// lib/brdf.glsl, lib/gbuffer_read.glsl and lib/upsample_weights.glsl.
#ifndef VCT_UPSAMPLE_GUIDE_GLSL
#define VCT_UPSAMPLE_GUIDE_GLSL

struct Guide {
    vec3 p;
    float cameraDistance;
    vec3 n;
    float specularSharpness;  // λ̄ of the specular lobe
    vec3 specularAxis;
};

Guide guideFromGBuffer(vec4 normalRoughness, vec3 p, vec3 cameraPosition, float kappa) {
    Guide g;
    g.p = p;
    const vec3 toCamera = cameraPosition - p;
    g.cameraDistance = length(toCamera);
    g.n = gbufferNormal(normalRoughness);
    const vec3 v = viewDirection(toCamera, g.n);
    const vec4 lobe = specularLobe(g.n, v, alphaFromPerceptual(normalRoughness.w));
    g.specularAxis = lobe.xyz;
    g.specularSharpness = smoothedSharpness(lobe.w, kappa);
    return g;
}

#endif  // VCT_UPSAMPLE_GUIDE_GLSL
