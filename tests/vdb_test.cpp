// OpenVDB export and the voxel cache (io/vdb_io.h, `vct voxelize`, `vct render --voxel-cache`): the file
// round trip on synthetic voxels (no GPU), then end to end on lavapipe: voxelize writes a sparse file that
// vdb_print reads, a cached render gives the very same image, a re-export from the cache the very same voxels,
// and bad caches end with one line and a non-zero exit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "core/error.h"
#include "io/image_io.h"
#include "io/vdb_io.h"
#include "test_util.h"

namespace vct {
namespace {

namespace fs = std::filesystem;
using test::RunResult;

// A fresh directory for one test, named after it (ctest runs tests in parallel processes).
fs::path caseDir() {
    const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
    return test::freshOutputDir(std::string("vdb/") + info->test_suite_name() + "." + info->name());
}

const std::vector<std::string> kGridNames = {"albedo",
                                             "normal",
                                             "emission",
                                             "opacity",
                                             "radiance",
                                             "static_count",
                                             "static_albedo_sum",
                                             "static_normal_sum",
                                             "static_emission_sum",
                                             "static_transparency_sum",
                                             "static_metallic_sum",
                                             "static_roughness_sum"};

// Voxels at the grid's corners and edges plus a pseudo-random scatter, with values that a lossy path would
// change: negative normals, tiny and huge floats, accumulator words with the top bit set. Sorted by linear
// index, as readVoxelFile returns them.
VoxelFile syntheticFile(uint32_t n) {
    VoxelFile file;
    file.info.resolution = n;
    file.info.origin = glm::vec3(-2.1333334f, -0.6333334f, 1.0e-7f);
    file.info.voxelSize = 0.13333334f;
    file.info.scene = "synthetic scene.glb";
    file.info.time = 0.0f;
    file.info.sceneHash = 0x8000000000000001ull;  // the top bit too
    uint32_t state = 12345;
    auto next = [&] { return state = state * 1664525u + 1013904223u; };
    auto unit = [&] { return float(next() >> 8) / float(1u << 24); };
    for (uint64_t index = 0; index < uint64_t(n) * n * n; ++index) {
        const glm::ivec3 ijk(int(index % n), int((index / n) % n), int(index / (uint64_t(n) * n)));
        const bool edge = (ijk.x == 0 || ijk.x == int(n) - 1) && (ijk.y == 0 || ijk.y == int(n) - 1);
        if (!edge && next() % 7 != 0) continue;
        VoxelSample v;
        v.ijk = ijk;
        v.albedo = glm::vec3(unit(), unit(), 1.0f);
        v.opacity = 1.0f;
        v.normal = glm::vec3(-unit(), unit() - 0.5f, 0.0f);
        v.emission = index % 3 == 0 ? glm::vec3(1e-30f, 4096.0f, 0.0f) : glm::vec3(0.0f);
        v.radiance = glm::vec3(unit() * 100.0f, 1e-8f, 3.0e38f);
        file.voxels.push_back(v);
        if (index % 2 == 0) {
            StaticAccumVoxel s;
            s.ijk = ijk;
            // Sums a voxelize pass can give for the count (the reader checks), bits up to the top one.
            const uint32_t count = 1 + next() % 5000;
            for (int c = 0; c < 3; ++c) {
                s.accum[size_t(c)] = next() % (1023 * count + 1);
                s.accum[size_t(3 + c)] =
                    uint32_t(int32_t(next() % (2046 * count + 1)) - int32_t(1023 * count));
                s.accum[size_t(6 + c)] =
                    next() % uint32_t(std::min<uint64_t>(UINT32_MAX, 1048576ull * count));
            }
            s.accum[3] = 0xFFFFFC01u;  // -1023: a normal sum pointing down
            s.accum[9] = count;
            s.accum[10] = next() % 3 == 0 ? next() % (1023 * count + 1) : 0;  // blended samples in some
            s.accum[VCT_VOXEL_ACCUM_METALLIC] = next() % (1023 * count + 1);
            s.accum[VCT_VOXEL_ACCUM_ROUGHNESS] = next() % (1023 * count + 1);
            file.staticAccum.push_back(s);
        }
    }
    return file;
}

TEST(VdbIo, RoundTripIsExact) {
    const fs::path dir = caseDir();
    const VoxelFile file = syntheticFile(32);
    ASSERT_GT(file.voxels.size(), 1000u);
    const std::vector<VoxelGridSummary> grids = writeVoxelFile(dir / "synthetic.vdb", file);
    ASSERT_EQ(grids.size(), kGridNames.size());
    for (size_t i = 0; i < grids.size(); ++i) {
        EXPECT_EQ(grids[i].name, kGridNames[i]);
        EXPECT_EQ(grids[i].activeVoxels, i < 5 ? file.voxels.size() : file.staticAccum.size())
            << grids[i].name;
    }

    const VoxelFile read = readVoxelFile(dir / "synthetic.vdb");
    EXPECT_EQ(read.info, file.info);
    ASSERT_EQ(read.voxels.size(), file.voxels.size());
    ASSERT_EQ(read.staticAccum.size(), file.staticAccum.size());
    for (size_t i = 0; i < file.voxels.size(); ++i)
        ASSERT_EQ(read.voxels[i], file.voxels[i]) << "voxel " << i;
    for (size_t i = 0; i < file.staticAccum.size(); ++i)
        ASSERT_EQ(read.staticAccum[i], file.staticAccum[i]) << "accumulator voxel " << i;
    EXPECT_EQ(read, file);

    // The cache needs only the static grids; the metadata alone is cheaper still.
    const VoxelFile staticOnly = readVoxelFile(dir / "synthetic.vdb", /*frame=*/false);
    EXPECT_TRUE(staticOnly.voxels.empty());
    EXPECT_EQ(staticOnly.staticAccum, file.staticAccum);
    EXPECT_EQ(readVoxelFileInfo(dir / "synthetic.vdb"), file.info);

    // Unsorted input writes the same voxels.
    VoxelFile reversed = file;
    std::reverse(reversed.voxels.begin(), reversed.voxels.end());
    std::reverse(reversed.staticAccum.begin(), reversed.staticAccum.end());
    writeVoxelFile(dir / "reversed.vdb", reversed);
    EXPECT_EQ(readVoxelFile(dir / "reversed.vdb"), file);
}

TEST(VdbIo, SparseFileIsSmallerThanDense) {
    const fs::path dir = caseDir();
    const VoxelFile file = syntheticFile(64);
    writeVoxelFile(dir / "synthetic.vdb", file);
    EXPECT_LT(fs::file_size(dir / "synthetic.vdb"), denseVoxelBytes(64) / 2);
    EXPECT_EQ(denseVoxelBytes(32), 32ull * 32 * 32 * 96);  // 4 vec3s + float + 2 int32 + 3 vec3i
}

TEST(VdbIo, EmptyGridRoundTrips) {
    const fs::path dir = caseDir();
    VoxelFile file;
    file.info.resolution = 32;
    file.info.voxelSize = 1.0f;
    file.info.scene = "empty";
    file.info.sceneHash = 7;
    writeVoxelFile(dir / "empty.vdb", file);
    EXPECT_EQ(readVoxelFile(dir / "empty.vdb"), file);
}

// vct::Error whose message contains `mention` and is one line.
template <typename F>
void expectError(F&& f, const std::string& mention) {
    try {
        f();
        ADD_FAILURE() << "no error; expected one mentioning '" << mention << "'";
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(mention), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        EXPECT_LT(message.size(), 400u) << message;
    }
}

TEST(VdbIo, BadFilesThrowOneLineErrors) {
    const fs::path dir = caseDir();
    expectError([&] { readVoxelFile(dir / "missing.vdb"); }, "does not exist");
    test::writeTextFile(dir / "garbage.vdb", "this is not an OpenVDB file\n");
    expectError([&] { readVoxelFile(dir / "garbage.vdb"); }, "not a vct voxel file");
    expectError([&] { readVoxelFileInfo(dir / "garbage.vdb"); }, "not a vct voxel file");
    expectError([&] { readVoxelFile(dir); }, "is a directory");

    // A vct file cut short: the header survives, the grids do not.
    const VoxelFile file = syntheticFile(32);
    writeVoxelFile(dir / "whole.vdb", file);
    std::ifstream in(dir / "whole.vdb", std::ios::binary);
    std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    bytes.resize(bytes.size() / 2);
    test::writeBinaryFile(dir / "truncated.vdb", bytes);
    expectError([&] { readVoxelFile(dir / "truncated.vdb"); }, "truncated.vdb");

    VoxelFile outside = file;
    outside.voxels.back().ijk.z = 32;
    expectError([&] { writeVoxelFile(dir / "outside.vdb", outside); }, "outside the 32^3 grid");
    expectError([&] { writeVoxelFile(dir / "no-such-dir" / "x.vdb", file); }, "cannot write voxel file");
}

// ---- end to end through the vct program (lavapipe) ----

// `vct voxelize --scene cornell --voxels N --out dir/name` (exit 0 asserted).
fs::path voxelize(const fs::path& dir, const std::string& name, uint32_t n,
                  std::vector<std::string> extra = {}) {
    const fs::path out = dir / name;
    std::vector<std::string> args = {"voxelize",        "--scene", "cornell",   "--voxels",
                                     std::to_string(n), "--out",   out.string()};
    args.insert(args.end(), extra.begin(), extra.end());
    RunResult r = test::runVct(args);
    EXPECT_TRUE(r.exited() && r.exitCode == 0) << r.describe();
    return out;
}

// vdb_print from libopenvdb-tools, if on PATH.
std::string findOnPath(const std::string& program) {
    const char* path = std::getenv("PATH");
    std::string dirs = path ? path : "/usr/bin:/bin";
    size_t start = 0;
    while (start <= dirs.size()) {
        const size_t end = std::min(dirs.find(':', start), dirs.size());
        const fs::path candidate = fs::path(dirs.substr(start, end - start)) / program;
        if (end > start && access(candidate.c_str(), X_OK) == 0) return candidate.string();
        start = end + 1;
    }
    return {};
}

TEST(Voxelize, WritesSparseFileThatVdbPrintLists) {
    const fs::path dir = caseDir();
    const fs::path file = voxelize(dir, "cornell32.vdb", 32, {"--validate"});
    ASSERT_TRUE(fs::exists(file));
    EXPECT_LT(fs::file_size(file), denseVoxelBytes(32))
        << "the sparse file should be smaller than dense grids";

    const VoxelFile read = readVoxelFile(file);
    EXPECT_EQ(read.info.resolution, 32u);
    EXPECT_EQ(read.info.scene, "cornell");
    EXPECT_GT(read.info.voxelSize, 0.0f);
    // A closed room: its walls alone occupy thousands of voxels, yet far from all of them.
    EXPECT_GT(read.voxels.size(), 2000u);
    EXPECT_LT(read.voxels.size(), 32u * 32 * 32 / 2);
    // The moving cube is in the frame's voxels but not in the static accumulator.
    EXPECT_GT(read.staticAccum.size(), 2000u);
    EXPECT_LT(read.staticAccum.size(), read.voxels.size());
    bool lit = false;
    for (const VoxelSample& v : read.voxels) {
        EXPECT_EQ(v.opacity, 1.0f);
        lit |= v.radiance.r > 0.0f;
    }
    EXPECT_TRUE(lit) << "no voxel received light";
    for (const StaticAccumVoxel& v : read.staticAccum) EXPECT_GT(v.accum[VCT_VOXEL_ACCUM_COUNT], 0u);

    const std::string vdbPrint = findOnPath("vdb_print");
    if (vdbPrint.empty()) GTEST_SKIP() << "vdb_print (libopenvdb-tools) not on PATH";
    RunResult r = test::runProcess(vdbPrint, {file.string()}, std::chrono::seconds(60));
    ASSERT_TRUE(r.exited() && r.exitCode == 0) << r.describe();
    for (const std::string& name : kGridNames)
        EXPECT_NE(r.out.find(name + " "), std::string::npos) << name << " not listed:\n" << r.out;
}

// Pixel data of DIR/final.exr.
ImageRgba32f renderCornell(const fs::path& dir, std::vector<std::string> extra = {}) {
    std::vector<std::string> args = {"render", "--scene",  "cornell", "--size", "160x90",    "--voxels",
                                     "32",     "--frames", "2",       "--out",  dir.string()};
    args.insert(args.end(), extra.begin(), extra.end());
    RunResult r = test::runVct(args);
    EXPECT_TRUE(r.exited() && r.exitCode == 0) << r.describe();
    return readExr(dir / "final.exr");
}

TEST(VoxelCache, RendersTheSameImage) {
    const fs::path dir = caseDir();
    const fs::path cache = voxelize(dir, "cornell32.vdb", 32);
    const ImageRgba32f computed = renderCornell(dir / "computed");
    const ImageRgba32f cached =
        renderCornell(dir / "cached", {"--voxel-cache", cache.string(), "--validate"});
    ASSERT_EQ(computed.width, 160u);
    ASSERT_EQ(cached.width, computed.width);
    ASSERT_EQ(cached.height, computed.height);
    size_t differing = 0;
    for (size_t i = 0; i < computed.pixels.size(); ++i) differing += computed.pixels[i] != cached.pixels[i];
    EXPECT_EQ(differing, 0u) << "values differ between the computed and the cached voxelization";
}

TEST(VoxelCache, ReexportGivesTheSameVoxels) {
    const fs::path dir = caseDir();
    const fs::path first = voxelize(dir, "first.vdb", 32);
    // Without --voxels: the cache's N.
    const fs::path again = dir / "again.vdb";
    RunResult r = test::runVct(
        {"voxelize", "--scene", "cornell", "--voxel-cache", first.string(), "--out", again.string()});
    ASSERT_TRUE(r.exited() && r.exitCode == 0) << r.describe();
    const VoxelFile a = readVoxelFile(first), b = readVoxelFile(again);
    EXPECT_EQ(a.info, b.info);
    EXPECT_EQ(a.staticAccum, b.staticAccum);
    EXPECT_EQ(a.voxels.size(), b.voxels.size());
    EXPECT_TRUE(a.voxels == b.voxels) << "the frame's voxels differ";
}

// `vct render` with a bad cache: exit `code`, by itself, one line on stderr that mentions `mention`.
void expectRenderFailure(const fs::path& dir, std::vector<std::string> extra, int code,
                         const std::string& mention) {
    std::vector<std::string> args = {
        "render", "--scene", "cornell", "--size", "32x18", "--frames", "1", "--out", (dir / "out").string()};
    args.insert(args.end(), extra.begin(), extra.end());
    std::string command = "vct";
    for (const std::string& a : args) command += " " + a;
    SCOPED_TRACE(command);
    RunResult r = test::runVct(args, std::chrono::seconds(120));
    ASSERT_TRUE(r.exited()) << r.describe();
    EXPECT_EQ(r.exitCode, code) << r.describe();
    std::string err = r.err;
    if (!err.empty() && err.back() == '\n') err.pop_back();
    EXPECT_FALSE(err.empty());
    EXPECT_EQ(err.find('\n'), std::string::npos) << "more than one line:\n" << r.err;
    EXPECT_NE(err.find(mention), std::string::npos) << err;
}

TEST(VoxelCache, BadCachesFailWithOneLine) {
    const fs::path dir = caseDir();
    expectRenderFailure(dir, {"--voxel-cache", (dir / "missing.vdb").string()}, 1, "does not exist");
    test::writeTextFile(dir / "garbage.vdb", "garbage, not OpenVDB");
    expectRenderFailure(dir, {"--voxel-cache", (dir / "garbage.vdb").string()}, 1, "not a vct voxel file");

    // vct files made for another grid (written here: no GPU voxelization needed).
    VoxelFile other;
    other.info.resolution = 32;
    other.info.origin = glm::vec3(-5.0f);
    other.info.voxelSize = 0.3f;
    other.info.scene = "elsewhere";
    other.info.sceneHash = 1;
    writeVoxelFile(dir / "other.vdb", other);
    expectRenderFailure(dir, {"--voxels", "64", "--voxel-cache", (dir / "other.vdb").string()}, 1,
                        "holds a 32^3 grid but this run uses 64^3");
    expectRenderFailure(dir, {"--voxels", "32", "--voxel-cache", (dir / "other.vdb").string()}, 1,
                        "other grid bounds");
    expectRenderFailure(dir, {"--voxel-cache", (dir / "other.vdb").string()}, 1, "other grid bounds");
    expectRenderFailure(dir, {"--gi", "off", "--voxel-cache", (dir / "other.vdb").string()}, 2,
                        "needs --gi on");

    RunResult r = test::runVct({"voxelize", "--out", (dir / "x.txt").string()});
    EXPECT_EQ(r.exitCode, 2) << r.describe();
    r = test::runVct({"voxelize"});
    EXPECT_EQ(r.exitCode, 2) << r.describe();
}

}  // namespace
}  // namespace vct
