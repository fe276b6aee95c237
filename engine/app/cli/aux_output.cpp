#include "app/cli/aux_output.h"

#include <algorithm>
#include <cmath>

#include "app/cli/upsample_views.h"
#include "core/error.h"
#include "io/image_io.h"
#include "render/shader_math.h"

namespace vct {

namespace {

// Per-pixel transforms of an RGBA32F image, in place.
void toGrey(std::vector<float>& rgba, int channel) {
    for (size_t i = 0; i < rgba.size(); i += 4) {
        const float v = rgba[i + size_t(channel)];
        rgba[i] = rgba[i + 1] = rgba[i + 2] = v;
        rgba[i + 3] = 1.0f;
    }
}

void toAlbedo(std::vector<float>& rgba) {  // base colour × (1 − metallic)
    for (size_t i = 0; i < rgba.size(); i += 4) {
        const float k = 1.0f - rgba[i + 3];
        for (size_t c = 0; c < 3; ++c) rgba[i + c] *= k;
        rgba[i + 3] = 1.0f;
    }
}

void opaque(std::vector<float>& rgba) {
    for (size_t i = 3; i < rgba.size(); i += 4) rgba[i] = 1.0f;
}

uint8_t toByte(float v) {
    return uint8_t(std::lround(std::clamp(std::isfinite(v) ? v : 0.0f, 0.0f, 1.0f) * 255.0f));
}

// direct.exr, and diffuse_indirect.exr and specular_indirect.exr with GI on: the light buffers of --aux.
void writeLightBuffers(Renderer& renderer, const std::filesystem::path& dir,
                       std::vector<std::string>& written) {
    FrameTargets& t = renderer.targets();
    std::vector<float> direct = renderer.readFloatImage(t.direct);  // at the image's own size
    opaque(direct);
    writeExr(dir / "direct.exr", t.direct.width(), t.direct.height(), direct);
    written.push_back("direct.exr");
    if (renderer.voxelGrid()) {
        Renderer::IndirectLight light = renderer.readIndirect();
        opaque(light.diffuse);
        opaque(light.specular);
        writeExr(dir / "diffuse_indirect.exr", t.width, t.height, light.diffuse);
        writeExr(dir / "specular_indirect.exr", t.width, t.height, light.specular);
        written.push_back("diffuse_indirect.exr");
        written.push_back("specular_indirect.exr");
    }
}

}  // namespace

const char* auxViewName(AuxView view) {
    switch (view) {
        case AuxView::Final:
            return "final";
        case AuxView::Direct:
            return "direct";
        case AuxView::Diffuse:
            return "diffuse";
        case AuxView::Specular:
            return "specular";
        case AuxView::Normals:
            return "normals";
        case AuxView::Roughness:
            return "roughness";
        case AuxView::Voxels:
            return "voxels";
        case AuxView::Resample:
            return "resample";
        case AuxView::Weights:
            return "weights";
    }
    return "?";
}

bool auxViewNeedsGi(AuxView view) {
    return view == AuxView::Diffuse || view == AuxView::Specular || view == AuxView::Voxels ||
           view == AuxView::Resample || view == AuxView::Weights;
}

AuxView parseAuxView(const std::string& value) {
    if (value == "final") return AuxView::Final;
    if (value == "direct") return AuxView::Direct;
    if (value == "diffuse") return AuxView::Diffuse;
    if (value == "specular") return AuxView::Specular;
    if (value == "normals") return AuxView::Normals;
    if (value == "roughness") return AuxView::Roughness;
    if (value == "voxels") return AuxView::Voxels;
    if (value == "resample") return AuxView::Resample;
    if (value == "weights") return AuxView::Weights;
    throw UsageError(
        "--view '" + value +
        "': expected final, direct, diffuse, specular, normals, roughness, voxels, resample or weights");
}

void writeFinalExr(Renderer& renderer, const std::filesystem::path& path) {
    writeExr(path, renderer.settings().width, renderer.settings().height, renderer.readFinalHdr());
}

std::vector<std::string> writeLightImages(Renderer& renderer, const std::filesystem::path& dir) {
    writeFinalExr(renderer, dir / "final.exr");
    std::vector<std::string> written = {"final.exr"};
    writeLightBuffers(renderer, dir, written);
    return written;
}

std::vector<std::string> writeAuxImages(Renderer& renderer, const std::filesystem::path& dir) {
    FrameTargets& t = renderer.targets();
    const uint32_t w = t.width, h = t.height;
    std::vector<std::string> written;
    auto write = [&](const std::string& name, std::vector<float> rgba) {
        writeExr(dir / name, w, h, rgba);
        written.push_back(name);
    };
    writeLightBuffers(renderer, dir, written);
    std::vector<float> normalRoughness = renderer.readFloatImage(t.normalRoughness);
    std::vector<float> normal = normalRoughness;
    opaque(normal);
    write("normal.exr", std::move(normal));
    toGrey(normalRoughness, 3);
    write("roughness.exr", std::move(normalRoughness));
    std::vector<float> albedo = renderer.readFloatImage(t.baseColorMetallic);
    toAlbedo(albedo);
    write("albedo.exr", std::move(albedo));
    std::vector<float> depth = renderer.readFloatImage(t.depth);
    toGrey(depth, 0);
    write("depth.exr", std::move(depth));
    for (std::string& name : writeUpsampleAux(renderer, dir)) written.push_back(std::move(name));
    return written;
}

std::vector<uint8_t> viewImage(Renderer& renderer, AuxView view, uint32_t voxelMip) {
    if (view == AuxView::Final) return renderer.readLdr();
    if (view == AuxView::Resample) return resampleOverlay(renderer);
    if (view == AuxView::Weights) return weightHeatMap(renderer);
    FrameTargets& t = renderer.targets();
    std::vector<float> rgba;
    uint32_t sw = t.width, sh = t.height;  // the source's size
    if (view == AuxView::Diffuse || view == AuxView::Specular) {
        if (!renderer.voxelGrid())
            throw UsageError(std::string("--view ") + auxViewName(view) + ": needs --gi on");
        Renderer::IndirectLight light = renderer.readIndirect();
        rgba = std::move(view == AuxView::Diffuse ? light.diffuse : light.specular);
    } else {
        vk::Image* source = &t.direct;
        if (view == AuxView::Normals || view == AuxView::Roughness) source = &t.normalRoughness;
        if (view == AuxView::Voxels)
            source = &renderer.renderVoxelView(voxelMip);  // radiance: tone mapped below
        rgba = renderer.readFloatImage(*source);
        sw = source->width();
        sh = source->height();
    }
    // A source of another size is shown nearest-neighbour.
    std::vector<uint8_t> bytes(size_t(t.width) * t.height * 4);
    const float exposure = renderer.settings().exposure;
    for (size_t i = 0; i < bytes.size(); i += 4) {
        const size_t x = (i / 4) % t.width, y = (i / 4) / t.width;
        const size_t s = ((y * sh / t.height) * sw + x * sw / t.width) * 4;
        glm::vec3 c(rgba[s], rgba[s + 1], rgba[s + 2]);
        if (view == AuxView::Normals)
            c = c * 0.5f + 0.5f;
        else if (view == AuxView::Roughness)
            c = glm::vec3(rgba[s + 3]);
        else
            c = glsl::linearToSrgb(glsl::toneMapAces(c, exposure));
        for (size_t k = 0; k < 3; ++k) bytes[i + k] = toByte(c[int(k)]);
        bytes[i + 3] = 255;
    }
    return bytes;
}

}  // namespace vct
