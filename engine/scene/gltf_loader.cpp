#include "scene/gltf_loader.h"

#include <stb/stb_image.h>  // implementation in Debian's libstb
#include <sys/stat.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <glm/gtc/type_ptr.hpp>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>

#include "core/error.h"
#include "scene/deform.h"
#include "scene/input_limits.h"
#include "scene/tangents.h"

namespace vct {

namespace {

[[noreturn]] void fail(const std::string& message) {
    throw Error(message);
}

// tinygltf reports several problems separated by newlines; our errors are one line.
std::string oneLine(const std::string& text) {
    std::string out;
    bool pendingBreak = false;
    for (char c : text) {
        if (c == '\n' || c == '\r') {
            pendingBreak = !out.empty();
        } else {
            if (pendingBreak) out += "; ";
            pendingBreak = false;
            out += c;
        }
    }
    return out;
}

// One accessor converted to doubles (exact for every glTF component type, uint32 indices included),
// `components` values per element, with normalized integers mapped to [0,1] / [-1,1] as glTF says.
struct AccessorData {
    size_t count = 0;
    int components = 0;
    std::vector<double> values;
    double at(size_t element, int c) const { return values[element * size_t(components) + size_t(c)]; }
};

double readComponent(const unsigned char* p, int type, bool normalized) {
    auto load = [p](auto v) -> double {
        std::memcpy(&v, p, sizeof(v));  // buffers need not be aligned for the host
        return double(v);
    };
    // glTF: a normalized integer's largest value maps to 1; signed ones clamp their smallest to -1.
    auto unorm = [normalized](double v, double max) { return normalized ? std::max(v / max, -1.0) : v; };
    // One line per component type reads as a table.
    // clang-format off
    switch (type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: return unorm(load(int8_t{}), 127.0);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return unorm(load(uint8_t{}), 255.0);
        case TINYGLTF_COMPONENT_TYPE_SHORT: return unorm(load(int16_t{}), 32767.0);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return unorm(load(uint16_t{}), 65535.0);
        case TINYGLTF_COMPONENT_TYPE_INT: return load(int32_t{});
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return load(uint32_t{});
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return load(float{});
        default: return load(double{});  // TINYGLTF_COMPONENT_TYPE_DOUBLE (not glTF 2.0, but harmless)
    }
    // clang-format on
}

// Pointer to `count` elements of `elementSize` bytes, `stride` apart, in a buffer view. Every range is
// checked with overflow-safe arithmetic (offsets near 2^64 must not wrap into the buffer), so a truncated
// .bin or a bad offset is an error instead of a read outside the buffer.
const unsigned char* viewData(const tinygltf::Model& model, int viewIndex, uint64_t offset, uint64_t count,
                              uint64_t elementSize, size_t& stride, const std::string& what) {
    if (viewIndex < 0 || size_t(viewIndex) >= model.bufferViews.size())
        fail(what + " has no valid bufferView");
    const tinygltf::BufferView& view = model.bufferViews[size_t(viewIndex)];
    if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size())
        fail(what + ": bufferView has no valid buffer");
    const tinygltf::Buffer& buffer = model.buffers[size_t(view.buffer)];
    if (!rangeWithin(view.byteOffset, view.byteLength, buffer.data.size()))
        fail(what + ": bufferView " + std::to_string(viewIndex) + " (" + std::to_string(view.byteLength) +
             " bytes at " + std::to_string(view.byteOffset) + ") lies outside buffer " +
             std::to_string(view.buffer) + " (" + std::to_string(buffer.data.size()) +
             " bytes; truncated or missing .bin file?)");
    if (stride == 0) stride = view.byteStride ? view.byteStride : size_t(elementSize);
    uint64_t span = 0;  // offset + stride * (count - 1) + elementSize
    bool fits = count == 0 || (checkedMul(stride, count - 1, span) && checkedAdd(span, elementSize, span) &&
                               checkedAdd(span, offset, span));
    if (!fits || span > view.byteLength)
        fail(what + " reads past the end of bufferView " + std::to_string(viewIndex) + " (" +
             std::to_string(count) + " elements at offset " + std::to_string(offset) + ", " +
             std::to_string(view.byteLength) + " bytes)");
    return buffer.data.data() + view.byteOffset + offset;
}

// `zeroFillLimit`: most elements an accessor without a bufferView may have (its values are zeros plus sparse
// ones, so nothing in the file pays for them).
AccessorData readAccessor(const tinygltf::Model& model, int index, const std::string& what,
                          uint64_t& zeroFillLeft) {
    if (index < 0 || size_t(index) >= model.accessors.size()) fail(what + ": accessor index out of range");
    const tinygltf::Accessor& acc = model.accessors[size_t(index)];
    std::string name = what + " (accessor " + std::to_string(index) + ")";
    int componentSize = tinygltf::GetComponentSizeInBytes(uint32_t(acc.componentType));
    int components = tinygltf::GetNumComponentsInType(uint32_t(acc.type));
    if (componentSize <= 0 || components <= 0) fail(name + " has an unknown component type or type");
    // Without a bufferView nothing in the file pays for the elements: what all such reads of one file may
    // create together is bounded by the file's size (each read counts: 3 000 primitives sharing one such
    // accessor are 3 000 of them).
    const uint64_t limit =
        acc.bufferView >= 0 ? kMaxAccessorElements : std::min(kMaxAccessorElements, zeroFillLeft);
    if (acc.count > limit)
        fail(name + " has " + std::to_string(acc.count) + " elements, more than the " +
             std::to_string(limit) +
             (acc.bufferView >= 0 ? " allowed"
                                  : " accessors without a bufferView may still have in this file (their "
                                    "elements are budgeted by the file's size)"));
    if (acc.bufferView < 0) zeroFillLeft -= acc.count;
    size_t elementSize = size_t(componentSize) * size_t(components);
    // Ranges first: nothing is allocated for data the file does not hold.
    size_t stride = 0;
    const unsigned char* p = acc.bufferView >= 0 ? viewData(model, acc.bufferView, acc.byteOffset, acc.count,
                                                            elementSize, stride, name)
                                                 : nullptr;
    const auto& sparse = acc.sparse;
    size_t n = 0, indexStride = 0, valueStride = elementSize;
    int indexSize = 0;
    const unsigned char *ip = nullptr, *vp = nullptr;
    if (sparse.isSparse) {
        if (sparse.count < 0 || uint64_t(sparse.count) > acc.count)
            fail(name + ": sparse count " + std::to_string(sparse.count) + " is not in 0.." +
                 std::to_string(acc.count));
        n = size_t(sparse.count);
        indexSize = tinygltf::GetComponentSizeInBytes(uint32_t(sparse.indices.componentType));
        if (sparse.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
            sparse.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            sparse.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
            fail(name + ": sparse indices have component type " +
                 std::to_string(sparse.indices.componentType) + ", not an unsigned integer type");
        indexStride = size_t(indexSize);
        // int offsets in tinygltf: a negative one becomes huge and fails the range check.
        ip = viewData(model, sparse.indices.bufferView, uint64_t(int64_t(sparse.indices.byteOffset)), n,
                      size_t(indexSize), indexStride, name + " sparse indices");
        vp = viewData(model, sparse.values.bufferView, uint64_t(int64_t(sparse.values.byteOffset)), n,
                      elementSize, valueStride, name + " sparse values");
    }
    AccessorData data;
    data.count = acc.count;
    data.components = components;
    data.values.assign(acc.count * size_t(components), 0.0);  // no bufferView: zeros (then sparse values)
    if (p)
        for (size_t i = 0; i < acc.count; ++i)
            for (int c = 0; c < components; ++c)
                data.values[i * size_t(components) + size_t(c)] = readComponent(
                    p + i * stride + size_t(c * componentSize), acc.componentType, acc.normalized);
    for (size_t s = 0; s < n; ++s) {
        auto target = size_t(readComponent(ip + s * indexStride, sparse.indices.componentType, false));
        if (target >= acc.count) fail(name + ": sparse index " + std::to_string(target) + " is out of range");
        if (s > 0 &&
            target <= size_t(readComponent(ip + (s - 1) * indexStride, sparse.indices.componentType, false)))
            fail(name + ": sparse indices are not strictly increasing (index " + std::to_string(s) + ")");
        for (int c = 0; c < components; ++c)
            data.values[target * size_t(components) + size_t(c)] = readComponent(
                vp + s * valueStride + size_t(c * componentSize), acc.componentType, acc.normalized);
    }
    return data;
}

TextureWrap wrapMode(int mode) {
    if (mode == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE) return TextureWrap::ClampToEdge;
    if (mode == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT) return TextureWrap::MirroredRepeat;
    return TextureWrap::Repeat;
}

// Number in an extension object, e.g. extensions["KHR_materials_emissive_strength"]["emissiveStrength"].
std::optional<double> extensionNumber(const tinygltf::ExtensionMap& extensions, const std::string& extension,
                                      const std::string& key) {
    auto it = extensions.find(extension);
    if (it == extensions.end() || !it->second.IsObject() || !it->second.Has(key)) return std::nullopt;
    const tinygltf::Value& v = it->second.Get(key);
    return v.IsNumber() ? std::optional<double>(v.GetNumberAsDouble()) : std::nullopt;
}

// An image file's bytes as read, kept for export (Texture::encodedImage), by image index.
struct EncodedImage {
    std::shared_ptr<const std::vector<uint8_t>> bytes;
    std::string mimeType;
};

// "image/png" or "image/jpeg" from the file's signature; empty for the other formats stb decodes (glTF allows
// only these two, so an exported file gets such an image re-encoded as PNG).
std::string imageMimeType(const unsigned char* bytes, size_t size) {
    static const unsigned char png[] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
    if (size >= sizeof(png) && std::memcmp(bytes, png, sizeof(png)) == 0) return "image/png";
    if (size >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF) return "image/jpeg";
    return {};
}

class GltfImporter {
  public:
    // `inputBytes`: the JSON and every buffer together, what bounds accessors without a bufferView.
    // `refused`: files the loader would not read, and why (named in the error of a texture that needs one).
    GltfImporter(const tinygltf::Model& model, uint64_t inputBytes,
                 const std::map<std::string, std::string>& refused,
                 const std::map<int, EncodedImage>& encoded)
        : model_(model),
          encoded_(encoded),
          zeroFillLeft_(std::max<uint64_t>(4096, inputBytes)),
          elementsLeft_(std::min(kMaxSceneElements, std::max(kMinElementBudget, inputBytes))),
          keysLeft_(std::min(kMaxSceneElements, std::max(kMinElementBudget, inputBytes))),
          refused_(refused) {}

    Scene run() {
        // KHR_mesh_quantization needs nothing more than readAccessor's normalized/integer support.
        auto supported = [](const std::string& ext) {
            return ext == "KHR_lights_punctual" || ext == "KHR_materials_emissive_strength" ||
                   ext == "KHR_mesh_quantization";
        };
        for (const std::string& ext : model_.extensionsRequired)
            if (!supported(ext)) fail("requires the unsupported extension " + ext);
        for (const std::string& ext : model_.extensionsUsed)
            if (!supported(ext)) note("extension " + ext + " is not supported: ignored");
        checkTotals();
        for (size_t i = 0; i < model_.materials.size(); ++i) scene_.materials.push_back(material(i));
        for (size_t i = 0; i < model_.meshes.size(); ++i) mesh(i);
        if (scene_.materials.empty()) scene_.materials.emplace_back();  // spec default material
        for (const tinygltf::Camera& cam : model_.cameras) camera(cam);
        for (const tinygltf::Light& light : model_.lights) punctualLight(light);
        nodes();
        skins();
        for (const tinygltf::Animation& anim : model_.animations) animation(anim);
        return std::move(scene_);
    }

  private:
    // The whole-file budgets summed over the file before anything is built (400 primitives reusing one
    // accessor are refused at once, not after 399 of them); the per-read charges below hold them exactly.
    void checkTotals() const {
        auto count = [&](int index) -> uint64_t {
            return index >= 0 && size_t(index) < model_.accessors.size()
                       ? model_.accessors[size_t(index)].count
                       : 0;
        };
        uint64_t elements = 0, keys = 0;
        auto add = [](uint64_t& total, uint64_t n) {
            if (!checkedAdd(total, n, total)) total = UINT64_MAX;
        };
        for (const tinygltf::Mesh& mesh : model_.meshes)
            for (const tinygltf::Primitive& prim : mesh.primitives) {
                auto position = prim.attributes.find("POSITION");
                add(elements, position == prim.attributes.end() ? 0 : count(position->second));
                add(elements, count(prim.indices));
                // Skin influences and morph target deltas are built per vertex too.
                for (const auto& [name, index] : prim.attributes)
                    if (name.rfind("JOINTS_", 0) == 0 || name.rfind("WEIGHTS_", 0) == 0)
                        add(elements, count(index));
                for (const auto& target : prim.targets)
                    for (const auto& [name, index] : target) add(elements, count(index));
            }
        for (const tinygltf::Skin& skin : model_.skins) add(elements, count(skin.inverseBindMatrices));
        for (const tinygltf::Animation& animation : model_.animations)
            for (const tinygltf::AnimationChannel& channel : animation.channels)
                if (channel.sampler >= 0 && size_t(channel.sampler) < animation.samplers.size()) {
                    const tinygltf::AnimationSampler& sampler = animation.samplers[size_t(channel.sampler)];
                    add(keys, count(sampler.input));
                    add(keys, count(sampler.output));
                }
        // Texels of every texture the materials make (an image used as colour and as data is two textures).
        std::set<std::pair<int, TextureKind>> textures;
        for (const tinygltf::Material& m : model_.materials) {
            textures.insert({m.pbrMetallicRoughness.baseColorTexture.index, TextureKind::Color});
            textures.insert({m.pbrMetallicRoughness.metallicRoughnessTexture.index, TextureKind::Linear});
            textures.insert({m.normalTexture.index, TextureKind::Normal});
            textures.insert({m.emissiveTexture.index, TextureKind::Color});
            textures.insert({m.occlusionTexture.index, TextureKind::Linear});
        }
        uint64_t texels = 0;
        for (const auto& [index, kind] : textures) {
            if (index < 0 || size_t(index) >= model_.textures.size()) continue;
            const int source = model_.textures[size_t(index)].source;
            if (source < 0 || size_t(source) >= model_.images.size()) continue;
            const tinygltf::Image& image = model_.images[size_t(source)];
            add(texels, uint64_t(std::max(image.width, 0)) * uint64_t(std::max(image.height, 0)));
        }
        if (texels > texelsLeft_)
            fail("its materials make textures of " + std::to_string(texels) +
                 " texels together (an image used as colour and as data counts twice), more than the " +
                 std::to_string(texelsLeft_) + " one file may have");
        if (elements > elementsLeft_)
            fail("its primitives build " + std::to_string(elements) +
                 " vertices and indices together, more than the file's budget of " +
                 std::to_string(elementsLeft_) + " (it reuses its data too often or is too large)");
        if (keys > keysLeft_)
            fail("its animation channels copy " + std::to_string(keys) +
                 " animation keys together, more than the file's budget of " + std::to_string(keysLeft_));
    }

    AccessorData accessor(int index, const std::string& what) {
        return readAccessor(model_, index, what, zeroFillLeft_);
    }

    // Whole-file budgets, charged before allocating: what one file may make us build in total, however
    // often it reuses one accessor or image (the file's size bounds it, within the fixed caps).
    static void charge(uint64_t& left, uint64_t amount, const std::string& what, const char* unit) {
        if (amount > left)
            fail(what + " would take the file past its budget of " + unit + " (" + std::to_string(amount) +
                 " more, " + std::to_string(left) +
                 " left: the file reuses its data too often or is "
                 "too large)");
        left -= amount;
    }

    void note(const std::string& text) {
        if (std::find(scene_.notes.begin(), scene_.notes.end(), text) == scene_.notes.end())
            scene_.notes.push_back(text);
    }

    // Scene texture for a glTF texture in one role; a texture used as colour and as data is duplicated,
    // because the two need different formats (sRGB vs UNORM) and different mip filtering.
    int texture(int gltfIndex, int texCoord, TextureKind kind) {
        if (gltfIndex < 0) return -1;
        if (size_t(gltfIndex) >= model_.textures.size())
            fail("texture index " + std::to_string(gltfIndex) + " is out of range");
        if (texCoord != 0) note("only TEXCOORD_0 is supported: textures using other UV sets use TEXCOORD_0");
        auto key = std::make_pair(gltfIndex, kind);
        if (auto it = textureCache_.find(key); it != textureCache_.end()) return it->second;
        const tinygltf::Texture& src = model_.textures[size_t(gltfIndex)];
        if (src.source < 0 || size_t(src.source) >= model_.images.size())
            fail("texture " + std::to_string(gltfIndex) +
                 " has no image (image extensions such as KTX2/WebP are not supported)");
        const tinygltf::Image& image = model_.images[size_t(src.source)];
        std::string imageName = !image.uri.empty()    ? image.uri
                                : !image.name.empty() ? image.name
                                                      : "image " + std::to_string(src.source);
        if (image.image.empty() || image.width <= 0 || image.height <= 0) {
            if (auto it = refused_.find("#image " + std::to_string(src.source)); it != refused_.end())
                fail("texture " + std::to_string(gltfIndex) + ": " + it->second);
            for (const auto& [file, why] : refused_)
                if (!image.uri.empty() &&
                    std::filesystem::path(file).filename() == std::filesystem::path(image.uri).filename())
                    fail("texture image '" + imageName + "': " + why);
            fail("texture image '" + imageName + "' is missing or could not be decoded");
        }
        charge(texelsLeft_, uint64_t(image.width) * uint64_t(image.height),
               "texture image '" + imageName + "'", "decoded texels");
        Texture tex;
        tex.name = imageName;
        tex.kind = kind;
        if (src.sampler >= 0 && size_t(src.sampler) < model_.samplers.size()) {
            tex.wrapS = wrapMode(model_.samplers[size_t(src.sampler)].wrapS);
            tex.wrapT = wrapMode(model_.samplers[size_t(src.sampler)].wrapT);
        }
        tex.width = uint32_t(image.width);
        tex.height = uint32_t(image.height);
        tex.mips.push_back(toRgba8(image, imageName));
        buildMipChain(tex);
        if (auto it = encoded_.find(src.source); it != encoded_.end()) {
            tex.encodedImage = it->second.bytes;
            tex.encodedMimeType = it->second.mimeType;
        }
        scene_.textures.push_back(std::move(tex));
        int index = int(scene_.textures.size()) - 1;
        textureCache_[key] = index;
        return index;
    }

    // Any 1-4 channel, 8- or 16-bit decoded image to RGBA8 (grey replicates, missing alpha is opaque).
    static std::vector<uint8_t> toRgba8(const tinygltf::Image& image, const std::string& name) {
        int channels = image.component, bytes = image.bits / 8;
        size_t pixels = size_t(image.width) * size_t(image.height);
        if (channels < 1 || channels > 4 || (bytes != 1 && bytes != 2))
            fail("texture image '" + name + "' has an unsupported pixel format (" + std::to_string(channels) +
                 " channels, " + std::to_string(image.bits) + " bits)");
        if (image.image.size() < pixels * size_t(channels * bytes))
            fail("texture image '" + name + "' is truncated");
        auto channel = [&](size_t pixel, int c) -> uint8_t {
            const unsigned char* p =
                image.image.data() + (pixel * size_t(channels) + size_t(c)) * size_t(bytes);
            if (bytes == 1) return p[0];
            uint16_t v;
            std::memcpy(&v, p, 2);
            return uint8_t((uint32_t(v) * 255u + 32767u) / 65535u);
        };
        std::vector<uint8_t> out(pixels * 4);
        for (size_t i = 0; i < pixels; ++i) {
            uint8_t* o = &out[i * 4];
            if (channels <= 2) {
                o[0] = o[1] = o[2] = channel(i, 0);
                o[3] = channels == 2 ? channel(i, 1) : 255;
            } else {
                for (int c = 0; c < 3; ++c) o[c] = channel(i, c);
                o[3] = channels == 4 ? channel(i, 3) : 255;
            }
        }
        return out;
    }

    Material material(size_t index) {
        const tinygltf::Material& src = model_.materials[index];
        const tinygltf::PbrMetallicRoughness& pbr = src.pbrMetallicRoughness;
        Material m;
        m.name = src.name.empty() ? "material " + std::to_string(index) : src.name;
        if (pbr.baseColorFactor.size() == 4) m.baseColorFactor = glm::make_vec4(pbr.baseColorFactor.data());
        m.metallicFactor = float(pbr.metallicFactor);
        m.roughnessFactor = float(pbr.roughnessFactor);
        if (src.emissiveFactor.size() == 3) m.emissiveFactor = glm::make_vec3(src.emissiveFactor.data());
        const std::string where = "material '" + m.name + "'";
        // Light cannot be negative: glTF bounds these factors to [0, 1] (strength to >= 0).
        if (src.emissiveFactor.size() == 3 &&
            !(src.emissiveFactor[0] >= 0.0 && src.emissiveFactor[1] >= 0.0 && src.emissiveFactor[2] >= 0.0))
            fail(where + ": emissiveFactor has a negative (or NaN) component");
        if (auto strength =
                extensionNumber(src.extensions, "KHR_materials_emissive_strength", "emissiveStrength")) {
            if (!(*strength >= 0.0) || !std::isfinite(*strength))
                fail(where + ": emissiveStrength " + numberText(*strength) +
                     " is not finite and non-negative");
            m.emissiveFactor *= float(*strength);
        }
        if (pbr.baseColorFactor.size() == 4)
            for (double c : pbr.baseColorFactor)
                if (!(c >= 0.0)) fail(where + ": baseColorFactor has a negative (or NaN) component");
        if (!(src.occlusionTexture.strength >= 0.0 && src.occlusionTexture.strength <= 1.0))
            fail(where + ": occlusionTexture.strength " + numberText(src.occlusionTexture.strength) +
                 " is not in [0, 1]");
        m.normalScale = float(src.normalTexture.scale);
        m.occlusionStrength = float(src.occlusionTexture.strength);
        m.alphaCutoff = float(src.alphaCutoff);
        m.alphaMode = src.alphaMode == "MASK"    ? AlphaMode::Mask
                      : src.alphaMode == "BLEND" ? AlphaMode::Blend
                                                 : AlphaMode::Opaque;
        m.doubleSided = src.doubleSided;
        m.baseColorTexture =
            texture(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord, TextureKind::Color);
        m.metallicRoughnessTexture = texture(pbr.metallicRoughnessTexture.index,
                                             pbr.metallicRoughnessTexture.texCoord, TextureKind::Linear);
        m.normalTexture = texture(src.normalTexture.index, src.normalTexture.texCoord, TextureKind::Normal);
        m.emissiveTexture =
            texture(src.emissiveTexture.index, src.emissiveTexture.texCoord, TextureKind::Color);
        m.occlusionTexture =
            texture(src.occlusionTexture.index, src.occlusionTexture.texCoord, TextureKind::Linear);
        return m;
    }

    // Material 0..n-1 are the file's; primitives without one share a spec-default material appended once.
    uint32_t defaultMaterial() {
        if (defaultMaterial_ < 0) {
            Material m;
            m.name = "default";
            scene_.materials.push_back(m);
            defaultMaterial_ = int(scene_.materials.size()) - 1;
        }
        return uint32_t(defaultMaterial_);
    }

    // Triangle-list indices for a primitive of any triangle mode.
    static std::vector<uint32_t> triangles(const std::vector<uint32_t>& in, int mode,
                                           const std::string& where) {
        if (mode == TINYGLTF_MODE_TRIANGLES) return in;
        std::vector<uint32_t> out;
        if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
            // Every other triangle of a strip is flipped so that all keep the strip's winding.
            for (size_t i = 0; i + 2 < in.size(); ++i) {
                bool odd = i & 1;
                out.insert(out.end(), {in[i], in[odd ? i + 2 : i + 1], in[odd ? i + 1 : i + 2]});
            }
        } else if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
            for (size_t i = 1; i + 1 < in.size(); ++i) out.insert(out.end(), {in[i], in[i + 1], in[0]});
        } else {
            fail(where + ": unsupported primitive mode " + std::to_string(mode) +
                 " (only triangles, strips and fans)");
        }
        return out;
    }

    void mesh(size_t meshIndex) {
        const tinygltf::Mesh& src = model_.meshes[meshIndex];
        Mesh out;
        out.name = src.name.empty() ? "mesh " + std::to_string(meshIndex) : src.name;
        if (src.primitives.empty()) fail("mesh '" + out.name + "' has no primitives (glTF requires one)");
        for (size_t p = 0; p < src.primitives.size(); ++p) {
            const tinygltf::Primitive& prim = src.primitives[p];
            std::string where = "mesh '" + out.name + "' primitive " + std::to_string(p);
            auto attribute = [&](const char* name) {
                auto it = prim.attributes.find(name);
                return it == prim.attributes.end() ? -1 : it->second;
            };
            if (attribute("POSITION") < 0) fail(where + " has no POSITION attribute");
            {
                const int index = attribute("POSITION");
                if (index >= 0 && size_t(index) < model_.accessors.size())
                    charge(elementsLeft_, model_.accessors[size_t(index)].count, where,
                           "vertices and indices");
                if (prim.indices >= 0 && size_t(prim.indices) < model_.accessors.size())
                    charge(elementsLeft_, model_.accessors[size_t(prim.indices)].count, where,
                           "vertices and indices");
            }
            AccessorData pos = accessor(attribute("POSITION"), where + " POSITION");
            if (pos.components < 3) fail(where + " POSITION is not a vec3");
            std::vector<Vertex> verts(pos.count);
            for (size_t i = 0; i < pos.count; ++i)
                verts[i].position = glm::vec3(pos.at(i, 0), pos.at(i, 1), pos.at(i, 2));
            auto readInto = [&](const char* name, int minComponents, auto store) {
                if (attribute(name) < 0) return false;
                AccessorData a = accessor(attribute(name), where + " " + name);
                if (a.count != pos.count || a.components < minComponents)
                    fail(where + " " + name + " has " + std::to_string(a.count) + " elements of " +
                         std::to_string(a.components) + " components, expected " + std::to_string(pos.count));
                for (size_t i = 0; i < a.count; ++i) store(verts[i], a, i);
                return true;
            };
            bool hasNormals = readInto("NORMAL", 3, [](Vertex& v, const AccessorData& a, size_t i) {
                v.normal = glm::vec3(a.at(i, 0), a.at(i, 1), a.at(i, 2));
            });
            readInto("TEXCOORD_0", 2, [](Vertex& v, const AccessorData& a, size_t i) {
                v.uv = glm::vec2(a.at(i, 0), a.at(i, 1));
            });
            bool hasTangents = readInto("TANGENT", 4, [](Vertex& v, const AccessorData& a, size_t i) {
                // glTF tangents are unit xyz with w = ±1; quantised data may be slightly off, so snap w.
                v.tangent = glm::vec4(a.at(i, 0), a.at(i, 1), a.at(i, 2), a.at(i, 3) < 0.0 ? -1.0 : 1.0);
            });

            const bool hasColors = vertexColors(prim, where, verts);

            std::vector<uint32_t> idx;
            if (prim.indices >= 0) {
                if (size_t(prim.indices) < model_.accessors.size()) {
                    const tinygltf::Accessor& ia = model_.accessors[size_t(prim.indices)];
                    if (ia.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
                        ia.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
                        ia.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
                        fail(where + " indices have component type " + std::to_string(ia.componentType) +
                             ", not an unsigned integer type");
                    if (ia.type != TINYGLTF_TYPE_SCALAR) fail(where + " indices are not scalars");
                }
                AccessorData a = accessor(prim.indices, where + " indices");
                for (double v : a.values) idx.push_back(uint32_t(v));
            } else {
                for (size_t i = 0; i < pos.count; ++i) idx.push_back(uint32_t(i));
            }
            idx = triangles(idx, prim.mode, where);
            idx.erase(idx.end() - std::ptrdiff_t(idx.size() % 3), idx.end());  // whole triangles only
            for (size_t i = 0; i < idx.size(); ++i)
                if (idx[i] >= verts.size())
                    fail(where + ": index " + std::to_string(i) + " (= " + std::to_string(idx[i]) +
                         ") is out of range (" + std::to_string(verts.size()) + " vertices)");

            DeformData deform = deformAttributes(prim, where, pos.count);
            if (!hasNormals) {
                const std::vector<uint32_t> welded = idx;  // flat vertex i is welded vertex welded[i]
                makeFlatNormals(verts, idx);
                hasTangents = false;  // the file's tangents belonged to the welded vertices
                deform.unweld(welded);
            }
            if (!hasTangents) generateTangents(verts, idx);

            Primitive out_prim;
            out_prim.firstIndex = uint32_t(scene_.indices.size());
            out_prim.indexCount = uint32_t(idx.size());
            out_prim.vertexOffset = int32_t(scene_.vertices.size());
            out_prim.vertexCount = uint32_t(verts.size());
            out_prim.hasColors = hasColors;
            if (prim.material >= 0 && size_t(prim.material) >= model_.materials.size())
                fail(where + ": material " + std::to_string(prim.material) + " is out of range");
            out_prim.material = prim.material >= 0 ? uint32_t(prim.material) : defaultMaterial();
            for (const Vertex& v : verts) out_prim.bounds.extend(v.position);
            scene_.vertices.insert(scene_.vertices.end(), verts.begin(), verts.end());
            scene_.indices.insert(scene_.indices.end(), idx.begin(), idx.end());
            if (!deform.skin.empty()) {
                out_prim.skinVertexOffset = int32_t(scene_.skinVertices.size());
                out_prim.maxJoint = deform.maxJoint;
                scene_.skinVertices.insert(scene_.skinVertices.end(), deform.skin.begin(), deform.skin.end());
            }
            out_prim.morphTargetCount = deform.targets;
            out_prim.morphDeltaOffset = uint32_t(scene_.morphDeltas.size());
            scene_.morphDeltas.insert(scene_.morphDeltas.end(), deform.deltas.begin(), deform.deltas.end());
            out.primitives.push_back(uint32_t(scene_.primitives.size()));
            scene_.primitives.push_back(out_prim);
        }
        for (uint32_t p : out.primitives)
            if (scene_.primitives[p].morphTargetCount !=
                scene_.primitives[out.primitives[0]].morphTargetCount)
                fail("mesh '" + out.name + "': its primitives have different numbers of morph targets (" +
                     std::to_string(scene_.primitives[out.primitives[0]].morphTargetCount) + " and " +
                     std::to_string(scene_.primitives[p].morphTargetCount) + ")");
        for (double w : src.weights) out.weights.push_back(float(w));
        scene_.meshes.push_back(std::move(out));
    }

    // COLOR_0 into Vertex::color (glTF: VEC3 or VEC4 of FLOAT, or of normalized UNSIGNED_BYTE / UNSIGNED_SHORT;
    // a VEC3 is opaque). False when the primitive has none. Further colour sets are named in a note.
    bool vertexColors(const tinygltf::Primitive& prim, const std::string& where, std::vector<Vertex>& verts) {
        for (const auto& [name, index] : prim.attributes)
            if (name.rfind("COLOR_", 0) == 0 && name != "COLOR_0")
                note("only COLOR_0 is supported: vertex colour sets COLOR_1 and above are ignored");
        auto it = prim.attributes.find("COLOR_0");
        if (it == prim.attributes.end()) return false;
        const std::string what = where + " COLOR_0";
        if (it->second < 0 || size_t(it->second) >= model_.accessors.size())
            fail(what + ": accessor index out of range");
        const tinygltf::Accessor& acc = model_.accessors[size_t(it->second)];
        if (acc.type != TINYGLTF_TYPE_VEC3 && acc.type != TINYGLTF_TYPE_VEC4)
            fail(what + " is not a VEC3 or VEC4 (type " + std::to_string(acc.type) + ")");
        const bool normalizedInteger = (acc.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                        acc.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) &&
                                       acc.normalized;
        if (acc.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !normalizedInteger)
            fail(what + " has component type " + std::to_string(acc.componentType) +
                 (acc.normalized ? "" : " (not normalized)") +
                 ", not FLOAT or normalized UNSIGNED_BYTE / UNSIGNED_SHORT");
        if (acc.count != verts.size())  // before reading: a long accessor is not copied to be refused
            fail(what + " has " + std::to_string(acc.count) + " elements, expected " +
                 std::to_string(verts.size()) + " (one per POSITION)");
        const AccessorData a = accessor(it->second, what);
        bool clamped = false;
        for (size_t i = 0; i < a.count; ++i) {
            glm::vec4 c(1.0f);
            for (int k = 0; k < a.components; ++k) {
                const double v = a.at(i, k);
                if (!std::isfinite(v)) fail(what + ": element " + std::to_string(i) + " is not finite");
                clamped |= v < 0.0 || v > 1.0;
                c[k] = float(std::clamp(v, 0.0, 1.0));
            }
            verts[i].color = c;
        }
        if (clamped) note(where + ": COLOR_0 values outside [0, 1] clamped (glTF colours are in [0, 1])");
        return true;
    }

    void camera(const tinygltf::Camera& src) {
        Camera cam;
        cam.name = src.name;
        if (src.type == "orthographic") {
            note("orthographic cameras are approximated by a 45 degree perspective camera");
            cam.yfov = 0.785398f;
            cam.znear = std::max(float(src.orthographic.znear), 0.01f);
            cam.zfar = std::max(float(src.orthographic.zfar), cam.znear * 2.0f);
        } else if (src.type == "perspective") {
            // What glTF requires of a perspective camera; nothing is guessed (an empty image would follow).
            const tinygltf::PerspectiveCamera& lens = src.perspective;
            const std::string where = "camera '" + src.name + "'";
            if (!(lens.yfov > 0.0 && lens.yfov < 3.14159265))
                fail(where + ": yfov " + numberText(lens.yfov) + " is not in (0, pi)");
            if (!(lens.znear > 0.0) || !std::isfinite(lens.znear))
                fail(where + ": znear " + numberText(lens.znear) + " is not finite and positive");
            if (lens.zfar < 0.0 || (lens.zfar > 0.0 && !(lens.zfar > lens.znear)))
                fail(where + ": zfar " + numberText(lens.zfar) + " is not greater than znear " +
                     numberText(lens.znear) + " (or 0: infinite)");
            cam.yfov = float(src.perspective.yfov);
            cam.znear = float(src.perspective.znear);
            cam.zfar = float(src.perspective.zfar);  // 0 (infinite) is made finite once the bounds are known
            cam.aspectRatio = float(src.perspective.aspectRatio);
        } else {
            fail("camera '" + src.name + "': type '" + printableText(src.type, 40) +
                 "' is not perspective or orthographic");
        }
        // Past float's range a far plane is as good as none: made finite from the bounds like an infinite
        // one.
        if (!std::isfinite(cam.zfar)) cam.zfar = 0.0f;
        if (!(cam.aspectRatio > 0.0f) || !std::isfinite(cam.aspectRatio)) cam.aspectRatio = 0.0f;
        scene_.cameras.push_back(cam);
    }

    void punctualLight(const tinygltf::Light& src) {
        Light light;
        light.name = src.name;
        if (src.type != "spot" && src.type != "point" && src.type != "directional")
            fail("light '" + src.name + "': type '" + printableText(src.type, 40) +
                 "' is not directional, point or spot");
        light.type = src.type == "spot"    ? LightType::Spot
                     : src.type == "point" ? LightType::Point
                                           : LightType::Directional;
        if (src.color.size() == 3) light.color = glm::make_vec3(src.color.data());
        light.intensity = float(src.intensity);
        light.range = float(src.range);
        light.innerConeAngle = float(src.spot.innerConeAngle);
        light.outerConeAngle = float(src.spot.outerConeAngle);
        scene_.lights.push_back(light);
    }

    void nodes() {
        size_t count = model_.nodes.size();
        scene_.nodes.resize(count);
        for (size_t i = 0; i < count; ++i) {
            const tinygltf::Node& src = model_.nodes[i];
            Node& node = scene_.nodes[i];
            node.name = src.name.empty() ? "node " + std::to_string(i) : src.name;
            if (src.matrix.size() == 16) {
                node.matrix = glm::mat4(glm::make_mat4(src.matrix.data()));  // both column-major
            } else {
                if (src.translation.size() == 3) node.translation = glm::make_vec3(src.translation.data());
                if (src.rotation.size() == 4)
                    node.rotation = glm::normalize(glm::quat(float(src.rotation[3]), float(src.rotation[0]),
                                                             float(src.rotation[1]), float(src.rotation[2])));
                if (src.scale.size() == 3) node.scale = glm::make_vec3(src.scale.data());
            }
            auto check = [&](int index, size_t size, const char* what) {
                if (index >= 0 && size_t(index) >= size)
                    fail("node '" + node.name + "': " + what + " index " + std::to_string(index) +
                         " is out of range");
                return index;
            };
            node.mesh = check(src.mesh, scene_.meshes.size(), "mesh");
            node.camera = check(src.camera, scene_.cameras.size(), "camera");
            node.skin = check(src.skin, model_.skins.size(), "skin");
            for (double w : src.weights) node.weights.push_back(float(w));
            if (auto light = extensionNumber(src.extensions, "KHR_lights_punctual", "light")) {
                if (!(*light >= 0.0 && *light < double(scene_.lights.size())))
                    fail("node '" + node.name + "': light index " + numberText(*light) + " is out of range");
                node.light = int(*light);
            }
            for (int c : src.children) {
                check(c, count, "child");
                if (c < 0 || scene_.nodes[size_t(c)].parent >= 0 || size_t(c) == i)
                    fail("node '" + node.name + "': child " + std::to_string(c) +
                         " is invalid or has two parents");
                scene_.nodes[size_t(c)].parent = int(i);
                node.children.push_back(c);
            }
        }
        // A node that is its own ancestor: its transform is undefined (and the hierarchy would loop).
        std::vector<int> state(count, 0);  // 0 unknown, 1 reaches a root
        for (size_t i = 0; i < count; ++i) {
            size_t steps = 0;
            for (int n = int(i); n >= 0 && state[size_t(n)] == 0; n = scene_.nodes[size_t(n)].parent)
                if (++steps > count)
                    fail("node '" + scene_.nodes[i].name +
                         "' is its own ancestor (the node hierarchy has a cycle)");
            for (int n = int(i); n >= 0 && state[size_t(n)] == 0; n = scene_.nodes[size_t(n)].parent)
                state[size_t(n)] = 1;
        }
        if (model_.defaultScene >= 0 && size_t(model_.defaultScene) >= model_.scenes.size())
            fail("scene index " + std::to_string(model_.defaultScene) + " is out of range (" +
                 std::to_string(model_.scenes.size()) + " scenes)");
        int sceneIndex = model_.defaultScene >= 0 ? model_.defaultScene : 0;
        if (size_t(sceneIndex) < model_.scenes.size()) {
            for (int n : model_.scenes[size_t(sceneIndex)].nodes) {
                if (n < 0 || size_t(n) >= count)
                    fail("scene " + std::to_string(sceneIndex) + ": node " + std::to_string(n) +
                         " is out of range");
                scene_.roots.push_back(n);
            }
        } else {
            for (size_t i = 0; i < count; ++i)
                if (scene_.nodes[i].parent < 0) scene_.roots.push_back(int(i));
        }
    }

    void animation(const tinygltf::Animation& src) {
        Animation anim;
        anim.name = src.name;
        for (const tinygltf::AnimationChannel& ch : src.channels) {
            if (ch.target_path == "weights") {
                weightsChannel(anim, src, ch);
                continue;
            }
            if (ch.target_node < 0 || size_t(ch.target_node) >= scene_.nodes.size() || ch.sampler < 0 ||
                size_t(ch.sampler) >= src.samplers.size())
                fail("animation '" + src.name + "': channel has an invalid node or sampler");
            if (scene_.nodes[size_t(ch.target_node)].matrix) {
                note("animation channels on nodes with a matrix are ignored (glTF forbids them)");
                continue;
            }
            const tinygltf::AnimationSampler& sampler = src.samplers[size_t(ch.sampler)];
            if (ch.target_path != "translation" && ch.target_path != "rotation" && ch.target_path != "scale")
                fail("animation '" + src.name + "': channel path '" + printableText(ch.target_path, 40) +
                     "' is not translation, rotation, scale or weights");
            if (!sampler.interpolation.empty() && sampler.interpolation != "LINEAR" &&
                sampler.interpolation != "STEP" && sampler.interpolation != "CUBICSPLINE")
                fail("animation '" + src.name + "': interpolation '" +
                     printableText(sampler.interpolation, 40) + "' is not LINEAR, STEP or CUBICSPLINE");
            for (int index : {sampler.input, sampler.output})
                if (index >= 0 && size_t(index) < model_.accessors.size())
                    charge(keysLeft_, model_.accessors[size_t(index)].count,
                           "animation '" + src.name + "' channel " + ch.target_path, "animation keys");
            AnimationChannel out;
            out.node = ch.target_node;
            out.path = ch.target_path == "rotation" ? AnimationPath::Rotation
                       : ch.target_path == "scale"  ? AnimationPath::Scale
                                                    : AnimationPath::Translation;
            out.interpolation = sampler.interpolation == "STEP"          ? Interpolation::Step
                                : sampler.interpolation == "CUBICSPLINE" ? Interpolation::CubicSpline
                                                                         : Interpolation::Linear;
            std::string where = "animation '" + src.name + "' channel " + ch.target_path;
            AccessorData in = accessor(sampler.input, where + " input");
            AccessorData values = accessor(sampler.output, where + " output");
            int wanted = out.path == AnimationPath::Rotation ? 4 : 3;
            size_t perKey = out.interpolation == Interpolation::CubicSpline ? 3 : 1;
            if (in.count == 0 || values.components != wanted || values.count != in.count * perKey)
                fail(where + ": " + std::to_string(values.count) + " output values do not match " +
                     std::to_string(in.count) + " key times");
            for (size_t k = 0; k < in.count; ++k) {
                double t = in.at(k, 0);
                if (!std::isfinite(t) || (k > 0 && t < out.times.back()))
                    fail(where + ": key times are not increasing");
                out.times.push_back(float(t));
            }
            for (size_t k = 0; k < values.count; ++k) {
                glm::vec4 v(values.at(k, 0), values.at(k, 1), values.at(k, 2),
                            wanted == 4 ? values.at(k, 3) : 0.0);
                if (!std::isfinite(v.x + v.y + v.z + v.w))
                    fail(where + ": key value " + std::to_string(k) + " is not finite");
                out.values.push_back(v);
            }
            anim.duration = std::max(anim.duration, out.times.back());
            anim.channels.push_back(std::move(out));
        }
        if (!anim.channels.empty() || !anim.weightChannels.empty())
            scene_.animations.push_back(std::move(anim));
    }

    // ---- skins and morph targets (scene/deform.h) ----

    // A primitive's skin influences and morph target deltas, parallel to its vertices.
    struct DeformData {
        std::vector<SkinVertex> skin;  // empty without JOINTS_0/WEIGHTS_0
        uint32_t maxJoint = 0;         // the largest joint index with a weight
        uint32_t targets = 0;
        std::vector<MorphDelta> deltas;  // target-major
        size_t vertexCount = 0;

        // makeFlatNormals gave every triangle corner its own vertex: the same for the per-vertex data (normal
        // deltas belonged to the welded normals and are dropped with them).
        void unweld(const std::vector<uint32_t>& welded) {
            if (!skin.empty()) {
                std::vector<SkinVertex> flat(welded.size());
                for (size_t i = 0; i < welded.size(); ++i) flat[i] = skin[welded[i]];
                skin = std::move(flat);
            }
            std::vector<MorphDelta> flat(size_t(targets) * welded.size());
            for (size_t t = 0; t < targets; ++t)
                for (size_t i = 0; i < welded.size(); ++i) {
                    flat[t * welded.size() + i] = deltas[t * vertexCount + welded[i]];
                    flat[t * welded.size() + i].normal = glm::vec4(0.0f);
                }
            deltas = std::move(flat);
            vertexCount = welded.size();
        }
    };

    DeformData deformAttributes(const tinygltf::Primitive& prim, const std::string& where, size_t count) {
        DeformData out;
        out.vertexCount = count;
        auto attribute = [&](const std::string& name) {
            auto it = prim.attributes.find(name);
            return it == prim.attributes.end() ? -1 : it->second;
        };
        auto chargeVertices = [&](int index, const std::string& what) {
            if (index >= 0 && size_t(index) < model_.accessors.size())
                charge(elementsLeft_, model_.accessors[size_t(index)].count, what, "vertices and indices");
        };
        // Two weight sets (8 influences per vertex); glTF allows more, which are named and left out.
        for (int set = 0; set < 2; ++set) {
            const std::string jointsName = "JOINTS_" + std::to_string(set),
                              weightsName = "WEIGHTS_" + std::to_string(set);
            const int joints = attribute(jointsName), weights = attribute(weightsName);
            if (joints < 0 && weights < 0) continue;
            if (joints < 0 || weights < 0)
                fail(where + " has " +
                     (joints < 0 ? weightsName + " without " + jointsName
                                 : jointsName + " without " + weightsName));
            for (auto [index, name] : {std::pair{joints, jointsName}, {weights, weightsName}}) {
                if (size_t(index) >= model_.accessors.size())
                    fail(where + " " + name + ": accessor index out of range");
                const tinygltf::Accessor& a = model_.accessors[size_t(index)];
                const bool integer = a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                     a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
                if (name == jointsName
                        ? !integer
                        : !(a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT || (integer && a.normalized)))
                    fail(where + " " + name + " has component type " + std::to_string(a.componentType) +
                         (name == jointsName ? ", not unsigned byte or short"
                                             : ", not float or normalized unsigned byte or short"));
                chargeVertices(index, where + " " + name);
            }
            const AccessorData j = accessor(joints, where + " " + jointsName);
            const AccessorData w = accessor(weights, where + " " + weightsName);
            for (const auto& [a, name] : {std::pair{&j, jointsName}, {&w, weightsName}})
                if (a->count != count || a->components != 4)
                    fail(where + " " + name + " has " + std::to_string(a->count) + " elements of " +
                         std::to_string(a->components) + " components, expected " + std::to_string(count) +
                         " VEC4");
            if (out.skin.empty()) out.skin.resize(count);
            for (size_t v = 0; v < count; ++v)
                for (int c = 0; c < 4; ++c) {
                    const double weight = w.at(v, c);
                    if (!(weight >= 0.0) || !std::isfinite(weight))
                        fail(where + " " + weightsName + " of vertex " + std::to_string(v) + " is " +
                             numberText(weight) + ", not finite and non-negative");
                    const auto joint = uint32_t(j.at(v, c));
                    SkinVertex& s = out.skin[v];
                    (set == 0 ? s.joints0 : s.joints1)[c] = joint;
                    (set == 0 ? s.weights0 : s.weights1)[c] = float(weight);
                    if (weight > 0.0) out.maxJoint = std::max(out.maxJoint, joint);
                }
        }
        if (attribute("JOINTS_2") >= 0 || attribute("WEIGHTS_2") >= 0)
            note(
                "skin weight sets past JOINTS_1/WEIGHTS_1 are not supported: left out (the others "
                "renormalised)");
        if (!out.skin.empty() && attribute("JOINTS_0") < 0) fail(where + " has JOINTS_1 without JOINTS_0");
        // Weights that do not sum to 1 are renormalised (quantised weights rarely do exactly); all zero: the
        // vertex keeps its bind pose.
        size_t unweighted = 0;
        for (SkinVertex& s : out.skin) {
            const float sum = s.weights0.x + s.weights0.y + s.weights0.z + s.weights0.w + s.weights1.x +
                              s.weights1.y + s.weights1.z + s.weights1.w;
            if (!(sum > 0.0f)) {
                ++unweighted;
            } else if (sum != 1.0f) {
                s.weights0 /= sum;
                s.weights1 /= sum;
            }
        }
        if (unweighted > 0)
            note(where + ": " + std::to_string(unweighted) +
                 " vertices have all-zero skin weights: drawn in the bind pose");

        out.targets = uint32_t(prim.targets.size());
        out.deltas.resize(size_t(out.targets) * count);
        for (size_t t = 0; t < prim.targets.size(); ++t)
            for (const auto& [name, index] : prim.targets[t]) {
                const int slot = name == "POSITION" ? 0 : name == "NORMAL" ? 1 : name == "TANGENT" ? 2 : -1;
                if (slot < 0) {
                    note("morph target attribute " + printableText(name, 40) + " is not supported: ignored");
                    continue;
                }
                const std::string what = where + " morph target " + std::to_string(t) + " " + name;
                chargeVertices(index, what);
                const AccessorData a = accessor(index, what);
                if (a.count != count || a.components != 3)
                    fail(what + " has " + std::to_string(a.count) + " elements of " +
                         std::to_string(a.components) + " components, expected " + std::to_string(count) +
                         " VEC3");
                for (size_t v = 0; v < count; ++v) {
                    const glm::vec4 d(a.at(v, 0), a.at(v, 1), a.at(v, 2), 0.0);
                    if (!std::isfinite(d.x + d.y + d.z))
                        fail(what + " of vertex " + std::to_string(v) + " is not finite");
                    MorphDelta& delta = out.deltas[t * count + v];
                    (slot == 0 ? delta.position : slot == 1 ? delta.normal : delta.tangent) = d;
                }
            }
        return out;
    }

    void skins() {
        for (size_t i = 0; i < model_.skins.size(); ++i) {
            const tinygltf::Skin& src = model_.skins[i];
            Skin skin;
            skin.name = src.name.empty() ? "skin " + std::to_string(i) : src.name;
            const std::string where = "skin '" + skin.name + "'";
            if (src.joints.empty()) fail(where + " has no joints");
            for (int joint : src.joints)
                if (joint < 0 || size_t(joint) >= scene_.nodes.size())
                    fail(where + ": joint node " + std::to_string(joint) + " is out of range (" +
                         std::to_string(scene_.nodes.size()) + " nodes)");
            if (src.skeleton >= 0 && size_t(src.skeleton) >= scene_.nodes.size())
                fail(where + ": skeleton node " + std::to_string(src.skeleton) + " is out of range");
            skin.joints = src.joints;
            skin.skeleton = src.skeleton;
            skin.inverseBindMatrices.assign(skin.joints.size(), glm::mat4(1.0f));  // glTF: absent = identity
            if (src.inverseBindMatrices >= 0) {
                const std::string what = where + " inverseBindMatrices";
                if (size_t(src.inverseBindMatrices) < model_.accessors.size())
                    charge(elementsLeft_, model_.accessors[size_t(src.inverseBindMatrices)].count, what,
                           "vertices and indices");
                const AccessorData m = accessor(src.inverseBindMatrices, what);
                if (m.components != 16 || m.count != skin.joints.size())
                    fail(what + " has " + std::to_string(m.count) + " elements of " +
                         std::to_string(m.components) + " components, expected " +
                         std::to_string(skin.joints.size()) + " MAT4 (one per joint)");
                for (size_t j = 0; j < m.count; ++j)
                    for (int c = 0; c < 16; ++c) {
                        const double value = m.at(j, c);
                        if (!std::isfinite(float(value)))
                            fail(what + ": matrix " + std::to_string(j) + " is not finite");
                        skin.inverseBindMatrices[j][c / 4][c % 4] = float(value);  // column-major, as glm
                    }
            }
            scene_.skins.push_back(std::move(skin));
        }
    }

    void weightsChannel(Animation& anim, const tinygltf::Animation& src,
                        const tinygltf::AnimationChannel& ch) {
        const std::string where = "animation '" + src.name + "' channel weights";
        if (ch.target_node < 0 || size_t(ch.target_node) >= scene_.nodes.size() || ch.sampler < 0 ||
            size_t(ch.sampler) >= src.samplers.size())
            fail("animation '" + src.name + "': channel has an invalid node or sampler");
        const uint32_t targets = meshMorphTargets(scene_, scene_.nodes[size_t(ch.target_node)].mesh);
        if (targets == 0) {
            note("weights channels on nodes without morph targets are ignored");
            return;
        }
        const tinygltf::AnimationSampler& sampler = src.samplers[size_t(ch.sampler)];
        if (!sampler.interpolation.empty() && sampler.interpolation != "LINEAR" &&
            sampler.interpolation != "STEP" && sampler.interpolation != "CUBICSPLINE")
            fail("animation '" + src.name + "': interpolation '" + printableText(sampler.interpolation, 40) +
                 "' is not LINEAR, STEP or CUBICSPLINE");
        for (int index : {sampler.input, sampler.output})
            if (index >= 0 && size_t(index) < model_.accessors.size())
                charge(keysLeft_, model_.accessors[size_t(index)].count, where, "animation keys");
        WeightsChannel out;
        out.node = ch.target_node;
        out.count = targets;
        out.interpolation = sampler.interpolation == "STEP"          ? Interpolation::Step
                            : sampler.interpolation == "CUBICSPLINE" ? Interpolation::CubicSpline
                                                                     : Interpolation::Linear;
        const AccessorData in = accessor(sampler.input, where + " input");
        const AccessorData values = accessor(sampler.output, where + " output");
        const size_t perKey = (out.interpolation == Interpolation::CubicSpline ? 3 : 1) * size_t(targets);
        if (in.count == 0 || values.components != 1 || values.count != in.count * perKey)
            fail(where + ": " + std::to_string(values.count) + " output values do not match " +
                 std::to_string(in.count) + " key times x " + std::to_string(targets) + " morph targets");
        for (size_t k = 0; k < in.count; ++k) {
            const double t = in.at(k, 0);
            if (!std::isfinite(t) || (k > 0 && t < out.times.back()))
                fail(where + ": key times are not increasing");
            out.times.push_back(float(t));
        }
        for (size_t k = 0; k < values.count; ++k) {
            if (!std::isfinite(float(values.at(k, 0))))
                fail(where + ": key value " + std::to_string(k) + " is not finite");
            out.values.push_back(float(values.at(k, 0)));
        }
        anim.duration = std::max(anim.duration, out.times.back());
        anim.weightChannels.push_back(std::move(out));
    }

    const tinygltf::Model& model_;
    const std::map<int, EncodedImage>& encoded_;
    uint64_t zeroFillLeft_;
    uint64_t elementsLeft_;
    uint64_t keysLeft_;
    uint64_t texelsLeft_ = kMaxSceneTexels;
    const std::map<std::string, std::string>& refused_;
    Scene scene_;
    std::map<std::pair<int, TextureKind>, int> textureCache_;
    int defaultMaterial_ = -1;
};

// ---- reading the file and what it names: only regular files, within the input limits ----

// What the callbacks below share during one load.
struct LoadContext {
    const tinygltf::Model* model = nullptr;      // being filled: buffers and views come before images
    std::map<std::string, std::string> refused;  // file → why it could not be read (image uris are optional)
    // The last file read and its size: tinygltf reads an image's uri right before decoding it, without saying
    // which uri the bytes came from.
    std::string lastRead;
    size_t lastReadBytes = 0;
    uint64_t texelsLeft = kMaxSceneTexels;  // what all images of the file may decode to together
    std::map<int, EncodedImage> encoded;    // the PNG and JPEG files of the images decoded, as read
};

std::string imageKey(int index) {
    return "#image " +
           std::to_string(index);  // not a file name: what LoadContext::refused holds for an image
}

bool fileExists(const std::string& path, void*) {
    struct stat info {};
    return stat(path.c_str(), &info) == 0;  // stat, not open: a FIFO must never be opened blocking
}

std::string expandFilePath(const std::string& path, void*) {
    return path;
}

bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
    FileRead read = readRegularFile(path);
    if (!read.error.empty()) {
        if (err) *err = read.error;
        static_cast<LoadContext*>(user)->refused[path] = read.error;
        return false;
    }
    auto& context = *static_cast<LoadContext*>(user);
    context.lastRead = std::filesystem::path(path).filename().string();
    context.lastReadBytes = read.bytes.size();
    *out = std::move(read.bytes);
    return true;
}

bool writeWholeFile(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
    if (err) *err = "vct does not write glTF files";
    return false;
}

// tinygltf's image callback: checks that an image stored in a buffer view lies inside its buffer (tinygltf
// passes a pointer without checking), and that the declared size is one we are willing to decode, then
// decodes with stb as tinygltf would (8- or 16-bit, the file's channel count).
bool loadImage(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int,
               const unsigned char* bytes, int size, void* user) {
    LoadContext& context = *static_cast<LoadContext*>(user);
    std::string name = "image " + std::to_string(index);
    if (!image->name.empty()) name += " '" + image->name + "'";
    if (image->bufferView < 0 && !context.lastRead.empty() &&
        context.lastReadBytes == size_t(std::max(size, 0)))
        name += " (" + context.lastRead + ")";
    // An image that cannot be used fails the load only if a texture uses it (the importer reports it then): a
    // file may list images it never uses, or ones an extension replaces with a PNG fallback (a WebP image
    // beside the texture's PNG source).
    (void)err;
    auto refuse = [&](const std::string& why) {
        static_cast<LoadContext*>(user)->refused[imageKey(index)] = name + ": " + why;
        return true;
    };
    if (image->bufferView >= 0) {
        const tinygltf::Model& model = *context.model;
        if (size_t(image->bufferView) >= model.bufferViews.size())
            return refuse("bufferView is out of range");
        const tinygltf::BufferView& view = model.bufferViews[size_t(image->bufferView)];
        if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size())
            return refuse("bufferView has no valid buffer");
        const size_t bufferSize = model.buffers[size_t(view.buffer)].data.size();
        if (!rangeWithin(view.byteOffset, view.byteLength, bufferSize) || view.byteLength > size_t(INT_MAX))
            return refuse("bufferView " + std::to_string(image->bufferView) + " (" +
                          std::to_string(view.byteLength) + " bytes at " + std::to_string(view.byteOffset) +
                          ") lies outside buffer " + std::to_string(view.buffer) + " (" +
                          std::to_string(bufferSize) + " bytes)");
    }
    if (!bytes || size <= 0) return refuse("no image data");
    int width = 0, height = 0, channels = 0;
    if (!stbi_info_from_memory(bytes, size, &width, &height, &channels))
        return refuse(std::string("cannot be decoded (") +
                      (stbi_failure_reason() ? stbi_failure_reason() : "?") + ")");
    if (width <= 0 || height <= 0 || uint64_t(width) * uint64_t(height) > kMaxTexturePixels)
        return refuse("is " + std::to_string(width) + "x" + std::to_string(height) + ", more than the " +
                      std::to_string(kMaxTexturePixels) + " pixels a texture may have");
    if (uint64_t(width) * uint64_t(height) > context.texelsLeft)
        return refuse("is " + std::to_string(width) + "x" + std::to_string(height) +
                      ": with the file's other images more than the " + std::to_string(kMaxSceneTexels) +
                      " pixels one file's images may have together");
    context.texelsLeft -= uint64_t(width) * uint64_t(height);
    const bool sixteen = stbi_is_16_bit_from_memory(bytes, size);
    std::unique_ptr<void, void (*)(void*)> pixels(
        sixteen ? static_cast<void*>(stbi_load_16_from_memory(bytes, size, &width, &height, &channels, 0))
                : static_cast<void*>(stbi_load_from_memory(bytes, size, &width, &height, &channels, 0)),
        stbi_image_free);
    if (!pixels)
        return refuse(std::string("cannot be decoded (") +
                      (stbi_failure_reason() ? stbi_failure_reason() : "?") + ")");
    const size_t byteCount = size_t(width) * size_t(height) * size_t(channels) * (sixteen ? 2 : 1);
    const auto* first = static_cast<const unsigned char*>(pixels.get());
    image->image.assign(first, first + byteCount);
    image->width = width;
    image->height = height;
    image->component = channels;
    image->bits = sixteen ? 16 : 8;
    image->pixel_type =
        sixteen ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT : TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    if (std::string mime = imageMimeType(bytes, size_t(size)); !mime.empty())
        context.encoded[index] = {std::make_shared<const std::vector<uint8_t>>(bytes, bytes + size), mime};
    return true;
}

// ---- integers tinygltf narrows to int without a check ("mesh": 4294967297 would draw mesh 1) ----

// Keys whose values (numbers, arrays of numbers, or objects of numbers for "attributes"/"targets") tinygltf
// stores as int: indices and enums. Inside "sparse", "count" and "byteOffset" are ints too.
bool intKey(const std::string& key) {
    static const std::set<std::string> keys = {
        "scene",      "nodes",      "children",  "mesh",       "camera", "skin",   "skeleton",
        "joints",     "material",   "indices",   "bufferView", "buffer", "source", "sampler",
        "index",      "texCoord",   "input",     "output",     "node",   "light",  "componentType",
        "mode",       "byteStride", "magFilter", "minFilter",  "wrapS",  "wrapT",  "inverseBindMatrices",
        "attributes", "targets"};
    return keys.count(key) > 0;
}

void checkJsonIntegers(const nlohmann::json& value, std::vector<std::string>& path, bool intValued,
                       bool inSparse) {
    auto where = [&] {
        std::string text;
        for (const std::string& part : path) text += "/" + part;
        return text;
    };
    if (value.is_number()) {
        if (!intValued) return;
        bool ok = true;
        if (value.is_number_unsigned())
            ok = value.get<uint64_t>() <= uint64_t(INT_MAX);
        else if (value.is_number_integer())
            ok = value.get<int64_t>() >= 0 && value.get<int64_t>() <= INT_MAX;
        else
            ok = value.get<double>() >= 0.0 && value.get<double>() <= double(INT_MAX) &&
                 std::floor(value.get<double>()) == value.get<double>();
        if (!ok)
            fail(where() + " is " + printableText(value.dump(), 40) + ", not an integer index in 0.." +
                 std::to_string(INT_MAX));
        return;
    }
    if (value.is_array()) {
        for (size_t i = 0; i < value.size(); ++i) {
            path.push_back(std::to_string(i));
            checkJsonIntegers(value[i], path, intValued, inSparse);
            path.pop_back();
        }
        return;
    }
    if (!value.is_object()) return;
    for (const auto& [key, child] : value.items()) {
        if (key == "extras") continue;  // the application's own data
        const bool sparse = inSparse || key == "sparse";
        const bool ints = intKey(key) || (intValued && child.is_number()) ||
                          (inSparse && (key == "count" || key == "byteOffset"));
        path.push_back(printableText(key, 40));
        checkJsonIntegers(child, path, ints, sparse);
        path.pop_back();
    }
}

// The JSON of a .glb (its first chunk), bounds-checked; empty when the header does not describe one.
std::string_view glbJson(const std::vector<unsigned char>& bytes) {
    if (bytes.size() < 20) return {};
    uint32_t length = 0, type = 0;
    std::memcpy(&length, bytes.data() + 12, 4);
    std::memcpy(&type, bytes.data() + 16, 4);
    if (type != 0x4E4F534Au || !rangeWithin(20, length, bytes.size())) return {};  // "JSON"
    return {reinterpret_cast<const char*>(bytes.data()) + 20, length};
}

// A camera's depth range from the scene's size: an infinite far plane made finite, and a ratio far / near
// that float depth can resolve (nearly everything lands on depth 1 past ~1e7, and positions reconstructed
// from it are no longer finite).
void fitCameraDepthRanges(Scene& scene) {
    constexpr float kMaxDepthRatio = 1e6f;
    constexpr float kMinYfov = 1e-3f;  // radians; narrower lenses lose the projection's precision
    const Aabb box = scene.bounds();
    const float extent = box.empty() ? 10.0f : glm::length(box.max - box.min);
    const std::vector<glm::mat4> world = scene.evaluate(0.0f);
    for (size_t n = 0; n < scene.nodes.size(); ++n) {
        if (scene.nodes[n].camera < 0) continue;
        Camera& cam = scene.cameras[size_t(scene.nodes[n].camera)];
        const std::string name =
            "camera '" + (cam.name.empty() ? "#" + std::to_string(scene.nodes[n].camera) : cam.name) + "'";
        if (cam.yfov > 0.0f && cam.yfov < kMinYfov) {
            scene.notes.push_back(name + ": yfov " + numberText(cam.yfov) + " widened to " +
                                  numberText(kMinYfov));
            cam.yfov = kMinYfov;
        }
        if (!(cam.znear > 0.0f) || !std::isfinite(cam.znear)) continue;  // validate() names it
        if (!(cam.zfar > cam.znear)) cam.zfar = std::max(100.0f * cam.znear, 10.0f * extent);
        if (cam.zfar / cam.znear <= kMaxDepthRatio) continue;
        // What the camera can see of the scene from where it stands at t = 0, with a wide margin for motion.
        const glm::vec3 eye(world[n][3]);
        const float reach = box.empty() ? extent : glm::length(eye - 0.5f * (box.min + box.max)) + extent;
        const float zfar = std::min(cam.zfar, std::max(100.0f * reach, cam.znear * kMaxDepthRatio));
        const float znear = std::max(cam.znear, zfar / kMaxDepthRatio);
        if (std::isfinite(zfar) && std::isfinite(znear)) {
            scene.notes.push_back(name + ": depth range " + numberText(cam.znear) + " .. " +
                                  numberText(cam.zfar) + " narrowed to " + numberText(znear) + " .. " +
                                  numberText(zfar) + " (float depth resolves a ratio of at most 1e6)");
            cam.znear = znear;
            cam.zfar = zfar;
        }
    }
}

// Amplification: nodes instancing a mesh multiply its triangles; what a frame draws is budgeted.
void checkInstancedTriangles(const Scene& scene) {
    std::vector<uint64_t> meshTriangles(scene.meshes.size(), 0);
    for (size_t m = 0; m < scene.meshes.size(); ++m)
        for (uint32_t p : scene.meshes[m].primitives)
            if (p < scene.primitives.size()) meshTriangles[m] += scene.primitives[p].indexCount / 3;
    uint64_t total = 0;
    for (const Node& node : scene.nodes)
        if (node.mesh >= 0 && size_t(node.mesh) < meshTriangles.size())
            total += meshTriangles[size_t(node.mesh)];
    if (total > kMaxInstancedTriangles)
        throw Error("its nodes instance " + std::to_string(total) + " triangles, more than the " +
                    std::to_string(kMaxInstancedTriangles) + " a frame may draw");
}

// Animations may carry geometry far outside the bounds at t = 0 that normalizeScale brought into range (a key
// at 3e38): the voxel grid spans where geometry goes, and past this its math leaves float (NaN in the
// indirect light). Sampled as the voxel grid samples it, and at the keys.
void checkAnimatedExtent(const Scene& scene) {
    constexpr double kMaxAnimatedExtent = 1e6;
    float duration = 0.0f;
    std::vector<float> times;
    for (const Animation& animation : scene.animations) {
        duration = std::max(duration, animation.duration);
        for (const AnimationChannel& channel : animation.channels)
            times.insert(times.end(), channel.times.begin(), channel.times.end());
    }
    if (!(duration > 0.0f)) return;
    std::sort(times.begin(), times.end());
    times.erase(std::unique(times.begin(), times.end()), times.end());
    if (times.size() > 256) times.resize(256);
    for (int k = 1; k <= 32; ++k) times.push_back(duration * float(k) / 32.0f);
    Aabb box = scene.bounds();
    for (float t : times)
        for (const Instance& instance : scene.instances(t)) box.extend(instance.bounds);
    if (box.empty()) return;
    const glm::dvec3 size = glm::dvec3(box.max) - glm::dvec3(box.min);
    const double extent = std::max(size.x, std::max(size.y, size.z));
    if (!(extent <= kMaxAnimatedExtent))
        throw Error("its animations move geometry across " + numberText(extent) + " units, more than the " +
                    numberText(kMaxAnimatedExtent) +
                    " float math is kept in (at the scale of the scene at t = 0)");
}

// loadGltf without the file name in its errors (loadGltf adds it to every one, whatever threw).
Scene importGltf(const std::string& path) {
    FileRead file = readRegularFile(path);
    if (!file.error.empty()) throw Error(file.error);

    // .glb starts with the magic "glTF"; decide by content so a misnamed file still loads.
    const bool binary = file.bytes.size() >= 4 && std::memcmp(file.bytes.data(), "glTF", 4) == 0;
    const std::string_view json =
        binary ? glbJson(file.bytes)
               : std::string_view(reinterpret_cast<const char*>(file.bytes.data()), file.bytes.size());
    // tinygltf converts JSON recursively: deep nesting would overflow the stack before it could say so.
    if (jsonNestingDepth(json, kMaxJsonDepth) > kMaxJsonDepth)
        throw Error("JSON is nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
    if (binary) {
        uint32_t version = 0;
        if (file.bytes.size() >= 8) std::memcpy(&version, file.bytes.data() + 4, 4);
        if (version != 2)
            throw Error("GLB container version " + std::to_string(version) + " is not 2 (glTF 2.0)");
    }
    {
        // Every index and enum as the file spells it, before tinygltf narrows it to int.
        const nlohmann::json doc = nlohmann::json::parse(json.begin(), json.end(), nullptr, false);
        if (!doc.is_discarded()) {
            std::vector<std::string> where;
            checkJsonIntegers(doc, where, false, false);
        }
    }

    tinygltf::TinyGLTF gltf;
    tinygltf::Model model;
    LoadContext context;
    context.model = &model;
    gltf.SetFsCallbacks({&fileExists, &expandFilePath, &readWholeFile, &writeWholeFile, &context});
    gltf.SetImageLoader(&loadImage, &context);
    std::string err, warn;
    const std::string baseDir = std::filesystem::path(path).parent_path().string();
    const bool ok =
        binary ? gltf.LoadBinaryFromMemory(&model, &err, &warn, file.bytes.data(),
                                           unsigned(file.bytes.size()), baseDir)
               : gltf.LoadASCIIFromString(&model, &err, &warn, json.data(), unsigned(json.size()), baseDir);
    if (!ok) throw Error(err.empty() ? std::string("not a valid glTF file") : err);

    uint64_t inputBytes = file.bytes.size();
    for (const tinygltf::Buffer& buffer : model.buffers) inputBytes += buffer.data.size();
    file.bytes = {};
    Scene scene = GltfImporter(model, inputBytes, context.refused, context.encoded).run();
    scene.name = std::filesystem::path(path).stem().string();
    checkInstancedTriangles(scene);
    fitCameraDepthRanges(scene);
    // Check the data before anything derives a camera or light from it (NaN bounds would spread).
    scene.validate();
    scene.normalizeScale();
    checkAnimatedExtent(scene);
    // Notes quote names from the file: printed to the terminal, they must not carry control characters.
    for (std::string& note : scene.notes) note = printableText(note, 300);
    scene.addDefaultsIfMissing();
    return scene;
}

}  // namespace

Scene loadGltf(const std::string& path) {
    try {
        return importGltf(path);
    } catch (const std::bad_alloc&) {
        throw Error(path + ": out of memory (the file declares more data than this machine can hold)");
    } catch (const std::exception& e) {  // ours, tinygltf's, the standard library's (length_error, ...)
        throw Error(path + ": " + oneLine(e.what()));
    }
}

}  // namespace vct
