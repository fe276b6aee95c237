// glTF export (scene/gltf_writer.h, vct export-scene): every built-in scene written as .glb and loaded back
// is the same Scene, field by field and bit for bit (vertices, indices, materials, texture texels and mips,
// lights, cameras, nodes, animation poses at several times); so is a small scene that uses what the built-ins
// do not (hierarchy, matrices, every texture slot, alpha, emission > 1, point light, step and cubic-spline
// keys). The committed scenes/*.glb are checked against the built-ins (so they never go stale), and rendering
// the built-in scene and its .glb gives the same final.exr.
#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/gtc/constants.hpp>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "hostile_util.h"
#include "io/image_io.h"
#include "scene/builtin_scenes.h"
#include "scene/gltf_loader.h"
#include "scene/gltf_writer.h"
#include "scene/tangents.h"
#include "test_util.h"

namespace vct {
namespace {

namespace fs = std::filesystem;

// ---- exact Scene comparison: collects every difference (up to a limit) with where it is ----

class SceneDiff {
  public:
    std::vector<std::string> differences;
    size_t total = 0;

    bool empty() const { return total == 0; }
    std::string report() const {
        std::ostringstream s;
        s << total << " differences";
        for (const std::string& d : differences) s << "\n  " << d;
        return s.str();
    }

    // Bit patterns, so -0 vs 0 or a last-bit change is a difference too.
    template <class T>
    void same(const std::string& where, const T& a, const T& b) {
        static_assert(std::is_trivially_copyable_v<T>);
        if (std::memcmp(&a, &b, sizeof(T)) != 0) add(where, show(a), show(b));
    }
    void same(const std::string& where, const std::string& a, const std::string& b) {
        if (a != b) add(where, "'" + a + "'", "'" + b + "'");
    }
    template <class T>
    void sameList(const std::string& where, const std::vector<T>& a, const std::vector<T>& b) {
        if (a.size() != b.size()) {
            add(where + ".size()", std::to_string(a.size()), std::to_string(b.size()));
            return;
        }
        for (size_t i = 0; i < a.size(); ++i) same(where + "[" + std::to_string(i) + "]", a[i], b[i]);
    }
    bool sameSize(const std::string& where, size_t a, size_t b) {
        if (a != b) add(where + ".size()", std::to_string(a), std::to_string(b));
        return a == b;
    }

  private:
    void add(const std::string& where, const std::string& a, const std::string& b) {
        if (++total <= 40) differences.push_back(where + ": " + a + " vs " + b);
    }
    template <class T>
    static std::string show(const T& value) {
        std::ostringstream s;
        s.precision(9);
        if constexpr (std::is_arithmetic_v<T>) {
            s << +value;
        } else if constexpr (std::is_enum_v<T>) {
            s << int(value);
        } else {  // glm vectors, quaternions and matrices: their floats
            const float* f = reinterpret_cast<const float*>(&value);
            for (size_t i = 0; i < sizeof(T) / sizeof(float); ++i) s << (i ? ", " : "(") << f[i];
            s << ")";
        }
        return s.str();
    }
};

std::string at(const std::string& list, size_t i) {
    return list + "[" + std::to_string(i) + "]";
}

void compareAabb(SceneDiff& d, const std::string& w, const Aabb& a, const Aabb& b) {
    d.same(w + ".min", a.min, b.min);
    d.same(w + ".max", a.max, b.max);
}

// Every field of two Scenes (`a` the original, `b` the one loaded back), and what they evaluate to.
SceneDiff compareScenes(const Scene& a, const Scene& b) {
    SceneDiff d;
    d.same("name", a.name, b.name);
    if (d.sameSize("vertices", a.vertices.size(), b.vertices.size()))
        for (size_t i = 0; i < a.vertices.size(); ++i) {
            const Vertex &va = a.vertices[i], &vb = b.vertices[i];
            std::string w = at("vertices", i);
            d.same(w + ".position", va.position, vb.position);
            d.same(w + ".normal", va.normal, vb.normal);
            d.same(w + ".uv", va.uv, vb.uv);
            d.same(w + ".tangent", va.tangent, vb.tangent);
            d.same(w + ".color", va.color, vb.color);
        }
    d.sameList("indices", a.indices, b.indices);
    if (d.sameSize("primitives", a.primitives.size(), b.primitives.size()))
        for (size_t i = 0; i < a.primitives.size(); ++i) {
            const Primitive &pa = a.primitives[i], &pb = b.primitives[i];
            std::string w = at("primitives", i);
            d.same(w + ".firstIndex", pa.firstIndex, pb.firstIndex);
            d.same(w + ".indexCount", pa.indexCount, pb.indexCount);
            d.same(w + ".vertexOffset", pa.vertexOffset, pb.vertexOffset);
            d.same(w + ".vertexCount", pa.vertexCount, pb.vertexCount);
            d.same(w + ".material", pa.material, pb.material);
            d.same(w + ".hasColors", pa.hasColors, pb.hasColors);
            compareAabb(d, w + ".bounds", pa.bounds, pb.bounds);
        }
    if (d.sameSize("meshes", a.meshes.size(), b.meshes.size()))
        for (size_t i = 0; i < a.meshes.size(); ++i) {
            d.same(at("meshes", i) + ".name", a.meshes[i].name, b.meshes[i].name);
            d.sameList(at("meshes", i) + ".primitives", a.meshes[i].primitives, b.meshes[i].primitives);
        }
    if (d.sameSize("materials", a.materials.size(), b.materials.size()))
        for (size_t i = 0; i < a.materials.size(); ++i) {
            const Material &ma = a.materials[i], &mb = b.materials[i];
            std::string w = at("materials", i);
            d.same(w + ".name", ma.name, mb.name);
            d.same(w + ".baseColorFactor", ma.baseColorFactor, mb.baseColorFactor);
            d.same(w + ".metallicFactor", ma.metallicFactor, mb.metallicFactor);
            d.same(w + ".roughnessFactor", ma.roughnessFactor, mb.roughnessFactor);
            d.same(w + ".emissiveFactor", ma.emissiveFactor, mb.emissiveFactor);
            d.same(w + ".normalScale", ma.normalScale, mb.normalScale);
            d.same(w + ".occlusionStrength", ma.occlusionStrength, mb.occlusionStrength);
            d.same(w + ".alphaCutoff", ma.alphaCutoff, mb.alphaCutoff);
            d.same(w + ".alphaMode", ma.alphaMode, mb.alphaMode);
            d.same(w + ".doubleSided", ma.doubleSided, mb.doubleSided);
            d.same(w + ".baseColorTexture", ma.baseColorTexture, mb.baseColorTexture);
            d.same(w + ".metallicRoughnessTexture", ma.metallicRoughnessTexture, mb.metallicRoughnessTexture);
            d.same(w + ".normalTexture", ma.normalTexture, mb.normalTexture);
            d.same(w + ".emissiveTexture", ma.emissiveTexture, mb.emissiveTexture);
            d.same(w + ".occlusionTexture", ma.occlusionTexture, mb.occlusionTexture);
        }
    if (d.sameSize("textures", a.textures.size(), b.textures.size()))
        for (size_t i = 0; i < a.textures.size(); ++i) {
            const Texture &ta = a.textures[i], &tb = b.textures[i];
            std::string w = at("textures", i);
            d.same(w + ".name", ta.name, tb.name);
            d.same(w + ".kind", ta.kind, tb.kind);
            d.same(w + ".wrapS", ta.wrapS, tb.wrapS);
            d.same(w + ".wrapT", ta.wrapT, tb.wrapT);
            d.same(w + ".width", ta.width, tb.width);
            d.same(w + ".height", ta.height, tb.height);
            if (d.sameSize(w + ".mips", ta.mips.size(), tb.mips.size()))
                for (size_t l = 0; l < ta.mips.size(); ++l) {
                    // One difference per level (a count), not one per texel.
                    const auto &la = ta.mips[l], &lb = tb.mips[l];
                    size_t differing = la.size() == lb.size() ? 0 : std::max(la.size(), lb.size());
                    for (size_t k = 0; k < std::min(la.size(), lb.size()); ++k) differing += la[k] != lb[k];
                    d.same(at(w + ".mips", l) + " differing bytes", size_t(0), differing);
                }
        }
    if (d.sameSize("lights", a.lights.size(), b.lights.size()))
        for (size_t i = 0; i < a.lights.size(); ++i) {
            const Light &la = a.lights[i], &lb = b.lights[i];
            std::string w = at("lights", i);
            d.same(w + ".name", la.name, lb.name);
            d.same(w + ".type", la.type, lb.type);
            d.same(w + ".color", la.color, lb.color);
            d.same(w + ".intensity", la.intensity, lb.intensity);
            d.same(w + ".range", la.range, lb.range);
            d.same(w + ".innerConeAngle", la.innerConeAngle, lb.innerConeAngle);
            d.same(w + ".outerConeAngle", la.outerConeAngle, lb.outerConeAngle);
        }
    if (d.sameSize("cameras", a.cameras.size(), b.cameras.size()))
        for (size_t i = 0; i < a.cameras.size(); ++i) {
            const Camera &ca = a.cameras[i], &cb = b.cameras[i];
            std::string w = at("cameras", i);
            d.same(w + ".name", ca.name, cb.name);
            d.same(w + ".yfov", ca.yfov, cb.yfov);
            d.same(w + ".znear", ca.znear, cb.znear);
            d.same(w + ".zfar", ca.zfar, cb.zfar);
            d.same(w + ".aspectRatio", ca.aspectRatio, cb.aspectRatio);
        }
    if (d.sameSize("nodes", a.nodes.size(), b.nodes.size()))
        for (size_t i = 0; i < a.nodes.size(); ++i) {
            const Node &na = a.nodes[i], &nb = b.nodes[i];
            std::string w = at("nodes", i);
            d.same(w + ".name", na.name, nb.name);
            d.same(w + ".translation", na.translation, nb.translation);
            d.same(w + ".rotation", na.rotation, nb.rotation);
            d.same(w + ".scale", na.scale, nb.scale);
            d.same(w + ".has matrix", na.matrix.has_value(), nb.matrix.has_value());
            if (na.matrix && nb.matrix) d.same(w + ".matrix", *na.matrix, *nb.matrix);
            d.same(w + ".parent", na.parent, nb.parent);
            d.sameList(w + ".children", na.children, nb.children);
            d.same(w + ".mesh", na.mesh, nb.mesh);
            d.same(w + ".camera", na.camera, nb.camera);
            d.same(w + ".light", na.light, nb.light);
            d.same(w + ".localMatrix()", na.localMatrix(), nb.localMatrix());
        }
    d.sameList("roots", a.roots, b.roots);
    if (d.sameSize("animations", a.animations.size(), b.animations.size()))
        for (size_t i = 0; i < a.animations.size(); ++i) {
            const Animation &aa = a.animations[i], &ab = b.animations[i];
            std::string w = at("animations", i);
            d.same(w + ".name", aa.name, ab.name);
            d.same(w + ".duration", aa.duration, ab.duration);
            if (d.sameSize(w + ".channels", aa.channels.size(), ab.channels.size()))
                for (size_t c = 0; c < aa.channels.size(); ++c) {
                    const AnimationChannel &ca = aa.channels[c], &cb = ab.channels[c];
                    std::string wc = at(w + ".channels", c);
                    d.same(wc + ".node", ca.node, cb.node);
                    d.same(wc + ".path", ca.path, cb.path);
                    d.same(wc + ".interpolation", ca.interpolation, cb.interpolation);
                    d.sameList(wc + ".times", ca.times, cb.times);
                    d.sameList(wc + ".values", ca.values, cb.values);
                }
        }
    d.sameList("notes", a.notes, b.notes);

    // What the renderer sees: poses and instances at several times (inside keys, on keys, past a loop).
    for (float t : {0.0f, 0.3f, 1.0f, 1.7f, 2.5f, 3.99f, 4.0f, 5.25f, 9.1f}) {
        std::string w = "t=" + std::to_string(t);
        d.sameList(w + " evaluate()", a.evaluate(t), b.evaluate(t));
        std::vector<Instance> ia = a.instances(t), ib = b.instances(t);
        if (d.sameSize(w + " instances()", ia.size(), ib.size()))
            for (size_t k = 0; k < ia.size(); ++k) {
                std::string wk = at(w + " instances()", k);
                d.same(wk + ".node", ia[k].node, ib[k].node);
                d.same(wk + ".mesh", ia[k].mesh, ib[k].mesh);
                d.same(wk + ".world", ia[k].world, ib[k].world);
                d.same(wk + ".moving", ia[k].moving, ib[k].moving);
            }
    }
    compareAabb(d, "bounds()", a.bounds(), b.bounds());
    d.sameList("animatedNodes()", a.animatedNodes(), b.animatedNodes());
    return d;
}

fs::path outputDir(const std::string& name) {
    return test::freshOutputDir("gltf_export/" + name + "-" + std::to_string(getpid()));
}

// Writes `scene` to DIR/<scene.name>.glb (the loader names the scene after the file) and loads it back.
Scene roundTrip(const Scene& scene, const fs::path& dir) {
    fs::path file = dir / (scene.name + ".glb");
    writeGlb(scene, file);
    return loadGltf(file.string());
}

std::vector<uint8_t> readBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string builtinName(const ::testing::TestParamInfo<std::string>& info) {
    std::string name = info.param;  // a test name takes letters, digits and '_' only (cornell-turned)
    std::replace(name.begin(), name.end(), '-', '_');
    return name;
}

// ---- built-in scenes ----

class ExportBuiltin : public ::testing::TestWithParam<std::string> {};

TEST_P(ExportBuiltin, LoadsBackIdentically) {
    const Scene original = *makeBuiltinScene(GetParam());
    const Scene loaded = roundTrip(original, outputDir("roundtrip-" + GetParam()));
    SceneDiff diff = compareScenes(original, loaded);
    EXPECT_TRUE(diff.empty()) << diff.report();
}

TEST_P(ExportBuiltin, OutputIsDeterministic) {
    const Scene scene = *makeBuiltinScene(GetParam());
    fs::path dir = outputDir("deterministic-" + GetParam());
    writeGlb(scene, dir / "a.glb");
    writeGlb(scene, dir / "b.glb");
    std::vector<uint8_t> a = readBytes(dir / "a.glb"), b = readBytes(dir / "b.glb");
    EXPECT_GT(a.size(), 1000u);
    EXPECT_TRUE(a == b) << "two exports of the same scene differ";
}

// scenes/<name>.glb in the repository is the built-in scene (regenerate it with the command in the message).
TEST_P(ExportBuiltin, CommittedGlbMatchesTheBuiltinScene) {
    fs::path committed = fs::path(VCT_SCENES_DIR) / (GetParam() + ".glb");
    std::string regenerate = "regenerate it: build/vct export-scene --scene " + GetParam() +
                             " --out scenes/" + GetParam() + ".glb";
    ASSERT_TRUE(fs::exists(committed)) << committed << " is missing; " << regenerate;
    SceneDiff diff = compareScenes(*makeBuiltinScene(GetParam()), loadGltf(committed.string()));
    EXPECT_TRUE(diff.empty()) << committed << " is stale (" << regenerate << "):\n" << diff.report();
}

INSTANTIATE_TEST_SUITE_P(Builtin, ExportBuiltin, ::testing::ValuesIn(builtinSceneNames()), builtinName);

// ---- what the built-in scenes do not use ----

Texture testTexture(const std::string& name, TextureKind kind, uint32_t w, uint32_t h, bool alpha,
                    uint32_t seed) {
    Texture t;
    t.name = name;
    t.kind = kind;
    t.width = w;
    t.height = h;
    t.mips.emplace_back(size_t(w) * h * 4);
    for (size_t i = 0; i < t.mips[0].size(); ++i) {
        seed = seed * 1664525u + 1013904223u;
        t.mips[0][i] = (i % 4 == 3 && !alpha) ? 255 : uint8_t(seed >> 24);
    }
    buildMipChain(t);
    return t;
}

// A scene with a node hierarchy (TRS parent, matrix child), every texture slot (a texture shared by two
// materials, RGBA with alpha, odd sizes, every wrap mode), alpha mask and blend, double-sided, emission above
// 1, a point light with a range, a spot and a directional light, a camera with an aspect ratio, and step,
// linear and cubic-spline channels on translation, rotation and scale.
Scene featureScene() {
    Scene s;
    s.name = "features";
    s.textures.push_back(testTexture("base colour", TextureKind::Color, 5, 3, true, 1));
    s.textures[0].wrapS = TextureWrap::MirroredRepeat;
    s.textures[0].wrapT = TextureWrap::ClampToEdge;
    s.textures.push_back(testTexture("metal rough", TextureKind::Linear, 4, 4, false, 2));
    s.textures.push_back(testTexture("normals", TextureKind::Normal, 8, 2, false, 3));
    s.textures[2].wrapT = TextureWrap::MirroredRepeat;
    s.textures.push_back(testTexture("glow", TextureKind::Color, 3, 7, false, 4));
    s.textures.push_back(testTexture("occlusion", TextureKind::Linear, 1, 1, false, 5));

    Material a;
    a.name = "everything";
    a.baseColorFactor = {0.9f, 0.8f, 0.7f, 0.6f};
    a.metallicFactor = 0.3f;
    a.roughnessFactor = 0.45f;
    a.emissiveFactor = {3.0f, 0.5f, 0.1f};  // above 1: KHR_materials_emissive_strength
    a.normalScale = 0.7f;
    a.occlusionStrength = 0.35f;
    a.alphaMode = AlphaMode::Mask;
    a.alphaCutoff = 0.3f;
    a.doubleSided = true;
    a.baseColorTexture = 0;
    a.metallicRoughnessTexture = 1;
    a.normalTexture = 2;
    a.emissiveTexture = 3;
    a.occlusionTexture = 4;
    Material b;
    b.name = "glass";
    b.baseColorFactor = {0.2f, 0.3f, 0.4f, 0.25f};
    b.metallicFactor = 0.0f;
    b.roughnessFactor = 0.05f;
    b.emissiveFactor = {0.2f, 0.3f, 0.4f};
    b.alphaMode = AlphaMode::Blend;
    b.baseColorTexture = 0;  // shared with "everything"
    s.materials = {a, b};

    auto addPrimitive = [&s](std::vector<Vertex> verts, std::vector<uint32_t> idx, uint32_t material) {
        generateTangents(verts, idx);
        Primitive p;
        p.firstIndex = uint32_t(s.indices.size());
        p.indexCount = uint32_t(idx.size());
        p.vertexOffset = int32_t(s.vertices.size());
        p.vertexCount = uint32_t(verts.size());
        p.material = material;
        for (const Vertex& v : verts) p.bounds.extend(v.position);
        s.vertices.insert(s.vertices.end(), verts.begin(), verts.end());
        s.indices.insert(s.indices.end(), idx.begin(), idx.end());
        s.primitives.push_back(p);
        return uint32_t(s.primitives.size() - 1);
    };
    auto vertex = [](glm::vec3 p, glm::vec3 n, glm::vec2 uv) {
        Vertex v;
        v.position = p;
        v.normal = glm::normalize(n);
        v.uv = uv;
        return v;
    };
    uint32_t tri = addPrimitive({vertex({0, 0, 0}, {0.1f, 0.2f, 1}, {0.1f, 0.9f}),
                                 vertex({1.3f, 0.1f, -0.2f}, {0, 0.3f, 1}, {1.7f, 0.8f}),
                                 vertex({0.2f, 1.1f, 0.3f}, {-0.2f, 0, 1}, {0.3f, -0.4f})},
                                {0, 1, 2}, 0);
    uint32_t quad =
        addPrimitive({vertex({-1, 0, 0}, {0, 1, 0}, {0, 0}), vertex({1, 0, 0}, {0, 1, 0}, {1, 0}),
                      vertex({1, 0, -1}, {0, 1, 0}, {1, 1}), vertex({-1, 0, -1}, {0, 1, 0}, {0, 1})},
                     {0, 1, 2, 0, 2, 3}, 1);
    uint32_t quad2 =
        addPrimitive({vertex({-1, 0, 0}, {0, 0, 1}, {0, 0}), vertex({1, 0, 0}, {0, 0, 1}, {1, 0}),
                      vertex({1, 1, 0}, {0, 0, 1}, {1, 1}), vertex({-1, 1, 0}, {0, 0, 1}, {0, 1})},
                     {0, 1, 2, 0, 2, 3}, 0);
    s.meshes.push_back(Mesh{"two parts", {tri, quad}});
    s.meshes.push_back(Mesh{"wall", {quad2}});  // (a primitive shared by two meshes would come back twice)

    Light point;
    point.name = "bulb";
    point.type = LightType::Point;
    point.color = {1.0f, 0.5f, 0.25f};
    point.intensity = 12.5f;
    point.range = 7.5f;
    Light spot;
    spot.name = "spot";
    spot.type = LightType::Spot;
    spot.intensity = 3.0f;
    spot.innerConeAngle = 0.1f;
    spot.outerConeAngle = 0.55f;
    Light sun;
    sun.name = "sun";
    sun.intensity = 2.0f;
    s.lights = {point, spot, sun};
    Camera cam;
    cam.name = "wide";
    cam.yfov = 1.1f;
    cam.znear = 0.01f;
    cam.zfar = 250.0f;
    cam.aspectRatio = 1.5f;
    s.cameras = {cam};

    auto node = [&s](const std::string& name, int parent) {
        Node n;
        n.name = name;
        n.parent = parent;
        s.nodes.push_back(n);
        int index = int(s.nodes.size()) - 1;
        if (parent >= 0)
            s.nodes[size_t(parent)].children.push_back(index);
        else
            s.roots.push_back(index);
        return index;
    };
    int root = node("root", -1);
    s.nodes[size_t(root)].translation = {0.5f, -1.0f, 2.0f};
    s.nodes[size_t(root)].rotation = glm::quat(0.5f, 0.5f, -0.5f, 0.5f);  // exactly unit
    s.nodes[size_t(root)].scale = {2.0f, 1.0f, 0.5f};
    int withMatrix = node("matrix child", root);
    glm::mat4 m(1.0f);
    m[0] = {0.0f, 1.0f, 0.0f, 0.0f};
    m[1] = {-1.5f, 0.0f, 0.0f, 0.0f};
    m[2] = {0.0f, 0.0f, 0.75f, 0.0f};
    m[3] = {0.25f, 0.125f, -3.0f, 1.0f};
    s.nodes[size_t(withMatrix)].matrix = m;
    s.nodes[size_t(withMatrix)].mesh = 0;
    int bulb = node("bulb", withMatrix);
    s.nodes[size_t(bulb)].light = 0;
    s.nodes[size_t(bulb)].translation = {0.0f, 2.0f, 0.0f};
    int spotNode = node("spot", -1);
    s.nodes[size_t(spotNode)].light = 1;
    s.nodes[size_t(spotNode)].rotation = glm::quat(0.0f, 1.0f, 0.0f, 0.0f);
    int sunNode = node("sun", root);
    s.nodes[size_t(sunNode)].light = 2;
    int camNode = node("camera", -1);
    s.nodes[size_t(camNode)].camera = 0;
    s.nodes[size_t(camNode)].translation = {0.0f, 1.0f, 5.0f};
    int spinner = node("spinner", root);
    s.nodes[size_t(spinner)].mesh = 1;
    int leaf = node("spinner child", spinner);
    s.nodes[size_t(leaf)].mesh = 0;
    s.nodes[size_t(leaf)].scale = {0.5f, 0.5f, 0.5f};
    int tilted = node("tilted", leaf);  // a rotation glm makes slightly off unit length
    s.nodes[size_t(tilted)].mesh = 1;
    s.nodes[size_t(tilted)].rotation = glm::angleAxis(0.7f, glm::normalize(glm::vec3(1.0f, 2.0f, 3.0f)));

    AnimationChannel step{spinner, AnimationPath::Translation, Interpolation::Step, {0.0f, 0.5f, 2.0f}, {}};
    step.values = {{0, 0, 0, 0}, {1, 2, 3, 0}, {-1, 0.5f, 0.25f, 0}};
    AnimationChannel cubic{
        spinner, AnimationPath::Scale, Interpolation::CubicSpline, {0.25f, 1.5f, 3.0f}, {}};
    cubic.values = {{0, 0, 0, 0},  {1, 1, 1, 0},    {0.5f, 0, -0.5f, 0},  // in, value, out
                    {1, 1, 1, 0},  {2, 1.5f, 1, 0}, {0, 0.25f, 0, 0},     //
                    {-1, 0, 0, 0}, {1, 2, 3, 0},    {0, 0, 0, 0}};
    AnimationChannel spin{spinner, AnimationPath::Rotation, Interpolation::Linear, {0.0f, 1.0f, 2.0f}, {}};
    spin.values = {{0, 0, 0, 1}, {0, 1, 0, 0}, {0.5f, 0.5f, 0.5f, 0.5f}};
    AnimationChannel cubicRotation{
        leaf, AnimationPath::Rotation, Interpolation::CubicSpline, {0.0f, 2.0f}, {}};
    cubicRotation.values = {{0, 0, 0, 0},     {0, 0, 0, 1}, {0, 0.5f, 0, 0},
                            {0, -0.5f, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 0}};
    s.animations.push_back(Animation{"motion", {step, cubic, spin}, 3.0f});
    s.animations.push_back(Animation{"tumble", {cubicRotation}, 2.0f});
    s.validate();
    return s;
}

TEST(ExportFeatures, LoadsBackIdentically) {
    const Scene original = featureScene();
    const Scene loaded = roundTrip(original, outputDir("features"));
    SceneDiff diff = compareScenes(original, loaded);
    EXPECT_TRUE(diff.empty()) << diff.report();
}

TEST(ExportFeatures, UnwritablePathIsAnError) {
    fs::path dir = outputDir("unwritable");
    test::writeTextFile(dir / "file", "not a directory");
    try {
        writeGlb(featureScene(), dir / "file" / "scene.glb");
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("cannot write"), std::string::npos) << e.what();
    }
}

// ---- the command ----

TEST(ExportCommand, WritesALoadableFile) {
    fs::path dir = outputDir("command");
    fs::path out = dir / "sub" / "plane.glb";  // the directory is created
    test::RunResult run = test::runVct({"export-scene", "--scene", "plane", "--out", out.string()});
    ASSERT_TRUE(run.exited() && run.exitCode == 0) << run.describe();
    EXPECT_NE(run.out.find("wrote"), std::string::npos) << run.out;
    SceneDiff diff = compareScenes(*makeBuiltinScene("plane"), loadGltf(out.string()));
    EXPECT_TRUE(diff.empty()) << diff.report();
}

TEST(ExportCommand, BadArgumentsFailWithOneLine) {
    fs::path dir = outputDir("command-errors");
    test::writeTextFile(dir / "file", "not a directory");
    struct Case {
        std::vector<std::string> args;
        int exitCode;
        std::string message;
    };
    const std::vector<Case> cases = {
        {{"export-scene"}, 2, "--out FILE.glb is required"},
        {{"export-scene", "--out", (dir / "x.gltf").string()}, 2, "expected a .glb file name"},
        {{"export-scene", "--out", (dir / "x.glb").string(), "--frobnicate"}, 2, "unknown flag"},
        {{"export-scene", "--scene", "no-such-scene", "--out", (dir / "x.glb").string()}, 1, "unknown scene"},
        {{"export-scene", "--out", (dir / "file" / "x.glb").string()}, 1, "cannot"},
    };
    for (const Case& c : cases) {
        test::RunResult run = test::runVct(c.args);
        ASSERT_TRUE(run.exited()) << run.describe();
        EXPECT_EQ(run.exitCode, c.exitCode) << run.describe();
        EXPECT_NE(run.err.find(c.message), std::string::npos) << run.describe();
        EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.describe();
    }
    test::RunResult help = test::runVct({"export-scene", "--help"});
    EXPECT_EQ(help.exitCode, 0) << help.describe();
    EXPECT_NE(help.out.find("--out"), std::string::npos) << help.out;
}

// ---- images as loaded (issue 20): not re-encoded unless asked ----

// The bytes of image `index` of a .glb written by the writer (its bufferView in the BIN chunk).
std::vector<uint8_t> glbImage(const fs::path& path, size_t index) {
    const std::vector<uint8_t> bytes = readBytes(path);
    auto u32 = [&](size_t at) {
        uint32_t v = 0;
        std::memcpy(&v, &bytes[at], 4);
        return v;
    };
    const uint32_t jsonLength = u32(12);
    const auto doc = nlohmann::json::parse(bytes.begin() + 20, bytes.begin() + 20 + jsonLength);
    const size_t bin = 20 + jsonLength + 8;
    const auto& view = doc["bufferViews"][doc["images"][index]["bufferView"].get<size_t>()];
    const size_t offset = bin + view.value("byteOffset", size_t(0)), length = view["byteLength"];
    return {bytes.begin() + std::ptrdiff_t(offset), bytes.begin() + std::ptrdiff_t(offset + length)};
}

// A 4x4 PNG with a text chunk after its header: decoders skip the chunk and no encoder writes it, so the file
// comes out of an export unchanged only if its bytes were copied.
std::vector<uint8_t> pngWithTextChunk(const fs::path& scratch) {
    std::vector<uint8_t> texels(4 * 4 * 4);
    for (size_t i = 0; i < texels.size(); ++i) texels[i] = uint8_t(i * 37 + 11);
    writePng(scratch, 4, 4, texels);
    std::vector<uint8_t> png = readBytes(scratch);
    std::vector<uint8_t> chunk = {0, 0, 0, 0, 't', 'E', 'X', 't'};
    const std::string text = std::string("Comment") + '\0' + "kept as loaded";
    chunk.insert(chunk.end(), text.begin(), text.end());
    chunk[3] = uint8_t(text.size());
    const uint32_t crc = uint32_t(::crc32(0, chunk.data() + 4, uInt(chunk.size() - 4)));
    for (int k = 3; k >= 0; --k) chunk.push_back(uint8_t(crc >> (8 * k)));
    png.insert(png.begin() + 33, chunk.begin(), chunk.end());  // after the signature and IHDR (8 + 25 bytes)
    return png;
}

TEST(ExportCommand, KeepsImageBytesAsLoadedUnlessAskedToReencode) {
    const fs::path dir = outputDir("image-bytes");
    const std::vector<uint8_t> png = pngWithTextChunk(dir / "plain.png");
    hostile::GltfScene s = hostile::triangleScene();
    s.texture = false;
    const size_t offset = s.bin.size();
    s.bin.insert(s.bin.end(), png.begin(), png.end());
    while (s.bin.size() % 4) s.bin.push_back(0);
    s.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", png.size()}});
    s.doc["buffers"][0]["byteLength"] = s.bin.size();
    s.doc["images"][0] = {{"bufferView", s.doc["bufferViews"].size() - 1}, {"mimeType", "image/png"}};
    const fs::path input = hostile::writeGlb(dir, s);
    const Scene loaded = loadGltf(input.string());
    ASSERT_EQ(loaded.textures.size(), 1u);
    for (bool reencode : {false, true}) {
        const fs::path out = dir / (reencode ? "reencoded.glb" : "kept.glb");
        std::vector<std::string> args = {"export-scene", "--scene", input.string(), "--out", out.string()};
        if (reencode) args.push_back("--reencode-images");
        const test::RunResult run = test::runVct(args);
        ASSERT_TRUE(run.exited() && run.exitCode == 0) << run.describe();
        const std::vector<uint8_t> image = glbImage(out, 0);
        if (reencode)
            EXPECT_NE(image, png) << "--reencode-images wrote the bytes as loaded";
        else
            EXPECT_EQ(image, png) << "the PNG's bytes changed (" << image.size() << " vs " << png.size()
                                  << ")";
        // Either way the texels are the same.
        const Scene back = loadGltf(out.string());
        ASSERT_EQ(back.textures.size(), 1u);
        EXPECT_EQ(back.textures[0].mips, loaded.textures[0].mips) << (reencode ? "reencoded" : "kept");
    }
}

// DamagedHelmet (five JPEGs, 3.8 MB as files) exports at about its own size, and loads back the same.
TEST(ExportCommand, DamagedHelmetKeepsItsJpegs) {
    const fs::path model = fs::path(VCT_SHARED_SCENES) / "DamagedHelmet" / "glTF" / "DamagedHelmet.gltf";
    if (!fs::exists(model)) GTEST_SKIP() << "no " << model << " (shared scenes not available)";
    uintmax_t source = 0;
    for (const fs::directory_entry& e : fs::directory_iterator(model.parent_path())) source += e.file_size();
    const fs::path out = outputDir("helmet") / "DamagedHelmet.glb";
    const test::RunResult run =
        test::runVct({"export-scene", "--scene", model.string(), "--out", out.string()});
    ASSERT_TRUE(run.exited() && run.exitCode == 0) << run.describe();
    const uintmax_t exported = fs::file_size(out);
    std::printf("DamagedHelmet: %ju bytes as files, %ju exported\n", source, exported);
    // Measured 4 008 164 of 3 776 265 (1.061: the tangents the loader generated are written too); 22.4 MB
    // when the JPEGs were re-encoded as PNG.
    EXPECT_LE(double(exported), 1.07 * double(source));
    Scene original = loadGltf(model.string()), back = loadGltf(out.string());
    // The default camera and light the loader added are in the file now: the notes saying so are not.
    original.notes.clear();
    back.notes.clear();
    SceneDiff diff = compareScenes(original, back);
    EXPECT_TRUE(diff.empty()) << diff.report();
}

// ---- rendering: the built-in scene and the committed .glb give the same image ----

class RenderExported : public ::testing::TestWithParam<std::string> {};

TEST_P(RenderExported, SameFinalExrAsTheBuiltinScene) {
    fs::path committed = fs::path(VCT_SCENES_DIR) / (GetParam() + ".glb");
    ASSERT_TRUE(fs::exists(committed)) << committed;
    fs::path dir = outputDir("render-" + GetParam());
    auto render = [&](const std::string& scene, const std::string& sub) {
        test::RunResult run = test::runVct({"render", "--scene", scene, "--size", "64x36", "--frames", "2",
                                            "--voxels", "32", "--validate", "--out", (dir / sub).string()});
        EXPECT_TRUE(run.exited() && run.exitCode == 0) << run.describe();
        return readExr(dir / sub / "final.exr");
    };
    ImageRgba32f builtin = render(GetParam(), "builtin");
    ImageRgba32f loaded = render(committed.string(), "glb");
    ASSERT_EQ(builtin.width, 64u);
    ASSERT_EQ(builtin.height, 36u);
    ASSERT_EQ(loaded.width, builtin.width);
    ASSERT_EQ(loaded.height, builtin.height);
    float brightest = 0.0f;
    for (size_t i = 0; i < builtin.pixels.size(); i += 4)
        brightest = std::max(
            brightest, test::luminance(builtin.pixels[i], builtin.pixels[i + 1], builtin.pixels[i + 2]));
    EXPECT_GT(brightest, 0.05f) << "the built-in scene rendered black";
    size_t differing = 0;
    for (size_t i = 0; i < builtin.pixels.size(); ++i)
        differing += std::memcmp(&builtin.pixels[i], &loaded.pixels[i], sizeof(float)) != 0;
    EXPECT_EQ(differing, 0u) << "final.exr values that differ (bit patterns), of " << builtin.pixels.size();
}

INSTANTIATE_TEST_SUITE_P(Builtin, RenderExported, ::testing::ValuesIn(builtinSceneNames()), builtinName);

}  // namespace
}  // namespace vct
