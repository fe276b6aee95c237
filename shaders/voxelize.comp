#version 460
#extension GL_GOOGLE_include_directive : require
// voxelize: one invocation per triangle of one instance × primitive (lavapipe has no conservative raster).
// Loops over the voxels of the triangle's voxel-space bounding box, keeps those the triangle overlaps
// (separating axis test) and adds the material at the triangle point closest to the voxel centre to the
// voxel's fixed-point accumulator with atomics. The resolve (voxel_resolve.comp) turns sums into averages.
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

void main() {
    const uint triangle = gl_GlobalInvocationID.x;
    if (triangle >= push.draw.w) return;
    const GpuInstance instance = instances[push.draw.x];
    const GpuMaterial material = materials[push.draw.y];
    const int vertexOffset = int(push.params.x);
    uint vi[3];
    for (int k = 0; k < 3; ++k) vi[k] = uint(int(indices[push.draw.z + triangle * 3 + k]) + vertexOffset);

    const vec4 grid = vec4(frame.voxels.origin, frame.voxels.voxelSize);
    const int n = int(frame.voxels.resolution);
    vec3 p[3], worldP[3], nrm[3];
    vec2 uv[3];
    vec4 color[3] = {vec4(1.0), vec4(1.0), vec4(1.0)};
    const bool colored = push.params.y != 0u;  // COLOR_0 multiplies the base colour (as in gbuffer.frag)
    for (int k = 0; k < 3; ++k) {
        worldP[k] = (instance.world * vec4(vertexPosition(vi[k]), 1.0)).xyz;
        p[k] = voxelFromWorld(worldP[k], grid);  // voxel units: the overlap test is well conditioned there
        nrm[k] = mat3(instance.normalMatrix) * vertexNormal(vi[k]);
        uv[k] = vertexUv(vi[k]);
        if (colored) color[k] = vertexColor(vi[k]);
    }
    const ivec3 lo = max(ivec3(floor(min(p[0], min(p[1], p[2])))), ivec3(0));
    const ivec3 hi = min(ivec3(floor(max(p[0], max(p[1], p[2])))), ivec3(n - 1));
    if (any(greaterThan(lo, hi))) return;  // entirely outside the grid

    const float worldArea2 = length(cross(worldP[1] - worldP[0], worldP[2] - worldP[0]));
    const float baseLod = lodForVoxel(baseColorTexture, uv[0], uv[1], uv[2], worldArea2);
    const float emissiveLod = lodForVoxel(emissiveTexture, uv[0], uv[1], uv[2], worldArea2);
    const float metallicRoughnessLod = lodForVoxel(metallicRoughnessTexture, uv[0], uv[1], uv[2], worldArea2);
    const vec3 faceNormal = cross(p[1] - p[0], p[2] - p[0]);
    const bool mask = material.flags.x == VCT_ALPHA_MASK;
    // A blended surface covers its voxels by its alpha (the resolve's opacity); opaque ones add nothing here.
    const bool blend = material.flags.x == VCT_ALPHA_BLEND;

    for (int z = lo.z; z <= hi.z; ++z)
        for (int y = lo.y; y <= hi.y; ++y)
            for (int x = lo.x; x <= hi.x; ++x) {
                const vec3 center = vec3(x, y, z) + 0.5;
                if (!triangleBoxOverlap(center, vec3(0.5), p[0], p[1], p[2])) continue;
                const vec3 bary = closestPointBarycentric(center, p[0], p[1], p[2]);
                const vec2 texcoord = bary.x * uv[0] + bary.y * uv[1] + bary.z * uv[2];
                vec4 base = material.baseColorFactor * fetchTexel(baseColorTexture, texcoord, baseLod);
                if (colored) base *= bary.x * color[0] + bary.y * color[1] + bary.z * color[2];
                if (mask && base.a < material.metallicRoughnessCutoffAo.z) continue;  // cut-out
                const vec3 emission =
                    material.emissiveNormalScale.rgb * fetchTexel(emissiveTexture, texcoord, emissiveLod).rgb;
                // As gbuffer.frag's surface (lib/surface.glsl): factor × texture, without the normal map's Toksvig
                // roughness (the voxel's own normals widen its lobe in inject.comp).
                const vec4 metallicRoughness =
                    fetchTexel(metallicRoughnessTexture, texcoord, metallicRoughnessLod);
                const float metallic = material.metallicRoughnessCutoffAo.x * metallicRoughness.b;
                const float roughness = material.metallicRoughnessCutoffAo.y * metallicRoughness.g;
                // Interpolated shading normal; the face normal when the vertex normals cancel out.
                vec3 normal = bary.x * nrm[0] + bary.y * nrm[1] + bary.z * nrm[2];
                if (dot(normal, normal) < 1e-12) normal = faceNormal;
                normal *= inversesqrt(max(dot(normal, normal), 1e-30));

                // Every voxel a triangle can reach has storage (render/voxel_bricks.h allocates the bricks
                // its bounds overlap, with the same overlap test): the check only guards the buffer.
                const uint k = brickIndex(voxelBrickOf(ivec3(x, y, z)));
                if (k == VCT_BRICK_NONE) continue;
                const uint base_ = voxelAccumIndex(k, ivec3(x, y, z) % VOXEL_BRICK);
                for (int c = 0; c < 3; ++c) {
                    atomicAdd(accum[base_ + c], voxelEncodeUnit(base.rgb[c]));
                    atomicAdd(accum[base_ + 3 + c], voxelEncodeSigned(normal[c]));
                    atomicAdd(accum[base_ + 6 + c], voxelEncodeEmission(emission[c]));
                }
                atomicAdd(accum[base_ + VCT_VOXEL_ACCUM_COUNT], 1u);
                atomicAdd(accum[base_ + VCT_VOXEL_ACCUM_METALLIC], voxelEncodeUnit(metallic));
                atomicAdd(accum[base_ + VCT_VOXEL_ACCUM_ROUGHNESS], voxelEncodeUnit(roughness));
                if (blend)
                    atomicAdd(accum[base_ + VCT_VOXEL_ACCUM_TRANSPARENCY], voxelEncodeUnit(1.0 - base.a));
            }
}
