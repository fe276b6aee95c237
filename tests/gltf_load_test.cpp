// glTF import: the sample models in shared/scenes, small files written here for every supported variant,
// and broken files that must fail with a one-line vct::Error naming the file and the problem.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "io/image_io.h"
#include "scene/builtin_scenes.h"
#include "scene/gltf_loader.h"
#include "scene/tangents.h"
#include "test_util.h"

namespace vct {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

fs::path outputDir() {
    fs::path dir = fs::path(VCT_TEST_OUTPUT) / "gltf_load";
    fs::create_directories(dir);
    return dir;
}

void writeBytes(const fs::path& path, const std::vector<uint8_t>& bytes) {
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}
void writeText(const fs::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

template <class T>
void append(std::vector<uint8_t>& bytes, std::initializer_list<T> values) {
    for (T v : values) {
        uint8_t raw[sizeof(T)];
        std::memcpy(raw, &v, sizeof(T));
        bytes.insert(bytes.end(), raw, raw + sizeof(T));
    }
}

// Binary layout of the test triangle: 3 float positions (0..35), 3 float UV pairs (36..59),
// 3 uint16 indices (60..65), padding, a sparse override (uint16 index at 68, vec3 at 72..83),
// then uint8 indices (84..86) and normalized uint8 UVs (88..93) for the component-type test.
std::vector<uint8_t> triangleBin(float x1 = 1.0f, uint16_t lastIndex = 2) {
    std::vector<uint8_t> b;
    append<float>(b, {0, 0, 0, x1, 0, 0, 0, 1, 0});
    append<float>(b, {0, 1, 1, 1, 0, 0});
    append<uint16_t>(b, {0, 1, lastIndex, 0});
    append<uint16_t>(b, {2, 0});
    append<float>(b, {0, 2, 0});
    append<uint8_t>(b, {0, 1, 2, 0, 0, 0, 255, 0, 0, 255, 0, 0});
    return b;
}

json triangleGltf(const std::string& bufferUri, size_t byteLength) {
    json buffer = {{"byteLength", byteLength}};
    if (!bufferUri.empty()) buffer["uri"] = bufferUri;
    return {
        {"asset", {{"version", "2.0"}}},
        {"scene", 0},
        {"scenes", {{{"nodes", {0}}}}},
        {"nodes", {{{"name", "tri"}, {"mesh", 0}}}},
        {"meshes",
         {{{"name", "Tri"},
           {"primitives", {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}}, {"indices", 2}}}}}}},
        {"buffers", {buffer}},
        {"bufferViews",
         {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 36}},
          {{"buffer", 0}, {"byteOffset", 36}, {"byteLength", 24}},
          {{"buffer", 0}, {"byteOffset", 60}, {"byteLength", 6}},
          {{"buffer", 0}, {"byteOffset", 68}, {"byteLength", 2}},
          {{"buffer", 0}, {"byteOffset", 72}, {"byteLength", 12}},
          {{"buffer", 0}, {"byteOffset", 84}, {"byteLength", 3}},
          {{"buffer", 0}, {"byteOffset", 88}, {"byteLength", 6}}}},
        {"accessors",
         {{{"bufferView", 0},
           {"componentType", 5126},
           {"count", 3},
           {"type", "VEC3"},
           {"min", {0, 0, 0}},
           {"max", {1, 1, 0}}},
          {{"bufferView", 1}, {"componentType", 5126}, {"count", 3}, {"type", "VEC2"}},
          {{"bufferView", 2}, {"componentType", 5123}, {"count", 3}, {"type", "SCALAR"}}}},
    };
}

fs::path writeTriangle(const std::string& name, const json& gltf, const std::vector<uint8_t>& bin) {
    fs::path dir = outputDir();
    writeBytes(dir / (name + ".bin"), bin);
    fs::path path = dir / (name + ".gltf");
    writeText(path, gltf.dump(2));
    return path;
}

fs::path validTriangle(const std::string& name, const std::function<void(json&)>& edit = {},
                       const std::vector<uint8_t>& bin = triangleBin()) {
    json g = triangleGltf(name + ".bin", bin.size());
    if (edit) edit(g);
    return writeTriangle(name, g, bin);
}

// Loading must throw a vct::Error whose message is one line, names the file and contains `needle`.
void expectLoadError(const fs::path& path, const std::string& needle) {
    try {
        loadScene(path.string());
        FAIL() << "loading " << path << " should have failed with '" << needle << "'";
    } catch (const Error& e) {
        std::string what = e.what();
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        EXPECT_NE(what.find(path.filename().string()), std::string::npos) << what;
        EXPECT_NE(what.find(needle), std::string::npos) << what;
    }
}

TEST(GltfLoad, TriangleWithExternalBuffer) {
    Scene s = loadScene(validTriangle("triangle").string());
    ASSERT_EQ(s.meshes.size(), 1u);
    EXPECT_EQ(s.indices.size(), 3u);
    ASSERT_EQ(s.vertices.size(), 3u);
    for (const Vertex& v : s.vertices) EXPECT_NEAR(v.normal.z, 1.0f, 1e-6f);  // flat normals were generated
    EXPECT_EQ(s.materials.size(), 1u);                                        // the default material
    EXPECT_EQ(s.cameras.size(), 1u);
    EXPECT_EQ(s.lights.size(), 1u);
    EXPECT_EQ(s.notes.size(), 2u);  // default camera and light
    EXPECT_EQ(s.instances(0.0f).size(), 1u);
}

TEST(GltfLoad, EmbeddedBase64AndGlb) {
    std::vector<uint8_t> bin = triangleBin();
    static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string b64;
    for (size_t i = 0; i < bin.size(); i += 3) {
        uint32_t n = uint32_t(bin[i]) << 16 | (i + 1 < bin.size() ? uint32_t(bin[i + 1]) << 8 : 0) |
                     (i + 2 < bin.size() ? bin[i + 2] : 0);
        for (size_t k = 0; k < 4; ++k) b64 += i + k <= bin.size() ? digits[(n >> (18 - 6 * k)) & 63] : '=';
    }
    json g = triangleGltf("data:application/octet-stream;base64," + b64, bin.size());
    fs::path embedded = outputDir() / "embedded.gltf";
    writeText(embedded, g.dump());
    EXPECT_EQ(loadScene(embedded.string()).vertices.size(), 3u);

    // GLB: 12-byte header, a JSON chunk and a BIN chunk, each padded to 4 bytes.
    std::string text = triangleGltf("", bin.size()).dump();
    while (text.size() % 4) text += ' ';
    std::vector<uint8_t> glb;
    append<uint32_t>(glb, {0x46546C67u, 2u, uint32_t(12 + 8 + text.size() + 8 + bin.size())});
    append<uint32_t>(glb, {uint32_t(text.size()), 0x4E4F534Au});
    glb.insert(glb.end(), text.begin(), text.end());
    append<uint32_t>(glb, {uint32_t(bin.size()), 0x004E4942u});
    glb.insert(glb.end(), bin.begin(), bin.end());
    fs::path glbPath = outputDir() / "triangle.glb";
    writeBytes(glbPath, glb);
    EXPECT_EQ(loadScene(glbPath.string()).vertices.size(), 3u);
}

TEST(GltfLoad, SparseStripsAndComponentTypes) {
    // Sparse accessor: vertex 2 is moved from (0,1,0) to (0,2,0).
    Scene sparse = loadScene(validTriangle("sparse", [](json& g) {
                                 g["accessors"][0]["sparse"] = {
                                     {"count", 1},
                                     {"indices", {{"bufferView", 3}, {"componentType", 5123}}},
                                     {"values", {{"bufferView", 4}}}};
                                 g["accessors"][0]["max"] = {1, 2, 0};
                             }).string());
    EXPECT_FLOAT_EQ(sparse.vertices[2].position.y, 2.0f);

    // Non-indexed triangle fan over 3 vertices: indices are generated and the winding stays
    // counter-clockwise (flat normals along +Z).
    Scene fan = loadScene(validTriangle("fan", [](json& g) {
                              g["meshes"][0]["primitives"][0].erase("indices");
                              g["meshes"][0]["primitives"][0]["mode"] = 6;
                          }).string());
    ASSERT_EQ(fan.indices.size(), 3u);
    for (const Vertex& v : fan.vertices) EXPECT_NEAR(v.normal.z, 1.0f, 1e-6f);

    // uint8 indices and normalized uint8 texture coordinates.
    Scene bytes =
        loadScene(validTriangle("bytes", [](json& g) {
                      g["accessors"][2] = {
                          {"bufferView", 5}, {"componentType", 5121}, {"count", 3}, {"type", "SCALAR"}};
                      g["accessors"][1] = {{"bufferView", 6},
                                           {"componentType", 5121},
                                           {"normalized", true},
                                           {"count", 3},
                                           {"type", "VEC2"}};
                  }).string());
    ASSERT_EQ(bytes.indices.size(), 3u);
    EXPECT_EQ(bytes.indices[2], 2u);
    EXPECT_FLOAT_EQ(bytes.vertices[1].uv.x, 1.0f);
    EXPECT_FLOAT_EQ(bytes.vertices[2].uv.y, 1.0f);
}

TEST(GltfLoad, CamerasLightsMaterialsAndNotes) {
    Scene s = loadScene(
        validTriangle("features", [](json& g) {
            g["extensionsUsed"] = {"KHR_lights_punctual", "KHR_materials_emissive_strength"};
            g["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", "spot"},
                                                                 {"intensity", 25.0},
                                                                 {"color", {1, 0.5, 0.25}},
                                                                 {"spot", {{"outerConeAngle", 0.5}}}}};
            g["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.7}, {"znear", 0.1}}}}};
            g["nodes"].push_back({{"camera", 0}, {"translation", {0, 0, 5}}});
            g["nodes"].push_back(
                {{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}, {"rotation", {0, 0, 0, 1}}});
            g["scenes"][0]["nodes"] = {0, 1, 2};
            g["materials"] = {
                {{"name", "glow"},
                 {"emissiveFactor", {1, 1, 1}},
                 {"alphaMode", "MASK"},
                 {"doubleSided", true},
                 {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4.0}}}}},
                 {"pbrMetallicRoughness", {{"metallicFactor", 0.0}, {"roughnessFactor", 0.3}}}}};
            g["meshes"][0]["primitives"][0]["material"] = 0;
            g["skins"] = {{{"joints", {0}}}};
        }).string());
    ASSERT_EQ(s.lights.size(), 1u);
    EXPECT_EQ(s.lights[0].type, LightType::Spot);
    EXPECT_FLOAT_EQ(s.lights[0].intensity, 25.0f);
    EXPECT_FLOAT_EQ(s.lights[0].outerConeAngle, 0.5f);
    ASSERT_EQ(s.cameras.size(), 1u);
    EXPECT_FLOAT_EQ(s.cameras[0].yfov, 0.7f);
    EXPECT_GT(s.cameras[0].zfar, s.cameras[0].znear);  // infinite far plane made finite
    ASSERT_EQ(s.materials.size(), 1u);
    EXPECT_FLOAT_EQ(s.materials[0].emissiveFactor.x, 4.0f);
    EXPECT_EQ(s.materials[0].alphaMode, AlphaMode::Mask);
    EXPECT_TRUE(s.materials[0].doubleSided);
    EXPECT_FLOAT_EQ(s.materials[0].roughnessFactor, 0.3f);
    // Skins load since issue 20 (was the note "skins are not supported: rendering the bind pose"): one skin of
    // one joint, identity inverse bind matrices, and nothing to note.
    ASSERT_EQ(s.skins.size(), 1u);
    EXPECT_EQ(s.skins[0].inverseBindMatrices, std::vector<glm::mat4>{glm::mat4(1.0f)});
    EXPECT_TRUE(s.notes.empty());

    Scene t = loadScene(validTriangle("texture_transform", [](json& g) {
                            g["extensionsUsed"] = {"KHR_texture_transform"};
                        }).string());
    EXPECT_NE(std::find(t.notes.begin(), t.notes.end(),
                        "extension KHR_texture_transform is not supported: ignored"),
              t.notes.end());
}

TEST(GltfLoad, TexturesAreConvertedDuplicatedPerRoleAndMipmapped) {
    std::vector<uint8_t> rgba(4 * 2 * 4);
    for (size_t i = 0; i < rgba.size(); ++i) rgba[i] = uint8_t(i * 7);
    writePng(outputDir() / "tex.png", 4, 2, rgba);
    Scene s = loadScene(validTriangle("textured", [](json& g) {
                            g["images"] = {{{"uri", "tex.png"}}};
                            g["samplers"] = {{{"wrapS", 33071}, {"wrapT", 33648}}};
                            g["textures"] = {{{"source", 0}, {"sampler", 0}}};
                            g["materials"] = {{{"pbrMetallicRoughness",
                                                {{"baseColorTexture", {{"index", 0}}},
                                                 {"metallicRoughnessTexture", {{"index", 0}}}}},
                                               {"occlusionTexture", {{"index", 0}}},
                                               {"normalTexture", {{"index", 0}, {"scale", 0.5}}}}};
                            g["meshes"][0]["primitives"][0]["material"] = 0;
                        }).string());
    ASSERT_EQ(s.textures.size(), 3u);  // one per kind: Color, Linear (shared by MR and occlusion), Normal
    const Material& m = s.materials[0];
    EXPECT_EQ(m.metallicRoughnessTexture, m.occlusionTexture);
    EXPECT_NE(m.baseColorTexture, m.normalTexture);
    EXPECT_FLOAT_EQ(m.normalScale, 0.5f);
    const Texture& t = s.textures[size_t(m.normalTexture)];
    EXPECT_EQ(t.kind, TextureKind::Normal);
    EXPECT_EQ(t.wrapS, TextureWrap::ClampToEdge);
    EXPECT_EQ(t.wrapT, TextureWrap::MirroredRepeat);
    EXPECT_EQ(t.mips.size(), 3u);  // 4x2, 2x1, 1x1
    EXPECT_EQ(t.mips[0], rgba);
}

TEST(GltfLoad, BrokenFilesFailWithOneLine) {
    expectLoadError(outputDir() / "does-not-exist.gltf", "no such file");

    fs::path malformed = outputDir() / "malformed.gltf";
    writeText(malformed, "{ \"asset\": { \"version\": \"2.0\" }, \"nodes\": [ {\n\n");
    expectLoadError(malformed, "malformed.gltf");

    std::vector<uint8_t> truncated = triangleBin();
    truncated.resize(40);
    expectLoadError(
        writeTriangle("truncated", triangleGltf("truncated.bin", triangleBin().size()), truncated),
        "truncated.bin");

    json missingBin = triangleGltf("nowhere.bin", triangleBin().size());
    fs::path missingBinPath = outputDir() / "missing_bin.gltf";
    writeText(missingBinPath, missingBin.dump());
    expectLoadError(missingBinPath, "nowhere.bin");

    expectLoadError(validTriangle("nan", {}, triangleBin(std::numeric_limits<float>::quiet_NaN())),
                    "mesh 'Tri' primitive 0: vertex 1 has a non-finite position");

    expectLoadError(validTriangle("badindex", {}, triangleBin(1.0f, 7)), "index 2 (= 7) is out of range");

    expectLoadError(validTriangle("lines", [](json& g) { g["meshes"][0]["primitives"][0]["mode"] = 1; }),
                    "unsupported primitive mode 1");

    expectLoadError(
        validTriangle(
            "noimage",
            [](json& g) {
                g["images"] = {{{"uri", "missing.png"}}};
                g["textures"] = {{{"source", 0}}};
                g["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
                g["meshes"][0]["primitives"][0]["material"] = 0;
            }),
        "missing.png");

    expectLoadError(
        validTriangle("draco", [](json& g) { g["extensionsRequired"] = {"KHR_draco_mesh_compression"}; }),
        "requires the unsupported extension KHR_draco_mesh_compression");

    expectLoadError(validTriangle("nonodes", [](json& g) { g["scenes"][0]["nodes"] = json::array(); }),
                    "no mesh instances");
}

// ---- the sample models in shared/scenes ----

using test::sharedModel;

TEST(GltfSamples, DamagedHelmet) {
    VCT_REQUIRE_SHARED("DamagedHelmet");
    Scene s = loadScene(sharedModel("DamagedHelmet").string());
    EXPECT_EQ(s.meshes.size(), 1u);
    EXPECT_GT(s.vertices.size(), 10000u);
    EXPECT_EQ(s.textures.size(), 5u);  // albedo, metal-roughness, normal, emissive, occlusion
    ASSERT_GE(s.materials.size(), 1u);
    const Material& m = s.materials[0];
    ASSERT_GE(m.normalTexture, 0);
    EXPECT_EQ(s.textures[size_t(m.normalTexture)].kind, TextureKind::Normal);
    EXPECT_EQ(s.textures[size_t(m.baseColorTexture)].kind, TextureKind::Color);
    EXPECT_EQ(s.textures[size_t(m.metallicRoughnessTexture)].kind, TextureKind::Linear);
    EXPECT_EQ(s.textures[size_t(m.normalTexture)].mips.size(), 12u);  // 2048² → 1²
    EXPECT_EQ(s.cameras.size(), 1u);                                  // default
    EXPECT_EQ(s.lights.size(), 1u);                                   // default
    for (const Vertex& v : s.vertices) ASSERT_NEAR(glm::length(glm::vec3(v.tangent)), 1.0f, 1e-3f);
}

TEST(GltfSamples, MetalRoughSpheresNoTextures) {
    VCT_REQUIRE_SHARED("MetalRoughSpheresNoTextures");
    Scene s = loadScene(sharedModel("MetalRoughSpheresNoTextures").string());
    EXPECT_GT(s.instances(0.0f).size(), 50u);
    EXPECT_GT(s.materials.size(), 50u);
    EXPECT_TRUE(s.textures.empty());
    EXPECT_FALSE(s.bounds().empty());
}

TEST(GltfSamples, BoxAnimated) {
    VCT_REQUIRE_SHARED("BoxAnimated");
    Scene s = loadScene(sharedModel("BoxAnimated").string());
    ASSERT_EQ(s.animations.size(), 1u);
    EXPECT_GT(s.animations[0].duration, 0.0f);
    std::vector<Instance> a = s.instances(0.0f), b = s.instances(0.5f * s.animations[0].duration);
    bool anyMoved = false;
    for (size_t i = 0; i < a.size(); ++i) anyMoved |= a[i].moving && a[i].world != b[i].world;
    EXPECT_TRUE(anyMoved);
}

TEST(GltfSamples, NormalTangentMirrorTestTangentsMatchOurGenerator) {
    VCT_REQUIRE_SHARED("NormalTangentMirrorTest");
    Scene s = loadScene(sharedModel("NormalTangentMirrorTest").string());
    ASSERT_EQ(s.primitives.size(), 1u);
    const Primitive& p = s.primitives[0];
    std::vector<Vertex> file(s.vertices.begin() + p.vertexOffset,
                             s.vertices.begin() + p.vertexOffset + p.vertexCount);
    std::vector<Vertex> ours = file;
    std::span<const uint32_t> indices(s.indices.data() + p.firstIndex, p.indexCount);
    generateTangents(ours, indices);
    // The file's tangents come from the exporter (MikkTSpace); ours must agree on the sign convention
    // (mirrored halves have w = -1) and on the direction.
    size_t sameSign = 0, sameDirection = 0, mirrored = 0;
    for (size_t i = 0; i < file.size(); ++i) {
        sameSign += file[i].tangent.w == ours[i].tangent.w;
        sameDirection += glm::dot(glm::vec3(file[i].tangent), glm::vec3(ours[i].tangent)) > 0.9f;
        mirrored += file[i].tangent.w < 0.0f;
    }
    EXPECT_GT(mirrored, 0u);
    EXPECT_GT(double(sameSign) / double(file.size()), 0.95);
    EXPECT_GT(double(sameDirection) / double(file.size()), 0.9);
}

}  // namespace
}  // namespace vct
