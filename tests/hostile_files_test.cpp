// Hostile files and flags around the scene (issue 11, classes 4, 5, 7, 8, 10, 12, 13): uris and caches that
// name FIFOs or devices, damaged and oversized voxel caches, caches of another scene, outputs that are files
// or planted symlinks, and flag combinations that used to fail late. Same promise as hostile_gltf_test.cpp.
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fstream>
#include <iterator>

#include "hostile_util.h"
#include "io/vdb_io.h"
#include "render/voxel_grid.h"
#include "scene/gltf_loader.h"

namespace vct::hostile {
namespace {

std::string readText(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

void makeFifo(const fs::path& path) {
    ASSERT_EQ(mkfifo(path.c_str(), 0600), 0) << path;
}

// ---- class 4: uris, caches and paths that are not regular files ----

enum class Special { Fifo, Directory, DevZero };

struct SpecialCase {
    std::string name;
    std::string field;  // "buffer", "image", "scene", "voxel-cache", "camera-path"
    Special kind;
};

void makeSpecial(const fs::path& path, Special kind) {
    if (kind == Special::Fifo) makeFifo(path);
    if (kind == Special::Directory) fs::create_directories(path);
    if (kind == Special::DevZero) fs::create_symlink("/dev/zero", path);
}

class HostileSpecialFile : public ::testing::TestWithParam<SpecialCase> {};

TEST_P(HostileSpecialFile, IsRefusedWithoutBlocking) {
    const SpecialCase& c = GetParam();
    const fs::path dir = caseDir();
    GltfScene scene = triangleScene();
    std::vector<std::string> extra;
    std::string named = "special";
    if (c.field == "buffer") scene.doc["buffers"][0]["uri"] = "special.bin", named = "special.bin";
    if (c.field == "image") scene.doc["images"][0]["uri"] = "special.png", named = "special.png";
    fs::path path = writeGltf(dir, scene);
    if (c.field == "buffer") makeSpecial(dir / "special.bin", c.kind);
    if (c.field == "image") makeSpecial(dir / "special.png", c.kind);
    if (c.field == "scene") makeSpecial(path = dir / "special.gltf", c.kind);
    if (c.field == "voxel-cache" || c.field == "camera-path") {
        makeSpecial(dir / "special", c.kind);
        extra = {"--" + c.field, (dir / "special").string()};
    }
    expectGraceful(renderArgs(path, dir / "out", extra), dir / "out", {Outcome::MustFail, {named}, 0});
}

std::vector<SpecialCase> specialCases() {
    std::vector<SpecialCase> cases;
    for (const char* field : {"buffer", "image", "scene", "voxel-cache", "camera-path"})
        for (auto [kind, label] : {std::pair{Special::Fifo, "Fifo"},
                                   {Special::Directory, "Directory"},
                                   {Special::DevZero, "DevZero"}})
            cases.push_back({std::string(field == std::string("voxel-cache")   ? "VoxelCache"
                                         : field == std::string("camera-path") ? "CameraPath"
                                                                               : field) +
                                 label,
                             field, kind});
    return cases;
}

INSTANTIATE_TEST_SUITE_P(Uris, HostileSpecialFile, ::testing::ValuesIn(specialCases()),
                         [](const auto& param) { return param.param.name; });

// ---- voxel caches: damaged, oversized, of another scene (classes 5, 10, 12) ----

// The triangle scene and a synthetic cache that fits its grid (or another's), written without the GPU.
struct CacheScene {
    fs::path scene;
    VoxelFile file;
};

CacheScene cacheScene(const fs::path& dir, uint32_t n = 32) {
    CacheScene c;
    c.scene = writeGltf(dir, triangleScene());
    const Scene loaded = loadGltf(c.scene.string());
    const Aabb bounds = voxelSceneBounds(loaded);
    const glm::vec4 fit = glsl::voxelGridFit(bounds.min, bounds.max, float(n));
    c.file.info = {n, glm::vec3(fit), fit.w, c.scene.string(), 0.0f, sceneContentHash(loaded)};
    for (int i = 0; i < 4; ++i) {
        StaticAccumVoxel v;
        v.ijk = glm::ivec3(i + 2, 2, 16);
        v.accum = {500, 500, 500, 0, 0, 1023, 0, 0, 0, 1};
        c.file.staticAccum.push_back(v);
    }
    return c;
}

std::vector<std::string> cacheArgs(const CacheScene& c, const fs::path& dir, const fs::path& cache) {
    return renderArgs(c.scene, dir / "out", {"--voxel-cache", cache.string()});
}

TEST(HostileVoxelCache, MatchingCacheRenders) {  // the control for the cases below
    const fs::path dir = caseDir();
    const CacheScene c = cacheScene(dir);
    writeVoxelFile(dir / "cache.vdb", c.file);
    expectGraceful(cacheArgs(c, dir, dir / "cache.vdb"), dir / "out", {Outcome::MustRender, {}, 0});
}

TEST(HostileVoxelCache, TruncatedFilesFailFast) {
    const fs::path dir = caseDir();
    const CacheScene c = cacheScene(dir);
    writeVoxelFile(dir / "cache.vdb", c.file);
    const std::string bytes = readText(dir / "cache.vdb");
    for (size_t length :
         {size_t(0), size_t(8), size_t(100), size_t(400), size_t(1500), bytes.size() / 2, bytes.size() - 1}) {
        const fs::path cut = dir / ("cut" + std::to_string(length) + ".vdb");
        test::writeTextFile(cut, bytes.substr(0, length));
        const test::RunResult r = expectGraceful(cacheArgs(c, dir, cut), dir / "out",
                                                 {Outcome::MustFail, {cut.filename().string()}, 1});
        EXPECT_LT(r.seconds, 20.0) << r.describe();
    }
}

// A tile of active values instead of voxels, at the root level (4096^3 voxels), one level down (128^3) or an
// 8^3 tile just outside the 32^3 grid.
TEST(HostileVoxelCache, ActiveTilesOutsideTheGridFailFast) {
    const fs::path dir = caseDir();
    const CacheScene c = cacheScene(dir);
    writeVoxelFile(dir / "cache.vdb", c.file);
    openvdb::initialize();
    for (auto [level, at] :
         {std::pair{3, openvdb::Coord(0)}, {2, openvdb::Coord(0)}, {1, openvdb::Coord(32, 0, 0)}}) {
        openvdb::io::File in((dir / "cache.vdb").string());
        in.open(false);
        openvdb::GridPtrVecPtr grids = in.getGrids();
        openvdb::MetaMap::Ptr meta = in.getMetadata();
        in.close();
        for (openvdb::GridBase::Ptr& grid : *grids)
            if (grid->getName() == "static_count")
                openvdb::gridPtrCast<openvdb::Int32Grid>(grid)->tree().addTile(level, at, 7, true);
        const fs::path tiled = dir / ("tile" + std::to_string(level) + ".vdb");
        openvdb::io::File out(tiled.string());
        out.write(*grids, *meta);
        out.close();
        const test::RunResult r = expectGraceful(cacheArgs(c, dir, tiled), dir / "out",
                                                 {Outcome::MustFail, {tiled.filename().string()}, 1});
        EXPECT_LT(r.seconds, 20.0) << r.describe();
    }
}

TEST(HostileVoxelCache, CacheOfAnotherSceneWithTheSameBoundsIsRefused) {
    const fs::path dir = caseDir();
    CacheScene c = cacheScene(dir);
    c.file.info.scene = "/elsewhere/other.gltf";
    c.file.info.sceneHash ^= 1;  // other content, same bounds
    writeVoxelFile(dir / "other.vdb", c.file);
    expectGraceful(cacheArgs(c, dir, dir / "other.vdb"), dir / "out",
                   {Outcome::MustFail, {"other.vdb", "scene"}, 1});
}

// Class 10: every cache the renderer refuses ends in one line, with no leaked Vulkan object reported by the
// validation layer (that would be a second line, and a non-zero count).
TEST(HostileVoxelCache, RefusedCachesLeakNothing) {
    const fs::path dir = caseDir();
    CacheScene c = cacheScene(dir);
    CacheScene wrongN = cacheScene(dir, 64);
    writeVoxelFile(dir / "n64.vdb", wrongN.file);
    c.file.info.origin += glm::vec3(1.0f);
    writeVoxelFile(dir / "moved.vdb", c.file);
    test::writeTextFile(dir / "text.vdb", "not a voxel file\n");
    for (const char* name : {"n64.vdb", "moved.vdb", "text.vdb"})
        expectGraceful(cacheArgs(c, dir, dir / name), dir / "out", {Outcome::MustFail, {name}, 0});
}

// ---- class 7: GI off writes no indirect images and refuses views of them before rendering ----

TEST(HostileFlags, GiOffAuxWritesOnlyFiniteImagesOfPassesThatRan) {
    const fs::path dir = caseDir();
    const fs::path scene = writeGltf(dir, triangleScene());
    expectGraceful(renderArgs(scene, dir / "out", {"--gi", "off"}), dir / "out",
                   {Outcome::MustRender, {}, 0});
    EXPECT_FALSE(fs::exists(dir / "out" / "diffuse_indirect.exr"));
    EXPECT_FALSE(fs::exists(dir / "out" / "specular_indirect.exr"));
    for (const char* view : {"diffuse", "specular", "weights", "resample", "voxels"}) {
        const test::RunResult r =
            expectGraceful(renderArgs(scene, dir / "out2", {"--gi", "off", "--view", view}), dir / "out2",
                           {Outcome::MustFail, {view}, 2});
        EXPECT_LT(r.seconds, 10.0) << "refused only after rendering: " << r.describe();
    }
}

// ---- class 8: every documented voxel resolution renders or is refused naming the device limit ----

TEST(HostileFlags, Voxels256RendersOrNamesTheDeviceLimit) {
    const fs::path dir = caseDir();
    const fs::path scene = writeGltf(dir, triangleScene());
    std::vector<std::string> args = renderArgs(scene, dir / "out");
    args[8] = "256";  // --voxels
    expectGraceful(args, dir / "out", {Outcome::Either, {"--voxels 256", "maxStorageBufferRange"}, 2});
}

// ---- class 12: flags that used to fail late or with a message that named nothing ----

TEST(HostileFlags, OutputPathThatIsAFileIsRefusedBeforeRendering) {
    const fs::path dir = caseDir();
    const fs::path scene = writeGltf(dir, triangleScene());
    test::writeTextFile(dir / "file", "x");
    const test::RunResult r =
        expectGraceful(renderArgs(scene, dir / "file"), dir / "file", {Outcome::MustFail, {"file"}, 0});
    EXPECT_EQ(r.out.find("device:"), std::string::npos)
        << "refused only after starting Vulkan: " << r.describe();
    EXPECT_EQ(readText(dir / "file"), "x");
    expectGraceful(
        {"benchmark", "--scene", scene.string(), "--frames", "2", "--out", (dir / "file").string()},
        dir / "file", {Outcome::MustFail, {"file"}, 0});
    // voxelize: a .vdb under a file, and a .vdb name that is a directory.
    fs::create_directories(dir / "dir.vdb");
    for (auto [out, named] : {std::pair{dir / "file" / "x.vdb", "file"}, {dir / "dir.vdb", "dir.vdb"}}) {
        const test::RunResult v =
            expectGraceful({"voxelize", "--scene", scene.string(), "--voxels", "32", "--out", out.string()},
                           dir / "none", {Outcome::MustFail, {named}, 0});
        EXPECT_EQ(v.out.find("device:"), std::string::npos)
            << "refused only after starting Vulkan: " << v.describe();
    }
}

TEST(HostileFlags, BenchmarkWithFewFramesNeedsNoWarmupFlag) {
    const fs::path dir = caseDir();
    const fs::path scene = writeGltf(dir, triangleScene());
    expectGraceful({"benchmark", "--scene", scene.string(), "--size", "32x18", "--frames", "3", "--voxels",
                    "32", "--block", "2", "--out", (dir / "out").string(), "--validate"},
                   dir / "out", {Outcome::MustRender, {}, 0});
    expectGraceful({"benchmark", "--scene", scene.string(), "--frames", "3", "--warmup", "3", "--out",
                    (dir / "out").string()},
                   dir / "out", {Outcome::MustFail, {"--warmup"}, 2});
}

// ---- class 13: a symlink planted in --out is replaced, never followed ----

TEST(HostileOutputs, PlantedSymlinksAreReplacedNotFollowed) {
    const fs::path dir = caseDir();
    const fs::path scene = writeGltf(dir, triangleScene());
    fs::create_directories(dir / "out");
    const char* outputs[] = {"final.png",  "final.exr", "timings.json",
                             "direct.exr", "depth.exr", "resample_mask.png"};
    for (const char* name : outputs) {
        test::writeTextFile(dir / (std::string("victim_") + name), "precious");
        fs::create_symlink(dir / (std::string("victim_") + name), dir / "out" / name);
    }
    expectGraceful(renderArgs(scene, dir / "out"), dir / "out", {Outcome::MustRender, {}, 0});
    for (const char* name : outputs) {
        EXPECT_EQ(readText(dir / (std::string("victim_") + name)), "precious")
            << name << " followed the symlink";
        EXPECT_FALSE(fs::is_symlink(dir / "out" / name)) << name;
        EXPECT_TRUE(fs::is_regular_file(dir / "out" / name)) << name;
    }
    // The voxel file of `vct voxelize` too.
    test::writeTextFile(dir / "victim.vdb", "precious");
    fs::create_symlink(dir / "victim.vdb", dir / "out" / "grid.vdb");
    expectGraceful({"voxelize", "--scene", scene.string(), "--voxels", "32", "--out",
                    (dir / "out" / "grid.vdb").string()},
                   dir / "out", {Outcome::MustRender, {}, 0});
    EXPECT_EQ(readText(dir / "victim.vdb"), "precious");
    EXPECT_FALSE(fs::is_symlink(dir / "out" / "grid.vdb"));
}

}  // namespace
}  // namespace vct::hostile
