// Shared by the hostile-input regression suite (tests/hostile_*_test.cpp): a valid one-triangle glTF scene
// as JSON + buffer that generators mutate, writers for .gltf/.glb, and the one check every hostile case must
// pass: the run ends by itself (no signal, no hang), and either exits 0 having written only finite images, or
// exits 1 or 2 with exactly one line on stderr naming the problem, of bounded length, control characters
// escaped.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/image_io.h"
#include "test_util.h"

namespace vct::hostile {

namespace fs = std::filesystem;
using nlohmann::json;

// Hostile input is rejected before (or instead of) real rendering, and renders are tiny: a case that takes
// longer than this hangs.
constexpr std::chrono::seconds kTimeout(60);

// A fresh directory for one test, named after its suite and case.
inline fs::path caseDir() {
    const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = std::string(info->test_suite_name()) + "." + info->name();
    std::replace(name.begin(), name.end(), '/', '_');
    return test::freshOutputDir("hostile/" + name);
}

inline std::string lower(std::string text) {
    for (char& c : text) c = char(std::tolower(static_cast<unsigned char>(c)));
    return text;
}

// ---- the valid base scene: one textured triangle, no camera, no light (the loader adds both) ----

struct GltfScene {
    json doc;
    std::vector<unsigned char> bin;  // buffer 0
    bool texture = true;             // write texture.png beside the scene
    // Text spliced into the written JSON in place of the first: for values too large to build as json.
    std::pair<std::string, std::string> replaceInText;
    // Writes further files the document names into the scene's directory.
    std::function<void(const fs::path& dir)> extraFiles;
};

inline std::string documentText(const GltfScene& scene) {
    std::string text = scene.doc.dump();
    const auto& [from, to] = scene.replaceInText;
    if (!from.empty())
        if (size_t at = text.find(from); at != std::string::npos) text.replace(at, from.size(), to);
    return text;
}

inline void appendFloats(std::vector<unsigned char>& bytes, std::initializer_list<float> values) {
    for (float v : values) {
        unsigned char b[4];
        std::memcpy(b, &v, 4);
        bytes.insert(bytes.end(), b, b + 4);
    }
}

// Positions (bytes 0..35, a unit right triangle scaled by `size`), then UVs (36..59).
inline GltfScene triangleScene(float size = 1.0f) {
    GltfScene scene;
    appendFloats(scene.bin, {0, 0, 0, size, 0, 0, 0, size, 0});
    appendFloats(scene.bin, {0, 1, 1, 1, 0, 0});
    scene.doc = {
        {"asset", {{"version", "2.0"}}},
        {"scene", 0},
        {"scenes", {{{"nodes", {0}}}}},
        {"nodes", {{{"name", "triangle"}, {"mesh", 0}}}},
        {"meshes",
         {{{"name", "Triangle"},
           {"primitives", {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}}, {"material", 0}}}}}}},
        {"materials",
         {{{"name", "textured"},
           {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}, {"metallicFactor", 0.0}}},
           {"doubleSided", true}}}},
        {"textures", {{{"source", 0}}}},
        {"images", {{{"uri", "texture.png"}}}},
        {"buffers", {{{"uri", "scene.bin"}, {"byteLength", scene.bin.size()}}}},
        {"bufferViews",
         {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 36}},
          {{"buffer", 0}, {"byteOffset", 36}, {"byteLength", 24}}}},
        {"accessors",
         {{{"bufferView", 0},
           {"componentType", 5126},
           {"count", 3},
           {"type", "VEC3"},
           {"min", {0, 0, 0}},
           {"max", {size, size, 0}}},
          {{"bufferView", 1}, {"componentType", 5126}, {"count", 3}, {"type", "VEC2"}}}},
    };
    return scene;
}

inline void writeTexture(const fs::path& path, uint32_t width = 4, uint32_t height = 4) {
    std::vector<uint8_t> pixels(size_t(width) * height * 4);
    for (size_t i = 0; i < pixels.size(); i += 4) {
        pixels[i] = uint8_t((i / 4) * 16);
        pixels[i + 1] = 128;
        pixels[i + 2] = 64;
        pixels[i + 3] = 255;
    }
    writePng(path, width, height, pixels);
}

// Writes DIR/scene.gltf (+ scene.bin, texture.png); returns the .gltf path.
inline fs::path writeGltf(const fs::path& dir, const GltfScene& scene, const std::string& text = "") {
    test::writeTextFile(dir / "scene.gltf", text.empty() ? documentText(scene) : text);
    test::writeBinaryFile(dir / "scene.bin", scene.bin);
    if (scene.texture) writeTexture(dir / "texture.png");
    if (scene.extraFiles) scene.extraFiles(dir);
    return dir / "scene.gltf";
}

// A .glb: the JSON chunk (space-padded) and the buffer as the BIN chunk (buffer 0 loses its uri).
inline fs::path writeGlb(const fs::path& dir, GltfScene scene, const std::string& jsonText = "") {
    scene.doc["buffers"][0].erase("uri");
    std::string text = jsonText.empty() ? documentText(scene) : jsonText;
    while (text.size() % 4) text += ' ';
    std::vector<unsigned char> bin = scene.bin;
    while (bin.size() % 4) bin.push_back(0);
    auto u32 = [](std::vector<unsigned char>& out, uint32_t v) {
        for (int i = 0; i < 4; ++i) out.push_back((unsigned char)(v >> (8 * i)));
    };
    std::vector<unsigned char> bytes;
    u32(bytes, 0x46546C67);  // "glTF"
    u32(bytes, 2);
    u32(bytes, uint32_t(12 + 8 + text.size() + 8 + bin.size()));
    u32(bytes, uint32_t(text.size()));
    u32(bytes, 0x4E4F534A);  // "JSON"
    bytes.insert(bytes.end(), text.begin(), text.end());
    u32(bytes, uint32_t(bin.size()));
    u32(bytes, 0x004E4942);  // "BIN\0"
    bytes.insert(bytes.end(), bin.begin(), bin.end());
    test::writeBinaryFile(dir / "scene.glb", bytes);
    if (scene.texture) writeTexture(dir / "texture.png");
    if (scene.extraFiles) scene.extraFiles(dir);
    return dir / "scene.glb";
}

// `vct render` of `scene` at the suite's tiny size, with validation and every auxiliary image.
inline std::vector<std::string> renderArgs(const fs::path& scene, const fs::path& out,
                                           std::vector<std::string> extra = {}) {
    std::vector<std::string> args = {"render",     "--scene",    scene.string(), "--size", "32x18",
                                     "--frames",   "1",          "--voxels",     "32",     "--out",
                                     out.string(), "--validate", "--aux"};
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
}

// Every .exr under `dir` read back: the number of NaN/Inf values in each (by file name).
inline std::vector<std::pair<std::string, size_t>> nonFiniteExrValues(const fs::path& dir) {
    std::vector<std::pair<std::string, size_t>> counts;
    std::error_code error;
    if (!fs::is_directory(dir, error)) return counts;
    for (const fs::directory_entry& entry : fs::directory_iterator(dir))
        if (entry.path().extension() == ".exr")
            counts.push_back(
                {entry.path().filename().string(), test::countNonFinite(readExr(entry.path()).pixels)});
    return counts;
}

// Pixels of DIR/albedo.exr (written by --aux) where something was drawn: the background's albedo is 0, the
// base scene's (non-metallic, textured) is not.
inline size_t coveredPixels(const fs::path& out) {
    if (!fs::exists(out / "albedo.exr")) return 0;
    const std::vector<float> albedo = readExr(out / "albedo.exr").pixels;
    size_t covered = 0;
    for (size_t i = 0; i < albedo.size(); i += 4)
        covered += albedo[i] + albedo[i + 1] + albedo[i + 2] > 0.0f ? 1 : 0;
    return covered;
}

enum class Outcome { Either, MustRender, MustFail };

struct Expectation {
    Outcome outcome = Outcome::Either;
    std::vector<std::string> mentions;  // in the error line (case-insensitive), when it fails
    int failCode = 0;                   // 1 or 2 when it must be that one; 0: either
    bool mustCover = false;             // when it renders, the scene must be in view (not an empty image)
};

// The promise every hostile case is held to (see the file comment). Returns the run for further checks.
inline test::RunResult expectGraceful(const std::vector<std::string>& args, const fs::path& out,
                                      const Expectation& expect = {}) {
    test::RunResult r = test::runVct(args, kTimeout);
    std::string command = "vct";
    for (const std::string& a : args) command += " " + a;
    SCOPED_TRACE(command);
    EXPECT_FALSE(r.timedOut) << "hang: " << r.describe();
    EXPECT_EQ(r.signal, 0) << "crash: " << r.describe();
    EXPECT_TRUE(r.exited()) << r.describe();
    if (!r.exited()) return r;
    if (r.exitCode == 0) {
        EXPECT_NE(expect.outcome, Outcome::MustFail) << "accepted: " << r.describe();
        EXPECT_TRUE(fs::is_regular_file(out / "final.png") || args[0] != "render") << r.describe();
        for (const auto& [name, count] : nonFiniteExrValues(out))
            EXPECT_EQ(count, 0u) << name << " has non-finite values; " << r.describe();
        if (expect.mustCover) {
            EXPECT_GT(coveredPixels(out), 0u) << "an empty image: " << r.describe();
        }
        return r;
    }
    EXPECT_NE(expect.outcome, Outcome::MustRender) << r.describe();
    EXPECT_TRUE(r.exitCode == 1 || r.exitCode == 2) << r.describe();
    if (expect.failCode) {
        EXPECT_EQ(r.exitCode, expect.failCode) << r.describe();
    }
    std::string err = r.err;
    if (!err.empty() && err.back() == '\n') err.pop_back();
    EXPECT_FALSE(err.empty()) << "nothing on stderr: " << r.describe();
    EXPECT_EQ(err.find_first_of("\r\n"), std::string::npos) << "stderr is not one line:\n" << r.err;
    // Bounded, whatever the file quotes (vct cuts its lines at ~600 characters), and no raw control characters.
    EXPECT_LE(err.size(), 700u) << "stderr line of " << err.size() << " characters: " << err.substr(0, 300);
    EXPECT_EQ(std::count_if(err.begin(), err.end(), [](char c) { return (unsigned char)c < 0x20; }), 0)
        << "control characters on stderr: " << err.substr(0, 300);
    for (const std::string& m : expect.mentions)
        EXPECT_NE(lower(err).find(lower(m)), std::string::npos)
            << "stderr does not mention '" << m << "': " << err;
    return r;
}

}  // namespace vct::hostile
