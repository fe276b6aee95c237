// Scene evaluation (animation, hierarchy), defaults, validation, mip chains and the built-in scenes.
#include "scene/scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <set>

#include "core/error.h"
#include "scene/builtin_scenes.h"

namespace vct {
namespace {

// One triangle mesh on one root node: the smallest scene that validates.
Scene triangleScene() {
    Scene s;
    s.name = "triangle";
    s.vertices.resize(3);
    s.vertices[1].position = {1, 0, 0};
    s.vertices[2].position = {0, 1, 0};
    s.indices = {0, 1, 2};
    Primitive p;
    p.indexCount = 3;
    p.vertexCount = 3;
    for (const Vertex& v : s.vertices) p.bounds.extend(v.position);
    s.primitives.push_back(p);
    s.meshes.push_back(Mesh{"tri", {0}});
    s.materials.emplace_back();
    Node n;
    n.name = "root";
    n.mesh = 0;
    s.nodes.push_back(n);
    s.roots.push_back(0);
    return s;
}

Scene withChannel(AnimationChannel ch) {
    Scene s = triangleScene();
    ch.node = 0;
    float duration = ch.times.back();
    s.animations.push_back(Animation{"a", {ch}, duration});
    return s;
}

glm::vec3 translationOf(const glm::mat4& m) {
    return glm::vec3(m[3]);
}
glm::vec4 quatValue(const glm::quat& q) {
    return glm::vec4(q.x, q.y, q.z, q.w);
}

void expectNear(glm::vec3 a, glm::vec3 b, float eps = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, eps);
    EXPECT_NEAR(a.y, b.y, eps);
    EXPECT_NEAR(a.z, b.z, eps);
}

void expectSingleLineError(const std::function<void()>& f, const std::string& needle) {
    try {
        f();
        FAIL() << "expected vct::Error containing '" << needle << "'";
    } catch (const Error& e) {
        std::string what = e.what();
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        EXPECT_NE(what.find(needle), std::string::npos) << what;
    }
}

TEST(Animation, LinearTranslationMidpointAndClamping) {
    AnimationChannel ch{
        0, AnimationPath::Translation, Interpolation::Linear, {0.0f, 2.0f}, {{0, 0, 0, 0}, {2, 4, 6, 0}}};
    Scene s = withChannel(ch);
    expectNear(translationOf(s.evaluate(1.0f)[0]), {1, 2, 3});
    expectNear(translationOf(s.evaluate(0.5f)[0]), {0.5f, 1, 1.5f});
}

TEST(Animation, StepHoldsThePreviousKey) {
    AnimationChannel ch{0,
                        AnimationPath::Translation,
                        Interpolation::Step,
                        {0.0f, 1.0f, 2.0f},
                        {{0, 0, 0, 0}, {5, 0, 0, 0}, {9, 0, 0, 0}}};
    Scene s = withChannel(ch);
    expectNear(translationOf(s.evaluate(0.99f)[0]), {0, 0, 0});
    expectNear(translationOf(s.evaluate(1.5f)[0]), {5, 0, 0});
}

TEST(Animation, RotationSlerpTakesTheShortWay) {
    glm::quat q90 = glm::angleAxis(glm::radians(90.0f), glm::vec3(0, 1, 0));
    // The second key is stored negated (the same rotation); slerp must still turn by 45°, not 135°.
    AnimationChannel ch{0,
                        AnimationPath::Rotation,
                        Interpolation::Linear,
                        {0.0f, 1.0f},
                        {quatValue(glm::quat(1, 0, 0, 0)), -quatValue(q90)}};
    Scene s = withChannel(ch);
    glm::mat4 m = s.evaluate(0.5f)[0];
    glm::vec3 x = glm::vec3(m * glm::vec4(1, 0, 0, 0));
    float c = std::cos(glm::radians(45.0f));
    expectNear(x, {c, 0, -c});
    EXPECT_NEAR(glm::length(x), 1.0f, 1e-5f);  // normalised: no scaling creeps in
}

TEST(Animation, CubicSplineWithFlatTangentsPassesTheMidpoint) {
    // Keys (in-tangent, value, out-tangent): flat tangents make the midpoint the average of the values.
    AnimationChannel ch{0,
                        AnimationPath::Scale,
                        Interpolation::CubicSpline,
                        {0.0f, 2.0f},
                        {{0, 0, 0, 0}, {1, 1, 1, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}, {3, 3, 3, 0}, {0, 0, 0, 0}}};
    Scene s = withChannel(ch);
    glm::mat4 m = s.evaluate(1.0f)[0];
    EXPECT_NEAR(m[0][0], 2.0f, 1e-5f);
    EXPECT_NEAR(s.evaluate(0.0f)[0][0][0], 1.0f, 1e-5f);
}

TEST(Animation, LoopsOverTheDuration) {
    AnimationChannel ch{
        0, AnimationPath::Translation, Interpolation::Linear, {0.0f, 2.0f}, {{0, 0, 0, 0}, {2, 0, 0, 0}}};
    Scene s = withChannel(ch);
    expectNear(translationOf(s.evaluate(3.0f)[0]), translationOf(s.evaluate(1.0f)[0]));
    expectNear(translationOf(s.evaluate(-0.5f)[0]), translationOf(s.evaluate(1.5f)[0]));
    expectNear(translationOf(s.evaluate(100.5f)[0]), {0.5f, 0, 0});
}

TEST(Scene, HierarchyComposesAndAnimationPropagatesToChildren) {
    Scene s = triangleScene();
    Node child;
    child.name = "child";
    child.parent = 0;
    child.mesh = 0;
    child.translation = {0, 1, 0};
    s.nodes.push_back(child);
    s.nodes[0].children.push_back(1);
    s.nodes[0].scale = glm::vec3(2.0f);
    AnimationChannel ch{
        0, AnimationPath::Translation, Interpolation::Linear, {0.0f, 1.0f}, {{0, 0, 0, 0}, {10, 0, 0, 0}}};
    s.animations.push_back(Animation{"a", {ch}, 1.0f});
    expectNear(translationOf(s.evaluate(0.5f)[1]), {5, 2, 0});
    std::vector<bool> animated = s.animatedNodes();
    EXPECT_TRUE(animated[0]);
    EXPECT_TRUE(animated[1]);
    std::vector<Instance> inst = s.instances(0.0f);
    ASSERT_EQ(inst.size(), 2u);
    EXPECT_TRUE(inst[0].moving && inst[1].moving);
}

TEST(Scene, AabbTransformedAndBounds) {
    Aabb box{glm::vec3(-1), glm::vec3(1)};
    Aabb rotated = box.transformed(glm::mat4_cast(glm::angleAxis(glm::radians(45.0f), glm::vec3(0, 0, 1))));
    EXPECT_NEAR(rotated.max.x, std::sqrt(2.0f), 1e-5f);
    EXPECT_TRUE(Aabb{}.transformed(glm::mat4(1.0f)).empty());
    Scene s = triangleScene();
    s.nodes[0].translation = {5, 0, 0};
    Aabb b = s.bounds();
    expectNear(b.min, {5, 0, 0});
    expectNear(b.max, {6, 1, 0});
}

TEST(Scene, DefaultsAddCameraLookingAtTheBoundsAndALight) {
    Scene s = triangleScene();
    s.addDefaultsIfMissing();
    ASSERT_EQ(s.cameras.size(), 1u);
    ASSERT_EQ(s.lights.size(), 1u);
    EXPECT_EQ(s.notes.size(), 2u);
    std::vector<glm::mat4> world = s.evaluate(0.0f);
    for (size_t n = 0; n < s.nodes.size(); ++n) {
        if (s.nodes[n].camera < 0) continue;
        glm::vec3 eye = translationOf(world[n]);
        glm::vec3 forward = -glm::vec3(world[n][2]);
        Aabb b = s.bounds();
        glm::vec3 toCentre = glm::normalize(0.5f * (b.min + b.max) - eye);
        EXPECT_GT(glm::dot(forward, toCentre), 0.999f);
        EXPECT_LT(s.cameras[0].znear, glm::length(0.5f * (b.min + b.max) - eye));
    }
    s.addDefaultsIfMissing();  // idempotent
    EXPECT_EQ(s.cameras.size(), 1u);
    EXPECT_EQ(s.lights.size(), 1u);
    EXPECT_NO_THROW(s.validate());
}

TEST(Scene, ValidateNamesTheProblem) {
    Scene s = triangleScene();
    EXPECT_NO_THROW(s.validate());
    Scene nanPos = s;
    nanPos.vertices[1].position.y = std::numeric_limits<float>::quiet_NaN();
    expectSingleLineError([&] { nanPos.validate(); },
                          "mesh 'tri' primitive 0: vertex 1 has a non-finite position");
    Scene infUv = s;
    infUv.vertices[2].uv.x = std::numeric_limits<float>::infinity();
    expectSingleLineError([&] { infUv.validate(); }, "non-finite texture coordinate");
    Scene badIndex = s;
    badIndex.indices[2] = 7;
    expectSingleLineError([&] { badIndex.validate(); }, "out of range");
    Scene badMaterial = s;
    badMaterial.primitives[0].material = 3;
    expectSingleLineError([&] { badMaterial.validate(); }, "material 3 is out of range");
    Scene badTexture = s;
    badTexture.materials[0].normalTexture = 0;
    expectSingleLineError([&] { badTexture.validate(); }, "texture index 0 is out of range");
    Scene empty = s;
    empty.nodes[0].mesh = -1;
    expectSingleLineError([&] { empty.validate(); }, "no mesh instances");
}

Texture texture(TextureKind kind, uint32_t w, uint32_t h, std::vector<uint8_t> rgba) {
    Texture t;
    t.kind = kind;
    t.width = w;
    t.height = h;
    t.mips.push_back(std::move(rgba));
    return t;
}

TEST(MipChain, SizesDownToOneByOne) {
    Texture t = texture(TextureKind::Linear, 5, 3, std::vector<uint8_t>(5 * 3 * 4, 7));
    buildMipChain(t);
    ASSERT_EQ(t.mips.size(), 3u);  // 5x3, 2x1, 1x1
    EXPECT_EQ(t.mips[1].size(), 2u * 1u * 4u);
    EXPECT_EQ(t.mips[2].size(), 4u);
    EXPECT_EQ(t.mips[2][0], 7);  // a constant image stays constant
    Texture square = texture(TextureKind::Color, 8, 8, std::vector<uint8_t>(8 * 8 * 4, 200));
    buildMipChain(square);
    EXPECT_EQ(square.mips.size(), 4u);
    EXPECT_EQ(square.mips[3][0], 200);  // sRGB round trip is exact enough for a constant
}

TEST(MipChain, OddSizesUseEveryTexel) {
    Texture t = texture(TextureKind::Linear, 3, 1, {0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255, 255});
    buildMipChain(t);
    ASSERT_EQ(t.mips.size(), 2u);
    EXPECT_EQ(t.mips[1][0], 85);  // (0 + 0 + 255) / 3
}

TEST(MipChain, ColourAveragesInLinearSpaceLinearDoesNot) {
    std::vector<uint8_t> blackWhite = {0, 0, 0, 255, 255, 255, 255, 255};
    Texture c = texture(TextureKind::Color, 2, 1, blackWhite);
    buildMipChain(c);
    EXPECT_NEAR(c.mips[1][0], 188, 1);  // linear 0.5 encoded as sRGB
    Texture l = texture(TextureKind::Linear, 2, 1, blackWhite);
    buildMipChain(l);
    EXPECT_NEAR(l.mips[1][0], 128, 1);
}

TEST(MipChain, OppositeNormalsAverageToAShortVector) {
    // +X and -X encoded as (255,128,128) and (0,128,128); the mip must not renormalise.
    Texture n = texture(TextureKind::Normal, 2, 1, {255, 128, 128, 255, 0, 128, 128, 255});
    buildMipChain(n);
    const uint8_t* texel = n.mips[1].data();
    glm::vec3 decoded = glm::vec3(texel[0], texel[1], texel[2]) / 255.0f * 2.0f - 1.0f;
    EXPECT_LT(glm::length(decoded), 0.05f);
    // Two normals 90° apart: |mean| = cos 45° ≈ 0.707.
    Texture m = texture(TextureKind::Normal, 2, 1, {255, 128, 128, 255, 128, 128, 255, 255});
    buildMipChain(m);
    texel = m.mips[1].data();
    decoded = glm::vec3(texel[0], texel[1], texel[2]) / 255.0f * 2.0f - 1.0f;
    EXPECT_NEAR(glm::length(decoded), 0.707f, 0.02f);
}

TEST(BuiltinScenes, CornellIsComplete) {
    EXPECT_EQ(builtinSceneNames().front(), "cornell");
    for (const std::string& name : builtinSceneNames()) EXPECT_FALSE(builtinSceneDescription(name).empty());
    Scene s = loadScene("cornell");
    EXPECT_NO_THROW(s.validate());
    EXPECT_TRUE(s.notes.empty());
    ASSERT_EQ(s.lights.size(), 1u);
    EXPECT_EQ(s.lights[0].type, LightType::Spot);
    EXPECT_EQ(s.cameras.size(), 1u);
    std::vector<Instance> a = s.instances(0.0f), b = s.instances(1.0f);
    int moving = 0, still = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        (a[i].moving ? moving : still)++;
        if (a[i].moving) {
            EXPECT_GT(glm::distance(translationOf(a[i].world), translationOf(b[i].world)), 0.5f);
            expectNear(translationOf(s.instances(4.0f)[i].world), translationOf(a[i].world), 1e-4f);  // loops
        } else {
            EXPECT_EQ(a[i].world, b[i].world);
        }
    }
    EXPECT_EQ(moving, 1);
    EXPECT_GE(still, 3);
    ASSERT_GE(s.textures.size(), 2u);
    for (const Texture& t : s.textures) {
        uint32_t levels = 1;
        while ((std::max(t.width, t.height) >> levels) > 0) ++levels;
        EXPECT_EQ(t.mips.size(), levels) << t.name;
        EXPECT_EQ(t.mips.back().size(), 4u);
    }
    for (const Vertex& v : s.vertices) {
        EXPECT_NEAR(glm::length(v.normal), 1.0f, 1e-4f);
        EXPECT_NEAR(glm::dot(glm::vec3(v.tangent), v.normal), 0.0f, 1e-4f);
        EXPECT_TRUE(v.tangent.w == 1.0f || v.tangent.w == -1.0f);
    }
    Aabb box = s.bounds();
    expectNear(box.min, {-2, 0, -2});
    expectNear(box.max, {2, 3, 2});
}

TEST(BuiltinScenes, CameraAndLightAreInsideTheRoom) {
    Scene s = loadScene("cornell");
    std::vector<glm::mat4> world = s.evaluate(0.0f);
    for (size_t n = 0; n < s.nodes.size(); ++n) {
        if (s.nodes[n].camera < 0 && s.nodes[n].light < 0) continue;
        glm::vec3 p = translationOf(world[n]);
        EXPECT_TRUE(glm::all(glm::greaterThan(p, glm::vec3(-2, 0, -2))) &&
                    glm::all(glm::lessThan(p, glm::vec3(2, 3, 2))));
        glm::vec3 forward = -glm::vec3(world[n][2]);
        if (s.nodes[n].light >= 0) {
            EXPECT_LT(forward.y, -0.99f);  // the spot points down
        }
        if (s.nodes[n].camera >= 0) {
            EXPECT_LT(forward.z, -0.9f);  // the camera looks at the back wall
        }
    }
}

// The large interior for issue 19's measurements: tens of metres, thin walls, a sun through openings and one
// moving object, all as its description says.
TEST(BuiltinScenes, HallIsALargeInteriorWithThinWallsAndOneMovingObject) {
    Scene s = loadScene("hall");
    EXPECT_NO_THROW(s.validate());
    const Aabb box = s.bounds();
    EXPECT_GE(box.max.x - box.min.x, 40.0f);
    EXPECT_GE(box.max.z - box.min.z, 16.0f);
    EXPECT_GE(box.max.y - box.min.y, 10.0f);
    ASSERT_EQ(s.lights.size(), 1u);
    EXPECT_EQ(s.lights[0].type, LightType::Directional);
    std::vector<Instance> a = s.instances(0.0f), b = s.instances(2.0f);
    int moving = 0;
    for (size_t i = 0; i < a.size(); ++i)
        if (a[i].moving) {
            ++moving;
            EXPECT_GT(glm::distance(translationOf(a[i].world), translationOf(b[i].world)), 10.0f);
        }
    EXPECT_EQ(moving, 1);
    // Thin walls: the partitions (the plaster primitive below the arches) are made of boxes 0.1 m thick in x,
    // thinner than a voxel at 256³ (40.6 m / 256 = 0.16 m).
    std::set<float> wallFaces;
    for (const Primitive& p : s.primitives)
        if (s.materials[p.material].name == "plaster" && p.bounds.max.y < 6.01f)
            for (uint32_t v = 0; v < p.vertexCount; ++v)
                wallFaces.insert(std::round(s.vertices[p.vertexOffset + v].position.x * 1000.0f) / 1000.0f);
    ASSERT_EQ(wallFaces.size(), 6u);  // x = -8, 0, 8, each ± 0.05
    for (auto it = wallFaces.begin(); it != wallFaces.end(); std::advance(it, 2))
        EXPECT_NEAR(*std::next(it) - *it, 0.1f, 1e-3f);
    EXPECT_LT(0.1f, (box.max.x - box.min.x) / 256.0f);
    // The camera stands inside the hall.
    std::vector<glm::mat4> world = s.evaluate(0.0f);
    for (size_t n = 0; n < s.nodes.size(); ++n)
        if (s.nodes[n].camera >= 0) {
            const glm::vec3 p = translationOf(world[n]);
            EXPECT_TRUE(glm::all(glm::greaterThan(p, box.min)) && glm::all(glm::lessThan(p, box.max)));
        }
    EXPECT_GT(s.indices.size() / 3, 5000u);
}

TEST(BuiltinScenes, PlaneAndUnknownNames) {
    Scene p = loadScene("plane");
    EXPECT_EQ(p.instances(0.0f).size(), 1u);
    EXPECT_EQ(p.lights.size(), 1u);
    EXPECT_GE(p.materials[0].normalTexture, 0);
    EXPECT_FALSE(makeBuiltinScene("nope").has_value());
    expectSingleLineError([] { loadScene("no-such-scene"); },
                          "unknown scene 'no-such-scene' (not a built-in scene and no such file)");
}

}  // namespace
}  // namespace vct
