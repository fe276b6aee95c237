// A pass's resources, declared once: one table row per resource (which one, how the pass touches it, the
// binding number its shader declares it at, the stages that use it). From the table follow the pipeline's
// descriptor-set layout (bindings(), checked against the shader's SPIR-V when the pipeline is made:
// vk/binding_check.h), the image and buffer barriers before the work (barriers()) and the descriptor writes
// (writer()).
//
//     resources_("trace", {{VCT_BINDING_FRAME, Resource::frameUniforms(), Access::Uniform},
//                          {1, Target::depth, Access::Sampled},
//                          {8, Target::guideAxis, Access::Write}, ...});
//     resources_.bind(frame, pipeline_);  // barriers, then every descriptor pushed
//
// Binding numbers are written in the table and in the shader's layout(binding = N); the check at pipeline
// creation is what keeps the two in agreement (type, image format, dimension, texel type, stages).
#pragma once

#include <string>
#include <vector>

#include "render/frame_targets.h"
#include "vk/buffer.h"
#include "vk/image.h"
#include "vk/pipeline.h"

namespace vct {

struct FrameContext;

// How a pass touches a resource. Read, Write and ReadWrite are imageLoad / imageStore on a storage image, or
// a storage buffer's reads and writes. The last five are no descriptor (binding kNoBinding): render targets,
// an indirect dispatch's arguments, copies.
enum class Access : uint8_t {
    Uniform,  // uniform buffer
    Sampled,  // texture(): combined image sampler (the renderer's nearest sampler, or the resource's own)
    SampledCompare,  // texture() on a sampler2DShadow: the renderer's depth-comparison sampler
    Read,
    Write,  // the contents before are not needed (an image may be discarded)
    ReadWrite,
    ColorAttachment,  // in row order: the pipeline's colour attachments 0, 1, …
    DepthAttachment,
    IndirectRead,
    TransferRead,
    TransferWrite,
};

// The scene's buffers (render/gpu_scene.h): written before the frame, read by shaders, never barriered.
enum class SceneBuffer : uint8_t { Instances, Materials, Vertices, Indices, Lights };

// Where a row's resource comes from when the pass runs.
struct Resource {
    enum class Kind : uint8_t { Target, TargetBuffer, FrameUniforms, Scene, Image, Buffer, PerDraw };

    Resource(Target t)
        : kind(Kind::Target), name(targetDesc(t).name), target(t) {}  // implicit: rows name targets
    static Resource frameUniforms() { return {Kind::FrameUniforms, "frame"}; }
    static Resource scene(SceneBuffer buffer);
    // FrameTargets' buffers (resampleList, resampleCount).
    static Resource targetBuffer(const char* name, vk::Buffer FrameTargets::*member);
    // An image or buffer the pass owns or was given (voxel volumes, the DFG table), sampled with `sampler`
    // where it is sampled.
    static Resource image(const char* name, vk::Image& image, VkSampler sampler = VK_NULL_HANDLE);
    static Resource buffer(const char* name, vk::Buffer& buffer);
    // A descriptor the pass writes itself at each draw or dispatch (material textures, the accumulator being
    // voxelized): in the layout and the check, not in barriers() or writer(). `buffer`: a storage buffer,
    // else a 2D texture.
    static Resource perDraw(const char* name, bool buffer = false);
    // This image, with the descriptor written by the pass at each dispatch (one mip level at a time) but its
    // barrier from the table.
    Resource eachDispatch() const;
    // This image's mip level `level` alone is bound (its barrier still covers every level).
    Resource atLevel(int level) const;

    Kind kind;
    const char* name;
    Target target = Target::count;
    SceneBuffer sceneBuffer = SceneBuffer::Instances;
    vk::Buffer FrameTargets::*targetMember = nullptr;
    vk::Image* ownImage = nullptr;
    vk::Buffer* ownBuffer = nullptr;
    VkSampler sampler = VK_NULL_HANDLE;
    int level = -1;
    bool perDrawBuffer = false;
    bool writtenByPass = false;  // perDraw and eachDispatch

  private:
    Resource(Kind k, const char* n) : kind(k), name(n) {}
};

constexpr uint32_t kNoBinding = ~0u;

struct ResourceRow {
    uint32_t binding;  // the shader's layout(set = 0, binding = N); kNoBinding for uses without a descriptor
    Resource resource;
    Access access;
    VkShaderStageFlags stages = VK_SHADER_STAGE_COMPUTE_BIT;
};

class ResourceTable {
  public:
    ResourceTable() = default;
    // `owner` names the pass in errors. Throws on a table that contradicts itself (a binding twice, a
    // descriptor access without a binding or the reverse, one image used two incompatible ways).
    ResourceTable(std::string owner, std::vector<ResourceRow> rows);

    const std::string& owner() const { return owner_; }
    const std::vector<ResourceRow>& rows() const { return rows_; }

    // The descriptor-set layout, with what the pipeline's check compares with the shaders.
    std::vector<vk::Binding> bindings() const;
    // Graphics pipelines: the ColorAttachment rows' formats in order, and the DepthAttachment row's.
    std::vector<VkFormat> colorFormats() const;
    VkFormat depthFormat() const;
    // The attachments themselves, in the same order (null: no depth attachment).
    std::vector<vk::Image*> colorAttachments(FrameTargets& targets) const;
    vk::Image* depthAttachment(FrameTargets& targets) const;

    // Every resource the table can reach (targets, own images and buffers) to the use the table declares for
    // it: the barriers the work needs after whatever used them before.
    void barriers(const FrameContext& frame) const;
    // The descriptors of every row but the perDraw and eachDispatch ones, which the caller adds.
    vk::DescriptorWriter writer(const FrameContext& frame) const;
    // barriers(), then writer() pushed: a pass with nothing to bind per dispatch.
    void bind(const FrameContext& frame, const vk::Pipeline& pipeline) const;

  private:
    // One resource the barriers reach, with the union of the table's uses of it.
    struct Use {
        size_t row;  // the first row naming it
        vk::ImageAccess image = vk::ImageAccess::Undefined;
        vk::BufferAccess buffer = vk::BufferAccess::None;
    };

    std::string owner_;
    std::vector<ResourceRow> rows_;
    std::vector<Use> uses_;
};

}  // namespace vct
