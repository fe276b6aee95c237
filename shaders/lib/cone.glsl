// Voxel cone tracing math (docs/design.md §5.3–5.5, Crassin et al. 2011): cone footprint, mip level, step length,
// front-to-back compositing with step-length opacity correction, the 6 diffuse cones and the specular aperture.
// Shared by GLSL and C++ (lib/cpp_glsl.h): pure functions, `f` literals. The march loop itself lives in
// trace.comp (GLSL cannot take a sample function as a parameter); tests/cone_test.cpp repeats it on the CPU
// with an emulated grid, built from these very functions.
//
// Units: distances in world units; v0 = the finest voxel size. A sample at mip m covers a cube of side v0·2^m.
//
// Normalisation of what the cones return (the trace pass's outputs):
//   diffuse  = Σ_i w_i·L_i with Σ w_i = 1: the cosine-weighted mean of incoming radiance, "radiance-equivalent".
//              Irradiance E = π·diffuse; outgoing Lambert radiance = albedo·diffuse (albedo/π · E).
//   specular = the incoming radiance averaged over the specular cone; outgoing = specularDfg(F0, DFG)·specular.
#ifndef VCT_CONE_GLSL
#define VCT_CONE_GLSL

#include "lib/constants.glsl"

// Diffuse cones: half-angle 30° (aperture 60°), tan(θ/2) = tan 30°: six such cones tile the hemisphere.
const float DIFFUSE_CONE_TAN_HALF = 0.577350269f;
const int DIFFUSE_CONE_COUNT = 6;
// Step length as a fraction of the footprint. Below 1 the trilinear samples overlap and thin walls are not
// skipped (opacity is corrected for the step length, coneComposite). 0.5 until the directional voxels made
// each step read up to three slabs; 0.75 cut the default frame's trace by a fifth on lavapipe (63 → 50 ms at
// 640×360, loaded machine) and moved cornell's per-surface indirect ratios against the path-traced truth by
// ≤ 0.04 at 64³ (indirect PSNR 20.14 → 20.17 dB).
const float CONE_STEP_SCALE = 0.75f;
// Marching stops once the cone is this opaque: what lies behind adds < 5%.
const float CONE_MAX_OPACITY = 0.95f;
// Where a cone starts, in voxels v0: from the origin p + n·v0·CONE_START_OFFSET, its first sample at distance
// t0 = v0·CONE_START_DISTANCE along the cone. Both are 1: the offset is taken twice, once along the normal and
// once along the cone (the normal cone's first sample is 2 voxels out, a 60° side cone's 1.5), where the
// usual reading of Crassin et al. is once (start at p + n·v0, t0 = 0; docs/design.md §5.4). Kept on purpose,
// measured against analytic cases under a uniform sky (tests/cone_test.cpp,
// Cone.StartOffsetAgainstAnalyticFloorAndWall; a 64-voxel march, the surface voxelized as the voxel containing it
// at 5 alignments): the surface's own voxel and its trilinear neighbourhood reach up to 2 voxels above it, and on
// an open black floor (exact irradiance π·L) the double start's self-occlusion is a mean −10.6 % (worst −22.0 %,
// surface at the bottom of its voxel) against −18.6 % (worst −49.8 %) for the single start and −50.7 % starting
// at p. Leaking beside a one-voxel-thin wall is the same (+37.0 % against +36.9 %: coarse mips, not the start).
// The price: under a one-voxel-thin ceiling 1–3 voxels up (exact: dark) it sees 39.8 % of the sky against 29.8 %.
// Starting 2 voxels out along n would cut the self-occlusion to −3.5 % but put the origin inside such occluders.
const float CONE_START_OFFSET = 1.0f;
const float CONE_START_DISTANCE = 1.0f;
// The jittered cone set (`--cone-jitter on`, cone_trace.glsl's ConeSet, docs/design.md §5.5) starts 1.5 voxels
// out along n: its cones leave at any elevation down to the horizon, and the first sample (one voxel along the
// cone) of a grazing one must still be 1.5 voxels above the surface, where a mip-0 trilinear read no longer
// reaches the voxel layer holding the surface (its centres are within half a voxel of it). At 1 the closed box of
// VoxelGi.HowMuchASurfaceShadowsAndLightsItselfInAClosedBox read 0.948 / 0.936 at 32³ / 128³ (exact 1), at 1.5
// 0.998 / 0.985.
const float CONE_START_OFFSET_JITTERED = 1.5f;
// Samples a cone takes beyond the grid's faces before it stops (cone_trace.glsl: why). Past a closed room's own face
// (a side of the closure box that is not the grid's: render/voxel_bricks.h's coneClosureBox) it takes one, on that
// face (cone_trace.glsl's closedFaceRead). Past the grid's faces 4 would read the edge texels, where the walls of
// open scenes may stand, twice as long: courtyard 25.40 → 24.45 dB, DamagedHelmet 22.02 → 21.28 dB (indirect sRGB
// PSNR against the truth, 64³).
const int CONE_STEPS_PAST_GRID = 2;
// coneSurfaceFootprint: how wide a footprint may be for its height above the surface the cone left.
// The fixed cone set: 0.5. A sample at height h then reads mip levels up to a texel of 2·0.5h = h, and a trilinear
// read there reaches 1.5 texels below it, into the surface's own voxel layer: the surface shadows (and, through
// its sideways slabs, lights) its own cones, more as voxels get finer (the closed box: 0.970 / 0.934 / 0.843 of
// the exact 1 at 32³ / 64³ / 128³). Narrower, the fixed set's cones become thin rays at six fixed directions
// (blotchy: cornell −3.7 dB at 0.25), so it keeps this compromise.
const float CONE_SURFACE_CLEARANCE = 0.5f;
// The jittered set: 0.25, the coarser level's texel ≤ h/2, so the trilinear read stays ≥ h/4 above the surface
// and out of its layer (the box: 1.000 at 32³ and 64³). Its narrower cones sample a random place of their
// tile of the hemisphere every frame, and the history integrates the tile (docs/design.md §5.5).
const float CONE_SURFACE_CLEARANCE_JITTERED = 0.25f;
// Widest specular cone: half-angle 45°. Wider lobes are as blurry as the diffuse cones, and a wider cone
// would reach coarse mips within a voxel or two (leaking through walls).
const float SPECULAR_CONE_MAX_TAN_HALF = 1.0f;

// Cone diameter at distance t: d = max(v0, 2·tan(θ/2)·t). Never below one voxel (mip 0 cannot be finer).
VCT_INLINE float coneDiameter(float tanHalfAngle, float t, float voxelSize) {
    return max(voxelSize, 2.0f * tanHalfAngle * max(t, 0.0f));
}

// The footprint a cone leaving a surface samples at: its diameter, but no wider than the sample's height above
// the surface (times CONE_SURFACE_CLEARANCE) and never below one voxel. A side cone's footprint reaches down to
// the surface it leaves (its edge runs along the tangent plane), and there the surface's own voxels, lit and
// opaque, would light or shadow it: a lit floor lighting itself, a wall shadowing its own side cones. Sampling a
// finer mip until the cone has risen clear of the surface keeps them out.
VCT_INLINE float coneSurfaceFootprint(float diameter, float height, float voxelSize, float clearance) {
    return max(voxelSize, min(diameter, clearance * height));
}

// How far a trilinear read at mip m reaches, in that mip's voxels: it weighs the texels whose centres lie within
// one texel of it, and each texel is the mean of half a texel either side.
const float CONE_MIP_REACH = 1.5f;

// How far to lift a sample at `height` above the surface its cone leaves (along that surface's normal) so that
// the coarser level of its fractional `mip` keeps the surface out as well. coneSurfaceFootprint bounds the finer
// level's voxels by clearance × height, but the trilinear blend between levels also reads the next one, whose
// voxels are twice as wide: at clearance 0.5 it reached the surface, whose own voxels then shadowed or lit the
// cone over many steps. So the lift clears the whole reach of the coarsest level the blend reads: level ⌈m⌉
// whenever it weighs anything. A black face of a closed emissive box gathers 1.000 of its light at 32³, 64³ and
// 128³ (0.970 / 0.934 / 0.843 unlifted), an emissive face under black ones lights itself with 0.001 (0.010 with
// the coarser level's reach counted only in proportion below a quarter of its weight, round 11: a lit floor's
// sideways voxels, read through that level, gave it 1.2 % of its own radiance back; docs/design.md §5.3).
// 0 once the cone has risen clear. The lift doubles where m passes an integer (round 11 had seen bands from that at
// 32³; cornell's diffuse view at 32³ and 64³ showed none in round 14).
VCT_INLINE float coneCoarseMipLift(float height, float mip, float voxelSize) {
    const float level = ceil(mip);  // the coarsest level read: ⌊m⌋ + 1 in a blend, m itself at an integer
    const float reach = CONE_MIP_REACH * ldexp(voxelSize, int(level));  // a whole level: exact, no exp2
    return max(reach - height, 0.0f);
}

// Where a cone's sample at x reads the box [boxMin, boxMax] (the grid, or the closure box of a closed room:
// cone_trace.glsl), and at which mip, for a cone that left the surface at p with unit normal n: lifted by
// coneCoarseMipLift, and kept inside the box. A sample past the box (a cone that has left it: cone_trace.glsl takes
// a few more, to close walls met obliquely at the border) reads the box's edge as if taken there: there its height
// above the surface, not x's, counts. Where the lift cannot be had within the box (a cone leaving it straight above an
// open floor that spans the grid) the mip is capped instead at the level whose reach ends above the surface:
// the top level's texel holds the whole grid, the floor among it, opaque in the slab along the normal, and an
// open white floor under a white sky gathered 0.46 of the sky (exact 1) before; 0.96 capped
// (`EnvironmentGpu.WhiteEnvironmentOverAnOpenWhitePlaneGivesTheAnalyticRadiance`, docs/design.md §5.3).
struct ConeSampleAt {
    vec3 position;
    float mip;
    // The read was moved back onto a face of the box that the surface the cone left lies within mip 0's reach of
    // (CONE_MIP_REACH voxels), and there to within that reach of the surface along its normal: even mip 0 reads the
    // surface's own voxel layer there (cone_trace.glsl: what then). A surface farther from that face (a floor beside
    // a wall at the grid's edge) is not in the face's layer, whatever its normal's tilt.
    bool ownLayer;
};

VCT_INLINE ConeSampleAt coneSampleAt(vec3 x, float mip, vec3 p, vec3 n, float voxelSize, vec3 boxMin,
                                     vec3 boxMax) {
    ConeSampleAt at;
    const vec3 edge = clamp(x, boxMin, boxMax);
    const vec3 lifted = edge + n * coneCoarseMipLift(dot(edge - p, n), mip, voxelSize);
    at.position = clamp(lifted, boxMin, boxMax);
    at.mip = mip;
    at.ownLayer = false;
    if (any(notEqual(at.position, lifted))) {
        const float height = max(dot(at.position - p, n), 0.0f);
        const float reach = CONE_MIP_REACH * voxelSize;
        // How far p lies inside the faces the read was clamped to (the others: infinitely far).
        const vec3 inside = mix(p - boxMin, boxMax - p, vec3(greaterThan(lifted, boxMax)));
        const vec3 fromFace = mix(vec3(1e30f), inside, vec3(notEqual(at.position, lifted)));
        at.ownLayer = height < reach && min(fromFace.x, min(fromFace.y, fromFace.z)) < reach;
        // ⌊log2 y⌋ from y's exponent (y = f·2^e, f in [0.5, 1)): e − 1, exactly, and no log2 per step.
        int e = 0;
        frexp(max(height / reach, 1e-6f), e);
        const float clear = float(e - 1);
        at.mip = min(mip, max(clear, 0.0f));
    }
    return at;
}

// Mip whose voxels match the footprint: log2(d / v0) ≥ 0 (fractional: trilinear between mips).
VCT_INLINE float coneMip(float diameter, float voxelSize) {
    return max(log2(max(diameter, voxelSize) / voxelSize), 0.0f);
}

// The mip a diffuse cone of the fixed or turned set, and the specular cone, read (cone_trace.glsl's traceCone with
// whole mips): the whole level ⌈m⌉ of the footprint's fractional mip m, alone. coneCoarseMipLift already lifts
// every sample clear of level ⌈m⌉'s reach, so that level keeps the surface out as the blend did; read alone it is
// one texture read per slab instead of a blend of two levels (lavapipe filters a read between two levels at about
// twice the cost: the default frame's trace 0.66× with every read at one level). The wider footprint also averages
// more of what a fixed direction sees: cornell (64³ / 128³, trace scale 4, one bounce, nf) 24.17 / 24.45 → 24.50 /
// 24.95 dB against the path-traced truth, where ⌊m⌋ gave 21.90 / 22.22 and the nearest level 23.82 / 22.96.
// ⌈log2(d / v0)⌉ is read off the exponent of x = d / v0 ≥ 1 (x = f·2^e, f in [0.5, 1): e, or e − 1 when x is a
// power of two), exactly and without the log2 coneMip takes (the trace 0.947× on lavapipe, 640×360).
VCT_INLINE float coneWholeMip(float diameter, float voxelSize) {
    int e = 0;
    const float f = frexp(max(diameter, voxelSize) / voxelSize, e);
    return float(f == 0.5f ? e - 1 : e);
}

// Step length Δt ∝ d.
VCT_INLINE float coneStep(float diameter) { return CONE_STEP_SCALE * diameter; }

// Opacity of a sample re-scaled from its voxel size (the depth it was averaged over) to the step length:
// a' = 1 − (1 − a)^(Δt / v_mip). Keeps the result independent of the step size.
VCT_INLINE float correctOpacity(float alpha, float stepLength, float mipVoxelSize) {
    float a = saturate(alpha);
    return 1.0f - pow(1.0f - a, stepLength / max(mipVoxelSize, 1e-20f));
}

// One front-to-back step: acc (rgb premultiplied radiance, a opacity) under sample s (premultiplied radiance,
// opacity), with s's opacity corrected for the step length; the radiance scales with the same factor (the
// sample's colour c/a is kept). c += (1 − a)·s.rgb, a += (1 − a)·s.a.
VCT_INLINE vec4 coneComposite(vec4 acc, vec4 s, float stepLength, float mipVoxelSize) {
    float a = saturate(s.a);
    float corrected = correctOpacity(a, stepLength, mipVoxelSize);
    // Premultiplied: s.rgb = colour·a, so the corrected sample is colour·a' = s.rgb·(a'/a).
    vec3 rgb = vec3(s) * (a > 1e-6f ? corrected / a : stepLength / max(mipVoxelSize, 1e-20f));
    float transmittance = 1.0f - acc.a;
    return vec4(vec3(acc) + transmittance * rgb, acc.a + transmittance * corrected);
}

// One step of a cone that counts a coverage once (the fixed and turned sets' diffuse cones and every specular cone,
// reading whole mips; the voxels' gathers, reading two blended: lib/cone_trace.glsl's CONE_MARCH_*): what the
// step's `coverage` adds over the previous step's, `previousCoverage`. coneComposite treats the steps' coverages as
// independent, as in a fog, but voxels hold surfaces: an object that stays in the footprint for k steps, or whose
// back faces lie behind its front ones, blocks the same rays each time, and was counted k times: 1 − Π(1 − cᵢ)
// where the rays it blocks are the largest cᵢ (benchmarks/cone_composite_model.py: a sphere covering 15–43 % of a
// 30° cone read 1.56–1.83× its share, with perfect prefiltering and no voxels at all). Here the steps' covered
// rays are taken as nested, as they are for one object: a rise in coverage blocks that part of the rays the
// previous step left, (c − c₋₁)/(1 − c₋₁), and a fall blocks nothing. Two objects one behind the other each count
// (coverage falls between them and rises again). The colour of a step is its sample's, s.rgb/s.a; `coverage` is
// the sample's opacity, or on the closed face a cone ends at, that face's (cone_trace.glsl's closedFaceCoverage).
// No step-length correction: coverage is a share of rays, not a density along them. Measured (docs/design.md §5.3, round 22):
// the indirect light against the path tracer +0.4 to +2.2 dB on cornell, plane, courtyard and DamagedHelmet.
VCT_INLINE vec4 coneCompositeNested(vec4 acc, vec4 s, float coverage, float previousCoverage) {
    const float c = saturate(coverage);
    const float blocked =
        c > previousCoverage ? (c - previousCoverage) / max(1.0f - previousCoverage, 1e-4f) : 0.0f;
    const float a = saturate(s.a);
    const vec3 colour = a > 1e-6f ? vec3(s) / a : vec3(0.0f);
    const float transmittance = 1.0f - acc.a;
    return vec4(vec3(acc) + (transmittance * blocked) * colour, acc.a + transmittance * blocked);
}

// Orthonormal tangent for a unit normal (Duff et al. 2017, "Building an Orthonormal Basis, Revisited"):
// continuous except at n.z = −1 exactly, where it is still orthonormal.
VCT_INLINE vec3 coneTangent(vec3 n) {
    float s = n.z >= 0.0f ? 1.0f : -1.0f;
    float a = -1.0f / (s + n.z);
    float b = n.x * n.y * a;
    return vec3(1.0f + s * n.x * n.x * a, s * b, -s * n.x);
}
VCT_INLINE vec3 coneBitangent(vec3 n) {
    float s = n.z >= 0.0f ? 1.0f : -1.0f;
    float a = -1.0f / (s + n.z);
    float b = n.x * n.y * a;
    return vec3(b, s + n.y * n.y * a, -n.y);
}

// The direction at polar angle θ (given as sin²θ) from unit n and azimuth φ in n's tangent frame. Unit length.
VCT_INLINE vec3 coneDirectionAt(vec3 n, float sin2Theta, float phi) {
    const float s2 = clamp(sin2Theta, 0.0f, 1.0f);
    return sqrt(1.0f - s2) * n + sqrt(s2) * (cos(phi) * coneTangent(n) + sin(phi) * coneBitangent(n));
}

// Diffuse cone i (0..5): 0 along n, 1..5 at 60° from n, 72° apart in azimuth, the side cones turned by
// `rotation` radians about n (the turned cone set, docs/design.md §5.5; rotations of 0 and multiples of 2π/5
// give the same set). Unit length for unit n.
// Azimuth of side cone i (1..5) in n's tangent frame, the set turned by `rotation`.
VCT_INLINE float diffuseConeAzimuth(int i, float rotation) {
    return float(i - 1) * (2.0f * PI / 5.0f) + rotation;
}
VCT_INLINE vec3 turnedDiffuseConeDirection(vec3 n, int i, float rotation) {
    if (i == 0) return n;
    float phi = diffuseConeAzimuth(i, rotation);
    const float sin60 = 0.866025404f;
    const float cos60 = 0.5f;
    return cos60 * n + sin60 * (cos(phi) * coneTangent(n) + sin(phi) * coneBitangent(n));
}
VCT_INLINE vec3 diffuseConeDirection(vec3 n, int i) { return turnedDiffuseConeDirection(n, i, 0.0f); }

// The turned set's central cone leaves n at the polar angle that halves its cap's cosine-weighted solid angle:
// sin²θ = sin²30°/2 = 1/8 (θ = 20.7°). It turns a whole turn about n while the side cones turn a fifth of one
// (turnedCentralConeDirection), so over frames it sweeps its cap as they sweep their band. Left on n it saw the
// same texels every frame, blotches the history cannot average: tilted, cornell (64³, trace scale 4, one
// bounce) gains 0.17 dB against the path-traced truth, and 15°, 20.7° and 25° give +0.17, +0.16 and +0.05 dB.
const float TURNED_CENTRAL_CONE_SIN2_THETA = 0.125f;
VCT_INLINE vec3 turnedCentralConeDirection(vec3 n, float rotation) {
    return coneDirectionAt(n, TURNED_CENTRAL_CONE_SIN2_THETA, 5.0f * rotation);
}

// The jittered cone set (docs/design.md §5.5): cone i at a random place of its tile of the hemisphere, the
// central cone's cap θ ≤ 30° or the side cones' band 30° ≤ θ < 90°, distributed by cos θ within it. With
// sin²θ uniform over the tile's range the density is ∝ cos θ·sin θ dθ, the cosine-weighted solid angle: so the
// mean over u of the radiance along the jittered direction is the tile's cosine-weighted mean radiance, which
// the fixed cone (weight diffuseConeWeight) stands for. u in [0, 1).
VCT_INLINE float jitteredDiffuseConeSin2Theta(int i, float u) {
    return i == 0 ? 0.25f * u : 0.25f + 0.75f * u;
}

// Cosine weights, normalised to sum to 1. The central 30° cone holds exactly ∫cos dω = π·sin²30° = π/4 of the
// hemisphere's π; the five side cones share the rest, 3π/20 each (Rauwendaal 2013). So a uniform radiance L
// gives exactly L, i.e. irradiance π·L.
VCT_INLINE float diffuseConeWeight(int i) { return i == 0 ? 0.25f : 0.15f; }

// Specular cone aperture from GGX α (= perceptual²). The GGX NDF falls to half its peak at the half-vector
// angle θ_h with tan θ_h = α·sqrt((√2 − 1)/(1 − √2·α²)) ≈ 0.644·α; reflection doubles angles around the mirror
// direction, so the cone's half-angle is 2·θ_h, with tan(2θ_h) = 2t/(1 − t²), t = 0.644·α (the small-α form,
// within 10% of the exact half-width up to α ≈ 0.45). Clamped to SPECULAR_CONE_MAX_TAN_HALF. α = 0 gives 0:
// a mirror ray, whose footprint is still one voxel (coneDiameter).
VCT_INLINE float specularLobeTanHalf(float alpha) {
    float t = 0.643594253f * clamp(alpha, 0.0f, 1.0f);  // sqrt(√2 − 1)
    float denominator = 1.0f - t * t;                   // ≥ 0.585 for α ≤ 1
    return 2.0f * t / denominator;
}
VCT_INLINE float specularConeTanHalf(float alpha) {
    return min(specularLobeTanHalf(alpha), SPECULAR_CONE_MAX_TAN_HALF);
}

// Inverse sharpness 1/λ of the GGX lobe as a spherical Gaussian G(ω) = exp(λ(ω·ξ − 1)) about the mirror
// direction ξ: the NDF as an SG about n with λ_h = 2/α², warped into the reflected direction with
// λ = λ_h / (4 n·v), i.e. 1/λ = 2α²·max(n·v, ε) (Wang et al. 2009). The n·v floor keeps grazing and
// back-facing views (normal maps) of rough surfaces from turning into mirror lobes.
const float SG_MIN_NOV = 1e-4f;
VCT_INLINE float specularLobeInverseSharpness(float alpha, float nov) {
    const float a = clamp(alpha, 0.0f, 1.0f);
    return 2.0f * a * a * max(nov, SG_MIN_NOV);
}

// 1 − cos θ of a cone of half-angle θ = atan(tanHalfAngle).
VCT_INLINE float coneOneMinusCos(float tanHalfAngle) {
    return 1.0f - inversesqrt(1.0f + tanHalfAngle * tanHalfAngle);
}

// Share of an SG lobe of inverse sharpness 1/λ (over the sphere) that falls inside a cone of half-angle θ
// about its axis: ∫_cone G / ∫_sphere G = (1 − e^{−λ(1 − cos θ)}) / (1 − e^{−2λ}). 1 for a mirror (1/λ = 0),
// (1 − cos θ)/2 as λ → 0 (a uniform lobe).
VCT_INLINE float sgShareInCone(float invLambda, float tanHalfAngle) {
    const float oneMinusCos = coneOneMinusCos(tanHalfAngle);
    if (invLambda <= 1e-6f) return 1.0f;
    if (invLambda >= 1e6f) return 0.5f * oneMinusCos;
    const float lambda = 1.0f / invLambda;
    return saturate((1.0f - exp(-lambda * oneMinusCos)) / (1.0f - exp(-2.0f * lambda)));
}

// Whether the specular cone is as wide as its lobe's half-maximum aperture, not clamped to
// SPECULAR_CONE_MAX_TAN_HALF: it then stands for all of the lobe.
VCT_INLINE bool specularConeHoldsLobe(float alpha) {
    return specularLobeTanHalf(alpha) <= SPECULAR_CONE_MAX_TAN_HALF;
}

// How much of the specular lobe the (clamped) specular cone stands for. A cone as wide as the lobe
// (specularLobeTanHalf) stands for all of it, as in Crassin et al.; clamped to 45° it loses the part of the
// lobe between the two apertures, which the diffuse cones estimate instead (cone_trace.glsl, traceSurface).
// 1 whenever the clamp is not reached; cornell's walls (α = 0.81 seen at n·v = 0.7) keep 0.74.
VCT_INLINE float specularConeShare(float alpha, float nov) {
    if (specularConeHoldsLobe(alpha)) return 1.0f;
    const float invLambda = specularLobeInverseSharpness(alpha, nov);
    return saturate(sgShareInCone(invLambda, SPECULAR_CONE_MAX_TAN_HALF) /
                    max(sgShareInCone(invLambda, specularLobeTanHalf(alpha)), 1e-6f));
}

// tan of the half-angle of the cap of the environment (render/environment_cones.h) whose mean radiance stands for
// an SG lobe of inverse sharpness 1/λ cut at 1 − cos θ ≤ xMax (2: the whole lobe): the cap with the lobe's mean of
// x = 1 − cos θ, so that the two weigh alike any radiance that varies linearly in x about the axis. The lobe's is
// E[x] = 1/λ − xMax/(e^{λ·xMax} − 1) (an exponential in x), a uniform cap's x_c/2; x_c = 2·E[x]. The cone's own
// aperture, the GGX lobe's half-maximum (specularLobeTanHalf), is narrower: read with it, the long tails of a
// rough lobe were missing, and an open plane of perceptual roughness 0.6 under the sky got 0.86× its specular
// light (docs/design.md §5.9). At most 89.9° (a tangent); 0 for a mirror.
VCT_INLINE float sgEquivalentCapTanHalf(float invLambda, float xMax) {
    if (invLambda <= 1e-6f) return 0.0f;
    const float lx = xMax / invLambda;
    const float meanX =
        lx > 60.0f ? invLambda : (lx < 1e-3f ? 0.5f * xMax : invLambda - xMax / (exp(lx) - 1.0f));
    const float cosCap = max(1.0f - 2.0f * meanX, 1e-3f);
    return sqrt(max(1.0f - cosCap * cosCap, 0.0f)) / cosCap;
}

// The environment aperture of the specular cone (traceCone's environmentTanHalf): for the part of its lobe the cone
// stands for (specularConeShare), the whole lobe or the part inside SPECULAR_CONE_MAX_TAN_HALF.
VCT_INLINE float specularEnvironmentTanHalf(float alpha, float nov) {
    const float xMax = specularConeHoldsLobe(alpha) ? 2.0f : coneOneMinusCos(SPECULAR_CONE_MAX_TAN_HALF);
    return sgEquivalentCapTanHalf(specularLobeInverseSharpness(alpha, nov), xMax);
}

// Weight of diffuse cone direction ω in the estimate of a lobe (unit axis ξ, inverse sharpness 1/λ) from the
// diffuse cones: the SG at ω times the cosine n·ω (the lobe as it meets the surface). The exponent is
// clamped so that a sharp lobe far from every cone gives 0, not a NaN from 0 · ∞.
VCT_INLINE float sgDiffuseConeWeight(vec3 xi, float invLambda, vec3 n, vec3 omega) {
    const float exponent = (dot(omega, xi) - 1.0f) / max(invLambda, 1e-6f);
    return exp(max(exponent, -80.0f)) * max(dot(n, omega), 0.0f);
}

// The share of a diffuse cone's tile that lies outside the specular cone at its widest (SPECULAR_CONE_MAX_TAN_HALF),
// from the cosine between the two axes: the tile taken as a cap of the diffuse cone's half-angle r_d, the
// specular cone's r_s; 0 while the tile is inside (an angle <= r_s - r_d), 1 once clear of it (>= r_s + r_d), linear
// in the angle between.
VCT_INLINE float diffuseTileOutsideSpecularCone(float cosAngle) {
    const float rd = atan(DIFFUSE_CONE_TAN_HALF), rs = atan(SPECULAR_CONE_MAX_TAN_HALF);
    return saturate((acos(clamp(cosAngle, -1.0f, 1.0f)) - (rs - rd)) / (2.0f * rd));
}

// The specular light from the specular cone's radiance and the diffuse cones' (`directions`, `cones`), for a
// surface of unit normal n seen at n·v = nov with GGX roughness alpha, its lobe about xi with inverse sharpness
// invLambda: the share of the lobe that the specular cone stands for is read from that cone; the rest, which a
// rough lobe spreads beyond the widest cone, from the diffuse cones weighted by the lobe at their directions and by
// how much of their tile lies beyond the specular cone (diffuseTileOutsideSpecularCone). A single cone capped at 45°
// saw only the lobe's centre: on cornell's rough walls (α = 0.81) it reflected the dark front wall and ceiling where
// the path-traced truth also sees the lit floor. Weighted by the lobe alone, the tiles nearest the axis, which the
// specular cone already covers, dominated the rest too: cornell's specular sRGB PSNR was 0.5 dB lower, an open
// plane of roughness 1 under the sky got 0.80× its specular light (0.83× now; docs/design.md §5.9). Shared with
// the CPU tests (lib/cone_trace.glsl's traceSurface combines the GPU's cones with it).
VCT_INLINE vec3 specularFromCones(vec3 n, float nov, float alpha, vec3 xi, float invLambda, vec3 specular,
                                  const vec3 directions[DIFFUSE_CONE_COUNT],
                                  const vec3 cones[DIFFUSE_CONE_COUNT]) {
    const float share = specularConeShare(alpha, nov);
    if (share >= 1.0f) return specular;
    vec3 lobe = vec3(0.0f);
    float lobeWeight = 0.0f;
    for (int i = 0; i < DIFFUSE_CONE_COUNT; ++i) {
        const float w = sgDiffuseConeWeight(xi, invLambda, n, directions[i]) *
                        diffuseTileOutsideSpecularCone(dot(directions[i], xi));
        lobe += w * cones[i];
        lobeWeight += w;
    }
    // No diffuse cone under the lobe at all: the specular cone stands for all of it.
    return lobeWeight > 0.0f ? share * specular + (1.0f - share) * lobe / lobeWeight : specular;
}

// cos θ of a direction drawn from an SG lobe of inverse sharpness 1/λ about its axis, truncated to the cone of
// half-angle atan(tanHalfAngle): the jittered specular cone (docs/design.md §5.5) samples the part of the lobe the
// cone stands for, by the lobe's own distribution. Inverting the SG's share inside angle θ,
// (1 − e^{−λ(1 − cos θ)}) / (1 − e^{−λ(1 − cos θ_c)}) = u, gives cos θ = 1 + ln(1 − u·(1 − e^{−λ(1 − cos θ_c)}))/λ.
// u in [0, 1). A mirror (1/λ → 0) gives 1; a uniform lobe (1/λ → ∞) cos θ = 1 − u·(1 − cos θ_c), the limit of the
// same formula, taken explicitly where the exponential form would cancel in float.
VCT_INLINE float sgConeSampleCosine(float invLambda, float tanHalfAngle, float u) {
    const float oneMinusCos = coneOneMinusCos(tanHalfAngle);
    if (invLambda <= 1e-6f) return 1.0f;
    const float lambda = 1.0f / invLambda;
    if (lambda * oneMinusCos < 1e-3f) return 1.0f - u * oneMinusCos;
    const float cosTheta = 1.0f + log(1.0f - u * (1.0f - exp(-lambda * oneMinusCos))) / lambda;
    return clamp(cosTheta, 1.0f - oneMinusCos, 1.0f);
}

// Mirror direction of unit v about unit n, reflect(−v, n) = 2(n·v)n − v, with n·v clamped to ≥ 0: back-facing
// shading normals (normal maps, grazing views) then reflect to −v's tangent part and never into the surface.
// |result| = |v| = 1 even with the clamp; the fallback to n only guards degenerate input.
VCT_INLINE vec3 specularConeDirection(vec3 n, vec3 v) {
    const vec3 r = 2.0f * max(dot(n, v), 0.0f) * n - v;
    const float len2 = dot(r, r);
    return len2 > 1e-12f ? r * inversesqrt(len2) : n;
}

#endif  // VCT_CONE_GLSL
