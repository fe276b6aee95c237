// Voxel-grid math shared by the voxelize / inject / mips shaders and the CPU (grid fitting, tests); see
// lib/cpp_glsl.h for the rules. The grid is a cube of N³ voxels: `originSize` packs the world position of its
// min corner (xyz) and the edge length of one voxel (w), exactly as FrameUniforms::voxels
// (origin, voxelSize).
// Voxel i covers [origin + i·size, origin + (i+1)·size); its centre is origin + (i + 0.5)·size.
#ifndef VCT_VOXEL_GLSL
#define VCT_VOXEL_GLSL

#include "lib/constants.glsl"

// ---- grid fitting and coordinates ----

// A cube around the bounds [bmin, bmax] with one voxel of padding on every side (so surfaces on the bounds
// still have an empty neighbour for the mip filter). Zero extent on any axis (a flat scene) stays valid:
// the cube's edge is at least a small positive length. Returns (origin, voxel size).
VCT_INLINE vec4 voxelGridFit(vec3 bmin, vec3 bmax, float n) {
    vec3 extent = max(bmax - bmin, vec3(0.0f));
    float side = max(max(extent.x, max(extent.y, extent.z)), 1e-3f);
    // N voxels span side·N/(N−2), leaving one voxel free at each end.
    float voxelSize = side / max(n - 2.0f, 1.0f);
    vec3 center = 0.5f * (bmin + bmax);
    return vec4(center - vec3(0.5f * n * voxelSize), voxelSize);
}

VCT_INLINE vec3 voxelFromWorld(vec3 p, vec4 originSize) { return (p - vec3(originSize)) / originSize.w; }
VCT_INLINE vec3 worldFromVoxel(vec3 v, vec4 originSize) { return vec3(originSize) + v * originSize.w; }
VCT_INLINE vec3 voxelCenterWorld(ivec3 i, vec4 originSize) {
    return worldFromVoxel(vec3(i) + 0.5f, originSize);
}
// Normalized texture coordinate of a world position (what the trace pass samples with).
VCT_INLINE vec3 voxelUvw(vec3 p, vec4 originSize, float n) { return voxelFromWorld(p, originSize) / n; }
VCT_INLINE uint voxelLinearIndex(ivec3 i, int n) { return uint(i.x + n * (i.y + n * i.z)); }

// ---- triangle / box overlap (separating axis theorem, Akenine-Möller 2001) ----

// Whether the projections of the triangle (relative to the box centre) and the box onto `axis` overlap.
// Touching counts as overlapping. A zero axis (parallel edges, degenerate triangle) never separates.
VCT_INLINE bool voxelAxisOverlaps(vec3 axis, vec3 v0, vec3 v1, vec3 v2, vec3 halfSize) {
    float p0 = dot(axis, v0), p1 = dot(axis, v1), p2 = dot(axis, v2);
    float r = dot(halfSize, abs(axis));
    return !(min(p0, min(p1, p2)) > r || max(p0, max(p1, p2)) < -r);
}

// A vertex's voxel coordinates as the voxelizer uses them (shaders/voxelize.comp; the CPU's checks in tests/
// alike): snapped to a 1024th of a voxel, so that a surface lying on a voxel face (cornell's walls at 128³, at
// voxel coordinate 127 up to float rounding) has the same coordinates on every device, whatever multiply-adds a
// compiler fuses: the overlap test (touching counts) and the walk's bounds then put it into the same voxels. Left
// to the rounding, the voxels beside such walls differed between lavapipe and an NVIDIA H200 (562 voxels of the
// hall at 256³). Exact in float for coordinates below 2¹³.
VCT_INLINE vec3 voxelSnap(vec3 p) { return floor(p * 1024.0f + 0.5f) / 1024.0f; }

// Exact overlap test of triangle (a, b, c) with the axis-aligned box centre ± halfSize. Only products and
// sums: a degenerate (zero-area, even single-point) triangle gives no NaN and overlaps where its points do.
VCT_INLINE bool triangleBoxOverlap(vec3 center, vec3 halfSize, vec3 a, vec3 b, vec3 c) {
    vec3 v0 = a - center, v1 = b - center, v2 = c - center;
    // 3 box face normals: the triangle's bounding box against the box.
    if (any(greaterThan(min(v0, min(v1, v2)), halfSize)) || any(lessThan(max(v0, max(v1, v2)), -halfSize)))
        return false;
    vec3 e0 = v1 - v0, e1 = v2 - v1, e2 = v0 - v2;
    // The triangle's plane.
    if (!voxelAxisOverlaps(cross(e0, e1), v0, v1, v2, halfSize)) return false;
    // 9 edge × box-axis cross products.
    vec3 edges[3] = {e0, e1, e2};
    for (int i = 0; i < 3; ++i) {
        if (!voxelAxisOverlaps(vec3(0.0f, -edges[i].z, edges[i].y), v0, v1, v2, halfSize)) return false;
        if (!voxelAxisOverlaps(vec3(edges[i].z, 0.0f, -edges[i].x), v0, v1, v2, halfSize)) return false;
        if (!voxelAxisOverlaps(vec3(-edges[i].y, edges[i].x, 0.0f), v0, v1, v2, halfSize)) return false;
    }
    return true;
}

// Whether the unit voxel centred at `center` holds triangle (a, b, c) (voxel coordinates, voxelSnap'd): the triangle
// overlaps the voxel (triangleBoxOverlap) and its plane passes within ½(|m_x| + |m_y| + |m_z| − min_i |m_i|) of the
// centre, m the face normal, in m's units. The overlap alone keeps every voxel the plane touches (within ½ Σ|m_i|),
// so a doubly oblique surface also fills the voxels it only cuts near a corner, a voxel-sized fringe on each side:
// a sphere 6.5 voxels across (MetalRoughSpheresNoTextures at 64³, 2.8 voxels apart) occluded its neighbours' sky as
// a larger one. A plane tilted about one axis (min |m_i| = 0) and an axis-aligned one keep every voxel they touch,
// as before, so walls and rooms are voxelized as they were. Measured (benchmarks/README.md, round 28): indirect sRGB
// PSNR against the path tracer +0.36 dB on MetalRoughSpheresNoTextures, +0.21 on the courtyard, within 0.03 dB of
// before elsewhere; light through a wall between two rooms turned about an oblique axis 0.062 → 0.067 of the lit
// room's. A degenerate triangle (m = 0) passes where it overlaps.
VCT_INLINE bool voxelHoldsTriangle(vec3 center, vec3 a, vec3 b, vec3 c) {
    if (!triangleBoxOverlap(center, vec3(0.5f), a, b, c)) return false;
    vec3 m = cross(b - a, c - a);
    vec3 am = abs(m);
    float smallest = min(am.x, min(am.y, am.z));
    return abs(dot(m, center - a)) <= 0.5f * (am.x + am.y + am.z - smallest);
}

// Barycentric weights of the point of triangle (a, b, c) closest to p (Ericson, Real-Time Collision
// Detection §5.1.5). Degenerate triangles fall back to a vertex or an edge; the weights always sum to 1.
VCT_INLINE vec3 closestPointBarycentric(vec3 p, vec3 a, vec3 b, vec3 c) {
    vec3 ab = b - a, ac = c - a, ap = p - a;
    float d1 = dot(ab, ap), d2 = dot(ac, ap);
    if (d1 <= 0.0f && d2 <= 0.0f) return vec3(1.0f, 0.0f, 0.0f);
    vec3 bp = p - b;
    float d3 = dot(ab, bp), d4 = dot(ac, bp);
    if (d3 >= 0.0f && d4 <= d3) return vec3(0.0f, 1.0f, 0.0f);
    float vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) {
        float t = d1 / max(d1 - d3, 1e-30f);
        return vec3(1.0f - t, t, 0.0f);
    }
    vec3 cp = p - c;
    float d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (d6 >= 0.0f && d5 <= d6) return vec3(0.0f, 0.0f, 1.0f);
    float vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) {
        float t = d2 / max(d2 - d6, 1e-30f);
        return vec3(1.0f - t, 0.0f, t);
    }
    float va = d3 * d6 - d5 * d4;
    if (va <= 0.0f && (d4 - d3) >= 0.0f && (d5 - d6) >= 0.0f) {
        float t = (d4 - d3) / max((d4 - d3) + (d5 - d6), 1e-30f);
        return vec3(0.0f, 1.0f - t, t);
    }
    float sum = va + vb + vc;
    if (!(sum > 0.0f)) return vec3(1.0f, 0.0f, 0.0f);  // zero area: any vertex will do
    float v = vb / sum, w = vc / sum;
    return vec3(1.0f - v - w, v, w);
}

// ---- fixed-point accumulation (atomicAdd on uint buffers) ----
// Per voxel VCT_VOXEL_ACCUM_STRIDE uints: albedo rgb, normal xyz (two's complement), emission rgb, count,
// transparency (1 − alpha of blended surfaces, × 1023 like albedo).
// Scales: albedo in [0,1] × 1023 and normals × 1023 overflow only beyond ~4M / ~2M samples in one voxel;
// emission × 256 is clamped to 4096 per sample (enough for any emissive material in practice).

const float VOXEL_UNIT_SCALE = 1023.0f;
const float VOXEL_EMISSION_SCALE = 256.0f;
const float VOXEL_EMISSION_MAX = 4096.0f;

VCT_INLINE uint voxelEncodeUnit(float x) { return uint(clamp(x, 0.0f, 1.0f) * VOXEL_UNIT_SCALE + 0.5f); }
VCT_INLINE uint voxelEncodeSigned(float x) {
    return uint(int(round(clamp(x, -1.0f, 1.0f) * VOXEL_UNIT_SCALE)));
}
VCT_INLINE uint voxelEncodeEmission(float x) {
    return uint(clamp(x, 0.0f, VOXEL_EMISSION_MAX) * VOXEL_EMISSION_SCALE + 0.5f);
}
// Averages of `count` samples (count > 0).
VCT_INLINE float voxelDecodeUnit(uint sum, uint count) {
    return float(sum) / (VOXEL_UNIT_SCALE * float(count));
}
VCT_INLINE float voxelDecodeSigned(uint sum, uint count) {
    return float(int(sum)) / (VOXEL_UNIT_SCALE * float(count));
}
VCT_INLINE float voxelDecodeEmission(uint sum, uint count) {
    return float(sum) / (VOXEL_EMISSION_SCALE * float(count));
}

// ---- lighting a voxel ----

// Cosine factor for a voxel whose averaged normal is nbar (|nbar| ≤ 1, short when the surfaces in it
// disagree, e.g. both sides of a thin wall): one-sided max(n·l, 0) when the normals agree, blending to
// two-sided |n·l| as they cancel, and 1/2 (the hemisphere-average guess) when no direction is left.
VCT_INLINE float voxelCosine(vec3 nbar, vec3 l) {
    float r = length(nbar);
    if (r < 1e-3f) return 0.5f;
    float ndl = dot(nbar, l) / r;
    return mix(abs(ndl), max(ndl, 0.0f), min(r, 1.0f));
}

// ---- directional radiance: six slabs (docs/design.md §5.2) ----
// A voxel seen along different directions is not the same: a one-voxel floor blocks a vertical ray fully and a
// horizontal one only within its layer, and it sends light up, not down or sideways. Averaged isotropically its
// coarse mips fade (opacity 2^-m at mip m: thin walls turn transparent as voxels get finer) and its own light
// reaches the cones that leave it. So the radiance texture holds six volumes of N³ side by side along x (width
// 6N, each with its own mip chain in the same image), one per direction a cone travels (Crassin et al. 2011's
// anisotropic voxels): slab s holds, premultiplied, the radiance that leaves each voxel towards the viewer of a
// cone travelling along voxelSlabDirection(s) (that is, towards −direction), and the voxel's opacity along it.
const int VOXEL_SLAB_COUNT = 6;

// Slab 2a travels along +axis a, slab 2a + 1 along −axis a.
VCT_INLINE vec3 voxelSlabDirection(int slab) {
    vec3 d = vec3(0.0f);
    d[slab / 2] = (slab % 2) == 0 ? 1.0f : -1.0f;
    return d;
}

// The slab a cone travelling along `dir` reads on `axis` (the face it sees of each voxel).
VCT_INLINE int voxelSlabFor(vec3 dir, int axis) { return 2 * axis + (dir[axis] < 0.0f ? 1 : 0); }

// How much of the three slabs along `dir` a sample takes: dir² per axis (sums to 1 for a unit dir), the share
// of each face in what a cone along dir sees. A face seen at a grazing angle (weight below
// VOXEL_SLAB_MIN_WEIGHT, i.e. under 18° from the cone's direction) is dropped and the others renormalised:
// every slab read is a trilinear sample between two mips (16 texels), the largest part of a cone step's
// cost, and such a face adds little that its neighbours do not already show.
const float VOXEL_SLAB_MIN_WEIGHT = 0.1f;
VCT_INLINE vec3 voxelSlabWeights(vec3 dir) {
    const vec3 w = dir * dir;
    const vec3 kept =
        vec3(w.x >= VOXEL_SLAB_MIN_WEIGHT ? w.x : 0.0f, w.y >= VOXEL_SLAB_MIN_WEIGHT ? w.y : 0.0f,
             w.z >= VOXEL_SLAB_MIN_WEIGHT ? w.z : 0.0f);
    // At least one of three weights summing to 1 is ≥ 1/3, so the sum is never 0 for a unit dir.
    const float sum = kept.x + kept.y + kept.z;
    return sum > 0.0f ? kept / sum : w;
}

// What a cone along a direction with slab weights `w` (voxelSlabWeights) sees of the three slabs it reads, `x`,
// `y` and `z` (premultiplied radiance, opacity). The radiance is their weighted mean. The opacity is the weighted
// mean too where `coverage` is false (coneComposite, which counts every step), and their largest where it is true
// (coneCompositeNested, which counts a rise in coverage once): a one-voxel wall met obliquely is opaque in the
// slab across it and thin in the others, and its weighted mean (0.25 for a cone 60° from the wall's normal) was
// made opaque only by counting it at every step; counted once it would let 3/4 of what lies behind through.
VCT_INLINE vec4 voxelSlabsSeen(vec3 w, vec4 x, vec4 y, vec4 z, bool coverage) {
    const vec4 mean = w.x * x + w.y * y + w.z * z;
    if (!coverage) return mean;
    // The largest opacity among the slabs read (a weight of 0: not read).
    const float most = max(max(w.x > 0.0f ? x.w : 0.0f, w.y > 0.0f ? y.w : 0.0f), w.z > 0.0f ? z.w : 0.0f);
    return mean.w > 1e-6f ? vec4(vec3(mean) * (most / mean.w), most) : mean;
}

// The u coordinate (0..1 across the whole 6N width) of point u (0..1 across one volume) in `slab`, at a mip of
// `texels` texels per slab: kept half a texel inside the slab, so that filtering never reads the slab beside
// it (the outermost half texel is the grid's empty padding).
VCT_INLINE float voxelSlabU(float u, int slab, float texels) {
    float inside = clamp(u, 0.5f / texels, 1.0f - 0.5f / texels);
    return (float(slab) + inside) / float(VOXEL_SLAB_COUNT);
}

// Share of a voxel's outgoing radiance that leaves towards unit `towards` (a slab's direction, −dir_s): 1 on the side
// its surfaces face and sideways (a floor seen edge-on from afar is lit; its own cones no longer see it,
// coneSurfaceFootprint), falling linearly to 0 straight behind them, 1 + cos for cos = n̂·towards < 0 (a lit floor
// sends nothing down), blending to 1 (two sided) as the averaged normal nbar shortens (|nbar| < 1: surfaces in the
// voxel disagree, e.g. both sides of a thin wall), as voxelCosine does for the light arriving.
// Why linear behind, not a step: a cone reads three slabs weighted d_i² (voxelSlabWeights), and a surface whose
// normal lies off the axes faces a cone that sees it from the front through slabs that lie behind it (a wall turned
// 30° about y, normal (0.87, 0, 0.5), is seen along (0.1, 0, −1) through the +x slab). With a step those slabs were
// dark: an emissive room turned 30° or 45° (exact 1) gathered 0.908 / 0.898 with every cone counting its steps as a
// fog, 0.938 / 0.926 with this ramp, 0.981 / 0.995 sending the light to every side (benchmarks/README.md, round 28).
// On the axes (n̂·towards ∈ {−1, 0, 1}) the ramp is the step: an axis-aligned room is lit as before.
VCT_INLINE float voxelFacing(vec3 nbar, vec3 towards) {
    float r = length(nbar);
    if (r < 1e-3f) return 1.0f;
    float facing = clamp(1.0f + dot(nbar, towards) / r, 0.0f, 1.0f);
    return mix(1.0f, facing, min(r, 1.0f));
}

// One mip texel of a slab from two voxels one behind the other along its direction: the front one (met
// first by the cone) over the back one, premultiplied. Four such pairs are averaged (voxelAverage4): a wall
// across the direction stays opaque at every mip, one along it covers its share of the footprint.
VCT_INLINE vec4 voxelOver(vec4 front, vec4 back) { return front + (1.0f - saturate(front.a)) * back; }
VCT_INLINE vec4 voxelAverage4(vec4 a, vec4 b, vec4 c, vec4 d) { return 0.25f * ((a + b) + (c + d)); }

#endif  // VCT_VOXEL_GLSL
