#include "passes/voxel_view_pass.h"

#include "core/error.h"
#include "passes/voxel_source.h"

namespace vct {

namespace {

vk::Image makeOutput(const vk::Context& context, uint32_t width, uint32_t height) {
    vk::ImageDesc desc;
    desc.width = width;
    desc.height = height;
    desc.format = VK_FORMAT_R16G16B16A16_SFLOAT;
    desc.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    return vk::Image(context, desc);
}

// Binding numbers: shaders/voxel_view.comp's.
ResourceTable viewResources(VoxelGrid& grid, vk::Image& output) {
    std::vector<ResourceRow> rows{{VCT_BINDING_FRAME, Resource::frameUniforms(), Access::Uniform},
                                  {2, Resource::image("output", output), Access::Write}};
    VoxelSource::of(grid).addRows(rows, 1, VK_SHADER_STAGE_COMPUTE_BIT, /*cones=*/false);
    return {"voxel_view", std::move(rows)};
}

}  // namespace

VoxelViewPass::VoxelViewPass(const vk::Context& context, VoxelGrid& grid)
    : context_(context),
      grid_(grid),
      // 1×1 until prepare() sizes it; made here so that the pipeline's check sees its format.
      output_(makeOutput(context, 1, 1)),
      resources_(viewResources(grid, output_)) {
    pipeline_ = vk::Pipeline::compute(context, name(), "voxel_view.comp", resources_.bindings(),
                                      sizeof(gpu::VoxelViewPushConstants), grid.specialization());
}

void VoxelViewPass::prepare(uint32_t mip, uint32_t width, uint32_t height) {
    if (mip >= grid_.mipCount())
        throw Error("voxel view: mip " + std::to_string(mip) + " is not in 0.." +
                    std::to_string(grid_.mipCount() - 1));
    mip_ = mip;
    if (output_.width() != width || output_.height() != height) output_ = makeOutput(context_, width, height);
}

void VoxelViewPass::execute(const FrameContext& frame) {
    pipeline_.bind(frame.cmd);
    resources_.bind(frame, pipeline_);
    gpu::VoxelViewPushConstants push{};
    push.params.x = mip_;
    pipeline_.pushConstants(frame.cmd, &push, sizeof(push));
    vkCmdDispatch(frame.cmd, tileCount(output_.width()), tileCount(output_.height()), 1);
}

}  // namespace vct
