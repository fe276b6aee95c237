#include "passes/voxel_bounce_pass.h"

#include <algorithm>

#include "passes/voxel_source.h"
#include "render/settings.h"

namespace vct {

namespace {

// Rounds of every slab after the grid last changed. Each round adds at least one bounce; a furnace of albedo ρ
// misses ρ^(rounds + 1) of its light after them (ρ = 0.8: 1.4 % after 18 rounds).
constexpr uint32_t kSettleRounds = 18;

// `--bounces all` starts from the light of this many bounces: on its first frame the whole grid gathers
// kWarmStartBounces − 1 times. Without it the light rose over the first rounds (N/4 frames each): cornell at
// 320×180 had 0.64 of the full GI after 16 frames at 64³ (0.54 at 128³) and 0.925 after 64 (0.790); starting
// from 4 bounces, 0.90 (0.83) and 0.942 (0.867), before round 11's cone samples. From 2 or 3 bounces, 0.934 /
// 0.939 after 64 frames at 64³ and 0.830 / 0.853 at 128³ (benchmarks/README.md, round 11). The price, once per
// load: 3 whole-grid gathers, on lavapipe 0.3 s at 64³, 1.7 s at 128³ and 13 s at 256³ (cornell), against rounds
// of 16, 128 or 1024 frames there (bandsPerLayer).
constexpr uint32_t kWarmStartBounces = 4;

// Binding numbers: shaders/voxel_bounce.comp's.
ResourceTable bounceResources(VoxelGrid& grid, const EnvironmentSource& environment) {
    std::vector<ResourceRow> rows{{VCT_BINDING_FRAME, Resource::frameUniforms(), Access::Uniform},
                                  {1, Resource::image("albedo", grid.albedo()), Access::Read},
                                  {2, Resource::image("normal", grid.normal()), Access::Read},
                                  {4, Resource::image("bounce", grid.bounce()), Access::Write}};
    VoxelSource::of(grid).addRows(rows, 3);
    // Cones that leave the grid see the environment: sky light bounces too.
    environment.addRows(rows, 5);
    return {"bounce", std::move(rows)};
}

}  // namespace

// Slabs of the grid for `--bounces all`: a layer of bricks (4 voxels deep) each, 16 slabs at 64³, whose gather took
// 0.10× cornell's default frame at 640×360 on lavapipe (with 8 slabs of two layers 0.20×: benchmarks/README.md,
// round 10). A layer holds more bricks at finer grids: at 128³ its gather cost 1.36× the one-bounce frame on
// lavapipe, at 256³ 4× (round 10). On a CPU device each layer is therefore cut into bands along y, so that a slab
// holds no more than a 64³ layer's 16 × 16 brick places: 4 bands at 128³ (128 slabs), 16 at 256³ (1024), the gather
// 0.29× and 0.07× of one layer's (round 11). The rounds are longer instead (the light after a change converges
// more slowly; cornell at 128³ has 0.83 of the full GI after 64 frames instead of 0.87), which a GPU need not
// pay: there a slab stays a whole layer.
constexpr uint32_t kCpuSlabBrickPlaces = 16 * 16;

uint32_t VoxelBouncePass::bandsPerLayer(uint32_t resolution, bool cpuDevice) {
    const uint32_t side = std::max(resolution / VCT_VOXEL_BRICK, 1u);
    return cpuDevice ? std::max(side * side / kCpuSlabBrickPlaces, 1u) : 1u;
}

uint32_t VoxelBouncePass::slabCount(uint32_t resolution, uint32_t bands) {
    return std::max(resolution / VCT_VOXEL_BRICK, 1u) * bands;
}

VoxelRegion VoxelBouncePass::slab(uint32_t resolution, uint32_t bands, uint32_t i) {
    const uint32_t n = resolution;
    const uint32_t layer = i / bands, band = i % bands, rows = n / bands;  // rows: voxels, whole bricks
    return {glm::uvec3(0u, band * rows, layer * VCT_VOXEL_BRICK),
            glm::uvec3(n, (band + 1) * rows, (layer + 1) * VCT_VOXEL_BRICK)};
}

uint32_t VoxelBouncePass::settleFrames() const {
    return slabCount(grid_.resolution(), bands_) * kSettleRounds;
}

VoxelBouncePass::VoxelBouncePass(const vk::Context& context, VoxelGrid& grid, InjectPass& inject,
                                 VoxelMipsPass& mips, uint32_t bounces, uint32_t coneLanes,
                                 const EnvironmentSource& environment)
    : grid_(grid),
      inject_(inject),
      mips_(mips),
      iterations_(bounces == kAllBounces || bounces < 2 ? 0 : bounces - 1),
      bands_(
          bandsPerLayer(grid.resolution(), context.properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU)),
      resources_(bounceResources(grid, environment)) {
    pipeline_ = vk::Pipeline::compute(context, name(), "voxel_bounce.comp", resources_.bindings(),
                                      sizeof(gpu::VoxelBouncePushConstants),
                                      grid.specialization({voxelPassLanes(context), coneLanes}));
    if (amortised()) {
        // Every frame's inject reads the gathers, the first one before any gather ran: none yet.
        context.submitAndWait([&](VkCommandBuffer cmd) {
            grid.bounce().use(cmd, vk::ImageAccess::TransferDst);
            const VkClearColorValue zero{};
            const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
            vkCmdClearColorImage(cmd, grid.bounce().handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero, 1,
                                 &all);
        });
    }
}

void VoxelBouncePass::gather(const FrameContext& frame, const std::optional<VoxelRegion>& region) {
    pipeline_.bind(frame.cmd);
    resources_.bind(frame, pipeline_);
    const gpu::VoxelBouncePushConstants push{region ? glm::uvec4(region->min, 1u) : glm::uvec4(0u)};
    pipeline_.pushConstants(frame.cmd, &push, sizeof(push));
    if (region)
        dispatchRegionBricks(frame.cmd, *region);
    else
        dispatchBricks(frame.cmd, grid_.bricks().brickCount());
}

void VoxelBouncePass::execute(const FrameContext& frame) {
    if (amortised() && !warmStarted_) {
        // The first frame: the gathers start from nothing (the atlas was cleared), so the whole grid gathers as
        // `--bounces kWarmStartBounces` does; the slabs carry on from there.
        warmStarted_ = true;
        wholeGridIterations(frame, kWarmStartBounces - 1);
        return;
    }
    if (amortised()) {
        // This frame's slab gathers from the grid as it stands and sends the result on at once.
        const VoxelRegion region = slab(grid_.resolution(), bands_, nextSlab_);
        nextSlab_ = (nextSlab_ + 1) % slabCount(grid_.resolution(), bands_);
        gather(frame, region);
        inject_.inject(frame, true, region);
        mips_.update(frame, region);
        return;
    }
    wholeGridIterations(frame, iterations_);
}

void VoxelBouncePass::wholeGridIterations(const FrameContext& frame, uint32_t iterations) {
    for (uint32_t i = 0; i < iterations; ++i) {
        // Gather from the grid as it stands (its mips included)...
        gather(frame, std::nullopt);
        // ...and send it on: direct light + albedo × gathered, and the mips of that.
        inject_.inject(frame, true, grid_.injectRegion());
        mips_.execute(frame);
    }
}

}  // namespace vct
