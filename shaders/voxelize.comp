#version 460
#extension GL_GOOGLE_include_directive : require
// voxelize: a workgroup per VCT_VOXEL_GROUP_SIZE triangles of one instance × primitive (lavapipe has no
// conservative raster). Each triangle's voxels are walked column by column along its dominant axis: for every
// column of its bounding box projected onto the other two axes, only the (at most four) voxels its plane can
// cross there; those the triangle overlaps (separating axis test) add the material at the triangle point closest
// to the voxel centre to the voxel's fixed-point accumulator with atomics. The resolve (voxel_resolve.comp)
// turns sums into averages.
//
// The workgroup shares the columns of its triangles among its invocations (docs/design.md §5.1), so that no
// triangle is one invocation's work:
// - lavapipe ends every loop of an invocation after 65 535 iterations in all (llvmpipe's
//   LP_MAX_TGSI_LOOP_ITERATIONS), without a word: one invocation walking a large triangle's bounding box left
//   out 15 % of cornell's occupied voxels at 128³ and 74 % at 256³;
// - on a GPU such an invocation is latency-bound while the rest of the chip idles: the moving cube's tilted faces
//   at 128³ cost an NVIDIA H200 as much as re-voxelizing the whole scene (0.78 of 0.81 ms).
// Integer atomics add in any order, so how the columns are dealt out changes nothing in the grid.
#include "lib/shared.h"
#include "lib/constants.glsl"
#include "lib/voxel.glsl"
#include "lib/voxel_bricks.glsl"

layout(local_size_x = VCT_VOXEL_GROUP_SIZE) in;

// Resources: bound by engine/passes/voxelize_pass.cpp (its resource table gives these binding numbers and is checked
// against them when the pipeline is made).
layout(set = 0, binding = VCT_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = 1) readonly buffer Instances { GpuInstance instances[]; };
layout(set = 0, binding = 2) readonly buffer Materials { GpuMaterial materials[]; };
// The Vertex struct (VCT_FLOATS_PER_VERTEX floats: position, normal, uv, tangent, color) read as floats:
// std430 would pad its vec3s.
layout(set = 0, binding = 3) readonly buffer Vertices { float vertexData[]; };
layout(set = 0, binding = 4) readonly buffer Indices { uint indices[]; };
layout(set = 0, binding = 5) uniform sampler2D baseColorTexture;
layout(set = 0, binding = 6) uniform sampler2D emissiveTexture;
layout(set = 0, binding = 7) buffer Accum { uint accum[]; };
layout(set = 0,
       binding = 8) uniform sampler2D metallicRoughnessTexture;  // glTF: metallic in b, roughness in g
#include "lib/voxel_storage.glsl"

layout(push_constant) uniform Push { VoxelizePushConstants push; };

const uint kFloatsPerVertex = VCT_FLOATS_PER_VERTEX;

vec3 vertexPosition(uint v) {
    return vec3(vertexData[v * kFloatsPerVertex], vertexData[v * kFloatsPerVertex + 1],
                vertexData[v * kFloatsPerVertex + 2]);
}
vec3 vertexNormal(uint v) {
    return vec3(vertexData[v * kFloatsPerVertex + 3], vertexData[v * kFloatsPerVertex + 4],
                vertexData[v * kFloatsPerVertex + 5]);
}
vec2 vertexUv(uint v) {
    return vec2(vertexData[v * kFloatsPerVertex + 6], vertexData[v * kFloatsPerVertex + 7]);
}
vec4 vertexColor(uint v) {
    const uint c = v * kFloatsPerVertex + VCT_VERTEX_COLOR_OFFSET;
    return vec4(vertexData[c], vertexData[c + 1], vertexData[c + 2], vertexData[c + 3]);
}

// One texel of the given mip (nearest, wrapping): voxels average many samples anyway, and a plain fetch avoids
// the filtering path, which is very slow in compute on software rasterizers with large textures.
vec4 fetchTexel(sampler2D tex, vec2 uv, float lod) {
    const int level = min(int(lod + 0.5), textureQueryLevels(tex) - 1);
    const ivec2 size = textureSize(tex, level);
    const ivec2 texel = clamp(ivec2(fract(uv) * vec2(size)), ivec2(0), size - 1);
    return texelFetch(tex, texel, level);
}

// Texture LOD whose texels match the voxel size: texel density from the ratio of UV area to world area.
float lodForVoxel(sampler2D tex, vec2 uvA, vec2 uvB, vec2 uvC, float worldArea2) {
    const vec2 size = vec2(textureSize(tex, 0));
    const vec2 du = (uvB - uvA) * size, dv = (uvC - uvA) * size;
    const float texelArea2 = abs(du.x * dv.y - du.y * dv.x);
    const float texelsPerUnit = sqrt(texelArea2 / max(worldArea2, 1e-20));
    return log2(max(texelsPerUnit * frame.voxels.voxelSize, 1.0));
}

// A vector's components in the order (d, u, v) of dominant axis d, u = (d+1)%3, v = (d+2)%3, and back. Selects
// rather than a variable component index, which a CPU driver may lower to memory.
vec3 alongAxis(vec3 a, int d) { return d == 0 ? a.xyz : (d == 1 ? a.yzx : a.zxy); }
ivec3 alongAxis(ivec3 a, int d) { return d == 0 ? a.xyz : (d == 1 ? a.yzx : a.zxy); }
ivec3 fromAxis(ivec3 a, int d) { return d == 0 ? a.xyz : (d == 1 ? a.zxy : a.yzx); }

// A triangle prepared for the walk (by the invocation that loaded it; read by whichever walks its columns).
struct TriangleSetup {
    vec3 p[3];  // voxel units
    vec3 normal[3];
    vec2 uv[3];
    vec4 color[3];
    vec3 lods;      // base colour, emissive, metallic-roughness
    ivec4 columns;  // dominant axis d, first column along u = (d+1)%3 and v = (d+2)%3, columns along u
    ivec3 extent;   // columns along v, the bounding box along d (first, last)
};
shared TriangleSetup triangles[VCT_VOXEL_GROUP_SIZE];
// Exclusive prefix sums of the triangles' column counts; [VCT_VOXEL_GROUP_SIZE] is the workgroup's total.
shared uint firstColumn[VCT_VOXEL_GROUP_SIZE + 1];

// Loads triangle `triangle` of the draw and prepares its walk; 0 columns when it is past the draw's end or
// entirely outside the grid.
uint prepareTriangle(uint triangle, out TriangleSetup t) {
    t.columns = ivec4(0);
    t.extent = ivec3(0);
    if (triangle >= push.draw.w) return 0u;
    const GpuInstance instance = instances[push.draw.x];
    const int vertexOffset = int(push.params.x);
    uint vi[3];
    for (int k = 0; k < 3; ++k) vi[k] = uint(int(indices[push.draw.z + triangle * 3 + k]) + vertexOffset);

    const vec4 grid = vec4(frame.voxels.origin, frame.voxels.voxelSize);
    const int n = int(frame.voxels.resolution);
    vec3 worldP[3];
    const bool colored = push.params.y != 0u;  // COLOR_0 multiplies the base colour (as in gbuffer.frag)
    for (int k = 0; k < 3; ++k) {
        // Snapped (lib/voxel.glsl): the same voxels on every device. The world position keeps its rounding (it only
        // sets the texture level).
        worldP[k] = (instance.world * vec4(vertexPosition(vi[k]), 1.0)).xyz;
        t.p[k] =
            voxelSnap(voxelFromWorld(worldP[k], grid));  // voxel units: the overlap test is well conditioned
        t.normal[k] = mat3(instance.normalMatrix) * vertexNormal(vi[k]);
        t.uv[k] = vertexUv(vi[k]);
        t.color[k] = colored ? vertexColor(vi[k]) : vec4(1.0);
    }
    const ivec3 lo = max(ivec3(floor(min(t.p[0], min(t.p[1], t.p[2])))), ivec3(0));
    const ivec3 hi = min(ivec3(floor(max(t.p[0], max(t.p[1], t.p[2])))), ivec3(n - 1));
    if (any(greaterThan(lo, hi))) return 0u;  // entirely outside the grid

    const float worldArea2 = length(cross(worldP[1] - worldP[0], worldP[2] - worldP[0]));
    t.lods = vec3(lodForVoxel(baseColorTexture, t.uv[0], t.uv[1], t.uv[2], worldArea2),
                  lodForVoxel(emissiveTexture, t.uv[0], t.uv[1], t.uv[2], worldArea2),
                  lodForVoxel(metallicRoughnessTexture, t.uv[0], t.uv[1], t.uv[2], worldArea2));
    // The dominant axis of the face normal: along it a column holds few voxels the plane can cross.
    const vec3 a = abs(cross(t.p[1] - t.p[0], t.p[2] - t.p[0]));
    const int d = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
    const ivec3 first = alongAxis(lo, d), last = alongAxis(hi, d);
    t.columns = ivec4(d, first.y, first.z, last.y - first.y + 1);
    t.extent = ivec3(last.z - first.z + 1, first.x, last.x);
    return uint(t.columns.w * t.extent.x);
}

// The voxels along the dominant axis d (first, last) whose centres can pass the plane test of the separating
// axis test in column (cu, cv) (voxel centres): |m·(c − p0)| ≤ ½(|m_x| + |m_y| + |m_z|) for the face normal m
// puts the centre within r = ½Σ|m| / |m_d| ≤ 1.5 of the plane's crossing c_d* along d, so at most four voxels;
// a quarter voxel of slack covers the rounding of either side. Clamped to the bounding box; a degenerate
// triangle (m_d = 0: not finite) keeps the box's whole extent, as the walk it replaces did.
ivec2 columnRange(TriangleSetup t, float cu, float cv) {
    const int d = t.columns.x;
    const vec3 m = alongAxis(cross(t.p[1] - t.p[0], t.p[2] - t.p[0]), d);
    const vec3 p0 = alongAxis(t.p[0], d);
    const float crossing = p0.x - (m.y * (cu - p0.y) + m.z * (cv - p0.z)) / m.x;
    const float reach = 0.5 * (abs(m.x) + abs(m.y) + abs(m.z)) / abs(m.x);
    const float first = ceil(crossing - reach - 0.75), last = floor(crossing + reach - 0.25);
    // NaN and ±inf fail both comparisons' finite bounds: the whole extent.
    const bool finite = abs(first) < 1e6 && abs(last) < 1e6;
    return finite ? ivec2(max(int(first), t.extent.y), min(int(last), t.extent.z)) : t.extent.yz;
}

// Adds triangle t's material at voxel (x, y, z) to the accumulator if the voxel holds the triangle (lib/voxel.glsl).
void voxelizeVoxel(TriangleSetup t, ivec3 voxel, GpuMaterial material) {
    const vec3 center = vec3(voxel) + 0.5;
    if (!voxelHoldsTriangle(center, t.p[0], t.p[1], t.p[2])) return;
    const bool mask = material.flags.x == VCT_ALPHA_MASK;
    // A blended surface covers its voxels by its alpha (the resolve's opacity); opaque ones add nothing here.
    const bool blend = material.flags.x == VCT_ALPHA_BLEND;
    const vec3 bary = closestPointBarycentric(center, t.p[0], t.p[1], t.p[2]);
    const vec2 texcoord = bary.x * t.uv[0] + bary.y * t.uv[1] + bary.z * t.uv[2];
    vec4 base = material.baseColorFactor * fetchTexel(baseColorTexture, texcoord, t.lods.x);
    if (push.params.y != 0u) base *= bary.x * t.color[0] + bary.y * t.color[1] + bary.z * t.color[2];
    if (mask && base.a < material.metallicRoughnessCutoffAo.z) return;  // cut-out
    const vec3 emission =
        material.emissiveNormalScale.rgb * fetchTexel(emissiveTexture, texcoord, t.lods.y).rgb;
    // As gbuffer.frag's surface (lib/surface.glsl): factor × texture, without the normal map's Toksvig
    // roughness (the voxel's own normals widen its lobe in inject.comp).
    const vec4 metallicRoughness = fetchTexel(metallicRoughnessTexture, texcoord, t.lods.z);
    const float metallic = material.metallicRoughnessCutoffAo.x * metallicRoughness.b;
    const float roughness = material.metallicRoughnessCutoffAo.y * metallicRoughness.g;
    // Interpolated shading normal; the face normal when the vertex normals cancel out.
    vec3 normal = bary.x * t.normal[0] + bary.y * t.normal[1] + bary.z * t.normal[2];
    if (dot(normal, normal) < 1e-12) normal = cross(t.p[1] - t.p[0], t.p[2] - t.p[0]);
    normal *= inversesqrt(max(dot(normal, normal), 1e-30));

    // Every voxel a triangle can reach has storage (render/voxel_bricks.h allocates the bricks its bounds
    // overlap, with the same overlap test): the check only guards the buffer.
    const uint k = brickIndex(voxelBrickOf(voxel));
    if (k == VCT_BRICK_NONE) return;
    const uint base_ = voxelAccumIndex(k, voxel % VOXEL_BRICK);
    for (int c = 0; c < 3; ++c) {
        atomicAdd(accum[base_ + c], voxelEncodeUnit(base.rgb[c]));
        atomicAdd(accum[base_ + 3 + c], voxelEncodeSigned(normal[c]));
        atomicAdd(accum[base_ + 6 + c], voxelEncodeEmission(emission[c]));
    }
    atomicAdd(accum[base_ + VCT_VOXEL_ACCUM_COUNT], 1u);
    atomicAdd(accum[base_ + VCT_VOXEL_ACCUM_METALLIC], voxelEncodeUnit(metallic));
    atomicAdd(accum[base_ + VCT_VOXEL_ACCUM_ROUGHNESS], voxelEncodeUnit(roughness));
    if (blend) atomicAdd(accum[base_ + VCT_VOXEL_ACCUM_TRANSPARENCY], voxelEncodeUnit(1.0 - base.a));
}

void main() {
    // 1. Every invocation prepares its triangle and publishes it with its column count.
    const uint local = gl_LocalInvocationID.x;
    TriangleSetup mine;
    const uint columns = prepareTriangle(gl_GlobalInvocationID.x, mine);
    triangles[local] = mine;
    firstColumn[local + 1] = columns;
    barrier();
    if (local == 0u) {
        firstColumn[0] = 0u;
        for (uint i = 1u; i <= uint(VCT_VOXEL_GROUP_SIZE); ++i) firstColumn[i] += firstColumn[i - 1u];
    }
    barrier();

    // 2. The workgroup's columns, dealt out in turn: column c belongs to the triangle whose range holds it.
    const GpuMaterial material = materials[push.draw.y];
    const uint total = firstColumn[VCT_VOXEL_GROUP_SIZE];
    for (uint c = local; c < total; c += uint(VCT_VOXEL_GROUP_SIZE)) {
        // The last triangle whose first column is ≤ c (binary search; empty triangles share their first column
        // with the next and are skipped by taking the last).
        uint owner = 0u;
        for (uint step = uint(VCT_VOXEL_GROUP_SIZE) / 2u; step > 0u; step /= 2u)
            if (firstColumn[owner + step] <= c) owner += step;
        const TriangleSetup t = triangles[owner];
        const uint column = c - firstColumn[owner];
        const int cu = t.columns.y + int(column % uint(t.columns.w));
        const int cv = t.columns.z + int(column / uint(t.columns.w));
        const ivec2 range = columnRange(t, float(cu) + 0.5, float(cv) + 0.5);
        for (int k = range.x; k <= range.y; ++k)
            voxelizeVoxel(t, fromAxis(ivec3(k, cu, cv), t.columns.x), material);
    }
}
