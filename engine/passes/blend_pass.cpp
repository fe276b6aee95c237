#include "passes/blend_pass.h"

#include <algorithm>

namespace vct {

namespace {

// Binding numbers: shaders/gbuffer.vert's (the scene-drawing rows and last frame's deformed vertices) and
// shaders/blend.frag's.
constexpr uint32_t kPreviousVertices = 8;

ResourceTable blendResources(DfgLut& dfg, vk::Image& voxelStandIn, vk::Image& regionStandIn,
                             vk::Buffer& brickStandIn, const VoxelSource* voxels,
                             const EnvironmentSource& environment) {
    constexpr VkShaderStageFlags fragment = VK_SHADER_STAGE_FRAGMENT_BIT;
    std::vector<ResourceRow> rows = sceneDrawRows();
    rows.push_back({kPreviousVertices, Resource::perDraw("previousVertices", true), Access::Read,
                    VK_SHADER_STAGE_VERTEX_BIT});
    rows.push_back({9, Resource::scene(SceneBuffer::Lights), Access::Read, fragment});
    rows.push_back({10, Target::shadowMap, Access::SampledCompare, fragment});
    VoxelSource standIn;
    standIn.radianceMips = standIn.radianceAtlas = &voxelStandIn;
    standIn.brickTable = &brickStandIn;
    standIn.regionLabels = &regionStandIn;
    (voxels ? *voxels : standIn).addRows(rows, 11, fragment);
    environment.addRows(rows, 12, fragment);
    rows.push_back({13, Resource::image("dfg", dfg.image(), dfg.sampler()), Access::Sampled, fragment});
    // The layer (cleared, then each surface "over" it), tested against the opaque frame's depth.
    rows.push_back({kNoBinding, Target::transparent, Access::ColorAttachment});
    rows.push_back({kNoBinding, Target::depth, Access::DepthAttachment});
    return {"blend", std::move(rows)};
}

vk::Image voxelStandIn(const vk::Context& context, const VoxelSource* voxels,
                       VkFormat format = VK_FORMAT_R16G16B16A16_SFLOAT) {
    if (voxels) return vk::Image();
    vk::ImageDesc desc;
    desc.depth = 2;  // a 3D image, as the shader's sampler3D (usampler3D for the region labels)
    desc.format = format;
    desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT;
    return vk::Image(context, desc);
}

}  // namespace

std::vector<DrawItem> blendedDrawsBackToFront(const GpuScene& gpuScene, const glm::mat4& view) {
    const Scene& scene = gpuScene.scene();
    std::vector<DrawItem> items = sceneDrawItems(gpuScene, DrawSet::Blended);
    std::vector<std::pair<float, DrawItem>> keyed;
    keyed.reserve(items.size());
    for (const DrawItem& item : items) {
        const Instance& instance = gpuScene.instances()[item.instance];
        const Primitive& primitive =
            scene.primitives[scene.meshes[size_t(instance.mesh)].primitives[item.meshPrimitive]];
        const Aabb world = primitive.bounds.transformed(instance.world);
        const glm::vec3 centre = 0.5f * (world.min + world.max);
        // The camera looks along −z in view space: the distance in front of it is −z.
        keyed.push_back({-(view * glm::vec4(centre, 1.0f)).z, item});
    }
    std::stable_sort(keyed.begin(), keyed.end(),
                     [](const auto& a, const auto& b) { return a.first > b.first; });
    for (size_t i = 0; i < keyed.size(); ++i) items[i] = keyed[i].second;
    return items;
}

BlendPass::BlendPass(const vk::Context& context, const VoxelSource* voxels,
                     const EnvironmentSource& environment, DfgLut& dfg, const Scene& scene, bool vertexColors,
                     bool textureLod0)
    : voxelStandIn_(voxelStandIn(context, voxels)),
      regionStandIn_(voxelStandIn(context, voxels, VK_FORMAT_R8_UINT)),
      brickStandIn_(
          voxels ? vk::Buffer()
                 : vk::Buffer(context, 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::DeviceLocal)),
      resources_(blendResources(dfg, voxelStandIn_, regionStandIn_, brickStandIn_, voxels, environment)) {
    vk::Pipeline::GraphicsDesc desc;
    desc.owner = name();
    desc.vertexShader = "gbuffer.vert";  // the same vertices and attributes as the opaque surfaces
    desc.fragmentShader = "blend.frag";
    desc.colorFormats = resources_.colorFormats();
    desc.depthFormat = resources_.depthFormat();
    desc.bindings = resources_.bindings();
    desc.pushConstantSize = sizeof(gpu::DrawPushConstants);
    desc.depthWrite = false;
    desc.blendOver = true;
    // VCT_SPEC_VERTEX_COLORS, then the voxels' (GI off: the shader reads no voxel).
    desc.specialization = voxels ? voxels->specialization({vertexColors ? 1u : 0u})
                                 : withConeVoxels({vertexColors ? 1u : 0u}, false, false);
    pipelines_ = MaterialPipelines(context, desc, scene, DrawSet::Blended, textureLod0);
}

void BlendPass::execute(const FrameContext& frame) {
    FrameTargets& t = frame.targets;
    resources_.barriers(frame);
    VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    color.imageView = resources_.colorAttachments(t)[0]->view();
    color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    color.loadOp =
        VK_ATTACHMENT_LOAD_OP_CLEAR;  // nothing blended: transparent black, composite keeps the frame
    color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    color.clearValue.color = {{0.0f, 0.0f, 0.0f, 0.0f}};
    VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth.imageView = resources_.depthAttachment(t)->view();
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;  // the opaque frame's depth, tested, kept as it is
    depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    beginSceneRendering(frame.cmd, {t.width, t.height}, {color}, depth);
    drawItems(frame, pipelines_, resources_, blendedDrawsBackToFront(frame.scene, frame.uniforms.view),
              kPreviousVertices);
    vkCmdEndRendering(frame.cmd);
}

}  // namespace vct
