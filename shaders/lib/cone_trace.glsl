// Cone tracing of one full-res pixel through the voxel grid (docs/design.md §5.3–5.5): shared by trace.comp (one
// low-res sample per thread) and resample.comp (the listed full-res pixels). GLSL only: it marches the radiance,
// mip 0 in the radiance atlas (declared here, with the brick table: lib/voxel_storage.glsl) and the coarser mips in
// the sampler3D the caller passes (its level m − 1 holds mip m). Expects before inclusion: `frame`
// (FrameUniforms), `environmentMap` (lib/environment_sample.glsl), lib/constants, brdf, cone, voxel and
// gbuffer_read.
#ifndef VCT_CONE_TRACE_GLSL
#define VCT_CONE_TRACE_GLSL

#include "lib/environment_sample.glsl"
#include "lib/voxel.glsl"
#include "lib/voxel_bricks.glsl"
#include "lib/voxel_storage.glsl"

// Mip 0 of the radiance: the six slabs' blocks of the allocated bricks (lib/voxel_bricks.glsl), trilinear, no mips.
layout(set = 0, binding = VCT_BINDING_VOXEL_ATLAS) uniform sampler3D voxelAtlas;

// The static grid's closed regions (render/voxel_regions.h): each empty voxel's label, 0 for a voxel holding a
// surface or a small pocket. With VOXEL_REGIONS a cone ends where its axis passes from the region it started in into
// another (traceCone): the walls of a room turned off the grid's axes, or between two rooms, then close it as the
// closure box's faces close an axis-aligned room's. A constant, so that scenes the box closes alone pay nothing.
layout(constant_id = VCT_SPEC_VOXEL_REGIONS) const bool VOXEL_REGIONS = false;
layout(set = 0, binding = VCT_BINDING_VOXEL_REGIONS) uniform usampler3D voxelRegions;

// The region label at world point x (0 outside the grid).
uint voxelRegionAt(vec3 x) {
    const ivec3 voxel = ivec3(floor((x - frame.voxels.origin) / frame.voxels.voxelSize));
    const int n = int(frame.voxels.resolution);
    const bool inside = all(greaterThanEqual(voxel, ivec3(0))) && all(lessThan(voxel, ivec3(n)));
    return inside ? texelFetch(voxelRegions, voxel, 0).r : 0u;
}

// The grid as a cone travelling along unit `dir` sees it at `uvw` and (fractional) `mip`: the three direction
// slabs facing it (lib/voxel.glsl), combined by voxelSlabsSeen with weights dir² per axis (their largest opacity
// with `coverage`, for coneCompositeNested; their weighted mean otherwise). Slabs with no weight are not sampled
// (an axis-aligned cone reads one). Below mip 1 the sample blends mip 0 from the atlas with mip 1 (what a
// trilinear read between the two levels of one texture does): the atlas read is the block of the brick holding
// the sample's lower corner voxel, which its apron makes hold all eight voxels the filter reads; no block there
// means none of them is occupied.
// Slab `axis` at `uvw`, read from the mips' texture at level `lod`; `texels` per slab at the coarser level read, to
// keep u inside the slab. The sampler picks one level (VoxelGrid: mipmap mode nearest): `wholeMip`, lod is a whole
// level and one read is all; else lod is fractional and the two levels around it are read and blended, as a
// trilinear read between levels does. `wholeMip` is a constant at every call, so each cone march compiles with one
// of the two; lavapipe would run both sides of a branch.
vec4 sampleMipSlab(sampler3D voxels, vec3 uvw, vec3 dir, int axis, float lod, float texels,
                   const bool wholeMip) {
    const float level = wholeMip ? lod : floor(lod);
    const vec3 slabUvw = vec3(voxelSlabU(uvw.x, voxelSlabFor(dir, axis), texels), uvw.yz);
    vec4 v = textureLod(voxels, slabUvw, level);
    if (!wholeMip) v = mix(v, textureLod(voxels, slabUvw, level + 1.0), lod - level);
    return v;
}

vec4 sampleVoxels(sampler3D voxels, vec3 uvw, vec3 dir, float mip, const bool wholeMip, bool coverage) {
    const vec3 w = voxelSlabWeights(dir);
    const int n = int(frame.voxels.resolution);
    vec4 seen[3] = vec4[3](vec4(0.0), vec4(0.0), vec4(0.0));
    if (!SPARSE_MIP0) {
        // Mip 0 dense (RenderSettings::sparseMip0From): every mip in the one texture, one read per slab.
        const float texels = float(max(n >> int(ceil(mip)), 1));
        for (int axis = 0; axis < 3; ++axis)
            if (w[axis] > 0.0) seen[axis] = sampleMipSlab(voxels, uvw, dir, axis, mip, texels, wholeMip);
    } else {
        const float fine = 1.0 - min(mip, 1.0);
        if (fine > 0.0) {
            // Voxel units, clamped to the outermost texel centres (the coarse sampler's clamp to the edge).
            const vec3 p = clamp(uvw * float(n), vec3(0.5), vec3(float(n) - 0.5));
            const ivec3 brick = voxelBrickOf(ivec3(floor(p - 0.5)));
            const uint k = brickIndex(brick);
            if (k != VCT_BRICK_NONE) {
                const vec3 inBlock = p - vec3(brick * VOXEL_BRICK);
                for (int axis = 0; axis < 3; ++axis) {
                    if (w[axis] <= 0.0) continue;
                    const ivec3 block =
                        radianceAtlasTexel(k, frame.voxels.brickAtlasSide, ivec3(0), voxelSlabFor(dir, axis));
                    seen[axis] +=
                        fine *
                        textureLod(voxelAtlas, (vec3(block) + inBlock) * frame.voxels.atlasInvSize.xyz, 0.0);
                }
            }
        }
        // Mip 1 and coarser: the texture's level mip − 1.
        if (mip > 0.0) {
            const float texels = float(max(n >> int(ceil(max(mip, 1.0))), 1));
            for (int axis = 0; axis < 3; ++axis)
                if (w[axis] > 0.0)
                    seen[axis] += min(mip, 1.0) * sampleMipSlab(voxels, uvw, dir, axis, max(mip - 1.0, 0.0),
                                                                texels, wholeMip);
        }
    }
    return voxelSlabsSeen(w, seen[0], seen[1], seen[2], coverage);
}

// The share of a closed face's layer that a read at `at` sees on each axis, for texels of side `texel`: the part of
// a texel's width about `at` within the face's extent [lo, hi] on that axis (a box in place of the bilinear tent:
// the same ½ at a wall whether the wall lies on a texel's edge or at its centre, and a third of the tent's
// arithmetic, which lavapipe runs at every step of every cone). A solid face reads this opacity, not 1, where the
// texel reaches past the room.
vec3 closedFaceShare(vec3 at, float texel, vec3 lo, vec3 hi) {
    return saturate((min(at + 0.5 * texel, hi) - max(at - 0.5 * texel, lo)) / texel);
}

// Where a cone reads the closed face it has passed (traceCone), so that it ends on that face: where the cone's axis
// crossed the face (`at`, kept inside the closure box [boxMin, boxMax] by coneSampleAt), at level ⌈m⌉, on the texel
// boundary just beyond the face along its axis (`face`: 1 on that axis; the face at `faceAt` on it, on the box's
// upper side where `high` is 1). The face is the content's bound, on a voxel boundary or within a voxel, and the
// conservative voxelizer marks the voxels touching it on one side or both: the read there takes half of the texel
// that holds the face's layer and half of the one beyond it, outside the room. `solid`: the opacity a whole face
// shows in that read, ½ along the axis (both sides holding it: ≥ 1, closed) times closedFaceShare on its two other
// axes (a coarse texel reaches past the room's other walls). The read itself is the march's one read per step, by
// the cone's direction: a separate read of the slab across the face for each closing cone cost the trace 2.9× on
// lavapipe, whose SIMD lanes run every branch that any lane takes (so this is vector arithmetic, no index by axis).
// At the grid's own edge the sampler's clamp reads the whole face texel, not half, so a whole face counts twice
// over there; counted once, the sky came in through walls on the grid's outermost voxel boundary (docs/design.md
// §5.3).
struct ClosedFaceRead {
    vec3 position;
    float mip;
    float solid;
};
ClosedFaceRead closedFaceRead(ConeSampleAt at, vec3 face, vec3 faceAt, vec3 high, vec3 boxMin, vec3 boxMax) {
    const vec3 gridOrigin = frame.voxels.origin;
    const float v0 = frame.voxels.voxelSize;
    ClosedFaceRead read;
    read.mip = ceil(at.mip);
    const float texel = ldexp(v0, int(read.mip));
    // The texel boundary just beyond the face (the texel holding the face's layer inside it, the one beyond it
    // outside the room), not the nearest: at a coarse level the nearest can lie inside the room, and the read there
    // took in the room itself (the hall's roof 10 m up, read at 20 m texels, took in the floor, and its skylights let
    // in 0.18 of the true sky). A face on a voxel boundary, to 1/64 voxel, is on it.
    const vec3 q = (faceAt - gridOrigin) / texel, onBoundary = vec3(v0 / (64.0 * texel));
    const vec3 boundary = gridOrigin + mix(floor(q + onBoundary), ceil(q - onBoundary), high) * texel;
    read.position = mix(at.position, boundary, face);
    const vec3 share = mix(closedFaceShare(at.position, texel, boxMin, boxMax), vec3(1.0), face);
    read.solid = 0.5 * share.x * share.y * share.z;
    return read;
}

// The face's read, of opacity `opacity`, as a coverage of the cone: that opacity over what a whole face shows there
// (`solid`), so that a whole face closes the cone (coverage 1) while a window or skylight in it (a face counts as
// closed with 95 % of its bricks holding surfaces, render/voxel_bricks.h) lets through its share of the footprint,
// and the sky beyond. Where a whole face would show almost nothing the read says nothing either: closed. The colour
// is the read's own (coneCompositeNested takes it from the sample).
float closedFaceCoverage(float opacity, float solid) {
    return solid > 0.05 ? saturate(opacity / solid) : 1.0;
}

// How a cone reads and composites its samples (traceCone's `march`, a constant at every call, so that each march
// compiles with one of them; lavapipe would run every branch):
// - CONE_MARCH_WHOLE_MIPS: every sample reads the whole level ⌈m⌉ of its fractional mip m alone (coneWholeMip), and
//   counts what its coverage adds to the last one's (coneCompositeNested): a pixel's fixed and turned diffuse cones,
//   and every specular cone;
// - CONE_MARCH_BLENDED: a blend of ⌊m⌋ and ⌈m⌉, each sample's opacity counted over its step (coneComposite, the fog
//   of classic cone tracing): the jittered set's narrow diffuse cones;
// - CONE_MARCH_BLENDED_COVERAGE: a blend of the two levels, the fog, but coverage counted once where the read reaches
//   a closed face of the closure box (within CONE_MIP_REACH texels of its level ⌈m⌉): the voxels' bounce gathers
//   (traceDiffuse). Such a texel holds the face, which the cone's last read accounts for (closedFaceRead); counted
//   over every step, a texel that holds a closed face and an opening in it (the hall's roof and its skylights, 10 m
//   up) closed the gathers before they reached that read: the hall's second bounce was 0.77× / 0.68× of the truth
//   (64³ / 128³). Counted once everywhere 1.18× / 1.18×, but cornell, whose gathers the fog suits elsewhere, lost
//   4 % of its every-bounce light; counted once near closed faces alone 1.10× / 1.04×, cornell within 1.5 % of the
//   fog (docs/design.md §5.7).
const int CONE_MARCH_WHOLE_MIPS = 0;
const int CONE_MARCH_BLENDED = 1;
const int CONE_MARCH_BLENDED_COVERAGE = 2;

// Marches one cone from `origin` along unit `dir`; returns premultiplied radiance (rgb) and opacity (a).
// Light that leaves the grid unoccluded sees the environment (docs/design.md §5.9): its mean over the cap of
// half-angle atan(environmentTanHalf) about the cone's axis (the cone's own aperture for a diffuse cone, the lobe's
// equivalent cap for a specular one: specularEnvironmentTanHalf), times what the cone left unoccluded.
// The cone leaves the surface at p with unit normal n (coneSurfaceFootprint, with `clearance`, keeps that
// surface out of it). `march`: CONE_MARCH_*. `stepPhase` in [0, 1): the first sample that part of its step farther
// out (ConeSet).
vec4 traceCone(sampler3D voxels, vec3 p, vec3 n, vec3 origin, vec3 dir, float tanHalfAngle, float clearance,
               const int march, float stepPhase, float environmentTanHalf) {
    // Whole mips count a coverage once at every sample; the gathers' blended reads near a closed face (below).
    const bool wholeMips = march == CONE_MARCH_WHOLE_MIPS;
    const vec3 gridOrigin = frame.voxels.origin;
    const float v0 = frame.voxels.voxelSize;
    const float gridSize = float(frame.voxels.resolution) * v0;
    const float maxMip = max(float(frame.voxels.mipCount) - 1.0, 0.0);
    // Where the cone closes (below): the closure box (render/voxel_bricks.h's coneClosureBox), whose sides are the
    // faces of what was voxelized where geometry covers them (a closed room's floor, walls and ceiling) and the
    // grid's elsewhere. With the grid's faces alone, a cone crossing cornell's floor or ceiling obliquely (both lie
    // 8 voxels inside the cubic grid) met nothing more and saw the sky: with the sky 30× brighter the gold sphere's
    // one-bounce light rose 40 % / 47 % (64³ / 128³); closed at them (round 18, by a few samples past them), 5 % /
    // 10 % (docs/design.md §5.3, §5.6), and since round 23 a cone ends on the face it passes (closedFaceRead). A
    // closed face reaches as far as the content does on the other axes: a cone that leaves the box beyond that (over
    // the top of a courtyard's wall, into the open) has left through an open side, and closes at the grid's faces
    // from there on, as a cone that starts outside the box does (nothing lies beyond the grid; from outside a room
    // its faces would be in every cone's way).
    const vec3 gridMax = gridOrigin + vec3(gridSize);
    const vec3 closureMin = frame.voxels.closureMin.xyz, closureMax = frame.voxels.closureMax.xyz;
    const vec3 contentMin = frame.voxels.contentMin.xyz, contentMax = frame.voxels.contentMax.xyz;
    // 1 on the sides of the box that are a closed room's faces, not the grid's.
    const vec3 closedLow = closedLowFaces(), closedHigh = closedHighFaces();
    // The box the cone closes at: the grid's once it is open (it starts outside the closure box, or has left it
    // through an open side), else the closure box. Changed only where the cone turns open, not per step.
    bool open = !(all(greaterThan(origin, closureMin)) && all(lessThan(origin, closureMax)));
    vec3 closeMin = open ? gridOrigin : closureMin, closeMax = open ? gridMax : closureMax;
    vec4 acc = vec4(0.0);
    // Start one voxel out along the cone, from an origin one voxel out along the normal (CONE_START_*: why twice).
    float t = v0 * CONE_START_DISTANCE;
    t += stepPhase * coneStep(coneDiameter(tanHalfAngle, t, v0));
    // Bounded even for a mirror cone (footprint v0): the grid diagonal is √3·N voxels, steps ≥ v0/2.
    const int maxSteps = 4 * int(frame.voxels.resolution) + 8;
    int stepsPastBox = 0;
    float previousCoverage = 0.0;  // the last sample's (where coverage is counted once)
    // The slabs the cone reads, for the closed face below, and how far back along the axis a distance past a face
    // on each axis lies (which face it crossed first).
    const vec3 slabWeights = voxelSlabWeights(dir);
    const vec3 inverseSpeed = 1.0 / max(abs(dir), vec3(1e-6));
    // The region the cone started in: the first labelled one its axis reaches (VOXEL_REGIONS).
    uint startRegion = 0u;
    float previousT = 0.0;  // the last sample's distance (where the axis was still in its region)
    for (int i = 0; i < maxSteps && acc.a < CONE_MAX_OPACITY; ++i) {
        const vec3 x = origin + dir * t;
        const float coneD = coneDiameter(tanHalfAngle, t, v0);
        const float d = coneSurfaceFootprint(coneD, dot(x - p, n), v0, clearance);
        // The axis leaves the box (above). Through a closed face of the closure box the cone ends on that face
        // (below). Past the grid's faces nothing lies beyond, but the footprint still covers the grid's outermost
        // texels, and a cone meeting a wall there obliquely sees it opaque only in the slab across the wall and
        // partly in the others (an oblique crossing within one texel is not certain): a room's walls at the grid's
        // edge passed (1 − α) of the environment, a closed emissive room gathered 0.79 of its radiance.
        // CONE_STEPS_PAST_GRID more samples of the edge texels (clamped to the box; the sampler clamps to the
        // grid's edge) close it: 0.99. A fixed count, not a margin that grows with d: wide cones would then never
        // leave.
        bool outside = any(lessThan(x, closeMin)) || any(greaterThan(x, closeMax));
        // The closed face the cone has just passed, if it has: 1 on its axis (`face`), where it lies (`faceAt`, on that
        // axis) and how far back along the cone's axis it was crossed (`back`).
        bool closing = false;
        vec3 face = vec3(0.0), faceAt = vec3(0.0), high = vec3(0.0);
        float back = 0.0;
        if (outside && !open) {
            // Through a closed face: beyond a closed side on some axis, and on each other axis within the content
            // or beyond a closed side too (a room's edge or corner). Else through an open side: the grid's box.
            const vec3 beyondClosed =
                max(vec3(lessThan(x, closureMin)) * closedLow, vec3(greaterThan(x, closureMax)) * closedHigh);
            const vec3 within = vec3(greaterThanEqual(x, contentMin)) * vec3(lessThanEqual(x, contentMax));
            open =
                all(lessThan(beyondClosed, vec3(0.5))) || any(lessThan(max(beyondClosed, within), vec3(0.5)));
            if (open) {
                closeMin = gridOrigin;
                closeMax = gridMax;
                outside = any(lessThan(x, gridOrigin)) || any(greaterThan(x, gridMax));
            } else {
                // Past a closed face (the one its axis crossed first, the farthest back along it): the cone ends on
                // that face's layer where its axis crossed it (closedFaceRead), which lets the sky in only through an
                // opening in the face.
                closing = true;
                const vec3 past = max(closureMin - x, x - closureMax) * beyondClosed * inverseSpeed;
                const bool alongX = past.x >= past.y && past.x >= past.z;
                face = vec3(alongX, !alongX && past.y >= past.z, !alongX && past.y < past.z);
                high = vec3(greaterThan(x, closureMax));
                faceAt = mix(closureMin, closureMax, high);
                back = dot(past, face);
            }
        }
        if (outside && !closing && ++stepsPastBox > CONE_STEPS_PAST_GRID) break;
        // Into another closed region (VOXEL_REGIONS): the cone has passed a wall that its samples covered only in
        // part. It ends on that wall, read halfway back to the last sample (between the two its axis crossed the
        // wall), as a cone ends on a closed face where its axis crossed it: read here, beyond the wall, it would take
        // in what lies there (a lit room next door).
        bool leavesRegion = false;
        if (VOXEL_REGIONS && !closing) {
            const uint region = voxelRegionAt(x);
            leavesRegion = startRegion != 0u && region != 0u && region != startRegion;
            startRegion = startRegion == 0u ? region : startRegion;
            back = leavesRegion ? 0.5 * (t - previousT) : back;
        }
        // Read where the coarser level of the blend keeps the surface out too, within the grid.
        const float mip = wholeMips ? coneWholeMip(d, v0) : coneMip(d, v0);
        // Read where the cone's axis crossed the closed face, if it has just passed one (`back` is 0 otherwise).
        ConeSampleAt at = coneSampleAt(x - dir * back, min(mip, maxMip), p, n, v0, closeMin, closeMax);
        // Past the grid's edge (an open side), where even mip 0 would read the surface the cone left, which lies in the
        // grid's edge layer: nothing lies beyond the grid, so the cone ends and sees the environment. A lone cube
        // fitted to the grid gathered 0.24 of a white sky before, its own faces closing its cones (round 26).
        if (outside && !closing && at.ownLayer) break;
        float solid = 1.0;
        if (closing) {
            const ClosedFaceRead read = closedFaceRead(at, face, faceAt, high, closureMin, closureMax);
            at.position = read.position;
            at.mip = read.mip;
            solid = read.solid;
        }
        // Whether this sample counts a coverage once: always or never by `march`, or where the read (up to
        // CONE_MIP_REACH texels of level ⌈m⌉ about it) reaches a closed face.
        bool counts = wholeMips;
        if (march == CONE_MARCH_BLENDED_COVERAGE) {
            const float reach = CONE_MIP_REACH * ldexp(v0, int(ceil(at.mip)));
            const vec3 fromLow = mix(vec3(1e30), at.position - closureMin, closedLow);
            const vec3 fromHigh = mix(vec3(1e30), closureMax - at.position, closedHigh);
            const vec3 nearest = min(fromLow, fromHigh);
            counts = min(nearest.x, min(nearest.y, nearest.z)) < reach;
        }
        // Opacity as a coverage (voxelSlabsSeen) where it is counted once, and on a closed face for every cone.
        const vec4 s = sampleVoxels(voxels, (at.position - gridOrigin) / gridSize, dir, at.mip, wholeMips,
                                    counts || closing);
        if (closing) {
            // Counted as a coverage whatever the composite; the cone ends here. A cone that meets the face at
            // under 18° does not read the slab across it (voxelSlabWeights), where alone the face is opaque at any
            // angle: the face closes it.
            const float coverage = closedFaceCoverage(s.a, dot(slabWeights, face) > 0.0 ? solid : 0.0);
            acc = coneCompositeNested(acc, s, coverage, previousCoverage);
            break;
        }
        if (leavesRegion) {
            // The rest of the cone sees the wall as that read shows what it covers or, where it covers too little,
            // what the cone saw so far (as a cone stopped nearly opaque, below): a closed room of uniform radiance
            // gathers it.
            const vec3 seen = s.a > 0.05 ? s.rgb / s.a : (acc.a > 0.05 ? acc.rgb / acc.a : vec3(0.0));
            acc = vec4(acc.rgb + (1.0 - saturate(acc.a)) * seen, 1.0);
            break;
        }
        const float dt = coneStep(coneD);
        if (counts) {
            // What the sample's coverage adds to the last one's (coneCompositeNested).
            acc = coneCompositeNested(acc, s, s.a, previousCoverage);
            previousCoverage = saturate(s.a);
        } else {
            // The fog counted this step's opacity already: a coverage after it adds whatever it holds.
            previousCoverage = 0.0;
            // The sample averaged its opacity over voxels of side v0·2^mip (the footprint, up to the top mip).
            acc = coneComposite(acc, s, dt, v0 * exp2(at.mip));
        }
        previousT = t;
        t += dt;
    }
    // Stopped as nearly opaque: what lies behind the last CONE_MAX_OPACITY would add its share of the cone in
    // any case, and is estimated as what the cone saw (else a closed room gathers 0.95 of its radiance).
    if (acc.a >= CONE_MAX_OPACITY) acc = vec4(acc.rgb / acc.a, 1.0);
    acc.rgb += (1.0 - saturate(acc.a)) * environmentCone(dir, environmentTanHalf);
    return acc;
}

// Demodulated indirect light at full-res `pixel` (lib/cone.glsl): diffuse = cosine-weighted mean incoming
// radiance of the 6 diffuse cones, specular = incoming radiance averaged over the specular lobe (traceSurface).
// Background pixels and a missing grid give 0.
struct IndirectSample {
    vec3 diffuse;
    vec3 specular;
};

// A pixel's cone set in one frame (docs/design.md §5.5). Fixed (`--cone-rotation off`, and the voxel gathers
// of §5.7): the six diffuse cones of lib/cone.glsl at their tiles' centres, one specular cone along the lobe's
// axis, footprints of CONE_SURFACE_CLEARANCE. Turned (`--cone-rotation on`, the default): the same with the five
// side cones turned about n by `rotation` (their set's 2π/5 symmetry), different at every pixel and frame, and
// the central cone tilted off n and turned with them (lib/cone.glsl's turnedCentralConeDirection). Jittered
// (`--cone-jitter on`): every cone at a random place of what it stands for, so that the history integrates it:
//   - the side cones turned as above, each at its own elevation in the band 30°–90° (u.x + golden-ratio steps
//     per cone, lib/cone.glsl's jitteredDiffuseConeSin2Theta);
//   - the central cone anywhere in its 30° cap (u.x for θ, u.y for the azimuth);
//   - the specular cone drawn from the lobe inside its aperture (u.zw, sgConeSampleCosine);
// with narrow footprints (CONE_SURFACE_CLEARANCE_JITTERED) that keep the surface's own voxels out of every
// sample; fixed, such narrow cones would be thin rays at six directions, jittered they sample their whole tile
// over frames.
// The turned set's cones also start a random part `stepPhase` of their first step farther out (traceCone), so
// that the history averages where along the cone the samples fall: every pixel's cones otherwise sample at the
// same distances, and cornell's error against the truth swung by 1 dB with the step scale (docs/design.md §5.5).
struct ConeSet {
    bool turned;  // turned or jittered: the side cones turned by `rotation`
    bool jittered;
    float rotation;   // radians, [0, 2π/5); 0 for the fixed set
    float stepPhase;  // [0, 1): the turned set's start within its first step; 0 for the others
    vec4 u;           // uniform numbers in [0, 1) (jittered only)
};

const ConeSet FIXED_CONE_SET = ConeSet(false, false, 0.0, 0.0, vec4(0.0));

// Interleaved gradient noise of a pixel (Jimenez 2014): in [0, 1), neighbours far apart.
float interleavedGradientNoise(vec2 pixel) {
    return fract(52.9829189 * fract(dot(pixel, vec2(0.06711056, 0.00583715))));
}

// The cone set of `pixel` in frame k: a full-res pixel, or trace.comp's low-res sample (whose neighbours the
// upsample combines). Each number is frac(g(pixel + offset) + k·α): its interleaved gradient noise, shifted per
// dimension, plus a low-discrepancy step per frame (the golden ratio φ⁻¹ for the
// turn, the R-sequence steps 1/g^d of the plastic-like number g = 1.1673 for the others), so that successive
// frames fill [0, 1) evenly in each. The renderer sets VCT_FLAG_CONE_ROTATION for jittered sets too.
ConeSet coneSetOf(ivec2 pixel, uint frameIndex) {
    if ((frame.flags & VCT_FLAG_CONE_ROTATION) == 0u) return FIXED_CONE_SET;
    const vec2 xy = vec2(pixel);
    const float r1 = float((frameIndex * 2654435769u) >> 8u) * (1.0 / 16777216.0);
    const float rotation = (2.0 * PI / 5.0) * fract(interleavedGradientNoise(xy) + r1);
    if ((frame.flags & VCT_FLAG_CONE_JITTER) == 0u) {
        // Its own noise and a step of another irrational (1/1.3247, the plastic number) than the turn's.
        const float phase = fract(interleavedGradientNoise(xy + vec2(23.0, 13.0)) +
                                  float(frameIndex % 65536u) * 0.7548776662);
        return ConeSet(true, false, rotation, phase, vec4(0.0));
    }
    const vec4 steps =
        fract(float(frameIndex % 65536u) * vec4(0.8566748839, 0.7338918566, 0.6287067210, 0.5385972572));
    const vec4 u = fract(vec4(interleavedGradientNoise(xy + vec2(17.0, 5.0)),
                              interleavedGradientNoise(xy + vec2(3.0, 29.0)),
                              interleavedGradientNoise(xy + vec2(41.0, 11.0)),
                              interleavedGradientNoise(xy + vec2(7.0, 37.0))) +
                         steps);
    return ConeSet(true, true, rotation, 0.0, u);
}

// Diffuse cone i of `set` for unit normal n.
vec3 diffuseConeDirectionOf(vec3 n, int i, ConeSet set) {
    if (!set.jittered)
        return i == 0 && set.turned ? turnedCentralConeDirection(n, set.rotation)
                                    : turnedDiffuseConeDirection(n, i, set.rotation);
    const float golden = 0.618034;
    if (i == 0) return coneDirectionAt(n, jitteredDiffuseConeSin2Theta(0, set.u.x), 2.0 * PI * set.u.y);
    return coneDirectionAt(n, jitteredDiffuseConeSin2Theta(i, fract(set.u.x + float(i) * golden)),
                           diffuseConeAzimuth(i, set.rotation));
}

// Where `set`'s cones leave p (unit normal n): CONE_START_OFFSET voxels out along n, 1.5 for the jittered set
// (lib/cone.glsl: why), and how wide their footprints may be.
vec3 coneOrigin(vec3 p, vec3 n, ConeSet set) {
    return p + n * (frame.voxels.voxelSize * (set.jittered ? CONE_START_OFFSET_JITTERED : CONE_START_OFFSET));
}
float coneClearance(ConeSet set) {
    return set.jittered ? CONE_SURFACE_CLEARANCE_JITTERED : CONE_SURFACE_CLEARANCE;
}

// The directions of the 6 diffuse cones of `set` for unit normal n (traceSurface weighs the specular lobe at
// the same directions it traced).
void diffuseConeDirectionsOf(vec3 n, ConeSet set, out vec3 directions[DIFFUSE_CONE_COUNT]) {
    for (int i = 0; i < DIFFUSE_CONE_COUNT; ++i) directions[i] = diffuseConeDirectionOf(n, i, set);
}

// The incoming radiance along diffuse cone `direction` of `set` from surface point p with unit normal n, marched as
// `march` says (CONE_MARCH_*, a constant at every call). Every diffuse march, a pixel's or voxel's cones one after
// the other or one per invocation (the cone layout), is this call.
vec3 marchDiffuseCone(sampler3D voxels, vec3 p, vec3 n, ConeSet set, vec3 direction, const int march) {
    return traceCone(voxels, p, n, coneOrigin(p, n, set), direction, DIFFUSE_CONE_TAN_HALF,
                     coneClearance(set), march, set.stepPhase, DIFFUSE_CONE_TAN_HALF)
        .rgb;
}

// The same along each of the set's 6 `directions`.
void marchDiffuseCones(sampler3D voxels, vec3 p, vec3 n, ConeSet set,
                       const vec3 directions[DIFFUSE_CONE_COUNT], const int march,
                       out vec3 radiance[DIFFUSE_CONE_COUNT]) {
    for (int i = 0; i < DIFFUSE_CONE_COUNT; ++i)
        radiance[i] = marchDiffuseCone(voxels, p, n, set, directions[i], march);
}

// The same for a pixel: the fixed and turned sets read whole mips (coneWholeMip); the jittered set's narrow
// footprints stay blended. Two marches, of which a lane runs one.
void traceDiffuseCones(sampler3D voxels, vec3 p, vec3 n, ConeSet set,
                       const vec3 directions[DIFFUSE_CONE_COUNT], out vec3 radiance[DIFFUSE_CONE_COUNT]) {
    if (set.jittered)
        marchDiffuseCones(voxels, p, n, set, directions, CONE_MARCH_BLENDED, radiance);
    else
        marchDiffuseCones(voxels, p, n, set, directions, CONE_MARCH_WHOLE_MIPS, radiance);
}

// Their cosine-weighted mean.
vec3 diffuseFromCones(const vec3 radiance[DIFFUSE_CONE_COUNT]) {
    vec3 diffuse = vec3(0.0);
    for (int i = 0; i < DIFFUSE_CONE_COUNT; ++i) diffuse += diffuseConeWeight(i) * radiance[i];
    return diffuse;
}

// The 6 diffuse cones of the fixed set from surface point p with unit normal n: cosine-weighted mean incoming
// radiance. The voxels' bounce gathers (voxel_bounce.comp). Their cones blend two mip levels, where a pixel's
// fixed and turned cones read the whole level ⌈m⌉: a wider footprint over a room-sized cone takes in more of what
// lies beside its path. From cornell's ceiling (not in the default view) a cone straight down read 0.56 of the
// floor's light with whole mips and 0.73 blended, and the ceiling got 0.53 of its true one-bounce light; the
// blended gathers took every bounce from 0.928 to 0.949 of the full GI (64³; docs/design.md §5.7). They count a
// coverage once, as a pixel's fixed and turned cones do (CONE_MARCH_BLENDED_COVERAGE: why there).
vec3 traceDiffuse(sampler3D voxels, vec3 p, vec3 n) {
    vec3 directions[DIFFUSE_CONE_COUNT];
    diffuseConeDirectionsOf(n, FIXED_CONE_SET, directions);
    vec3 radiance[DIFFUSE_CONE_COUNT];
    marchDiffuseCones(voxels, p, n, FIXED_CONE_SET, directions, CONE_MARCH_BLENDED_COVERAGE, radiance);
    return diffuseFromCones(radiance);
}

// Diffuse cone `i` of the fixed set from surface point p with unit normal n, as traceDiffuse marches it: the voxel
// gathers' cone layout (voxel_bounce.comp), whose invocations march one cone each and combine them with
// diffuseFromCones.
vec3 traceDiffuseCone(sampler3D voxels, vec3 p, vec3 n, int i) {
    vec3 directions[DIFFUSE_CONE_COUNT];
    diffuseConeDirectionsOf(n, FIXED_CONE_SET, directions);  // all of them: why at traceSurfaceCone
    return marchDiffuseCone(voxels, p, n, FIXED_CONE_SET, directions[i], CONE_MARCH_BLENDED_COVERAGE);
}

// The specular cone of a surface with unit normal n seen along unit v, of GGX roughness alpha, in `set`: the GGX lobe
// as an SG (lib/cone.glsl) about xi, the cone along `direction` (xi, or a direction of the lobe for the jittered set).
struct SpecularCone {
    vec3 xi;                   // the lobe's axis
    vec3 direction;            // the cone's
    float tanHalf;             // its aperture
    float invLambda;           // the lobe's inverse sharpness
    float environmentTanHalf;  // the aperture of its environment read (specularEnvironmentTanHalf)
};

SpecularCone specularConeOf(vec3 n, vec3 v, float alpha, ConeSet set) {
    SpecularCone cone;
    cone.xi = specularConeDirection(n, v);
    cone.tanHalf = specularConeTanHalf(alpha);
    cone.invLambda = specularLobeInverseSharpness(alpha, dot(n, v));
    cone.environmentTanHalf = specularEnvironmentTanHalf(alpha, dot(n, v));
    cone.direction = cone.xi;
    if (set.jittered) {
        // A direction of the lobe inside the cone; one that would leave below the surface (a grazing lobe's
        // lower edge) keeps the axis.
        const float cosTheta = sgConeSampleCosine(cone.invLambda, cone.tanHalf, set.u.z);
        const vec3 w = coneDirectionAt(cone.xi, 1.0 - cosTheta * cosTheta, 2.0 * PI * set.u.w);
        cone.direction = dot(w, n) > 0.02 ? w : cone.xi;
        // A direction drawn from the lobe already spreads the reads over it: the environment at the cone's own
        // aperture, as its voxels.
        cone.environmentTanHalf = cone.tanHalf;
    }
    return cone;
}

// The specular cone's march. It reads whole mips (coneWholeMip) with every set, as the fixed and turned diffuse
// cones do: its footprint grows by up to 2× (a glossy reflection a little blurrier), for 0.86× the default frame's
// trace (docs/design.md §5.3).
vec3 marchSpecularCone(sampler3D voxels, vec3 p, vec3 n, ConeSet set, SpecularCone cone) {
    return traceCone(voxels, p, n, coneOrigin(p, n, set), cone.direction, cone.tanHalf, coneClearance(set),
                     CONE_MARCH_WHOLE_MIPS, set.stepPhase, cone.environmentTanHalf)
        .rgb;
}

// Both cone sets from surface point p with unit normal n, seen along unit v (towards the camera), one cone after the
// other (an invocation per pixel; the cone layout, below, traces them in parallel and combines them the same way).
IndirectSample traceSurface(sampler3D voxels, vec3 p, vec3 n, vec3 v, float perceptualRoughness,
                            ConeSet set) {
    vec3 directions[DIFFUSE_CONE_COUNT];
    diffuseConeDirectionsOf(n, set, directions);
    vec3 cones[DIFFUSE_CONE_COUNT];
    traceDiffuseCones(voxels, p, n, set, directions, cones);
    const float alpha = alphaFromPerceptual(perceptualRoughness);
    const SpecularCone cone = specularConeOf(n, v, alpha, set);
    const vec3 specular = marchSpecularCone(voxels, p, n, set, cone);
    return IndirectSample(
        diffuseFromCones(cones),
        specularFromCones(n, dot(n, v), alpha, cone.xi, cone.invLambda, specular, directions, cones));
}

// ---- one invocation per cone (the cone layout: RenderSettings::TraceLayout, docs/design.md §5.5) ----
// On a GPU a pass that traces few pixels (the low-res trace below 1280×720, the re-trace of a few hundred) costs one
// invocation's chain of dependent texture reads, whatever its pixel count: on an NVIDIA H200 the scale-4 trace took
// 0.072 ms at 320×180 and at 640×360 alike, the re-trace of a few dozen pixels 0.070 ms. Each of a pixel's cones in
// its own invocation makes that chain one cone long instead of seven. The invocations of a pixel share its
// surface; each marches cone `index` (0 .. DIFFUSE_CONE_COUNT − 1 the diffuse cones, SPECULAR_CONE_INDEX the
// specular one), and one combines the radiances (surfaceFromCones) with the arithmetic of traceSurface.
const int SPECULAR_CONE_INDEX = DIFFUSE_CONE_COUNT;
const int SURFACE_CONE_COUNT = DIFFUSE_CONE_COUNT + 1;
// Invocations per pixel in the cone layout: the cones, rounded up to a power of two (one idles).
const int CONE_LANES_PER_PIXEL = VCT_CONE_LANES_PER_PIXEL;

// Cone `index` of the surface's set (`index` < SURFACE_CONE_COUNT): its incoming radiance, as traceSurface marches it.
vec3 traceSurfaceCone(sampler3D voxels, vec3 p, vec3 n, vec3 v, float perceptualRoughness, ConeSet set,
                      int index) {
    if (index == SPECULAR_CONE_INDEX)
        return marchSpecularCone(voxels, p, n, set,
                                 specularConeOf(n, v, alphaFromPerceptual(perceptualRoughness), set));
    // Every direction of the set, each with a constant index as the pixel layout computes them, then the one this
    // invocation marches: with a runtime index the fixed set's trigonometry (its angles constants) ran on the device
    // instead of folding at compile time, and an NVIDIA H200's approximate sine and cosine made 3 channels of a
    // 96×54 image differ between the layouts (the hall, four bounces).
    vec3 directions[DIFFUSE_CONE_COUNT];
    diffuseConeDirectionsOf(n, set, directions);
    // The fixed and turned sets read whole mips, the jittered set's narrow footprints a blend (traceDiffuseCones).
    if (set.jittered) return marchDiffuseCone(voxels, p, n, set, directions[index], CONE_MARCH_BLENDED);
    return marchDiffuseCone(voxels, p, n, set, directions[index], CONE_MARCH_WHOLE_MIPS);
}

// The surface's light from its cones' radiances (`radiance[SPECULAR_CONE_INDEX]` the specular cone's).
IndirectSample surfaceFromCones(vec3 n, vec3 v, float perceptualRoughness, ConeSet set,
                                const vec3 radiance[SURFACE_CONE_COUNT]) {
    vec3 directions[DIFFUSE_CONE_COUNT];
    diffuseConeDirectionsOf(n, set, directions);
    vec3 cones[DIFFUSE_CONE_COUNT];
    for (int i = 0; i < DIFFUSE_CONE_COUNT; ++i) cones[i] = radiance[i];
    const float alpha = alphaFromPerceptual(perceptualRoughness);
    const SpecularCone cone = specularConeOf(n, v, alpha, set);
    return IndirectSample(diffuseFromCones(cones),
                          specularFromCones(n, dot(n, v), alpha, cone.xi, cone.invLambda,
                                            radiance[SPECULAR_CONE_INDEX], directions, cones));
}

// ---- a full-res pixel ----
// What its cones need of full-res `pixel`: its surface from the G-buffer (none on the background, with no grid, or
// at a position that cannot be shaded) and its cone set.
struct PixelSurface {
    bool lit;  // false: no indirect light
    vec3 p, n, v;
    float perceptualRoughness;
    ConeSet set;
};

PixelSurface pixelSurface(sampler2D depthTexture, sampler2D normalRoughnessTexture, ivec2 pixel) {
    PixelSurface s;
    s.lit = false;
    s.p = vec3(0.0);
    s.n = vec3(0.0, 0.0, 1.0);
    s.v = vec3(0.0, 0.0, 1.0);
    s.perceptualRoughness = 1.0;
    s.set = FIXED_CONE_SET;
    const float depth = texelFetch(depthTexture, pixel, 0).r;
    if (isBackground(depth) || frame.voxels.voxelSize <= 0.0) return s;
    const vec2 uv = (vec2(pixel) + 0.5) * frame.texelSize;
    const vec4 normalRoughness = texelFetch(normalRoughnessTexture, pixel, 0);
    const vec3 p = worldFromDepth(frame.invViewProj, uv, depth);
    if (isDegeneratePosition(p)) return s;
    s.lit = true;
    s.p = p;
    s.n = gbufferNormal(normalRoughness);
    s.v = viewDirection(frame.cameraPosition - p, s.n);
    s.perceptualRoughness = normalRoughness.w;
    s.set = coneSetOf(pixel, frame.upsample.frameIndex);
    return s;
}

IndirectSample tracePixel(sampler3D voxels, sampler2D depthTexture, sampler2D normalRoughnessTexture,
                          ivec2 pixel) {
    const PixelSurface s = pixelSurface(depthTexture, normalRoughnessTexture, pixel);
    if (!s.lit) return IndirectSample(vec3(0.0), vec3(0.0));
    return traceSurface(voxels, s.p, s.n, s.v, s.perceptualRoughness, s.set);
}

#endif  // VCT_CONE_TRACE_GLSL
