// The vct program on bad input: every case must end promptly with a non-zero exit status (2: bad usage,
// 1: a bad file), by itself (no signal, no hang), and with exactly one non-empty line on stderr that names
// the problem. The glTF files are written here: a valid one-triangle scene with a texture (which must render)
// and broken variants of it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/image_io.h"
#include "test_util.h"

namespace vct {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::RunResult;

constexpr int kUsageError = 2;
constexpr int kFileError = 1;
// Bad input is rejected before (or instead of) any real rendering; far less than the default 300 s.
constexpr std::chrono::seconds kTimeout(120);

// A fresh directory for one test, named after it (ctest may run tests in parallel processes).
fs::path caseDir() {
    const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
    return test::freshOutputDir(std::string("bad_input/") + info->name());
}

std::string lower(std::string text) {
    for (char& c : text) c = char(std::tolower(static_cast<unsigned char>(c)));
    return text;
}

// Runs vct with `args` and checks the failure: exit status `expectedCode` (and 1..127 in any case, i.e. not
// a crash or a signal), one non-empty line on stderr containing every string in `mentions` (case-insensitive).
void expectFailure(const std::vector<std::string>& args, int expectedCode,
                   const std::vector<std::string>& mentions) {
    RunResult r = test::runVct(args, kTimeout);
    std::string command = "vct";
    for (const std::string& a : args) command += " " + a;
    SCOPED_TRACE(command);
    ASSERT_FALSE(r.timedOut) << r.describe();
    ASSERT_TRUE(r.startError.empty()) << r.describe();
    ASSERT_EQ(r.signal, 0) << "crashed: " << r.describe();
    ASSERT_TRUE(r.exited()) << r.describe();
    EXPECT_GE(r.exitCode, 1) << r.describe();
    EXPECT_LE(r.exitCode, 127) << r.describe();
    EXPECT_EQ(r.exitCode, expectedCode) << r.describe();

    std::string err = r.err;
    if (!err.empty() && err.back() == '\n') err.pop_back();
    EXPECT_FALSE(err.empty()) << "nothing on stderr: " << r.describe();
    EXPECT_EQ(err.find_first_of("\r\n"), std::string::npos) << "stderr is not one line:\n" << r.err;
    EXPECT_NE(err.find_first_not_of(" \t"), std::string::npos) << "stderr is blank";
    for (const std::string& m : mentions)
        EXPECT_NE(lower(err).find(lower(m)), std::string::npos)
            << "stderr does not mention '" << m << "': " << err;
}

// ---- a minimal scene: one triangle with UVs and a base colour texture ----

// 3 float positions (bytes 0..35), then 3 float UV pairs (36..59).
constexpr size_t kBinSize = 60;

std::vector<unsigned char> triangleBin(float x1 = 1.0f) {
    const float values[] = {0, 0, 0, x1, 0, 0, 0, 1, 0,  // POSITION
                            0, 1, 1, 1,  0, 0};          // TEXCOORD_0
    std::vector<unsigned char> bytes(sizeof(values));
    std::memcpy(bytes.data(), values, sizeof(values));
    return bytes;
}

std::string triangleGltf(const std::string& imageUri) {
    json gltf = {
        {"asset", {{"version", "2.0"}}},
        {"scene", 0},
        {"scenes", {{{"nodes", {0}}}}},
        {"nodes", {{{"name", "triangle"}, {"mesh", 0}}}},
        {"meshes",
         {{{"name", "Triangle"},
           {"primitives", {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}}, {"material", 0}}}}}}},
        {"materials",
         {{{"name", "textured"},
           {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}},
           {"doubleSided", true}}}},
        {"textures", {{{"source", 0}}}},
        {"images", {{{"uri", imageUri}}}},
        {"buffers", {{{"uri", "scene.bin"}, {"byteLength", kBinSize}}}},
        {"bufferViews",
         {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 36}},
          {{"buffer", 0}, {"byteOffset", 36}, {"byteLength", 24}}}},
        {"accessors",
         {{{"bufferView", 0},
           {"componentType", 5126},
           {"count", 3},
           {"type", "VEC3"},
           {"min", {0, 0, 0}},
           {"max", {1, 1, 0}}},
          {{"bufferView", 1}, {"componentType", 5126}, {"count", 3}, {"type", "VEC2"}}}},
    };
    return gltf.dump(2);
}

// Writes scene.gltf, scene.bin and texture.png into `dir`; returns the .gltf path.
fs::path writeTriangleScene(const fs::path& dir, const std::vector<unsigned char>& bin,
                            const std::string& imageUri = "texture.png") {
    test::writeTextFile(dir / "scene.gltf", triangleGltf(imageUri));
    test::writeBinaryFile(dir / "scene.bin", bin);
    std::vector<uint8_t> pixels(4 * 4 * 4);
    for (size_t i = 0; i < pixels.size(); i += 4) {
        pixels[i] = uint8_t((i / 4) * 16);
        pixels[i + 1] = 128;
        pixels[i + 2] = 64;
        pixels[i + 3] = 255;
    }
    writePng(dir / "texture.png", 4, 4, pixels);
    return dir / "scene.gltf";
}

std::vector<std::string> renderArgs(const fs::path& scene, const fs::path& dir) {
    return {"render", "--scene", scene.string(),        "--size", "32x18", "--frames",
            "1",      "--out",   (dir / "out").string()};
}

// The control: the unbroken scene renders, so each failure below is caused by its one defect.
TEST(BadInput, ValidMinimalSceneRenders) {
    const fs::path dir = caseDir();
    const fs::path scene = writeTriangleScene(dir, triangleBin());
    std::vector<std::string> args = renderArgs(scene, dir);
    args.push_back("--validate");
    RunResult r = test::runVct(args, kTimeout);
    ASSERT_TRUE(r.exited() && r.exitCode == 0) << r.describe();
    EXPECT_TRUE(fs::is_regular_file(dir / "out" / "final.exr"));
}

// ---- bad files: exit status 1 ----

TEST(BadInput, MissingSceneFile) {
    const fs::path dir = caseDir();
    expectFailure(renderArgs("/nonexistent.gltf", dir), kFileError, {"/nonexistent.gltf"});
}

TEST(BadInput, MalformedJson) {
    const fs::path dir = caseDir();
    test::writeTextFile(dir / "broken.gltf",
                        "{\"asset\": {\"version\": \"2.0\"}, \"scenes\": [{\"nodes\": [0}\n");
    expectFailure(renderArgs(dir / "broken.gltf", dir), kFileError, {"broken.gltf", "parse"});
}

TEST(BadInput, TruncatedBin) {
    const fs::path dir = caseDir();
    std::vector<unsigned char> bin = triangleBin();
    bin.resize(20);  // in the middle of the positions
    const fs::path scene = writeTriangleScene(dir, bin);
    expectFailure(renderArgs(scene, dir), kFileError, {"scene.gltf", "scene.bin"});
}

TEST(BadInput, NanPosition) {
    const fs::path dir = caseDir();
    const fs::path scene = writeTriangleScene(dir, triangleBin(std::numeric_limits<float>::quiet_NaN()));
    expectFailure(renderArgs(scene, dir), kFileError, {"scene.gltf", "position"});
}

TEST(BadInput, MissingTextureImage) {
    const fs::path dir = caseDir();
    const fs::path scene = writeTriangleScene(dir, triangleBin(), "no_such_texture.png");
    expectFailure(renderArgs(scene, dir), kFileError, {"scene.gltf", "no_such_texture.png"});
}

// ---- bad usage: exit status 2 ----

TEST(BadInput, ZeroSize) {
    const fs::path dir = caseDir();
    expectFailure({"render", "--size", "0x0", "--frames", "1", "--out", (dir / "out").string()}, kUsageError,
                  {"--size", "0x0"});
}

TEST(BadInput, HugeSize) {
    const fs::path dir = caseDir();
    expectFailure({"render", "--size", "100000x100000", "--frames", "1", "--out", (dir / "out").string()},
                  kUsageError, {"--size", "100000x100000"});
}

TEST(BadInput, UnknownFlag) {
    const fs::path dir = caseDir();
    expectFailure({"render", "--bogus", "--frames", "1", "--out", (dir / "out").string()}, kUsageError,
                  {"--bogus"});
}

TEST(BadInput, NonNumericFrames) {
    const fs::path dir = caseDir();
    expectFailure({"render", "--frames", "abc", "--out", (dir / "out").string()}, kUsageError,
                  {"--frames", "abc"});
}

TEST(BadInput, UnknownSubcommand) {
    expectFailure({"frobnicate"}, kUsageError, {"frobnicate"});
}

}  // namespace
}  // namespace vct
