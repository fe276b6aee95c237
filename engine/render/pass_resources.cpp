#include "render/pass_resources.h"

#include "core/error.h"
#include "render/pass.h"

namespace vct {

namespace {

bool isDescriptor(Access access) {
    return access <= Access::ReadWrite;
}

bool isImage(const Resource& r) {
    return r.kind == Resource::Kind::Target || r.kind == Resource::Kind::Image ||
           (r.kind == Resource::Kind::PerDraw && !r.perDrawBuffer);
}

bool isTracked(const Resource& r) {
    using Kind = Resource::Kind;
    return r.kind == Kind::Target || r.kind == Kind::Image || r.kind == Kind::TargetBuffer ||
           r.kind == Kind::Buffer;
}

bool sameResource(const Resource& a, const Resource& b) {
    return a.kind == b.kind && a.target == b.target && a.targetMember == b.targetMember &&
           a.ownImage == b.ownImage && a.ownBuffer == b.ownBuffer;
}

vk::ImageAccess imageAccess(Access access) {
    switch (access) {
        case Access::Sampled:
        case Access::SampledCompare:
            return vk::ImageAccess::Sampled;
        case Access::Read:
            return vk::ImageAccess::StorageRead;
        case Access::Write:
            return vk::ImageAccess::StorageWrite;
        case Access::ReadWrite:
            return vk::ImageAccess::StorageReadWrite;
        case Access::ColorAttachment:
            return vk::ImageAccess::ColorAttachment;
        case Access::DepthAttachment:
            return vk::ImageAccess::DepthAttachment;
        case Access::TransferRead:
            return vk::ImageAccess::TransferSrc;
        case Access::TransferWrite:
            return vk::ImageAccess::TransferDst;
        default:
            return vk::ImageAccess::Undefined;
    }
}

vk::BufferAccess bufferAccess(Access access) {
    using B = vk::BufferAccess;
    switch (access) {
        case Access::Read:
            return B::ShaderRead;
        case Access::Write:
            return B::ShaderWrite;
        case Access::ReadWrite:
            return B::ShaderRead | B::ShaderWrite;
        case Access::IndirectRead:
            return B::IndirectRead;
        case Access::TransferRead:
            return B::TransferRead;
        case Access::TransferWrite:
            return B::TransferWrite;
        default:
            return B::None;
    }
}

// Two uses of one image in one table: storage reads and writes combine; anything else must agree.
bool mergeImageAccess(vk::ImageAccess& into, vk::ImageAccess next) {
    using I = vk::ImageAccess;
    auto storage = [](I a) {
        return a == I::StorageRead || a == I::StorageWrite || a == I::StorageReadWrite;
    };
    if (into == I::Undefined || into == next)
        into = next;
    else if (storage(into) && storage(next))
        into = I::StorageReadWrite;
    else
        return false;
    return true;
}

VkDescriptorType descriptorType(const ResourceRow& row) {
    switch (row.access) {
        case Access::Uniform:
            return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
        case Access::Sampled:
        case Access::SampledCompare:
            return VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        default:
            return isImage(row.resource) ? VK_DESCRIPTOR_TYPE_STORAGE_IMAGE
                                         : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    }
}

vk::Image* imageOf(const Resource& r, FrameTargets& targets) {
    if (r.kind == Resource::Kind::Target) return &targets.image(r.target);
    return r.ownImage;
}

vk::Buffer* bufferOf(const Resource& r, FrameTargets& targets) {
    if (r.kind == Resource::Kind::TargetBuffer) return &(targets.*r.targetMember);
    return r.ownBuffer;
}

VkBuffer sceneBuffer(const GpuScene& scene, SceneBuffer buffer) {
    switch (buffer) {
        case SceneBuffer::Instances:
            return scene.instanceBuffer();
        case SceneBuffer::Materials:
            return scene.materialBuffer();
        case SceneBuffer::Vertices:
            return scene.vertexBuffer();
        case SceneBuffer::Indices:
            return scene.indexBuffer();
        case SceneBuffer::Lights:
            return scene.lightBuffer();
    }
    return VK_NULL_HANDLE;
}

}  // namespace

Resource Resource::scene(SceneBuffer buffer) {
    static constexpr const char* names[] = {"instances", "materials", "vertices", "indices", "lights"};
    Resource r(Kind::Scene, names[size_t(buffer)]);
    r.sceneBuffer = buffer;
    return r;
}

Resource Resource::targetBuffer(const char* name, vk::Buffer FrameTargets::*member) {
    Resource r(Kind::TargetBuffer, name);
    r.targetMember = member;
    return r;
}

Resource Resource::image(const char* name, vk::Image& image, VkSampler sampler) {
    Resource r(Kind::Image, name);
    r.ownImage = &image;
    r.sampler = sampler;
    return r;
}

Resource Resource::atLevel(int mipLevel) const {
    Resource r = *this;
    r.level = mipLevel;
    return r;
}

Resource Resource::buffer(const char* name, vk::Buffer& buffer) {
    Resource r(Kind::Buffer, name);
    r.ownBuffer = &buffer;
    return r;
}

Resource Resource::perDraw(const char* name, bool buffer) {
    Resource r(Kind::PerDraw, name);
    r.perDrawBuffer = buffer;
    r.writtenByPass = true;
    return r;
}

Resource Resource::eachDispatch() const {
    Resource r = *this;
    r.writtenByPass = true;
    return r;
}

ResourceTable::ResourceTable(std::string owner, std::vector<ResourceRow> rows)
    : owner_(std::move(owner)), rows_(std::move(rows)) {
    auto fail = [&](const ResourceRow& row, const std::string& what) {
        throw Error(owner_ + ": resource table: " + row.resource.name + ": " + what);
    };
    for (size_t i = 0; i < rows_.size(); ++i) {
        const ResourceRow& row = rows_[i];
        const Resource& r = row.resource;
        if (isDescriptor(row.access) != (row.binding != kNoBinding))
            fail(row, isDescriptor(row.access) ? "a descriptor needs a binding"
                                               : "only descriptors have bindings");
        for (size_t j = 0; j < i; ++j)
            if (row.binding != kNoBinding && rows_[j].binding == row.binding)
                fail(row,
                     "binding " + std::to_string(row.binding) + " is also " + rows_[j].resource.name + "'s");
        if ((row.access == Access::Uniform) != (r.kind == Resource::Kind::FrameUniforms))
            fail(row, "only the frame uniforms are a uniform buffer");
        const bool imageOnly = row.access == Access::Sampled || row.access == Access::SampledCompare ||
                               row.access == Access::ColorAttachment || row.access == Access::DepthAttachment;
        if (imageOnly && !isImage(r)) fail(row, "not an image");
        if (row.access == Access::IndirectRead && isImage(r)) fail(row, "an image is no indirect dispatch");
        const bool attachment =
            row.access == Access::ColorAttachment || row.access == Access::DepthAttachment;
        if (attachment && r.kind != Resource::Kind::Target) fail(row, "render targets are frame targets");
        if (!isTracked(r)) continue;
        // The union of this table's uses of each resource, in the order they first appear.
        size_t u = 0;
        while (u < uses_.size() && !sameResource(rows_[uses_[u].row].resource, r)) ++u;
        if (u == uses_.size()) uses_.push_back({i});
        if (isImage(r) && !mergeImageAccess(uses_[u].image, imageAccess(row.access)))
            fail(row, "used two ways that need different image layouts");
        if (!isImage(r)) uses_[u].buffer = uses_[u].buffer | bufferAccess(row.access);
    }
}

std::vector<vk::Binding> ResourceTable::bindings() const {
    std::vector<vk::Binding> result;
    for (const ResourceRow& row : rows_) {
        if (row.binding == kNoBinding) continue;
        vk::Binding b{row.binding, descriptorType(row), row.stages};
        const Resource& r = row.resource;
        b.name = r.name;
        b.depthCompare = row.access == Access::SampledCompare;
        if (r.kind == Resource::Kind::Target) {
            b.format = targetDesc(r.target).format;
            b.dimension = VK_IMAGE_VIEW_TYPE_2D;
        } else if (r.kind == Resource::Kind::Image && r.ownImage->valid()) {
            b.format = r.ownImage->format();
            b.dimension = r.ownImage->desc().depth > 1 ? VK_IMAGE_VIEW_TYPE_3D : VK_IMAGE_VIEW_TYPE_2D;
        }
        result.push_back(b);
    }
    return result;
}

std::vector<VkFormat> ResourceTable::colorFormats() const {
    std::vector<VkFormat> formats;
    for (const ResourceRow& row : rows_)
        if (row.access == Access::ColorAttachment) formats.push_back(targetDesc(row.resource.target).format);
    return formats;
}

VkFormat ResourceTable::depthFormat() const {
    for (const ResourceRow& row : rows_)
        if (row.access == Access::DepthAttachment) return targetDesc(row.resource.target).format;
    return VK_FORMAT_UNDEFINED;
}

std::vector<vk::Image*> ResourceTable::colorAttachments(FrameTargets& targets) const {
    std::vector<vk::Image*> images;
    for (const ResourceRow& row : rows_)
        if (row.access == Access::ColorAttachment) images.push_back(imageOf(row.resource, targets));
    return images;
}

vk::Image* ResourceTable::depthAttachment(FrameTargets& targets) const {
    for (const ResourceRow& row : rows_)
        if (row.access == Access::DepthAttachment) return imageOf(row.resource, targets);
    return nullptr;
}

void ResourceTable::barriers(const FrameContext& frame) const {
    for (const Use& use : uses_) {
        const Resource& r = rows_[use.row].resource;
        if (isImage(r)) {
            vk::Image* image = imageOf(r, frame.targets);
            if (!image->valid())
                throw Error(owner_ + ": " + r.name + " does not exist in this configuration");
            image->use(frame.cmd, use.image);
        } else {
            vk::Buffer* buffer = bufferOf(r, frame.targets);
            if (buffer->handle() == VK_NULL_HANDLE)
                throw Error(owner_ + ": " + r.name + " does not exist in this configuration");
            buffer->use(frame.cmd, use.buffer);
        }
    }
}

vk::DescriptorWriter ResourceTable::writer(const FrameContext& frame) const {
    vk::DescriptorWriter writer;
    for (const ResourceRow& row : rows_) {
        const Resource& r = row.resource;
        if (row.binding == kNoBinding || r.writtenByPass) continue;
        switch (r.kind) {
            case Resource::Kind::FrameUniforms:
                writer.uniform(row.binding, frame.frameUniforms);
                break;
            case Resource::Kind::Scene:
                writer.storageBuffer(row.binding, sceneBuffer(frame.scene, r.sceneBuffer));
                break;
            case Resource::Kind::TargetBuffer:
            case Resource::Kind::Buffer:
                writer.storageBuffer(row.binding, bufferOf(r, frame.targets)->handle());
                break;
            case Resource::Kind::Target:
            case Resource::Kind::Image: {
                const vk::Image& image = *imageOf(r, frame.targets);
                const VkImageView view = r.level >= 0 ? image.mipView(uint32_t(r.level)) : image.view();
                if (row.access == Access::Sampled || row.access == Access::SampledCompare) {
                    const VkSampler sampler = row.access == Access::SampledCompare
                                                  ? frame.samplers.shadowCompare
                                              : r.sampler ? r.sampler
                                                          : frame.samplers.nearestClamp;
                    writer.sampled(
                        row.binding, view, sampler,
                        vk::accessInfo(vk::ImageAccess::Sampled, vk::isDepthFormat(image.format())).layout);
                } else {
                    writer.storage(row.binding, view);
                }
                break;
            }
            case Resource::Kind::PerDraw:
                break;
        }
    }
    return writer;
}

void ResourceTable::bind(const FrameContext& frame, const vk::Pipeline& pipeline) const {
    barriers(frame);
    writer(frame).push(frame.context, frame.cmd, pipeline);
}

}  // namespace vct
