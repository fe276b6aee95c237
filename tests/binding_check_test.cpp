// Declaring a pass's resources once (render/pass_resources.h): the SPIR-V reflection of the built shaders,
// the check of a pass's bindings against it (vk/binding_check.h), the resource table's own consistency checks
// and the frame-target table (render/frame_targets.h). CPU only: no device is needed.
#include "vk/binding_check.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "core/error.h"
#include "lib/shared.h"
#include "render/pass_resources.h"
#include "test_util.h"
#include "vk/spirv_reflect.h"

namespace vct {
namespace {

const vk::ShaderBinding& find(const std::vector<vk::ShaderBinding>& bindings, uint32_t binding) {
    for (const vk::ShaderBinding& b : bindings)
        if (b.binding == binding) return b;
    throw Error("no binding " + std::to_string(binding));
}

// The message of the vct::Error `f` throws ("" when it throws none).
template <typename F>
std::string errorOf(F&& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(SpirvReflect, TraceShader) {
    const std::vector<vk::ShaderBinding> bindings = vk::reflectBindings(vk::readSpirv("trace.comp"));
    // 9: the environment map (issue 20); 10-13: the history at trace scale 1; the radiance atlas and the brick
    // table (sparse voxel storage, issue 19); the environment's cone layers; the region labels (round 29)
    EXPECT_EQ(bindings.size(), 17u);
    const vk::ShaderBinding& regions = find(bindings, VCT_BINDING_VOXEL_REGIONS);
    EXPECT_EQ(regions.dimension, VK_IMAGE_VIEW_TYPE_3D);
    EXPECT_EQ(regions.texel, vk::TexelClass::Uint);
    EXPECT_EQ(find(bindings, VCT_BINDING_ENVIRONMENT_CONES).dimension, VK_IMAGE_VIEW_TYPE_3D);
    EXPECT_EQ(find(bindings, 0).type, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER);
    EXPECT_EQ(find(bindings, VCT_BINDING_BRICKS).type, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
    EXPECT_EQ(find(bindings, VCT_BINDING_VOXEL_ATLAS).dimension, VK_IMAGE_VIEW_TYPE_3D);
    const vk::ShaderBinding& voxels = find(bindings, 3);
    EXPECT_EQ(voxels.type, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER);
    EXPECT_EQ(voxels.dimension, VK_IMAGE_VIEW_TYPE_3D);
    EXPECT_EQ(voxels.name, "voxels");
    const vk::ShaderBinding& indirect = find(bindings, 4);
    EXPECT_EQ(indirect.type, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE);
    EXPECT_EQ(indirect.format, VK_FORMAT_R32G32B32A32_UINT);
    EXPECT_EQ(indirect.texel, vk::TexelClass::Uint);
    const vk::ShaderBinding& axis = find(bindings, 8);
    EXPECT_EQ(axis.type, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE);
    EXPECT_EQ(axis.format, VK_FORMAT_R16G16B16A16_SFLOAT);
    EXPECT_EQ(axis.dimension, VK_IMAGE_VIEW_TYPE_2D);
    EXPECT_EQ(axis.name, "guideAxisImage");
    for (const vk::ShaderBinding& b : bindings) EXPECT_EQ(b.set, 0u);
}

TEST(SpirvReflect, BuffersUnsignedSamplersAndShadowSamplers) {
    const auto upsample = vk::reflectBindings(vk::readSpirv("upsample.comp"));
    EXPECT_EQ(find(upsample, 13).type, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
    EXPECT_EQ(find(upsample, 1).texel, vk::TexelClass::Uint);  // usampler2D indirectLow
    EXPECT_EQ(find(upsample, 14).texel, vk::TexelClass::Float);
    const auto direct = vk::reflectBindings(vk::readSpirv("direct.comp"));
    EXPECT_TRUE(find(direct, 6).depthCompare);  // sampler2DShadow
    EXPECT_FALSE(find(direct, 2).depthCompare);
    EXPECT_EQ(find(direct, 1).type, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
    EXPECT_THROW(vk::reflectBindings({1, 2, 3, 4, 5}), Error);  // not SPIR-V
}

// What TracePass declares (passes/trace_pass.cpp), spelled out.
std::vector<vk::Binding> traceBindings() {
    constexpr VkShaderStageFlags cs = VK_SHADER_STAGE_COMPUTE_BIT;
    constexpr auto sampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                   storage = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    constexpr auto d2 = VK_IMAGE_VIEW_TYPE_2D;
    return {
        {0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, cs, "frame"},
        {1, sampled, cs, "depth", VK_FORMAT_D32_SFLOAT, d2},
        {2, sampled, cs, "normalRoughness", VK_FORMAT_R16G16B16A16_SFLOAT, d2},
        {3, sampled, cs, "voxels", VK_FORMAT_R16G16B16A16_SFLOAT, VK_IMAGE_VIEW_TYPE_3D},
        {4, storage, cs, "indirectLow", VK_FORMAT_R32G32B32A32_UINT, d2},
        {6, storage, cs, "guidePosition", VK_FORMAT_R32G32B32A32_SFLOAT, d2},
        {7, storage, cs, "guideNormal", VK_FORMAT_R16G16B16A16_SFLOAT, d2},
        {8, storage, cs, "guideAxis", VK_FORMAT_R16G16B16A16_SFLOAT, d2},
        {9, sampled, cs, "environment", VK_FORMAT_R32G32B32A32_SFLOAT, d2},  // the map (issue 20)
        // Trace scale 1's own history while the diffuse cones turn (docs/design.md §6.5).
        {10, sampled, cs, "motion", VK_FORMAT_R16G16_SFLOAT, d2},
        {11, sampled, cs, "prevDepth", VK_FORMAT_D32_SFLOAT, d2},
        {12, sampled, cs, "prevNormalRoughness", VK_FORMAT_R16G16B16A16_SFLOAT, d2},
        {13, sampled, cs, "indirectHistory", VK_FORMAT_R32G32B32A32_UINT, d2},
        // Sparse voxel storage (docs/design.md §5.10): mip 0 of the radiance and the brick table.
        {VCT_BINDING_BRICKS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs, "bricks"},
        {VCT_BINDING_VOXEL_ATLAS, sampled, cs, "radianceAtlas", VK_FORMAT_R16G16B16A16_SFLOAT,
         VK_IMAGE_VIEW_TYPE_3D},
        // The environment as the cones read it (render/environment_cones.h): one slice a cap size.
        {VCT_BINDING_ENVIRONMENT_CONES, sampled, cs, "environmentCones", VK_FORMAT_R32G32B32A32_SFLOAT,
         VK_IMAGE_VIEW_TYPE_3D},
        // The static grid's closed regions (render/voxel_regions.h).
        {VCT_BINDING_VOXEL_REGIONS, sampled, cs, "voxelRegions", VK_FORMAT_R8_UINT, VK_IMAGE_VIEW_TYPE_3D}};
}

std::string checkTrace(const std::vector<vk::Binding>& declared) {
    const std::vector<vk::ShaderInterface> shaders = {
        {VK_SHADER_STAGE_COMPUTE_BIT, "trace.comp", vk::reflectBindings(vk::readSpirv("trace.comp"))}};
    return errorOf([&] { vk::checkBindings("trace", declared, shaders); });
}

TEST(BindingCheck, TheTraceTableMatchesItsShader) {
    EXPECT_EQ(checkTrace(traceBindings()), "");
}

TEST(BindingCheck, FormatMismatchNamesPassBindingAndBothFormats) {
    std::vector<vk::Binding> declared = traceBindings();
    declared[7].format = VK_FORMAT_R32G32B32A32_SFLOAT;  // guideAxis as rgba32f
    const std::string error = checkTrace(declared);
    EXPECT_NE(error.find("trace: binding 8 (guideAxis)"), std::string::npos) << error;
    EXPECT_NE(error.find("storage image rgba32f"), std::string::npos) << error;
    EXPECT_NE(error.find("trace.comp declares a storage image rgba16f"), std::string::npos) << error;
}

TEST(BindingCheck, TypeMismatchNamesBothTypes) {
    std::vector<vk::Binding> declared = traceBindings();
    declared[3].type = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;  // voxels as a storage image
    const std::string error = checkTrace(declared);
    EXPECT_NE(error.find("binding 3 (voxels)"), std::string::npos) << error;
    EXPECT_NE(error.find("storage image"), std::string::npos) << error;
    EXPECT_NE(error.find("combined image sampler"), std::string::npos) << error;
}

TEST(BindingCheck, MissingStaleAndMisplacedBindings) {
    std::vector<vk::Binding> missing = traceBindings();
    missing.erase(missing.begin() + 7);  // guideAxis
    EXPECT_NE(
        checkTrace(missing).find("binding 8: trace.comp declares a storage image rgba16f ('guideAxisImage'), "
                                 "which the pass does not bind"),
        std::string::npos)
        << checkTrace(missing);

    std::vector<vk::Binding> stale = traceBindings();
    stale.push_back({14, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT, "debug"});
    EXPECT_NE(checkTrace(stale).find("binding 14 (debug)"), std::string::npos) << checkTrace(stale);

    std::vector<vk::Binding> wrongStage = traceBindings();
    wrongStage[1].stages = VK_SHADER_STAGE_FRAGMENT_BIT;
    EXPECT_NE(checkTrace(wrongStage).find("binding 1 (depth)"), std::string::npos) << checkTrace(wrongStage);
}

TEST(BindingCheck, DimensionTexelTypeAndComparison) {
    std::vector<vk::Binding> flat = traceBindings();
    flat[3].dimension = VK_IMAGE_VIEW_TYPE_2D;
    EXPECT_NE(checkTrace(flat).find("a 2D image, trace.comp declares a 3D one"), std::string::npos)
        << checkTrace(flat);

    std::vector<vk::Binding> uintDepth = traceBindings();
    uintDepth[1].format = VK_FORMAT_R32_UINT;
    EXPECT_NE(checkTrace(uintDepth).find("uint texels"), std::string::npos) << checkTrace(uintDepth);

    std::vector<vk::Binding> compare = traceBindings();
    compare[1].depthCompare = true;
    EXPECT_NE(checkTrace(compare).find("depth-comparison"), std::string::npos) << checkTrace(compare);
}

// End to end: a shader whose declaration disagrees with its pass's table stops the renderer at pipeline
// creation with that one message.
TEST(BindingCheck, AShaderThatDisagreesWithItsPassStopsTheRenderer) {
    namespace fs = std::filesystem;
    // The build needs glslangValidator, so it is there wherever the tests were built; a build carried to another
    // machine (the GPU machine of benchmarks/README.md, round 7) may lack it.
    if (access(VCT_GLSLANG, X_OK) != 0)
        GTEST_SKIP() << VCT_GLSLANG << " is not here: nothing to compile with";
    const fs::path dir = test::freshOutputDir("binding_check/shaders");
    fs::copy(VCT_SHADER_DIR, dir, fs::copy_options::recursive);
    std::ifstream in(fs::path(VCT_SHADER_SOURCE_DIR) / "trace.comp");
    std::stringstream source;
    source << in.rdbuf();
    std::string text = source.str();
    const std::string from = "binding = 8, rgba16f", to = "binding = 8, rgba32f";
    ASSERT_NE(text.find(from), std::string::npos);
    text.replace(text.find(from), from.size(), to);
    std::ofstream(dir / "trace.comp") << text;
    const std::string compile = std::string(VCT_GLSLANG) + " --target-env vulkan1.3 -I" +
                                VCT_SHADER_SOURCE_DIR + " -o " + (dir / "trace.comp.spv").string() + " " +
                                (dir / "trace.comp").string() + " > /dev/null";
    ASSERT_EQ(std::system(compile.c_str()), 0) << compile;

    setenv("VCT_SHADER_DIR", dir.c_str(), 1);
    const test::RunResult run =
        test::runVct({"render", "--scene", "cornell", "--size", "32x18", "--frames", "1", "--out",
                      test::freshOutputDir("binding_check/out").string()});
    unsetenv("VCT_SHADER_DIR");
    ASSERT_TRUE(run.exited()) << run.describe();
    EXPECT_NE(run.exitCode, 0) << run.describe();
    EXPECT_NE(run.err.find("trace: binding 8 (guideAxis): the pass binds a storage image rgba16f, trace.comp "
                           "declares a storage image rgba32f ('guideAxisImage')"),
              std::string::npos)
        << run.err;
}

TEST(ResourceTable, DerivesDescriptorTypesAndTargetFormats) {
    const ResourceTable table("test", {{0, Resource::frameUniforms(), Access::Uniform},
                                       {1, Target::depth, Access::Sampled},
                                       {2, Target::guideAxis, Access::Write},
                                       {3, Resource::scene(SceneBuffer::Lights), Access::Read},
                                       {4, Target::shadowMap, Access::SampledCompare},
                                       {kNoBinding, Target::motion, Access::ColorAttachment}});
    const std::vector<vk::Binding> b = table.bindings();
    ASSERT_EQ(b.size(), 5u);
    EXPECT_EQ(b[0].type, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER);
    EXPECT_EQ(b[1].type, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER);
    EXPECT_EQ(b[1].format, VK_FORMAT_D32_SFLOAT);
    EXPECT_EQ(b[2].type, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE);
    EXPECT_EQ(b[2].format, targetDesc(Target::guideAxis).format);
    EXPECT_EQ(b[2].name, "guideAxis");
    EXPECT_EQ(b[3].type, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
    EXPECT_TRUE(b[4].depthCompare);
    EXPECT_EQ(table.colorFormats(), std::vector<VkFormat>{VK_FORMAT_R16G16_SFLOAT});
}

TEST(ResourceTable, RejectsTablesThatContradictThemselves) {
    auto error = [](std::vector<ResourceRow> rows) {
        return errorOf([&] { ResourceTable("p", std::move(rows)); });
    };
    EXPECT_NE(
        error({{1, Target::depth, Access::Sampled}, {1, Target::motion, Access::Sampled}}).find("binding 1"),
        std::string::npos);
    EXPECT_NE(error({{kNoBinding, Target::depth, Access::Sampled}}), "");  // a descriptor without binding
    EXPECT_NE(error({{2, Target::depth, Access::ColorAttachment}}), "");   // an attachment with one
    EXPECT_NE(error({{2, Resource::scene(SceneBuffer::Lights), Access::Sampled}}), "");  // a buffer sampled
    EXPECT_NE(error({{1, Target::direct, Access::Sampled}, {2, Target::direct, Access::Write}}),
              "");  // two layouts
    EXPECT_EQ(error({{1, Target::direct, Access::Read}, {2, Target::direct, Access::Write}}),
              "");  // read-write
}

TEST(FrameTargetTable, NamesAreUniqueAndHistoriesMatchTheirPartners) {
    std::set<std::string> names;
    for (const TargetDesc& row : kTargets) {
        EXPECT_TRUE(names.insert(row.name).second) << row.name;
        EXPECT_NE(row.format, VK_FORMAT_UNDEFINED) << row.name;
        if (row.historyOf == Target::count) continue;
        const TargetDesc& of = targetDesc(row.historyOf);
        EXPECT_EQ(row.format, of.format) << row.name;
        EXPECT_EQ(row.size, of.size) << row.name;
        EXPECT_EQ(row.usage, of.usage) << row.name;
        EXPECT_NE(row.swap, HistorySwap::None) << row.name;
    }
    EXPECT_STREQ(targetDesc(Target::prevDepth).name, "prevDepth");
    EXPECT_EQ(targetDesc(Target::prevDepth).historyOf, Target::depth);
    EXPECT_EQ(targetDesc(Target::indirectHistory).swap, HistorySwap::EveryFrame);
}

}  // namespace
}  // namespace vct
