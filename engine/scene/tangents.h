// Vertex attributes that glTF allows a file to leave out and that the renderer needs anyway:
// per-vertex tangents (for normal maps) and normals (flat, as the glTF spec requires when absent).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "scene/scene.h"

namespace vct {

// Fills vertices[i].tangent for one primitive from its UV layout. `indices` index into `vertices`
// (a triangle list). Each triangle's dP/du is accumulated (area-weighted) at its corners, then
// Gram-Schmidt orthogonalised against the vertex normal. tangent.w is +1 when the UV layout is upright
// (glTF: bitangent = cross(N, T.xyz) * w points to decreasing v, i.e. "up" in the image) and -1 when
// the UVs are mirrored. Degenerate UVs fall back to an arbitrary unit vector perpendicular to the
// normal; the result is never NaN, even for zero-length normals.
void generateTangents(std::span<Vertex> vertices, std::span<const uint32_t> indices);

// Replaces an indexed triangle list by one without shared vertices whose normals are the face normals
// (glTF: "when normals are not specified, client implementations MUST calculate flat normals").
// Degenerate triangles get +Z. Indices become 0, 1, 2, ...
void makeFlatNormals(std::vector<Vertex>& vertices, std::vector<uint32_t>& indices);

// Any unit vector perpendicular to the unit vector n (stable for every n, including the axes).
glm::vec3 anyPerpendicular(const glm::vec3& n);

}  // namespace vct
