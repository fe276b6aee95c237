#include "scene/tangents.h"

#include <cmath>

namespace vct {

namespace {

bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Unit vector or `fallback` when v is zero, tiny or not finite, so nothing downstream sees a NaN.
glm::vec3 safeNormalize(const glm::vec3& v, const glm::vec3& fallback) {
    if (!finite(v)) return fallback;
    float len = glm::length(v);
    return len > 1e-20f && std::isfinite(len) ? v / len : fallback;
}

}  // namespace

glm::vec3 anyPerpendicular(const glm::vec3& n) {
    // Cross with the axis least aligned with n: never parallel, so the result is well conditioned.
    glm::vec3 a = std::abs(n.x) < 0.577f   ? glm::vec3(1, 0, 0)
                  : std::abs(n.y) < 0.577f ? glm::vec3(0, 1, 0)
                                           : glm::vec3(0, 0, 1);
    return safeNormalize(glm::cross(n, a), glm::vec3(1, 0, 0));
}

void generateTangents(std::span<Vertex> vertices, std::span<const uint32_t> indices) {
    std::vector<glm::vec3> tanSum(vertices.size(), glm::vec3(0.0f));
    std::vector<glm::vec3> bitSum(vertices.size(), glm::vec3(0.0f));

    for (size_t i = 0; i + 2 < indices.size(); i += 3) {
        uint32_t ia = indices[i], ib = indices[i + 1], ic = indices[i + 2];
        if (ia >= vertices.size() || ib >= vertices.size() || ic >= vertices.size())
            continue;  // validate() reports it
        const Vertex& a = vertices[ia];
        const Vertex& b = vertices[ib];
        const Vertex& c = vertices[ic];
        glm::vec3 e1 = b.position - a.position, e2 = c.position - a.position;
        glm::vec2 d1 = b.uv - a.uv, d2 = c.uv - a.uv;
        float det = d1.x * d2.y - d2.x * d1.y;
        if (!(std::abs(det) > 1e-20f)) continue;  // degenerate (or NaN) UVs: no information about the tangent
        // Solve e = du * dP/du + dv * dP/dv for both edges.
        glm::vec3 dPdu = (e1 * d2.y - e2 * d1.y) / det;
        glm::vec3 dPdv = (e2 * d1.x - e1 * d2.x) / det;
        // glTF's bitangent points "up" in the image; glTF's v grows downwards, hence the minus.
        glm::vec3 t = safeNormalize(dPdu, glm::vec3(0.0f));
        glm::vec3 bt = safeNormalize(-dPdv, glm::vec3(0.0f));
        // Area weighting: big triangles dominate, slivers with wild UV derivatives barely count.
        float area = glm::length(glm::cross(e1, e2));
        if (!std::isfinite(area)) continue;
        for (uint32_t v : {ia, ib, ic}) {
            tanSum[v] += t * area;
            bitSum[v] += bt * area;
        }
    }

    for (size_t v = 0; v < vertices.size(); ++v) {
        glm::vec3 n = safeNormalize(vertices[v].normal, glm::vec3(0, 0, 1));
        glm::vec3 t = tanSum[v] - n * glm::dot(n, tanSum[v]);  // Gram-Schmidt
        glm::vec3 bt = bitSum[v];
        float tLen = glm::length(t);
        if (tLen > 1e-6f * (glm::length(tanSum[v]) + 1e-30f) && std::isfinite(tLen)) {
            t /= tLen;
        } else {
            // dP/du is parallel to the normal or unknown: derive it from the bitangent if that is usable.
            glm::vec3 fromBit = glm::cross(bt, n);
            t = glm::length(fromBit) > 1e-12f ? safeNormalize(fromBit, anyPerpendicular(n))
                                              : anyPerpendicular(n);
        }
        float w = glm::dot(glm::cross(n, t), bt) < 0.0f ? -1.0f : 1.0f;
        vertices[v].tangent = glm::vec4(t, w);
    }
}

void makeFlatNormals(std::vector<Vertex>& vertices, std::vector<uint32_t>& indices) {
    std::vector<Vertex> flat;
    flat.reserve(indices.size());
    for (size_t i = 0; i + 2 < indices.size(); i += 3) {
        Vertex corner[3];
        for (int k = 0; k < 3; ++k) {
            uint32_t index = indices[i + static_cast<size_t>(k)];
            // An out-of-range index keeps a zero vertex here; the caller validates indices before this.
            corner[k] = index < vertices.size() ? vertices[index] : Vertex{};
        }
        // In double: the cross product of edges near float's limits (1e-30 or 1e30 long) under- or overflows
        // float, and the triangle's normal would be lost.
        const glm::dvec3 p0(corner[0].position), p1(corner[1].position), p2(corner[2].position);
        const glm::dvec3 cross = glm::cross(p1 - p0, p2 - p0);
        const double length = glm::length(cross);
        glm::vec3 n = length > 0.0 && std::isfinite(length) ? glm::vec3(cross / length) : glm::vec3(0, 0, 1);
        for (Vertex& c : corner) {
            c.normal = n;
            flat.push_back(c);
        }
    }
    vertices = std::move(flat);
    indices.resize(vertices.size());
    for (size_t i = 0; i < indices.size(); ++i) indices[i] = static_cast<uint32_t>(i);
}

}  // namespace vct
