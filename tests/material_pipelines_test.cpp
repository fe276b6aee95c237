// Material textures per pipeline (render/scene_draw.h MaterialPipelines, lib/surface.glsl materialTextureOr): on
// a CPU device the G-buffer has one pipeline per set of textured slots among the scene's materials, and a slot
// without a texture is not sampled. These tests check that every material is still drawn with its own textures.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "io/image_io.h"
#include "render/gpu_scene.h"
#include "test_util.h"

namespace vct {
namespace {

namespace fs = std::filesystem;

TEST(MaterialPipelines, TexturedSlotsNameTheSlotsThatHaveATexture) {
    Material none;
    EXPECT_EQ(GpuScene::texturedSlots(none), 0u);
    Material bumpy;
    bumpy.normalTexture = 0;
    bumpy.metallicRoughnessTexture = 3;
    EXPECT_EQ(GpuScene::texturedSlots(bumpy),
              (1u << VCT_TEXTURE_SLOT_NORMAL) | (1u << VCT_TEXTURE_SLOT_METALLIC_ROUGHNESS));
    Material all;
    all.baseColorTexture = all.metallicRoughnessTexture = all.normalTexture = all.emissiveTexture =
        all.occlusionTexture = 1;
    EXPECT_EQ(GpuScene::texturedSlots(all), VCT_EVERY_TEXTURE_SLOT);
    EXPECT_EQ(VCT_EVERY_TEXTURE_SLOT, 31u);
}

// The G-buffer's roughness of the pixels where the path tracer saw surface `id`: {min, max, count}.
struct Range {
    float min = 1e30f, max = -1e30f;
    size_t count = 0;
};
Range roughnessOn(const ImageRgba32f& roughness, const ImageRgba32f& ids, float id) {
    Range r;
    for (size_t i = 0; i < size_t(ids.width) * ids.height; ++i) {
        if (ids.pixels[i * 4] != id) continue;
        r.min = std::min(r.min, roughness.pixels[i * 4]);
        r.max = std::max(r.max, roughness.pixels[i * 4]);
        ++r.count;
    }
    return r;
}

// cornell's floor has only a metallic-roughness texture (stripes of roughness 0.05 and 0.8), its back wall only
// a normal map (bumps, roughness factor 0.35), the red wall none (roughness 0.9): three pipelines on lavapipe.
// Each must sample what its material has: the floor's stripes, the back wall's bumps (at 160×90 its mip-mapped
// normals average flat, and Toksvig widens its roughness from the map's shortened normals), and the red wall
// exactly its factor.
TEST(MaterialPipelinesGpu, EveryMaterialIsDrawnWithItsOwnTextures) {
    const fs::path dir = test::freshOutputDir("material_pipelines/render");
    const fs::path ref = test::freshOutputDir("material_pipelines/reference");
    auto r = test::runVct({"render", "--scene", "cornell", "--size", "160x90", "--frames", "1", "--aux",
                           "--out", dir.string()});
    ASSERT_TRUE(r.exited() && r.exitCode == 0) << r.describe();
    // The path tracer's surface ids (cornell's surfaces: floor 0, back wall 2, red wall 4) at the same frame.
    r = test::runVct(
        {"reference", "--scene", "cornell", "--size", "160x90", "--spp", "1", "--out", ref.string()});
    ASSERT_TRUE(r.exited() && r.exitCode == 0) << r.describe();
    // Without --bounces the reference is the truth of vct's default: every bounce.
    std::ifstream referenceJson(ref / "reference.json");
    EXPECT_EQ(nlohmann::json::parse(referenceJson).at("bounces"), "all");
    const ImageRgba32f ids = readExr(ref / "surface_id.exr");
    const ImageRgba32f roughness = readExr(dir / "roughness.exr");
    ASSERT_EQ(ids.width, roughness.width);

    // Measured on lavapipe: floor 0.051 to 0.800, back wall 0.690 everywhere, red wall 0.900.
    const Range floor = roughnessOn(roughness, ids, 0.0f);
    ASSERT_GT(floor.count, 1000u);
    EXPECT_LT(floor.min, 0.1f) << "the floor's roughness stripes are missing";
    EXPECT_GT(floor.max, 0.7f) << "the floor's roughness stripes are missing";
    const Range back = roughnessOn(roughness, ids, 2.0f);
    ASSERT_GT(back.count, 1000u);
    EXPECT_GT(back.min, 0.6f) << "the back wall's normal map was not sampled (its factor alone: 0.35)";
    const Range red = roughnessOn(roughness, ids, 4.0f);
    ASSERT_GT(red.count, 1000u);
    EXPECT_NEAR(red.min, 0.9f, 1e-3f);
    EXPECT_NEAR(red.max, 0.9f, 1e-3f);
}

}  // namespace
}  // namespace vct
