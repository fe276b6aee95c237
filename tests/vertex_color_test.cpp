// Vertex colours (glTF COLOR_0, issue 20 part 3): the loader reads float and normalized-integer colours
// exactly as glTF defines them (BoxVertexColors against its accessor read by hand; n/255 and n/65535 for every
// n), the writer keeps them through a round trip, and the renderer multiplies them into the base colour
// wherever it evaluates one: a wall with vertex colour c over base b renders as a wall of base c × b, in the
// G-buffer (albedo), in the voxels (the light it bounces) and in the path-traced reference (direct light).
// Bad COLOR_0 accessors are in hostile_gltf_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "hostile_util.h"
#include "io/image_io.h"
#include "scene/gltf_loader.h"
#include "scene/gltf_writer.h"
#include "scene_util.h"
#include "test_util.h"

namespace vct {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::vector<unsigned char> readBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The float at byte `offset` of `bytes` (little-endian, as glTF and this machine store it).
float floatAt(const std::vector<unsigned char>& bytes, size_t offset) {
    float v = 0.0f;
    std::memcpy(&v, &bytes[offset], 4);
    return v;
}

bool sameBits(const glm::vec4& a, const glm::vec4& b) {
    return std::memcmp(&a, &b, sizeof(a)) == 0;
}

TEST(VertexColors, BoxVertexColorsLoadAsItsAccessorHoldsThem) {
    const fs::path dir = fs::path(VCT_SHARED_SCENES) / "BoxVertexColors" / "glTF";
    if (!fs::exists(dir / "BoxVertexColors.gltf"))
        GTEST_SKIP() << "no " << dir << " (shared scenes not available)";
    // The accessors by hand, from the JSON: float VEC4 COLOR_0 and VEC3 POSITION, tightly packed.
    const json doc = json::parse(std::ifstream(dir / "BoxVertexColors.gltf"));
    const std::vector<unsigned char> bin = readBytes(dir / "buffer.bin");
    const json& attributes = doc["meshes"][0]["primitives"][0]["attributes"];
    auto start = [&](int accessor) {
        const json& a = doc["accessors"][accessor];
        EXPECT_EQ(a["componentType"], 5126);
        const json& view = doc["bufferViews"][a["bufferView"].get<int>()];
        EXPECT_FALSE(view.contains("byteStride"));
        return view.value("byteOffset", size_t(0)) + a.value("byteOffset", size_t(0));
    };
    const int colorAccessor = attributes["COLOR_0"], positionAccessor = attributes["POSITION"];
    ASSERT_EQ(doc["accessors"][colorAccessor]["type"], "VEC4");
    const size_t count = doc["accessors"][colorAccessor]["count"];
    ASSERT_EQ(count, 24u);
    const size_t colors = start(colorAccessor), positions = start(positionAccessor);
    ASSERT_LE(colors + count * 16, bin.size());

    const Scene scene = loadGltf((dir / "BoxVertexColors.gltf").string());
    ASSERT_EQ(scene.primitives.size(), 1u);
    const Primitive& p = scene.primitives[0];
    EXPECT_TRUE(p.hasColors);
    ASSERT_EQ(p.vertexCount, count);
    // The loader scales a scene to its working size: positions are compared by direction from the first.
    size_t distinct = 0;
    for (size_t i = 0; i < count; ++i) {
        const Vertex& v = scene.vertices[size_t(p.vertexOffset) + i];
        const glm::vec4 expected(floatAt(bin, colors + 16 * i), floatAt(bin, colors + 16 * i + 4),
                                 floatAt(bin, colors + 16 * i + 8), floatAt(bin, colors + 16 * i + 12));
        EXPECT_TRUE(sameBits(v.color, expected))
            << "vertex " << i << ": (" << v.color.r << ", " << v.color.g << ", " << v.color.b << ", "
            << v.color.a << ") vs (" << expected.r << ", " << expected.g << ", " << expected.b << ", "
            << expected.a << ")";
        const glm::vec3 position(floatAt(bin, positions + 12 * i), floatAt(bin, positions + 12 * i + 4),
                                 floatAt(bin, positions + 12 * i + 8));
        // Same vertex order: the position's signs match the file's (a cube about the origin).
        EXPECT_EQ(glm::sign(v.position), glm::sign(position)) << "vertex " << i;
        if (i > 0 && !sameBits(v.color, scene.vertices[size_t(p.vertexOffset)].color)) ++distinct;
    }
    EXPECT_GT(distinct, 0u) << "every vertex has the same colour: nothing would show";
    for (const std::string& note : scene.notes) EXPECT_EQ(note.find("COLOR"), std::string::npos) << note;
}

// A triangle list of count/components vertices whose COLOR_0 is `values` as `componentType` (5121 or 5123,
// normalized) and `type`; returns the .gltf written into `dir`.
fs::path integerColorScene(const fs::path& dir, int componentType, const char* type,
                           const std::vector<uint32_t>& values) {
    const size_t components = std::string(type) == "VEC4" ? 4 : 3;
    const size_t vertices = values.size() / components;
    hostile::GltfScene s;
    s.texture = false;
    for (size_t v = 0; v < vertices; ++v)  // a row of small triangles
        hostile::appendFloats(s.bin,
                              {float(v / 3) + (v % 3 == 1 ? 1.0f : 0.0f), v % 3 == 2 ? 1.0f : 0.0f, 0.0f});
    const size_t colorOffset = s.bin.size();
    for (uint32_t value : values) {
        if (componentType == 5121)
            s.bin.push_back((unsigned char)value);
        else {
            s.bin.push_back((unsigned char)(value & 0xFF));
            s.bin.push_back((unsigned char)(value >> 8));
        }
    }
    while (s.bin.size() % 4) s.bin.push_back(0);
    const size_t stride = components * (componentType == 5121 ? 1 : 2);
    s.doc = {
        {"asset", {{"version", "2.0"}}},
        {"scene", 0},
        {"scenes", {{{"nodes", {0}}}}},
        {"nodes", {{{"mesh", 0}}}},
        {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"COLOR_0", 1}}}}}}}}},
        {"buffers", {{{"uri", "scene.bin"}, {"byteLength", s.bin.size()}}}},
        {"bufferViews",
         {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", colorOffset}},
          {{"buffer", 0}, {"byteOffset", colorOffset}, {"byteLength", vertices * stride}}}},
        {"accessors",
         {{{"bufferView", 0},
           {"componentType", 5126},
           {"count", vertices},
           {"type", "VEC3"},
           {"min", {0, 0, 0}},
           {"max", {float((vertices - 1) / 3) + 1.0f, 1, 0}}},
          {{"bufferView", 1},
           {"componentType", componentType},
           {"normalized", true},
           {"count", vertices},
           {"type", type}}}},
    };
    return hostile::writeGltf(dir, s);
}

// Every value of both normalized integer types decodes to the float nearest n / (2^bits − 1), and a VEC3's
// alpha is exactly 1; the colours then survive the writer (float VEC4) bit for bit.
TEST(VertexColors, NormalizedIntegersDecodeExactlyAndSurviveExport) {
    struct Case {
        int componentType;
        const char* type;
        uint32_t max;
    };
    for (const Case& c : {Case{5121, "VEC4", 255}, Case{5121, "VEC3", 255}, Case{5123, "VEC4", 65535},
                          Case{5123, "VEC3", 65535}}) {
        const size_t components = std::string(c.type) == "VEC4" ? 4 : 3;
        std::vector<uint32_t> values;
        for (uint32_t n = 0; n <= c.max; ++n) values.push_back(n);
        while (values.size() % (components * 3)) values.push_back(c.max);  // whole triangles
        const std::string tag = std::to_string(c.componentType) + c.type;
        const fs::path dir = test::freshOutputDir("vertex_color/decode-" + tag);
        const Scene scene = loadGltf(integerColorScene(dir, c.componentType, c.type, values).string());
        ASSERT_EQ(scene.primitives.size(), 1u) << tag;
        const Primitive& p = scene.primitives[0];
        ASSERT_TRUE(p.hasColors) << tag;
        // Without NORMAL the loader unwelds the triangles (flat normals): vertex i stays vertex i here, as the
        // file has no indices.
        ASSERT_EQ(p.vertexCount, values.size() / components) << tag;
        size_t wrong = 0;
        for (size_t i = 0; i < values.size(); ++i) {
            const Vertex& v = scene.vertices[size_t(p.vertexOffset) + i / components];
            const float expected = float(values[i]) / float(c.max);  // IEEE: the float nearest n / max
            wrong += std::memcmp(&v.color[int(i % components)], &expected, 4) != 0;
        }
        EXPECT_EQ(wrong, 0u) << tag << ": components that are not n / " << c.max;
        if (components == 3) {
            for (uint32_t i = 0; i < p.vertexCount; ++i)
                ASSERT_EQ(scene.vertices[size_t(p.vertexOffset) + i].color.a, 1.0f) << tag;
        }

        writeGlb(scene, dir / "exported.glb");
        const Scene back = loadGltf((dir / "exported.glb").string());
        ASSERT_EQ(back.primitives.size(), 1u);
        EXPECT_TRUE(back.primitives[0].hasColors) << tag;
        ASSERT_EQ(back.vertices.size(), scene.vertices.size()) << tag;
        size_t changed = 0;
        for (size_t i = 0; i < scene.vertices.size(); ++i)
            changed += !sameBits(scene.vertices[i].color, back.vertices[i].color);
        EXPECT_EQ(changed, 0u) << tag << ": colours changed by the export";
    }
}

TEST(VertexColors, ScenesWithoutColorsExportWithoutThem) {
    const fs::path dir = test::freshOutputDir("vertex_color/no-colors");
    writeGlb(test::scenes::vertexColorRoom(false, glm::vec4(0.5f), glm::vec3(0.8f)), dir / "room.glb");
    const std::vector<unsigned char> bytes = readBytes(dir / "room.glb");
    const std::string text(bytes.begin(), bytes.end());
    EXPECT_EQ(text.find("COLOR_0"), std::string::npos);
    const Scene back = loadGltf((dir / "room.glb").string());
    for (const Primitive& p : back.primitives) EXPECT_FALSE(p.hasColors);
}

// ---- rendered ----

const glm::vec4 kColor(0.9f, 0.45f, 0.2f, 1.0f);
const glm::vec3 kBase(0.8f, 0.7f, 0.9f);

std::string roomFile(const std::string& name, bool vertexColors) {
    const fs::path path = test::freshOutputDir("vertex_color/scene-" + name) / (name + ".glb");
    writeGlb(test::scenes::vertexColorRoom(vertexColors, kColor, kBase), path);
    return path.string();
}

fs::path render(const std::string& name, const std::string& scene, std::vector<std::string> extra = {}) {
    const fs::path dir = test::freshOutputDir("vertex_color/" + name);
    std::vector<std::string> args = {"render",   "--scene", scene,        "--size", "96x54", "--frames",  "1",
                                     "--voxels", "32",      "--validate", "--aux",  "--out", dir.string()};
    args.insert(args.end(), extra.begin(), extra.end());
    const test::RunResult r = test::runVct(args);
    EXPECT_TRUE(r.exited() && r.exitCode == 0) << r.describe();
    return dir;
}

// The wall of vertex colour c over base b has the G-buffer albedo c × b (to the albedo target's 8 bits), and the
// whole frame (its light bounced through the voxels included) matches the wall of base c × b.
TEST(VertexColors, RenderAsTheBaseColorTheyMultiply) {
    const fs::path colored = render("colored", roomFile("colored", true));
    const fs::path factor = render("factor", roomFile("factor", false));
    const ImageRgba32f albedo = readExr(colored / "albedo.exr");
    const ImageRgba32f albedoFactor = readExr(factor / "albedo.exr");
    const ImageRgba32f final = readExr(colored / "final.exr");
    const ImageRgba32f finalFactor = readExr(factor / "final.exr");
    ASSERT_EQ(albedo.pixels.size(), albedoFactor.pixels.size());
    ASSERT_EQ(final.pixels.size(), finalFactor.pixels.size());
    const glm::vec3 expected = glm::vec3(kColor) * kBase;
    // The wall's pixels: those whose albedo is near c × b in the factor render (the floor and left wall are grey).
    size_t wall = 0;
    float albedoError = 0.0f, albedoDiff = 0.0f;
    for (size_t i = 0; i < albedo.pixels.size(); i += 4) {
        const glm::vec3 f(albedoFactor.pixels[i], albedoFactor.pixels[i + 1], albedoFactor.pixels[i + 2]);
        if (glm::length(f - expected) > 0.02f) continue;
        ++wall;
        const glm::vec3 a(albedo.pixels[i], albedo.pixels[i + 1], albedo.pixels[i + 2]);
        for (int c = 0; c < 3; ++c) {
            albedoError = std::max(albedoError, std::abs(a[c] - expected[c]));
            albedoDiff = std::max(albedoDiff, std::abs(a[c] - f[c]));
        }
    }
    // The centre pixel is on the wall.
    const size_t centre = (size_t(albedo.height / 2) * albedo.width + albedo.width / 2) * 4;
    const glm::vec3 atCentre(albedo.pixels[centre], albedo.pixels[centre + 1], albedo.pixels[centre + 2]);
    std::printf(
        "vertex colours: %zu wall pixels, albedo vs c*b max %.5f, vs the factor render max %.5f; centre "
        "(%.4f, %.4f, %.4f), c*b (%.4f, %.4f, %.4f)\n",
        wall, albedoError, albedoDiff, atCentre.r, atCentre.g, atCentre.b, expected.r, expected.g,
        expected.b);
    // Measured: 1079 wall pixels; albedo within 0.00157 of c × b (the 8-bit target's rounding: half a step is
    // 0.00196), and the same bits as the factor render's.
    EXPECT_GT(wall, 800u) << "the wall is not in view";
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(atCentre[c], expected[c], 0.5f / 255.0f + 1e-6f) << c;
    EXPECT_LE(albedoError, 0.5f / 255.0f + 1e-6f);
    EXPECT_LE(albedoDiff, 1e-6f);

    // The frame: direct light and the light the coloured wall bounces onto the floor through the voxels.
    double maxRelative = 0.0, floorTint = 0.0;
    for (size_t i = 0; i < final.pixels.size(); i += 4)
        for (int c = 0; c < 3; ++c) {
            const double a = final.pixels[i + size_t(c)], b = finalFactor.pixels[i + size_t(c)];
            maxRelative = std::max(maxRelative, std::abs(a - b) / std::max(b, 1e-3));
        }
    // And the bounce is coloured at all (red over blue on the floor below the wall), or the comparison is empty.
    const ImageRgba32f diffuse = readExr(colored / "diffuse_indirect.exr");
    for (size_t i = 0; i < diffuse.pixels.size(); i += 4)
        floorTint =
            std::max(floorTint, double(diffuse.pixels[i]) / std::max(double(diffuse.pixels[i + 2]), 1e-6));
    std::printf(
        "vertex colours: final.exr vs the factor render, max relative difference %.2e; indirect r/b up to "
        "%.2f\n",
        maxRelative, floorTint);
    // Measured: 0 (the same bits) and r/b 2.78.
    EXPECT_LE(maxRelative, 1e-6);
    EXPECT_GT(floorTint, 1.5) << "the wall's colour does not bounce";
}

// The vertex colour's alpha multiplies the base colour's, which an alpha-masked material compares with its
// cutoff: a masked wall whose vertex alpha is 0.2 (cutoff 0.5) is cut out in vct's G-buffer and in the
// reference alike, and the same wall with vertex alpha 1 is there in both.
TEST(VertexColors, VertexAlphaBelowTheMaskCutoffCutsTheSurfaceOut) {
    for (float alpha : {1.0f, 0.2f}) {
        const std::string tag = alpha < 0.5f ? "masked-out" : "masked-in";
        Scene scene = test::scenes::vertexColorRoom(true, glm::vec4(glm::vec3(kColor), alpha), kBase);
        scene.materials[1].alphaMode = AlphaMode::Mask;
        scene.materials[1].alphaCutoff = 0.5f;
        const fs::path file = test::freshOutputDir("vertex_color/scene-" + tag) / (tag + ".glb");
        writeGlb(scene, file);
        const ImageRgba32f albedo = readExr(render(tag, file.string()) / "albedo.exr");
        const glm::vec3 expected = glm::vec3(kColor) * kBase;
        size_t wall = 0;
        for (size_t i = 0; i < albedo.pixels.size(); i += 4)
            wall += glm::length(glm::vec3(albedo.pixels[i], albedo.pixels[i + 1], albedo.pixels[i + 2]) -
                                expected) < 0.02f;
        // The reference: pixels whose centre sees a surface of the wall's material (reference.json, per surface).
        const fs::path refDir = test::freshOutputDir("vertex_color/reference-" + tag);
        const test::RunResult r = test::runVct({"reference", "--scene", file.string(), "--size", "96x54",
                                                "--spp", "1", "--bounces", "0", "--out", refDir.string()});
        ASSERT_TRUE(r.exited() && r.exitCode == 0) << r.describe();
        const json info = json::parse(std::ifstream(refDir / "reference.json"));
        size_t referenceWall = 0;
        for (const json& surface : info["surfaces"])
            if (surface["material"] == 1) referenceWall += surface["pixels"].get<size_t>();
        std::printf("vertex alpha %.1f under a 0.5 mask: %zu wall pixels in vct, %zu in the reference\n",
                    alpha, wall, referenceWall);
        if (alpha < 0.5f) {
            EXPECT_EQ(wall, 0u);
            EXPECT_EQ(referenceWall, 0u);
        } else {
            EXPECT_GT(wall, 800u);  // measured 1079 in both, as unmasked
            EXPECT_GT(referenceWall, 800u);
        }
    }
}

}  // namespace
}  // namespace vct
