// Tangent generation: known UV layouts, mirrored UVs, and degenerate input that must not produce NaN.
#include "scene/tangents.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace vct {
namespace {

// Unit quad in the XY plane facing +Z; uv(x, y) gives each corner's texture coordinate.
template <class UvOf>
std::vector<Vertex> quad(UvOf uvOf) {
    std::vector<Vertex> v(4);
    const glm::vec2 corners[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int i = 0; i < 4; ++i) {
        v[size_t(i)].position = glm::vec3(corners[i], 0.0f);
        v[size_t(i)].normal = glm::vec3(0, 0, 1);
        v[size_t(i)].uv = uvOf(corners[i]);
    }
    return v;
}
const std::vector<uint32_t> kQuadIndices = {0, 1, 2, 0, 2, 3};

bool finite(const glm::vec4& t) {
    return std::isfinite(t.x) && std::isfinite(t.y) && std::isfinite(t.z) && std::isfinite(t.w);
}

void expectValidFrame(const Vertex& v) {
    ASSERT_TRUE(finite(v.tangent));
    EXPECT_NEAR(glm::length(glm::vec3(v.tangent)), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(glm::vec3(v.tangent), glm::normalize(v.normal)), 0.0f, 1e-5f);
    EXPECT_TRUE(v.tangent.w == 1.0f || v.tangent.w == -1.0f);
}

TEST(Tangents, UprightUvsGiveTangentAlongUAndPositiveSign) {
    // glTF layout: u grows to the right, v grows downwards in the image, so v = 1 - y for an upright image.
    auto v = quad([](glm::vec2 p) { return glm::vec2(p.x, 1.0f - p.y); });
    generateTangents(v, kQuadIndices);
    for (const Vertex& vert : v) {
        expectValidFrame(vert);
        EXPECT_NEAR(vert.tangent.x, 1.0f, 1e-5f);
        EXPECT_EQ(vert.tangent.w, 1.0f);
        // Bitangent = cross(N, T) * w points up in the image = +Y here.
        glm::vec3 b = glm::cross(vert.normal, glm::vec3(vert.tangent)) * vert.tangent.w;
        EXPECT_NEAR(b.y, 1.0f, 1e-5f);
    }
}

TEST(Tangents, MirroredUvsGiveNegativeSign) {
    auto v = quad([](glm::vec2 p) { return glm::vec2(1.0f - p.x, 1.0f - p.y); });  // mirrored in u
    generateTangents(v, kQuadIndices);
    for (const Vertex& vert : v) {
        expectValidFrame(vert);
        EXPECT_NEAR(vert.tangent.x, -1.0f, 1e-5f);  // still along increasing u
        EXPECT_EQ(vert.tangent.w, -1.0f);
    }
}

TEST(Tangents, ScaledAndRotatedUvs) {
    // u runs along +Y and v along +X (a 90° rotation of the image) with a non-unit scale.
    auto v = quad([](glm::vec2 p) { return glm::vec2(3.0f * p.y, 3.0f * p.x); });
    generateTangents(v, kQuadIndices);
    for (const Vertex& vert : v) {
        expectValidFrame(vert);
        EXPECT_NEAR(vert.tangent.y, 1.0f, 1e-5f);
        // dP/dv = +X, so the bitangent (-dP/dv) is -X: cross(Z, Y) * w = -X * w → w = +1.
        EXPECT_EQ(vert.tangent.w, 1.0f);
    }
}

TEST(Tangents, TiltedNormalIsOrthogonalised) {
    auto v = quad([](glm::vec2 p) { return glm::vec2(p.x, 1.0f - p.y); });
    for (Vertex& vert : v) vert.normal = glm::normalize(glm::vec3(0.5f, 0.0f, 1.0f));
    generateTangents(v, kQuadIndices);
    for (const Vertex& vert : v) expectValidFrame(vert);
}

TEST(Tangents, DegenerateUvsFallBackToAPerpendicular) {
    auto v = quad([](glm::vec2) { return glm::vec2(0.5f); });  // every corner at the same UV
    generateTangents(v, kQuadIndices);
    for (const Vertex& vert : v) expectValidFrame(vert);

    auto line = quad([](glm::vec2 p) { return glm::vec2(p.x, 0.0f); });  // UVs on a line: det = 0
    generateTangents(line, kQuadIndices);
    for (const Vertex& vert : line) expectValidFrame(vert);
}

TEST(Tangents, BadInputNeverProducesNaN) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    auto v = quad([](glm::vec2 p) { return glm::vec2(p.x, 1.0f - p.y); });
    v[0].position.x = nan;                       // NaN position
    v[1].normal = glm::vec3(0.0f);               // zero normal
    v[2].uv = glm::vec2(nan, 0.0f);              // NaN UV
    v[3].position = glm::vec3(1e30f, 1e30f, 0);  // huge triangle: area overflows
    std::vector<uint32_t> indices = kQuadIndices;
    indices.push_back(0);
    indices.push_back(1);
    indices.push_back(99);  // out of range: ignored here, reported by Scene::validate
    generateTangents(v, indices);
    for (const Vertex& vert : v) EXPECT_TRUE(finite(vert.tangent));

    std::vector<Vertex> unused(3);  // vertices no triangle uses
    generateTangents(unused, std::vector<uint32_t>{});
    for (const Vertex& vert : unused) expectValidFrame(vert);
}

TEST(Tangents, AnyPerpendicularIsUnitAndOrthogonal) {
    for (glm::vec3 n :
         {glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, -1), glm::normalize(glm::vec3(1, 1, 1))}) {
        glm::vec3 t = anyPerpendicular(n);
        EXPECT_NEAR(glm::length(t), 1.0f, 1e-6f);
        EXPECT_NEAR(glm::dot(t, n), 0.0f, 1e-6f);
    }
}

TEST(FlatNormals, UnweldsAndUsesFaceNormals) {
    std::vector<Vertex> v(4);
    v[0].position = {0, 0, 0};
    v[1].position = {1, 0, 0};
    v[2].position = {0, 1, 0};
    v[3].position = {0, 0, 1};
    std::vector<uint32_t> indices = {0, 1, 2, 0, 3, 1, 0, 0, 0};  // a +Z face, a +Y face, a degenerate one
    makeFlatNormals(v, indices);
    ASSERT_EQ(v.size(), 9u);
    ASSERT_EQ(indices.size(), 9u);
    for (size_t i = 0; i < indices.size(); ++i) EXPECT_EQ(indices[i], i);
    for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(glm::distance(v[size_t(k)].normal, glm::vec3(0, 0, 1)), 0.0f, 1e-6f);
    for (int k = 3; k < 6; ++k)
        EXPECT_NEAR(glm::distance(v[size_t(k)].normal, glm::vec3(0, 1, 0)), 0.0f, 1e-6f);
    for (int k = 6; k < 9; ++k)
        EXPECT_NEAR(glm::length(v[size_t(k)].normal), 1.0f, 1e-6f);  // degenerate: still unit
}

}  // namespace
}  // namespace vct
