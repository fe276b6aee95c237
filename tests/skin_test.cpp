// Skins and morph targets on the CPU (scene/deform.h, the twin of the skin pass): the deformed vertices of
// files made in code against positions computed by hand (a two-bone strip turned by 90°, a morph target at
// weight 0.5 from every weight source, a sparse target), the shared RiggedSimple and SimpleMorph against
// their files' numbers, weights renormalised, and hostile skins refused in one line naming the file.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "scene/builtin_scenes.h"
#include "scene/deform.h"
#include "scene/gltf_loader.h"
#include "skin_util.h"

namespace vct {
namespace {

namespace fs = std::filesystem;
using namespace skin_test;

Scene loadWritten(const std::string& name, const GltfScene& scene) {
    const fs::path dir = test::freshOutputDir("skin/" + name);
    return loadGltf(hostile::writeGltf(dir, scene).string());
}

// The deformed vertices of instance `k`'s primitive `slot` at time t.
std::vector<Vertex> deformedAt(const Scene& scene, float t, size_t k = 0, size_t slot = 0) {
    const std::vector<Instance> instances = scene.instances(t);
    const Instance& instance = instances.at(k);
    return deformPrimitive(scene, instance, scene.meshes[size_t(instance.mesh)].primitives.at(slot),
                           jointMatrices(scene, instance.skin, scene.evaluate(t)));
}

void expectNear(const glm::vec3& got, const glm::vec3& want, float tolerance, const std::string& what) {
    EXPECT_LE(glm::length(got - want), tolerance)
        << what << ": got (" << got.x << ", " << got.y << ", " << got.z << "), want (" << want.x << ", "
        << want.y << ", " << want.z << ")";
}

TEST(SkinCpu, TwoBoneStripTurnedByNinetyDegrees) {
    const Scene scene = loadWritten("strip", twoBoneStrip());
    ASSERT_EQ(scene.skins.size(), 1u);
    const std::vector<Instance> instances = scene.instances(1.0f);
    ASSERT_EQ(instances.size(), 1u);
    EXPECT_TRUE(instances[0].deformed);
    EXPECT_TRUE(instances[0].moving);  // joint 1 is animated
    EXPECT_EQ(instances[0].world, glm::mat4(1.0f));
    const std::vector<Vertex> at1 = deformedAt(scene, 1.0f), at0 = deformedAt(scene, 0.0f);
    ASSERT_EQ(at1.size(), size_t(2 * kStripColumns));
    for (int v = 0; v < 2 * kStripColumns; ++v) {
        // float's rotation of 90° from a quaternion is exact to ~1e-7.
        expectNear(at1[size_t(v)].position, stripExpectedAtOneSecond(v), 1e-6f,
                   "vertex " + std::to_string(v));
        expectNear(at0[size_t(v)].position, scene.vertices[size_t(v)].position, 1e-6f,
                   "rest vertex " + std::to_string(v));
        expectNear(at1[size_t(v)].normal, glm::vec3(0, 0, 1), 1e-6f, "normal " + std::to_string(v));
    }
    // The bounds hold the deformed strip.
    const Aabb box = instances[0].bounds;
    for (const Vertex& v : at1)
        EXPECT_TRUE(glm::all(glm::greaterThanEqual(v.position, box.min - 1e-6f)) &&
                    glm::all(glm::lessThanEqual(v.position, box.max + 1e-6f)));
}

TEST(SkinCpu, SecondWeightSetQuantisedAndUnnormalisedWeights) {
    for (const auto& [name, options] :
         {std::pair{"second-set", StripOptions{.secondSet = true}},
          {"quantised", StripOptions{.quantised = true}},
          {"scaled", StripOptions{.weightScale = 0.25f}},
          {"quantised-second-scaled",
           StripOptions{.secondSet = true, .quantised = true, .weightScale = 0.5f}}}) {
        SCOPED_TRACE(name);
        const Scene scene = loadWritten(std::string("strip-") + name, twoBoneStrip(options));
        const std::vector<Vertex> at1 = deformedAt(scene, 1.0f);
        // Quantised half weights are 128/255 and 127/255 before renormalising: 1/255 of the 1-unit lever.
        const float tolerance = options.quantised ? 5e-3f : 1e-6f;
        for (int v = 0; v < 2 * kStripColumns; ++v)
            expectNear(at1[size_t(v)].position, stripExpectedAtOneSecond(v), tolerance,
                       "vertex " + std::to_string(v));
        for (const SkinVertex& s : scene.skinVertices)
            EXPECT_NEAR(glm::dot(s.weights0, glm::vec4(1)) + glm::dot(s.weights1, glm::vec4(1)), 1.0f, 1e-6f);
    }
}

TEST(SkinCpu, AllZeroWeightsKeepTheBindPoseWithANote) {
    const Scene scene = loadWritten("strip-zero", twoBoneStrip({.zeroWeights = true}));
    bool noted = false;
    for (const std::string& note : scene.notes)
        noted |= note.find("all-zero skin weights") != std::string::npos;
    EXPECT_TRUE(noted);
    const std::vector<Vertex> at1 = deformedAt(scene, 1.0f);
    for (int v = 0; v < 2 * kStripColumns; ++v)
        EXPECT_EQ(at1[size_t(v)].position, scene.vertices[size_t(v)].position) << "vertex " << v;
}

TEST(SkinCpu, MorphTargetAtHalfWeightMovesHalfTheDelta) {
    for (WeightSource source : {WeightSource::MeshDefault, WeightSource::NodeOverride, WeightSource::Linear,
                                WeightSource::Step, WeightSource::CubicSpline}) {
        SCOPED_TRACE(int(source));
        const Scene scene = loadWritten("morph-" + std::to_string(int(source)), morphTriangle(source));
        const float t = morphHalfTime(source);
        const std::vector<Instance> instances = scene.instances(t);
        ASSERT_EQ(instances.at(0).morphWeights.size(), 1u);
        EXPECT_FLOAT_EQ(instances[0].morphWeights[0], 0.5f);
        const bool animated = source != WeightSource::MeshDefault && source != WeightSource::NodeOverride;
        EXPECT_EQ(instances[0].moving, animated);
        const std::vector<Vertex> v = deformedAt(scene, t);
        expectNear(v[0].position, {0, 0, 1}, 1e-6f, "vertex 0");
        expectNear(v[1].position, {1, 0, 2}, 1e-6f, "vertex 1");
        expectNear(v[2].position, {0, 1, 0}, 1e-6f, "vertex 2");
        // Normal + 0.5 (1, 0, 0), renormalised.
        expectNear(v[0].normal, glm::normalize(glm::vec3(0.5f, 0, 1)), 1e-6f, "normal 0");
        if (animated) expectNear(deformedAt(scene, 0.0f)[1].position, {1, 0, 0}, 1e-6f, "vertex 1 at t = 0");
    }
}

TEST(SkinCpu, SparseMorphTargetMovesOnlyItsVertex) {
    const Scene scene = loadWritten("morph-sparse", morphTriangle(WeightSource::MeshDefault, true));
    const std::vector<Vertex> v = deformedAt(scene, 0.0f);
    expectNear(v[0].position, {0, 0, 0}, 0.0f, "vertex 0");
    expectNear(v[1].position, {1, 0, 2}, 1e-6f, "vertex 1");
    expectNear(v[2].position, {0, 1, 0}, 0.0f, "vertex 2");
}

// ---- hostile skins and morph targets: one clear error naming the file ----

void expectRefused(const std::string& name, const GltfScene& scene, const std::string& problem) {
    const fs::path dir = test::freshOutputDir("skin/hostile-" + name);
    const fs::path path = hostile::writeGltf(dir, scene);
    try {
        loadGltf(path.string());
        ADD_FAILURE() << name << ": loaded";
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_EQ(what.rfind(path.string() + ": ", 0), 0u) << what;
        EXPECT_NE(what.find(problem), std::string::npos) << name << ": " << what;
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
}

TEST(SkinHostile, RefusedInOneLine) {
    expectRefused("joint-out-of-range", twoBoneStrip({.badJoint = 7}), "names joint 7");
    expectRefused("nan-inverse-bind", twoBoneStrip({.nanInverseBind = true}), "matrix 1 is not finite");
    GltfScene s = twoBoneStrip();
    s.doc["accessors"][2]["count"] = 4;  // JOINTS_0: 4 of 10 vertices
    expectRefused("joints-count", s, "expected 10 VEC4");
    s = twoBoneStrip();
    s.doc["accessors"][2]["componentType"] = kFloat;  // JOINTS_0 as floats (and 4 bytes each: still in range)
    expectRefused("joints-float", s, "not unsigned byte or short");
    s = twoBoneStrip();
    s.doc["skins"][0]["joints"] = {1, 9};
    expectRefused("joint-node", s, "joint node 9 is out of range");
    s = twoBoneStrip();
    s.doc["nodes"][0]["skin"] = 3;
    expectRefused("node-skin", s, "skin index 3 is out of range");
    s = twoBoneStrip();
    s.doc["skins"][0]["joints"] = {1};  // one joint, two inverse bind matrices (and joint 1 named)
    expectRefused("inverse-bind-count", s, "expected 1 MAT4");
    s = morphTriangle();
    s.doc["meshes"][0]["weights"] = {0.5, 0.5};
    expectRefused("mesh-weights", s, "2 weights for 1 morph targets");
    s = morphTriangle();
    s.doc["nodes"][0]["weights"] = {0.5, 0.5, 0.5};
    expectRefused("node-weights", s, "3 morph weights for 1 morph targets");
    s = morphTriangle(WeightSource::Linear);
    s.doc["animations"][0]["samplers"][0]["input"] = 3;  // 3 key times from the normal deltas' 9 floats
    expectRefused("weights-keys", s, "do not match");
    s = morphTriangle();
    s.doc["accessors"][2]["count"] = 2;  // the target's POSITION deltas: 2 of 3 vertices
    expectRefused("target-count", s, "expected");
}

TEST(SkinHostile, NegativeWeightIsRefused) {
    GltfScene s = twoBoneStrip();
    // WEIGHTS_0 is accessor 3: its first float made negative.
    const size_t offset = size_t(s.doc["bufferViews"][3]["byteOffset"].get<uint64_t>());
    const float negative = -0.5f;
    std::memcpy(&s.bin[offset], &negative, 4);
    expectRefused("negative-weight", s, "not finite and non-negative");
}

// ---- the shared sample models ----

using test::sharedModel;

TEST(SkinSamples, SimpleMorphFollowsItsWeights) {
    VCT_REQUIRE_SHARED("SimpleMorph");
    const Scene scene = loadScene(sharedModel("SimpleMorph").string());
    // The file: base (0,0,0), (1,0,0), (0.5,0.5,0); targets move vertex 2 by (-1,1,0) and (1,1,0); weights
    // (0,0), (0,1), (1,1), (1,0), (0,0) at t = 0..4 s (LINEAR).
    for (const auto& [t, want] : {std::pair{0.0f, glm::vec3(0.5f, 0.5f, 0)},
                                  {0.5f, glm::vec3(1.0f, 1.0f, 0)},
                                  {1.5f, glm::vec3(1.0f, 2.0f, 0)},
                                  {2.5f, glm::vec3(0.0f, 2.0f, 0)}}) {
        const std::vector<Vertex> v = deformedAt(scene, t);
        expectNear(v[2].position, want, 1e-6f, "vertex 2 at t = " + std::to_string(t));
        expectNear(v[0].position, {0, 0, 0}, 0.0f, "vertex 0");
    }
    EXPECT_TRUE(scene.instances(0.0f)[0].moving);
}

TEST(SkinSamples, RiggedSimpleBendsItsUpperHalf) {
    VCT_REQUIRE_SHARED("RiggedSimple");
    const Scene scene = loadScene(sharedModel("RiggedSimple").string());
    ASSERT_EQ(scene.skins.size(), 1u);
    EXPECT_EQ(scene.skins[0].joints.size(), 2u);
    for (const std::string& note : scene.notes) EXPECT_EQ(note.find("skin"), std::string::npos) << note;
    const std::vector<Instance> instances = scene.instances(0.0f);
    ASSERT_EQ(instances.size(), 1u);
    EXPECT_TRUE(instances[0].moving && instances[0].deformed);
    // At t = 0 the pose is the bind pose up to the file's rounding: vertices within 1e-3 of their rest positions
    // placed by the root's matrix (a -90° turn about x).
    const glm::mat4 root = scene.evaluate(0.0f)[0];
    const std::vector<Vertex> at0 = deformedAt(scene, 0.0f), at1 = deformedAt(scene, 1.0f);
    size_t moved = 0, still = 0;
    for (size_t v = 0; v < at0.size(); ++v) {
        expectNear(at0[v].position, glm::vec3(root * glm::vec4(scene.vertices[v].position, 1.0f)), 1e-3f,
                   "vertex " + std::to_string(v));
        const float distance = glm::length(at1[v].position - at0[v].position);
        const SkinVertex& s = scene.skinVertices[v];
        const float upper = s.joints0.x == 1 ? s.weights0.x : s.joints0.y == 1 ? s.weights0.y : 0.0f;
        // Vertices held by joint 0 alone stay; the upper joint's move.
        if (upper == 0.0f) {
            EXPECT_LT(distance, 1e-5f) << "vertex " << v;
            ++still;
        } else if (upper > 0.5f) {
            EXPECT_GT(distance, 0.05f) << "vertex " << v;
            ++moved;
        }
    }
    EXPECT_GT(moved, 10u);
    EXPECT_GT(still, 10u);
}

}  // namespace
}  // namespace vct
