#include "render/voxel_grid.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <glm/gtc/packing.hpp>
#include <sstream>
#include <string>

#include "core/error.h"
#include "lib/shared.h"
#include "scene/input_limits.h"
#include "vk/check.h"

namespace vct {

uint32_t voxelPassLanes(const vk::Context& context) {
    constexpr uint32_t kVoxelsPerBrick = VCT_VOXEL_BRICK * VCT_VOXEL_BRICK * VCT_VOXEL_BRICK;
    if (context.properties().deviceType != VK_PHYSICAL_DEVICE_TYPE_CPU) return kVoxelsPerBrick;
    VkPhysicalDeviceSubgroupProperties subgroup{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
    VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    properties.pNext = &subgroup;
    vkGetPhysicalDeviceProperties2(context.physicalDevice(), &properties);
    // A power of two from 1 to 64 divides the brick's 64 voxels; anything else gets one invocation per voxel.
    const uint32_t size = subgroup.subgroupSize;
    return size >= 1 && size <= kVoxelsPerBrick && (size & (size - 1)) == 0 ? size : kVoxelsPerBrick;
}

namespace {

constexpr VkDeviceSize kAccumVoxelBytes = VCT_VOXEL_ACCUM_STRIDE * sizeof(uint32_t);

// f(k, local, voxel) for every voxel of every allocated brick: its brick index, its place in the brick
// (0..VCT_VOXEL_BRICK − 1 per axis) and in the grid.
template <typename F>
void forEachVoxel(const BrickLayout& bricks, F&& f) {
    for (uint32_t k = 0; k < bricks.brickCount(); ++k)
        for (int z = 0; z < VCT_VOXEL_BRICK; ++z)
            for (int y = 0; y < VCT_VOXEL_BRICK; ++y)
                for (int x = 0; x < VCT_VOXEL_BRICK; ++x) {
                    const glm::ivec3 local(x, y, z);
                    f(k, local, glm::ivec3(bricks.bricks[k]) * VCT_VOXEL_BRICK + local);
                }
}

// Device bytes of an image's texels, every mip level.
uint64_t imageBytes(const vk::Image& image) {
    const vk::ImageDesc& d = image.desc();
    uint64_t bytes = 0;
    for (uint32_t level = 0; level < d.mipLevels; ++level)
        bytes += uint64_t(std::max(1u, d.width >> level)) * std::max(1u, d.height >> level) *
                 std::max(1u, d.depth >> level) * vk::bytesPerPixel(d.format);
    return bytes;
}

}  // namespace

uint32_t chooseVoxelResolution(const vk::Context& context, const RenderSettings& settings) {
    uint32_t n = settings.voxelResolution;
    // A voxel cache fixes N: without --voxels, take the file's (its metadata only; loadStaticCache checks
    // it).
    if (n == 0 && !settings.voxelCache.empty()) n = readVoxelFileInfo(settings.voxelCache).resolution;
    if (n == 0) {
        // A software rasterizer pays for every voxel on the CPU each frame (resolve, inject, mips), so it
        // gets 64³ (8× fewer voxels); GPUs get 128³, enough for room-sized scenes at 1–2 voxels per 10 cm.
        n = context.properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU ? 64u : 128u;
    }
    if (n < 32 || n > 256 || !std::has_single_bit(n))
        throw UsageError("voxel resolution " + std::to_string(n) + " must be a power of two in 32..256");
    // What the grid's buffers and images need of the device is checked with the scene's bricks (VoxelGrid's
    // constructor).
    return n;
}

Aabb voxelSceneBounds(const Scene& scene) {
    Aabb box = scene.bounds();
    float duration = 0.0f;
    for (const Animation& animation : scene.animations) duration = std::max(duration, animation.duration);
    if (duration <= 0.0f) return box;
    // Sampled, not exact: moving geometry may poke out between samples by a little (dropped voxels there).
    constexpr int kSamples = 32;
    for (int s = 1; s <= kSamples; ++s)
        for (const Instance& instance : scene.instances(duration * float(s) / float(kSamples)))
            if (instance.moving) box.extend(instance.bounds);  // deformed too (skins, morph targets)
    return box;
}

VoxelGrid::VoxelGrid(const vk::Context& context, const Scene& scene, uint32_t resolution, bool sparseMip0,
                     bool regions)
    : context_(context), scene_(scene), resolution_(resolution), sparseMip0_(sparseMip0) {
    mipCount_ = uint32_t(std::countr_zero(resolution)) + 1;
    Aabb bounds = voxelSceneBounds(scene);
    if (bounds.empty()) bounds = Aabb{glm::vec3(-1.0f), glm::vec3(1.0f)};
    contentBounds_ = bounds;
    originSize_ = glsl::voxelGridFit(bounds.min, bounds.max, float(resolution));

    // Sparse storage (docs/design.md §5.10): which bricks the scene can reach, and the table the shaders read.
    bricks_ = allocateBricks(scene, originSize_, resolution);
    coneClosure_ = coneClosureBox(scene, bricks_, originSize_, contentBounds_);
    // Off, no regions: none needed (usesRegions() false), and no labelling at start-up.
    if (regions) regions_ = labelVoxelRegions(scene, originSize_, resolution, coneClosure_);
    const uint64_t brickCount = std::max<uint64_t>(bricks_.brickCount(), 1);  // no empty buffers or images
    const std::vector<uint32_t> table = bricks_.table();
    brickTable_ = vk::Buffer::withData(context, table.data(), table.size() * sizeof(uint32_t),
                                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);

    // The voxelize and resolve passes bind each accumulator whole as one storage buffer (only 2^27 bytes are
    // guaranteed: lavapipe's 128 MiB holds about 47,000 bricks).
    const VkDeviceSize accumBytes =
        brickCount * VCT_VOXEL_BRICK * VCT_VOXEL_BRICK * VCT_VOXEL_BRICK * kAccumVoxelBytes;
    const VkDeviceSize maxRange = context.properties().limits.maxStorageBufferRange;
    const std::string occupancy =
        std::to_string(bricks_.brickCount()) + " of " + std::to_string(bricks_.map.size()) + " bricks";
    if (accumBytes > maxRange)
        throw UsageError("--voxels " + std::to_string(resolution) + ": the scene reaches " + occupancy +
                         ", whose voxel accumulator needs " + byteSizeText(accumBytes) +
                         ", more than this device's maxStorageBufferRange (" + byteSizeText(maxRange) +
                         "); use a smaller --voxels");
    const uint32_t side = bricks_.atlasSide, layers = bricks_.atlasLayers;
    const uint32_t apron = uint32_t(glsl::VOXEL_BRICK_APRON), slabs = uint32_t(glsl::VOXEL_SLAB_COUNT);

    // Every volume is checked against the device's 3D image limit before it is made (the radiance mips are 6N
    // or 3N texels wide, the atlases grow with the scene's bricks).
    const uint32_t maxImage = context.properties().limits.maxImageDimension3D;
    auto volume = [&](const char* name, VkFormat format, glm::uvec3 size, uint32_t mips,
                      VkImageUsageFlags usage) {
        if (glm::any(glm::greaterThan(size, glm::uvec3(maxImage))))
            throw UsageError("--voxels " + std::to_string(resolution) + ": the scene reaches " + occupancy +
                             ", whose " + name + " (" + std::to_string(size.x) + "x" +
                             std::to_string(size.y) + "x" + std::to_string(size.z) +
                             " texels) exceeds this device's maxImageDimension3D (" +
                             std::to_string(maxImage) + "); use a smaller --voxels");
        vk::ImageDesc desc;
        desc.width = size.x;
        desc.height = size.y;
        desc.depth = size.z;
        desc.mipLevels = mips;
        desc.format = format;
        desc.usage = usage;
        return vk::Image(context, desc);
    };
    // TRANSFER_SRC so that later tools (OpenVDB export, tests) can read them back.
    constexpr VkImageUsageFlags storage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    constexpr VkImageUsageFlags sampledStorage = storage | VK_IMAGE_USAGE_SAMPLED_BIT;
    // Transfer destination: inject clears mip 0 (the atlas or level 0) before writing the occupied voxels only.
    const uint32_t first = resolution >> mipBase();  // texels per slab of the texture's level 0
    radianceMips_ =
        volume("radiance mips", VK_FORMAT_R16G16B16A16_SFLOAT, {first * slabs, first, first},
               std::max(mipCount_ - mipBase(), 1u), sampledStorage | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    const glm::uvec3 atlasSize = sparseMip0 ? glm::uvec3(slabs * side * apron, side * apron, layers * apron)
                                            : glm::uvec3(1, 1, 2);  // 3D
    radianceAtlas_ = volume("radiance atlas", VK_FORMAT_R16G16B16A16_SFLOAT, atlasSize, 1,
                            sampledStorage | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    const uint32_t brick = VCT_VOXEL_BRICK;
    const glm::uvec3 materialSize(side * brick, side * brick, layers * brick);
    albedo_ = volume("albedo atlas", VK_FORMAT_R8G8B8A8_UNORM, materialSize, 1, storage);
    normal_ = volume("normal atlas", VK_FORMAT_R16G16B16A16_SFLOAT, materialSize, 1, storage);
    emission_ = volume("emission atlas", VK_FORMAT_R16G16B16A16_SFLOAT, materialSize, 1, storage);
    // Transfer destination: `--bounces all` clears it before the first frame (its gathers persist).
    bounce_ = volume("bounce atlas", VK_FORMAT_R16G16B16A16_SFLOAT, materialSize, 1,
                     storage | VK_IMAGE_USAGE_TRANSFER_DST_BIT);

    // TRANSFER_DST: cleared, and filled from a voxel cache; TRANSFER_SRC: read back for `vct voxelize`.
    constexpr VkBufferUsageFlags accumUsage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                              VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                                              VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
    staticAccum_ = vk::Buffer(context, accumBytes, accumUsage, vk::MemoryUsage::DeviceLocal);
    // Only scenes with animated instances pay for the second accumulator.
    bool moving = false;
    for (const Instance& instance : scene.instances(0.0f)) moving |= instance.moving;
    if (moving) dynamicAccum_ = vk::Buffer(context, accumBytes, accumUsage, vk::MemoryUsage::DeviceLocal);

    // The region labels (render/voxel_regions.h), uploaded once: they follow the static geometry only.
    const glm::uvec3 regionSize = usesRegions() ? glm::uvec3(resolution) : glm::uvec3(1, 1, 2);  // 3D
    regionLabels_ = volume("region labels", VK_FORMAT_R8_UINT, regionSize, 1,
                           VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    {
        const std::vector<uint8_t> zeros(2, 0);
        const std::vector<uint8_t>& labels = usesRegions() ? regions_.labels : zeros;
        vk::Buffer staging(context, labels.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                           vk::MemoryUsage::HostVisible);
        std::memcpy(staging.mapped(), labels.data(), labels.size());
        context.submitAndWait([&](VkCommandBuffer cmd) {
            regionLabels_.use(cmd, vk::ImageAccess::TransferDst);
            VkBufferImageCopy region{};
            region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
            region.imageExtent = {regionSize.x, regionSize.y, regionSize.z};
            vkCmdCopyBufferToImage(cmd, staging.handle(), regionLabels_.handle(),
                                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
            regionLabels_.use(cmd, vk::ImageAccess::Sampled);
        });
        regions_.labels = {};  // on the device now (N³ bytes; 16 MiB at 256³): the grid keeps the counts only
    }

    // For the report: what the grid's images and buffers take, and what dense N³ storage of the same data would
    // (per voxel: each material atlas's texel and the accumulators' words; the radiance's six slabs at every mip).
    const vk::Image* images[] = {&radianceMips_, &radianceAtlas_, &albedo_,      &normal_,
                                 &emission_,     &bounce_,        &regionLabels_};
    memory_.bytes = brickTable_.size() + staticAccum_.size() + dynamicAccum_.size();
    for (const vk::Image* image : images) memory_.bytes += imageBytes(*image);
    const uint64_t voxels = uint64_t(resolution) * resolution * resolution;
    uint64_t denseRadiance = 0;
    for (uint64_t size = resolution; size >= 1; size /= 2) denseRadiance += slabs * size * size * size;
    memory_.denseBytes = denseRadiance * vk::bytesPerPixel(radianceMips_.format()) +
                         voxels * kAccumVoxelBytes * (hasMovingInstances() ? 2 : 1);
    for (const vk::Image* image : {&albedo_, &normal_, &emission_, &bounce_})
        memory_.denseBytes += voxels * vk::bytesPerPixel(image->format());
    memory_.denseBytes += imageBytes(regionLabels_);  // dense either way

    VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    info.magFilter = VK_FILTER_LINEAR;
    info.minFilter = VK_FILTER_LINEAR;
    // One level per read: the diffuse cones read whole mips, the others blend two reads themselves
    // (lib/cone_trace.glsl's sampleMipSlab), which lavapipe does at the cost of one read between levels.
    info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    // Clamped to the edge, not to a transparent border: at coarse mips the outermost texels hold the walls of a
    // room fitted to the grid (the one voxel of padding is a fraction of them), and a border would fade them by
    // up to half, more the coarser the mip. Cones stop where their axis leaves the grid (cone_trace.glsl); the
    // slabs' u is kept inside each slab (lib/voxel.glsl's voxelSlabU), so edge clamping never mixes two.
    info.addressModeU = info.addressModeV = info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    info.minLod = 0.0f;
    info.maxLod = float(radianceMips_.desc().mipLevels - 1);
    sampler_ = vk::Sampler(context, info);
    // The atlas: one level, filtered within a block (lib/cone_trace.glsl never reads across one).
    info.maxLod = 0.0f;
    atlasSampler_ = vk::Sampler(context, info);
}

VoxelGrid::~VoxelGrid() = default;

namespace {

std::string formatVec3(glm::vec3 v) {
    std::ostringstream s;
    s.precision(9);
    s << "(" << v.x << ", " << v.y << ", " << v.z << ")";
    return s.str();
}

}  // namespace

void VoxelGrid::loadStaticCache(const std::filesystem::path& path) {
    const VoxelFile file = readVoxelFile(path, /*frame=*/false);
    const VoxelFileInfo& info = file.info;
    const std::string name = "voxel cache '" + path.string() + "'";
    if (info.resolution != resolution_)
        throw Error(name + " holds a " + std::to_string(info.resolution) + "^3 grid but this run uses " +
                    std::to_string(resolution_) + "^3 (--voxels " + std::to_string(info.resolution) +
                    " or leave --voxels out)");
    // The same scene gives the very same floats (voxelGridFit on the same bounds); the tolerance only
    // forgives last-bit differences between builds. Anything more is another scene (or another version of
    // it).
    const float tolerance = 1e-5f * voxelSize();
    const bool sameBounds =
        std::abs(info.voxelSize - voxelSize()) <= tolerance &&
        glm::all(glm::lessThanEqual(glm::abs(info.origin - origin()), glm::vec3(tolerance)));
    if (!sameBounds)
        throw Error(name + " was voxelized for other grid bounds (scene '" + info.scene + "': origin " +
                    formatVec3(info.origin) + ", voxel size " + std::to_string(info.voxelSize) +
                    ") than this scene's (origin " + formatVec3(origin()) + ", voxel size " +
                    std::to_string(voxelSize()) + ")");

    // Same bounds do not make the same scene: the file records what it voxelized (older files only the name).
    if (info.sceneHash != 0 && info.sceneHash != sceneContentHash(scene_))
        throw Error(name + " was voxelized from another scene ('" + info.scene +
                    "': other geometry, materials or placement) than '" + scene_.name + "'");
    if (info.sceneHash == 0 && std::filesystem::path(info.scene).stem().string() != scene_.name)
        throw Error(name + " was voxelized from scene '" + info.scene + "', not '" + scene_.name + "'");

    // Pack the voxels back to back; one copy region per run of voxels consecutive in the accumulator.
    staticCache_ = vk::Buffer(context_, std::max<VkDeviceSize>(1, file.staticAccum.size()) * kAccumVoxelBytes,
                              VK_BUFFER_USAGE_TRANSFER_SRC_BIT, vk::MemoryUsage::HostVisible);
    staticCacheRegions_.clear();
    auto* dst = static_cast<uint8_t*>(staticCache_.mapped());
    uint64_t previous = 0;
    for (size_t i = 0; i < file.staticAccum.size(); ++i) {
        const StaticAccumVoxel& voxel = file.staticAccum[i];  // in the grid (readVoxelFile)
        const glm::ivec3 brick = glsl::voxelBrickOf(voxel.ijk);
        const uint32_t k = bricks_.map[glsl::brickLinearIndex(brick, int(bricks_.bricksPerAxis))];
        // The same scene's voxels are all where its triangles are (the hash above); a voxel elsewhere was put
        // there by hand.
        if (k == VCT_BRICK_NONE)
            throw Error(name + " has a voxel at " + formatVec3(glm::vec3(voxel.ijk)) +
                        " where this scene has no surface");
        const uint64_t index =
            glsl::voxelAccumIndex(k, voxel.ijk - brick * glsl::VOXEL_BRICK) / VCT_VOXEL_ACCUM_STRIDE;
        std::memcpy(dst + i * kAccumVoxelBytes, voxel.accum.data(), kAccumVoxelBytes);
        if (i > 0 && index == previous + 1)
            staticCacheRegions_.back().size += kAccumVoxelBytes;
        else
            staticCacheRegions_.push_back({i * kAccumVoxelBytes, index * kAccumVoxelBytes, kAccumVoxelBytes});
        previous = index;
    }
}

void VoxelGrid::recordStaticCacheUpload(VkCommandBuffer cmd) const {
    if (!staticCacheRegions_.empty())
        vkCmdCopyBuffer(cmd, staticCache_.handle(), staticAccum_.handle(),
                        uint32_t(staticCacheRegions_.size()), staticCacheRegions_.data());
}

void VoxelGrid::releaseStaticCache() {
    staticCache_.reset();
    staticCacheRegions_ = {};
}

std::vector<glm::vec4> VoxelGrid::readLevel(vk::Image& volume, uint32_t mip) {
    const uint32_t width = std::max(1u, volume.width() >> mip), height = std::max(1u, volume.height() >> mip),
                   depth = std::max(1u, volume.depth() >> mip);
    const size_t texels = size_t(width) * height * depth;
    const VkFormat format = volume.format();
    if (format != VK_FORMAT_R8G8B8A8_UNORM && format != VK_FORMAT_R16G16B16A16_SFLOAT)
        throw Error("readLevel: only RGBA8 and RGBA16F volumes are supported");
    const uint32_t texelBytes = vk::bytesPerPixel(format);
    vk::Buffer staging(context_, texels * texelBytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                       vk::MemoryUsage::HostVisible);
    context_.submitAndWait([&](VkCommandBuffer cmd) {
        // Put the volume back the way the passes left it, so the next frame's barriers stay right (a pure
        // write would discard the contents on the way back: read-write keeps them).
        vk::ImageAccess previous = volume.lastAccess();
        if (previous == vk::ImageAccess::StorageWrite) previous = vk::ImageAccess::StorageReadWrite;
        volume.use(cmd, vk::ImageAccess::TransferSrc);
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, mip, 0, 1};
        region.imageExtent = {width, height, depth};
        staging.use(cmd, vk::BufferAccess::TransferWrite);
        vkCmdCopyImageToBuffer(cmd, volume.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging.handle(),
                               1, &region);
        staging.use(cmd, vk::BufferAccess::HostRead);
        if (previous != vk::ImageAccess::Undefined) volume.use(cmd, previous);
    });
    std::vector<glm::vec4> texelsOut(texels);
    const auto* src = static_cast<const uint8_t*>(staging.mapped());
    for (size_t i = 0; i < texels; ++i) {
        for (int c = 0; c < 4; ++c) {
            if (format == VK_FORMAT_R8G8B8A8_UNORM) {
                texelsOut[i][c] = float(src[i * 4 + size_t(c)]) / 255.0f;
            } else {
                uint16_t bits;
                std::memcpy(&bits, src + (i * 4 + size_t(c)) * 2, 2);
                texelsOut[i][c] = glm::unpackHalf1x16(bits);
            }
        }
    }
    return texelsOut;
}

std::vector<glm::vec4> VoxelGrid::readVolume(vk::Image& atlas) {
    const std::vector<glm::vec4> texels = readLevel(atlas, 0);
    const size_t n = resolution_;
    std::vector<glm::vec4> out(n * n * n, glm::vec4(0.0f));
    const uint32_t side = bricks_.atlasSide;
    const size_t width = atlas.width(), height = atlas.height();
    forEachVoxel(bricks_, [&](uint32_t k, glm::ivec3 local, glm::ivec3 voxel) {
        const glm::ivec3 t = glsl::materialAtlasTexel(k, side, local);
        out[glsl::voxelLinearIndex(voxel, int(n))] =
            texels[size_t(t.x) + width * (size_t(t.y) + height * size_t(t.z))];
    });
    return out;
}

std::vector<StaticAccumVoxel> VoxelGrid::readStaticAccumulator() {
    // In slabs of bricks (at most ~64 MiB of staging each).
    constexpr uint64_t brickVoxels = uint64_t(VCT_VOXEL_BRICK) * VCT_VOXEL_BRICK * VCT_VOXEL_BRICK;
    const VkDeviceSize brickBytes = brickVoxels * kAccumVoxelBytes;
    const uint64_t count = bricks_.brickCount();
    const uint64_t bricksPerSlab = std::max<uint64_t>(1, (VkDeviceSize(64) << 20) / brickBytes);
    vk::Buffer staging(context_, brickBytes * std::max<uint64_t>(1, std::min(count, bricksPerSlab)),
                       VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUsage::HostVisible);
    std::vector<StaticAccumVoxel> voxels;
    for (uint64_t first = 0; first < count; first += bricksPerSlab) {
        const uint64_t slab = std::min(bricksPerSlab, count - first);
        context_.submitAndWait([&](VkCommandBuffer cmd) {
            staticAccum_.use(cmd, vk::BufferAccess::TransferRead);
            staging.use(cmd, vk::BufferAccess::TransferWrite);
            VkBufferCopy region{first * brickBytes, 0, slab * brickBytes};
            vkCmdCopyBuffer(cmd, staticAccum_.handle(), staging.handle(), 1, &region);
            staging.use(cmd, vk::BufferAccess::HostRead);
        });
        const auto* src = static_cast<const uint32_t*>(staging.mapped());
        for (uint64_t i = 0; i < slab * brickVoxels; ++i) {
            const uint32_t* accum = src + i * VCT_VOXEL_ACCUM_STRIDE;
            if (accum[VCT_VOXEL_ACCUM_COUNT] == 0) continue;  // no sample: empty
            const uint64_t k = first + i / brickVoxels, inBrick = i % brickVoxels;
            const glm::ivec3 local(int(inBrick % VCT_VOXEL_BRICK),
                                   int((inBrick / VCT_VOXEL_BRICK) % VCT_VOXEL_BRICK),
                                   int(inBrick / (VCT_VOXEL_BRICK * VCT_VOXEL_BRICK)));
            StaticAccumVoxel voxel;
            voxel.ijk = glm::ivec3(bricks_.bricks[k]) * glsl::VOXEL_BRICK + local;
            std::memcpy(voxel.accum.data(), accum, kAccumVoxelBytes);
            voxels.push_back(voxel);
        }
    }
    // The file lists voxels in linear-index order (io/vdb_io.h); bricks are not.
    std::sort(voxels.begin(), voxels.end(),
              [n = int(resolution_)](const StaticAccumVoxel& a, const StaticAccumVoxel& b) {
                  return glsl::voxelLinearIndex(a.ijk, n) < glsl::voxelLinearIndex(b.ijk, n);
              });
    return voxels;
}

std::vector<glm::vec4> VoxelGrid::readRadiance(uint32_t mip) {
    const size_t size = std::max(1u, resolution_ >> mip);
    std::vector<glm::vec4> out(size * size * size, glm::vec4(0.0f));
    if (mip == 0 && sparseMip0_) {
        // From the atlas: each brick's voxels (not its apron), the largest of the six slabs.
        const std::vector<glm::vec4> texels = readLevel(radianceAtlas_, 0);
        const size_t width = radianceAtlas_.width(), height = radianceAtlas_.height();
        forEachVoxel(bricks_, [&](uint32_t k, glm::ivec3 local, glm::ivec3 voxel) {
            glm::vec4& o = out[glsl::voxelLinearIndex(voxel, int(size))];
            for (int slab = 0; slab < glsl::VOXEL_SLAB_COUNT; ++slab) {
                const glm::ivec3 t = glsl::radianceAtlasTexel(k, bricks_.atlasSide, local, slab);
                o = glm::max(o, texels[size_t(t.x) + width * (size_t(t.y) + height * size_t(t.z))]);
            }
        });
        return out;
    }
    const std::vector<glm::vec4> slabs = readLevel(radianceMips_, mip - mipBase());
    for (size_t i = 0; i < out.size(); ++i) {
        const size_t x = i % size, yz = i / size;
        for (size_t slab = 0; slab < size_t(glsl::VOXEL_SLAB_COUNT); ++slab)
            out[i] = glm::max(out[i], slabs[yz * size * glsl::VOXEL_SLAB_COUNT + slab * size + x]);
    }
    return out;
}

uint64_t VoxelRegion::voxelCount() const {
    if (empty()) return 0;
    const glm::uvec3 size = max - min;
    return uint64_t(size.x) * size.y * size.z;
}

VoxelRegion VoxelRegion::atLevel(uint32_t level) const {
    if (empty()) return *this;
    const glm::uvec3 round((1u << level) - 1u);
    return {min >> level, (max + round) >> level};
}

VoxelRegion VoxelGrid::regionOf(const Aabb& box, uint32_t margin) const {
    if (box.empty()) return {};
    const glm::vec3 lo = (box.min - origin()) / voxelSize(), hi = (box.max - origin()) / voxelSize();
    const float n = float(resolution_), m = float(margin), tile = float(VCT_VOXEL_TILE);
    // Tile-aligned, so that a region's dispatch covers whole tiles as the full grid's does.
    const glm::vec3 first = glm::clamp(glm::floor((lo - m) / tile) * tile, 0.0f, n);
    const glm::vec3 last = glm::clamp(glm::ceil((hi + m + 1.0f) / tile) * tile, 0.0f, n);
    return {glm::uvec3(first), glm::uvec3(last)};
}

}  // namespace vct
