#include "render/renderer.h"

#include <algorithm>
#include <cstring>
#include <glm/gtc/packing.hpp>

#include "passes/blend_pass.h"
#include "passes/composite_pass.h"
#include "passes/direct_pass.h"
#include "passes/gbuffer_pass.h"
#include "passes/inject_pass.h"
#include "passes/resample_pass.h"
#include "passes/shadow_pass.h"
#include "passes/skin_pass.h"
#include "passes/trace_pass.h"
#include "passes/upsample_pass.h"
#include "passes/voxel_bounce_pass.h"
#include "passes/voxel_mips_pass.h"
#include "passes/voxel_view_pass.h"
#include "passes/voxelize_pass.h"
#include "render/setting_table.h"
#include "render/shader_math.h"
#include "render/voxel_update.h"
#include "scene/camera_path.h"
#include "vk/check.h"

namespace vct {

namespace {

// The settings with what depends on the device resolved before anything is created from them.
RenderSettings resolveForDevice(const vk::Context& context, RenderSettings settings) {
    settings.anisotropy = chooseAnisotropy(context, settings.anisotropy);
    return settings;
}

}  // namespace

Renderer::Renderer(const vk::Context& context, const Scene& scene, const RenderSettings& settings,
                   uint32_t framesInFlight)
    : context_(context),
      settings_(resolveForDevice(context, settings)),
      gpuScene_(context, scene, settings_.anisotropy, std::clamp(framesInFlight, 1u, 2u)),
      slots_(std::clamp(framesInFlight, 1u, 2u)),
      timer_(context, 64, uint32_t(slots_.size())) {
    const VkPhysicalDeviceLimits& limits = context.properties().limits;
    if (settings.width > limits.maxImageDimension2D || settings.height > limits.maxImageDimension2D)
        throw UsageError("size " + std::to_string(settings.width) + "x" + std::to_string(settings.height) +
                         " exceeds the device's maximum image dimension " +
                         std::to_string(limits.maxImageDimension2D));
    targets_.create(context, settings.width, settings.height, VCT_SHADOW_MAP_SIZE, settings.traceScale,
                    settings.gi, gpuScene_.hasBlended());
    createSamplers();
    // The environment (docs/design.md §5.9), made once from the settings and the scene's sun at t = 0.
    environmentMap_ = std::make_shared<const EnvironmentMap>(sceneEnvironment(scene, settings_));
    gpuEnvironment_ = std::make_unique<GpuEnvironment>(context, *environmentMap_);
    const EnvironmentSource environment = gpuEnvironment_->source();
    dfg_ = std::make_unique<DfgLut>(context);
    // The frame, in order (docs/design.md §2.1). Skinned and morphed instances are deformed before anything
    // draws them; a scene without any has no skin pass.
    if (gpuScene_.deform().active())
        passes_.push_back(std::make_unique<SkinPass>(context, gpuScene_.deform()));
    auto shadow = std::make_unique<ShadowPass>(context);
    shadowPass_ = shadow.get();
    passes_.push_back(std::move(shadow));
    // The cone-tracing passes' invocations per pixel or voxel (trace, resample, bounce).
    const uint32_t coneLanes = settings.gi ? traceConeLanes(context, settings.traceLayout) : 1u;
    if (settings.gi) {
        // The voxel grid and its light (docs/design.md §5.1–5.2); inject reads the shadow map drawn just before.
        const uint32_t n = chooseVoxelResolution(context, settings);
        voxelGrid_ = std::make_unique<VoxelGrid>(context, scene, n, n >= settings.sparseMip0From,
                                                 settings.voxelRegions);
        settings_.voxelResolution = voxelGrid_->resolution();
        // The static voxelization from a file (vct voxelize) instead of computing it; validated here.
        if (!settings.voxelCache.empty()) voxelGrid_->loadStaticCache(settings.voxelCache);
        passes_.push_back(std::make_unique<VoxelizePass>(context, *voxelGrid_));
        // `--bounces all`: every inject adds the gathers, which persist from frame to frame.
        const bool allBounces = settings.bounces == kAllBounces;
        auto inject = std::make_unique<InjectPass>(context, *voxelGrid_, *dfg_, allBounces);
        auto mips = std::make_unique<VoxelMipsPass>(context, *voxelGrid_);
        // Multiple bounces run inject and mips again, after the first of each (docs/design.md §5.7).
        std::unique_ptr<VoxelBouncePass> bounce;
        if (settings.bounces > 1)
            bounce = std::make_unique<VoxelBouncePass>(context, *voxelGrid_, *inject, *mips, settings.bounces,
                                                       coneLanes, environment);
        if (allBounces) voxelLightSettleFrames_ = bounce->settleFrames();
        passes_.push_back(std::move(inject));
        passes_.push_back(std::move(mips));
        if (bounce) passes_.push_back(std::move(bounce));
    }
    // The colour varying only where some primitive has COLOR_0 (VCT_SPEC_VERTEX_COLORS).
    const std::vector<Primitive>& primitives = scene.primitives;
    const bool vertexColors =
        std::any_of(primitives.begin(), primitives.end(), [](const Primitive& p) { return p.hasColors; });
    auto gbuffer = std::make_unique<GBufferPass>(context, scene, vertexColors, settings.textureLod0);
    gbufferPass_ = gbuffer.get();
    passes_.push_back(std::move(gbuffer));
    auto direct = std::make_unique<DirectPass>(context, environment, gpuScene_, settings.gi, *shadowPass_);
    directPass_ = direct.get();
    passes_.push_back(std::move(direct));
    if (settings.gi) {
        // Indirect light: traced at low resolution, brought back to full resolution (docs/design.md §5, §6).
        const VoxelSource voxels = VoxelSource::of(*voxelGrid_, environment);
        passes_.push_back(std::make_unique<TracePass>(context, settings.traceScale, coneLanes, voxels));
        // Upsampling and adaptive re-tracing only where something is traced at low resolution: at scale 1 the
        // trace writes the full-res targets itself.
        if (settings.traceScale > 1) {
            passes_.push_back(std::make_unique<UpsamplePass>(context));
            if (settings.adaptive)
                passes_.push_back(std::make_unique<ResamplePass>(context, coneLanes, voxels));
        }
    }
    // Blended surfaces, drawn forward over the opaque frame's depth into their own layer, which composite puts
    // over the frame (docs/design.md §2.6); a scene without any has no blend pass.
    if (gpuScene_.hasBlended()) {
        const VoxelSource voxels = voxelGrid_ ? VoxelSource::of(*voxelGrid_, environment) : VoxelSource{};
        passes_.push_back(std::make_unique<BlendPass>(context, voxelGrid_ ? &voxels : nullptr, environment,
                                                      *dfg_, scene, vertexColors, settings.textureLod0));
    }
    auto composite = std::make_unique<CompositePass>(context, *dfg_, gpuScene_, settings.gi);
    composite_ = composite.get();
    passes_.push_back(std::move(composite));

    for (FrameSlot& slot : slots_) {
        VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        alloc.commandPool = context.commandPool();
        alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        alloc.commandBufferCount = 1;
        VK_CHECK(vkAllocateCommandBuffers(context.device(), &alloc, &slot.cmd));
        VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        VK_CHECK(vkCreateFence(context.device(), &fenceInfo, nullptr, &slot.fence));
        slot.uniforms = vk::Buffer(context, sizeof(gpu::FrameUniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                                   vk::MemoryUsage::HostVisible);
        if (settings.gi) {
            slot.resampleCount = vk::Buffer(context, sizeof(uint32_t), VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                            vk::MemoryUsage::HostVisible);
            *static_cast<uint32_t*>(slot.resampleCount.mapped()) = 0;
        }
    }
}

Renderer::~Renderer() {
    vkDeviceWaitIdle(context_.device());
    for (FrameSlot& slot : slots_) {
        vkDestroyFence(context_.device(), slot.fence, nullptr);
        vkFreeCommandBuffers(context_.device(), context_.commandPool(), 1, &slot.cmd);
    }
}

void Renderer::createSamplers() {
    auto make = [&](VkFilter filter, bool compare) {
        VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
        info.magFilter = filter;
        info.minFilter = filter;
        info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
        info.addressModeU = info.addressModeV = info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
        info.compareEnable = compare;
        info.compareOp = VK_COMPARE_OP_LESS_OR_EQUAL;
        info.maxLod = VK_LOD_CLAMP_NONE;
        return vk::Sampler(context_, info);
    };
    // Owned (RAII): a constructor that throws later (a bad voxel cache) must not leak them.
    samplerOwners_ = {make(VK_FILTER_LINEAR, false), make(VK_FILTER_NEAREST, false),
                      make(VK_FILTER_LINEAR, true)};
    samplers_.linearClamp = samplerOwners_[0].handle();
    samplers_.nearestClamp = samplerOwners_[1].handle();
    samplers_.shadowCompare = samplerOwners_[2].handle();
}

void Renderer::resize(uint32_t width, uint32_t height) {
    finishFrames();
    vkDeviceWaitIdle(context_.device());
    settings_.width = width;
    settings_.height = height;
    sceneBuilt_ = false;  // the shadow map is recreated with the targets
    targets_.create(context_, width, height, VCT_SHADOW_MAP_SIZE, settings_.traceScale, settings_.gi,
                    gpuScene_.hasBlended());
    hasPrevious_ = false;
}

bool Renderer::canApplyLive(const RenderSettings& wanted) const {
    return settingsChange(settings_, wanted) == SettingApply::Live;
}

void Renderer::applyLive(const RenderSettings& wanted) {
    if (!canApplyLive(wanted)) throw Error("Renderer::applyLive: these settings need a new renderer");
    settings_ = withResolvedSettings(settings_, wanted);
}

void Renderer::writeFrameUniforms(const FrameInput& input, vk::Buffer& uniforms) {
    gpu::FrameUniforms u{};
    const float aspect = float(settings_.width) / float(settings_.height);
    u.view = input.camera.view;
    u.proj = input.camera.projection(aspect);
    u.viewProj = u.proj * u.view;
    u.invViewProj = glm::inverse(u.viewProj);
    u.prevViewProj = (input.cut || !hasPrevious_) ? u.viewProj : previousViewProj_;
    u.lightViewProj = gpuScene_.lightViewProj();
    u.cameraPosition = input.camera.position();
    u.exposure = settings_.exposure;
    u.imageSize = glm::vec2(settings_.width, settings_.height);
    u.texelSize = glm::vec2(1.0f / float(settings_.width), 1.0f / float(settings_.height));

    u.lighting.ambient = environmentMap_->meanRadiance();
    u.lighting.environmentRotation = environmentMap_->rotation;
    u.lighting.lightCount = gpuScene_.lightCount();
    u.lighting.shadowLight = gpuScene_.shadowLightIndex();
    u.lighting.shadowNormalOffset = gpuScene_.shadowTexelWorldSize();
    u.lighting.shadowTexelSize = 1.0f / float(VCT_SHADOW_MAP_SIZE);

    if (voxelGrid_) {
        u.voxels.origin = voxelGrid_->origin();
        u.voxels.voxelSize = voxelGrid_->voxelSize();
        u.voxels.resolution = voxelGrid_->resolution();
        u.voxels.mipCount = voxelGrid_->mipCount();
        u.voxels.brickAtlasSide = voxelGrid_->bricks().atlasSide;
        u.voxels.brickCount = voxelGrid_->bricks().brickCount();
        const vk::Image& atlas = voxelGrid_->radianceAtlas();
        u.voxels.atlasInvSize =
            glm::vec4(1.0f / glm::vec3(atlas.width(), atlas.height(), atlas.depth()), 0.0f);
        u.voxels.closureMin = glm::vec4(voxelGrid_->coneClosure().min, 0.0f);
        u.voxels.closureMax = glm::vec4(voxelGrid_->coneClosure().max, 0.0f);
        u.voxels.contentMin = glm::vec4(voxelGrid_->contentBounds().min, 0.0f);
        u.voxels.contentMax = glm::vec4(voxelGrid_->contentBounds().max, 0.0f);
    }

    // Spatio-temporal upsampling (docs/design.md §6): weights, history and this frame's trace offset o_k. The
    // weights, temporal and the trace scale are specialization constants (passes/upsample_pass.cpp,
    // passes/trace_pass.cpp).
    const bool history = settings_.temporal && !input.cut && hasPrevious_;
    u.prevInvViewProj = history ? previousInvViewProj_ : u.invViewProj;
    u.prevCameraPosition = history ? previousCameraPosition_ : u.cameraPosition;
    const bool adaptive = settings_.adaptive && settings_.traceScale > 1;
    u.upsample.traceOffset = glsl::jitterOffset(frameIndex_, int(settings_.traceScale));
    u.upsample.beta = settings_.beta;
    u.upsample.kappa = settings_.kappa;
    u.upsample.normalVariance = settings_.sigmaN * settings_.sigmaN;
    u.upsample.diffuseSharpness = settings_.diffuseSharpness;
    u.upsample.gamma = settings_.gamma;
    u.upsample.tau = adaptive ? resampleThreshold(settings_) : 0.0f;
    u.upsample.maxHistoryWeight = settings_.historyCap * kExactSampleWeight;
    u.upsample.frameIndex = frameIndex_;

    u.flags = (settings_.gi ? VCT_FLAG_GI : 0u) | (settings_.toksvig ? VCT_FLAG_TOKSVIG : 0u) |
              (settings_.specularAA ? VCT_FLAG_SPECULAR_AA : 0u) | (history ? VCT_FLAG_HISTORY : 0u) |
              // Jittered cones are turned too (their turn is one of the jitter's dimensions).
              (settings_.coneRotation || settings_.coneJitter ? VCT_FLAG_CONE_ROTATION : 0u) |
              (settings_.coneJitter ? VCT_FLAG_CONE_JITTER : 0u) |
              (settings_.voxelGlossy ? VCT_FLAG_VOXEL_GLOSSY : 0u);

    std::memcpy(uniforms.mapped(), &u, sizeof(u));
    uniforms_ = u;
    previousViewProj_ = u.viewProj;
    previousInvViewProj_ = u.invViewProj;
    previousCameraPosition_ = u.cameraPosition;
    hasPrevious_ = true;
}

FrameInput fixedStepFrame(const Scene& scene, uint32_t index, uint32_t warmup, const CameraPath* path) {
    FrameInput input;
    input.timeSeconds = float(index) / 60.0f;
    input.camera = sceneCamera(scene, input.timeSeconds);
    if (path) input.camera = path->evaluate(input.timeSeconds, input.camera);
    input.cut = index == 0;
    input.recordTimings = index >= warmup;
    return input;
}

void Renderer::render(const FrameInput& input, const FrameSubmit& submit) {
    // The slot's previous frame (two frames back with two in flight) must be done before its copies of what
    // the CPU writes are written again.
    FrameSlot& slot = slots_[submitted_ % slots_.size()];
    finishSlot(slot);
    gpuScene_.useFrameSlot(submitted_ % uint32_t(slots_.size()));
    gpuScene_.update(input.timeSeconds, input.cut || !hasPrevious_);
    // What this frame must recompute (a pass that has nothing to do does not run; its output persists):
    // - the shadow map and voxel grid depend only on the scene's geometry and lights: rebuilt when they
    //   changed, on a cut (every cut starts from the state of a first frame) and after a resize;
    // - the G-buffer and direct light also depend on the camera: reused once scene and camera have been the
    //   same for two frames, so that both G-buffer copies (current and previous, for the history) hold them.
    const bool sceneChanged = !sceneBuilt_ || input.cut || !hasPrevious_ || gpuScene_.changedInLastUpdate() ||
                              settings_.recomputeEveryFrame;
    // `--bounces all`: the grid's light keeps converging for a while after the grid last changed.
    voxelLightFramesLeft_ = sceneChanged ? voxelLightSettleFrames_ : std::max(voxelLightFramesLeft_, 1u) - 1;
    // Moving instances alone: the voxel passes update only the voxels the move touched (render/voxel_update.h).
    if (voxelGrid_)
        voxelGrid_->setUpdateRegions(voxelUpdateRegions(*voxelGrid_, gpuScene_, settings_,
                                                        !sceneBuilt_ || input.cut || !hasPrevious_));
    const float aspect = float(settings_.width) / float(settings_.height);
    const glm::mat4 viewProj = input.camera.projection(aspect) * input.camera.view;
    const bool viewChanged =
        sceneChanged || viewProj != previousViewProj_ || input.camera.position() != previousCameraPosition_;
    stableFrames_ = viewChanged ? 0 : stableFrames_ + 1;
    const bool reuseView = stableFrames_ >= 2;
    // Last frame's indirect light and G-buffer become the history (before the uniforms say whether it is valid).
    if (hasPrevious_) targets_.swapHistory(!reuseView);
    writeFrameUniforms(input, slot.uniforms);
    ++frameIndex_;

    const VkCommandBuffer cmd = slot.cmd;
    VK_CHECK(vkResetCommandBuffer(cmd, 0));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
    timer_.beginFrame(cmd);
    // The slot's re-trace count is the one the resample pass copies into while this frame is recorded.
    std::swap(targets_.resampleCount, slot.resampleCount);
    try {
        FrameContext frame{context_,  cmd,       gpuScene_, targets_, slot.uniforms.handle(),
                           settings_, samplers_, uniforms_};
        for (const auto& pass : passes_) {
            const PassReuse reuse = pass->reuse();
            if ((reuse == PassReuse::WhileSceneUnchanged && !sceneChanged) ||
                (reuse == PassReuse::WhileVoxelLightSettled && !sceneChanged && voxelLightFramesLeft_ == 0) ||
                (reuse == PassReuse::WhileViewUnchanged && reuseView)) {
                timer_.skipScope(pass->name());  // timed as 0 ms, with a run count (vk/timer.h)
                pass->skipped();
                continue;
            }
            timer_.beginScope(cmd, pass->name());
            pass->execute(frame);  // its barriers first, from its resource table
            timer_.endScope(cmd);
        }
        if (submit.afterPasses) submit.afterPasses(cmd);
        VK_CHECK(vkEndCommandBuffer(cmd));

        VkSubmitInfo info{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        info.commandBufferCount = 1;
        info.pCommandBuffers = &cmd;
        if (submit.wait) {
            info.waitSemaphoreCount = 1;
            info.pWaitSemaphores = &submit.wait;
            info.pWaitDstStageMask = &submit.waitStage;
        }
        if (submit.signal) {
            info.signalSemaphoreCount = 1;
            info.pSignalSemaphores = &submit.signal;
        }
        VK_CHECK(vkResetFences(context_.device(), 1, &slot.fence));
        VK_CHECK(vkQueueSubmit(context_.queue(), 1, &info, slot.fence));
    } catch (...) {
        // An error while recording: the frame never runs, its timestamps are never written.
        std::swap(targets_.resampleCount, slot.resampleCount);
        timer_.cancelFrame();
        throw;
    }
    std::swap(targets_.resampleCount, slot.resampleCount);
    slot.pending = true;
    slot.recordTimings = input.recordTimings;
    ++submitted_;
    sceneBuilt_ = true;
    if (slots_.size() == 1) finishSlot(slot);
}

void Renderer::finishSlot(FrameSlot& slot) {
    if (!slot.pending) return;
    VK_CHECK(vkWaitForFences(context_.device(), 1, &slot.fence, VK_TRUE, UINT64_MAX));
    slot.pending = false;
    timer_.collect(slot.recordTimings);
    if (slot.resampleCount.handle() != VK_NULL_HANDLE)
        resampleCount_ = *static_cast<const uint32_t*>(slot.resampleCount.mapped());
    if (voxelGrid_) {
        // A voxel cache's staging buffer, uploaded by the first frame's voxelize pass, is no longer needed.
        if (voxelGrid_->staticVoxelized() && voxelGrid_->hasStaticCache()) voxelGrid_->releaseStaticCache();
    }
}

void Renderer::finishFrames() {
    // Oldest first, so that the timestamps are collected in the order the frames ran.
    for (size_t k = 0; k < slots_.size(); ++k) finishSlot(slots_[(submitted_ + k) % slots_.size()]);
}

namespace {

// How the texels of a readable format are laid out: channel count and component type.
struct TexelLayout {
    uint32_t channels;
    enum { Float32, Float16, Unorm8 } type;
};

TexelLayout texelLayout(VkFormat format) {
    switch (format) {
        case VK_FORMAT_R32G32B32A32_SFLOAT:
            return {4, TexelLayout::Float32};
        case VK_FORMAT_R32_SFLOAT:
        case VK_FORMAT_D32_SFLOAT:
            return {1, TexelLayout::Float32};
        case VK_FORMAT_R16G16B16A16_SFLOAT:
            return {4, TexelLayout::Float16};
        case VK_FORMAT_R16G16_SFLOAT:
            return {2, TexelLayout::Float16};
        case VK_FORMAT_R8G8B8A8_UNORM:
            return {4, TexelLayout::Unorm8};
        default:
            throw Error("readback of this image format is not supported");
    }
}

}  // namespace

vk::Buffer Renderer::copyToHost(vk::Image& image) {
    vk::Buffer staging(context_,
                       VkDeviceSize(image.width()) * image.height() * vk::bytesPerPixel(image.format()),
                       VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUsage::HostVisible);
    context_.submitAndWait([&](VkCommandBuffer cmd) {
        // Put the image back the way the passes left it, so the next frame's barriers stay right.
        const vk::ImageAccess previous = image.lastAccess();
        image.use(cmd, vk::ImageAccess::TransferSrc);
        VkBufferImageCopy region{};
        region.imageSubresource = {image.aspect(), 0, 0, 1};
        region.imageExtent = {image.width(), image.height(), 1};
        vkCmdCopyImageToBuffer(cmd, image.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging.handle(), 1,
                               &region);
        if (previous != vk::ImageAccess::Undefined) image.use(cmd, previous);
    });
    return staging;
}

std::vector<float> Renderer::readFinalHdr() {
    if (submitted_ == 0) throw Error("there is no final image before the first frame");
    // The frame uniforms still hold the last frame's exposure; the targets composite reads, its results.
    runAfterFrame([&](const FrameContext& frame) { composite_->executeWithHdr(frame); });
    return readImage(targets_.hdr);
}

std::vector<float> Renderer::readFloatImage(vk::Image& image) {
    // The frames do not write it: only readFinalHdr does, on demand.
    if (&image == &targets_.hdr) throw Error("the final HDR image is read with Renderer::readFinalHdr");
    return readImage(image);
}

std::vector<float> Renderer::readImage(vk::Image& image) {
    const TexelLayout layout = texelLayout(image.format());
    vk::Buffer staging = copyToHost(image);
    const auto* src = static_cast<const uint8_t*>(staging.mapped());
    const size_t pixels = size_t(image.width()) * image.height();
    // Missing channels read as 0, alpha as 1.
    std::vector<float> rgba(pixels * 4, 0.0f);
    for (size_t i = 0; i < pixels; ++i) {
        rgba[i * 4 + 3] = 1.0f;
        for (uint32_t c = 0; c < layout.channels; ++c) {
            const size_t index = i * layout.channels + c;
            float value = 0.0f;
            if (layout.type == TexelLayout::Float32) {
                std::memcpy(&value, src + index * 4, 4);
            } else if (layout.type == TexelLayout::Float16) {
                uint16_t bits;
                std::memcpy(&bits, src + index * 2, 2);
                value = glm::unpackHalf1x16(bits);
            } else {
                value = float(src[index]) / 255.0f;
            }
            rgba[i * 4 + c] = value;
        }
    }
    return rgba;
}

uint64_t Renderer::shadowTexelsRedrawn() const {
    const std::optional<TexelRect>& rect = shadowPass_->lastRect();
    return rect ? rect->area() : shadowTexels();
}

uint64_t Renderer::gbufferPixelsRedrawn() const {
    const std::optional<TexelRect>& rect = gbufferPass_->lastRect();
    return rect ? rect->area() : uint64_t(settings_.width) * settings_.height;
}

uint64_t Renderer::directPixelsDispatched() const {
    return directPass_->lastDispatched();
}

bool Renderer::directLightPartial() const {
    return directPass_->lastRunPartial();
}

uint64_t Renderer::shadowTexels() const {
    return uint64_t(targets_.shadowMap.width()) * targets_.shadowMap.height();
}

float Renderer::resampledFraction() const {
    if (!targets_.gi) return 0.0f;  // nothing traced, nothing re-traced
    return float(resampleCount_) / float(std::max<uint64_t>(uint64_t(targets_.width) * targets_.height, 1));
}

Renderer::IndirectLight Renderer::readIndirect() {
    if (!voxelGrid_) throw Error("there is no indirect light with GI off");
    vk::Buffer staging = copyToHost(targets_.indirect);
    const auto* texels = static_cast<const glm::uvec4*>(staging.mapped());
    const size_t pixels = size_t(targets_.width) * targets_.height;
    IndirectLight light{std::vector<float>(pixels * 4), std::vector<float>(pixels * 4)};
    for (size_t i = 0; i < pixels; ++i) {
        const glm::vec4 diffuse = glsl::unpackIndirectDiffuse(texels[i]);
        const glm::vec4 specular = glsl::unpackIndirectSpecular(texels[i]);
        for (int c = 0; c < 4; ++c) {
            light.diffuse[i * 4 + size_t(c)] = diffuse[c];
            light.specular[i * 4 + size_t(c)] = specular[c];
        }
    }
    return light;
}

std::vector<uint8_t> Renderer::readLdr() {
    vk::Buffer staging = copyToHost(targets_.ldr);
    const auto* src = static_cast<const uint8_t*>(staging.mapped());
    return std::vector<uint8_t>(src, src + size_t(targets_.width) * targets_.height * 4);
}

vk::Image& Renderer::renderVoxelView(uint32_t mip) {
    if (!voxelGrid_) throw Error("the voxel view needs the voxel grid, which GI off does not build");
    if (!voxelView_) voxelView_ = std::make_unique<VoxelViewPass>(context_, *voxelGrid_);
    voxelView_->prepare(mip, targets_.width, targets_.height);
    // The frame uniforms still hold the last frame's camera and grid placement.
    runAfterFrame([&](const FrameContext& frame) { voxelView_->execute(frame); });
    return voxelView_->output();
}

void Renderer::runAfterFrame(const std::function<void(const FrameContext&)>& record) {
    context_.submitAndWait([&](VkCommandBuffer cmd) {
        const FrameContext frame{context_,  cmd,       gpuScene_, targets_, lastSubmitted().uniforms.handle(),
                                 settings_, samplers_, uniforms_};
        record(frame);
    });
}

}  // namespace vct
