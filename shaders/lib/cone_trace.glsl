// Cone tracing of one full-res pixel through the voxel grid (docs/design.md §5.3–5.5): shared by trace.comp (one
// low-res sample per thread) and resample.comp (the listed full-res pixels). GLSL only: it marches a sampler3D.
// Expects before inclusion: `frame` (FrameUniforms), lib/constants, brdf, cone, voxel and gbuffer_read.
#ifndef VCT_CONE_TRACE_GLSL
#define VCT_CONE_TRACE_GLSL

#include "lib/voxel.glsl"

// The grid as a cone travelling along unit `dir` sees it at `uvw` and (fractional) `mip`: the three direction
// slabs facing it (lib/voxel.glsl), weighted by dir² per axis. Slabs with no weight are not sampled (an
// axis-aligned cone reads one).
vec4 sampleVoxels(sampler3D voxels, vec3 uvw, vec3 dir, float mip) {
    const vec3 w = voxelSlabWeights(dir);
    // Texels per slab at the coarser of the two mips the sample blends.
    const float texels = float(max(int(frame.voxels.resolution) >> int(ceil(mip)), 1));
    vec4 s = vec4(0.0);
    for (int axis = 0; axis < 3; ++axis) {
        if (w[axis] <= 0.0) continue;
        const vec3 slabUvw = vec3(voxelSlabU(uvw.x, voxelSlabFor(dir, axis), texels), uvw.yz);
        s += w[axis] * textureLod(voxels, slabUvw, mip);
    }
    return s;
}

// Marches one cone from `origin` along unit `dir`; returns premultiplied radiance (rgb) and opacity (a).
// Light that leaves the grid unoccluded sees the environment, the constant ambient radiance (the background
// shows the same value, so the two agree).
// The cone leaves the surface at p with unit normal n (coneSurfaceFootprint keeps that surface out of it).
vec4 traceCone(sampler3D voxels, vec3 p, vec3 n, vec3 origin, vec3 dir, float tanHalfAngle) {
    const vec3 gridOrigin = frame.voxels.origin;
    const float v0 = frame.voxels.voxelSize;
    const float gridSize = float(frame.voxels.resolution) * v0;
    const float maxMip = max(float(frame.voxels.mipCount) - 1.0, 0.0);
    vec4 acc = vec4(0.0);
    // Start one voxel out along the cone, from an origin one voxel out along the normal (CONE_START_*: why twice).
    float t = v0 * CONE_START_DISTANCE;
    // Bounded even for a mirror cone (footprint v0): the grid diagonal is √3·N voxels, steps ≥ v0/2.
    const int maxSteps = 4 * int(frame.voxels.resolution) + 8;
    int stepsPastGrid = 0;
    for (int i = 0; i < maxSteps && acc.a < CONE_MAX_OPACITY; ++i) {
        const vec3 x = origin + dir * t;
        const float coneD = coneDiameter(tanHalfAngle, t, v0);
        const float d = coneSurfaceFootprint(coneD, dot(x - p, n), v0);
        const vec3 uvw = (x - gridOrigin) / gridSize;
        // The axis leaves the grid: the grid is padded around the scene bounds, so nothing lies beyond, but
        // the footprint still covers the grid's outermost texels. A cone meeting a wall obliquely sees it
        // opaque only in the slab across the wall and partly in the others (an oblique crossing within one
        // texel is not certain), so a room's walls at the grid's edge would pass (1 − α) of the environment:
        // a closed emissive room gathered 0.79 of its radiance. CONE_STEPS_PAST_GRID more samples of the edge
        // texels (the sampler clamps to the edge) close it: 0.99. A fixed count, not a margin that grows
        // with d: wide cones would then never leave.
        if (any(lessThan(uvw, vec3(0.0))) || any(greaterThan(uvw, vec3(1.0)))) {
            if (++stepsPastGrid > CONE_STEPS_PAST_GRID) break;
        }
        const float mip = min(coneMip(d, v0), maxMip);
        const vec4 s = sampleVoxels(voxels, uvw, dir, mip);
        const float dt = coneStep(coneD);
        // The sample averaged its opacity over voxels of side v0·2^mip (the footprint, up to the top mip).
        acc = coneComposite(acc, s, dt, v0 * exp2(mip));
        t += dt;
    }
    // Stopped as nearly opaque: what lies behind the last CONE_MAX_OPACITY would add its share of the cone in
    // any case, and is estimated as what the cone saw (else a closed room gathers 0.95 of its radiance).
    if (acc.a >= CONE_MAX_OPACITY) acc = vec4(acc.rgb / acc.a, 1.0);
    acc.rgb += (1.0 - saturate(acc.a)) * frame.lighting.ambient;
    return acc;
}

// Demodulated indirect light at full-res `pixel` (lib/cone.glsl): diffuse = cosine-weighted mean incoming
// radiance of the 6 diffuse cones, specular = incoming radiance along the specular cone. Background pixels
// and a missing grid give 0.
struct IndirectSample {
    vec3 diffuse;
    vec3 specular;
};

// The 6 diffuse cones from surface point p with unit normal n: cosine-weighted mean incoming radiance.
vec3 traceDiffuse(sampler3D voxels, vec3 p, vec3 n) {
    const vec3 origin = p + n * (frame.voxels.voxelSize * CONE_START_OFFSET);
    vec3 diffuse = vec3(0.0);
    for (int i = 0; i < DIFFUSE_CONE_COUNT; ++i)
        diffuse += diffuseConeWeight(i) *
                   traceCone(voxels, p, n, origin, diffuseConeDirection(n, i), DIFFUSE_CONE_TAN_HALF).rgb;
    return diffuse;
}

// Both cone sets from surface point p with unit normal n, seen along unit v (towards the camera).
// Specular: the GGX lobe as an SG (lib/cone.glsl). The share of it that the specular cone stands for is read
// from that cone; the rest, which a rough lobe spreads beyond the widest cone, from the diffuse cones weighted
// by the lobe at their directions. A single cone capped at 45° saw only the lobe's centre: on cornell's rough
// walls (α = 0.81) it reflected the dark front wall and ceiling where the path-traced truth also sees the
// lit floor.
IndirectSample traceSurface(sampler3D voxels, vec3 p, vec3 n, vec3 v, float perceptualRoughness) {
    const vec3 origin = p + n * (frame.voxels.voxelSize * CONE_START_OFFSET);
    const float alpha = alphaFromPerceptual(perceptualRoughness);
    const vec3 xi = specularConeDirection(n, v);
    const float invLambda = specularLobeInverseSharpness(alpha, dot(n, v));
    const float tanHalf = specularConeTanHalf(alpha);
    vec3 diffuse = vec3(0.0), lobe = vec3(0.0);
    float lobeWeight = 0.0;
    for (int i = 0; i < DIFFUSE_CONE_COUNT; ++i) {
        const vec3 dir = diffuseConeDirection(n, i);
        const vec3 l = traceCone(voxels, p, n, origin, dir, DIFFUSE_CONE_TAN_HALF).rgb;
        diffuse += diffuseConeWeight(i) * l;
        const float w = sgDiffuseConeWeight(xi, invLambda, n, dir);
        lobe += w * l;
        lobeWeight += w;
    }
    const float inCone = lobeWeight > 0.0 ? specularConeShare(alpha, dot(n, v)) : 1.0;
    vec3 specular = inCone * traceCone(voxels, p, n, origin, xi, tanHalf).rgb;
    if (inCone < 1.0) specular += (1.0 - inCone) * lobe / lobeWeight;
    return IndirectSample(diffuse, specular);
}

IndirectSample tracePixel(sampler3D voxels, sampler2D depthTexture, sampler2D normalRoughnessTexture,
                          ivec2 pixel) {
    const float depth = texelFetch(depthTexture, pixel, 0).r;
    if (isBackground(depth) || frame.voxels.voxelSize <= 0.0) return IndirectSample(vec3(0.0), vec3(0.0));
    const vec2 uv = (vec2(pixel) + 0.5) * frame.texelSize;
    const vec4 normalRoughness = texelFetch(normalRoughnessTexture, pixel, 0);
    const vec3 p = worldFromDepth(frame.invViewProj, uv, depth);
    if (isDegeneratePosition(p)) return IndirectSample(vec3(0.0), vec3(0.0));
    const vec3 n = gbufferNormal(normalRoughness);
    return traceSurface(voxels, p, n, viewDirection(frame.cameraPosition - p, n), normalRoughness.w);
}

#endif  // VCT_CONE_TRACE_GLSL
