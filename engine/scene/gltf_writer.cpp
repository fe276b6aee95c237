// Scene → glTF 2.0 binary. The model is built with tinygltf's structures and serialised by its writer; this
// file only decides what goes where. Round trip through loadGltf():
//  - Numbers: every float goes into the BIN chunk as float32, or into the JSON as a double that tinygltf
//    prints with 17 significant digits, so the loader reads back the very same float. Vertex attributes
//    (COLOR_0 as float VEC4, for primitives that have one), indices, node TRS (rotations: see
//    rotationTheLoaderKeeps) and matrices, material factors, lights, cameras and animation keys come back
//    bit for bit.
//  - Textures: a texture loaded from a PNG or JPEG file keeps that file's bytes (Texture::encodedImage), and
//    they are written back unchanged (one image for the textures one file image made), so the loader
//    decodes the very same texels. Other textures (made in code, other formats, or all with
//    GlbOptions::reencodeImages) are RGBA8 (the loader already turns 16-bit images into 8 bits; there are
//    no float textures), so level 0 is stored losslessly as an 8-bit PNG (RGB when every alpha is 255, else
//    RGBA). Mips are not stored: the loader rebuilds them with the same buildMipChain() the procedural
//    textures use. Images go into the BIN chunk (bufferView + mimeType): tinygltf 2.7's own image writer
//    would embed them as base64 data URIs in the JSON chunk, a third larger.
//  - Emission above 1 is written as emissiveFactor / 2^k with KHR_materials_emissive_strength 2^k (exact).
// What glTF cannot hold, and the loader therefore gives back differently (none of it occurs in the built-in
// scenes): a texture's kind is implied by the material slot that uses it (a texture no material uses is
// dropped; one used both as colour and as data comes back twice), and textures come back in the order the
// materials first use them; empty mesh, material and node names come back as "mesh 3" etc.; a primitive
// shared by several meshes comes back once per mesh; a non-spot light's cone angles are not written;
// normalScale and occlusionStrength exist only with their texture; an animation's duration is its last key
// time; an animation without channels is dropped; Scene::notes are not written.
#include "scene/gltf_writer.h"

#include <stb/stb_image_write.h>  // implementation in Debian's libstb
#include <tiny_gltf.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <system_error>

#include "core/error.h"
#include "scene/input_limits.h"

namespace vct {

namespace {

std::vector<double> doubles(const float* values, size_t count) {
    return std::vector<double>(values, values + count);
}

int gltfWrap(TextureWrap wrap) {
    switch (wrap) {
        case TextureWrap::ClampToEdge:
            return TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
        case TextureWrap::MirroredRepeat:
            return TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT;
        case TextureWrap::Repeat:
            break;
    }
    return TINYGLTF_TEXTURE_WRAP_REPEAT;
}

// The loader normalises node rotations (glTF's are unit quaternions). A float quaternion made by glm
// (angleAxis, quatLookAtRH) is often off unit length by rounding (|q|² = 1 - 6e-8 in the built-in scenes),
// and normalising moves it by an ulp or two: cornell's tall box, spot light and plane's camera and sun would
// come back rotated by ~1e-7. So the file holds, where one exists, the quaternion within ±3 ulps per non-zero
// component (fewest ulps in all) that the loader's glm::normalize turns into exactly `q`; else `q` itself.
glm::quat rotationTheLoaderKeeps(const glm::quat& q) {
    auto same = [](const glm::quat& a, const glm::quat& b) { return std::memcmp(&a, &b, sizeof(a)) == 0; };
    if (same(glm::normalize(q), q)) return q;
    auto step = [](float v, int ulps) {
        if (v == 0.0f) return v;  // zero components stay exactly zero
        for (; ulps > 0; --ulps) v = std::nextafter(v, std::numeric_limits<float>::infinity());
        for (; ulps < 0; ++ulps) v = std::nextafter(v, -std::numeric_limits<float>::infinity());
        return v;
    };
    constexpr int kRange = 3;
    glm::quat best = q;
    int bestCost = std::numeric_limits<int>::max();
    for (int w = -kRange; w <= kRange; ++w)
        for (int x = -kRange; x <= kRange; ++x)
            for (int y = -kRange; y <= kRange; ++y)
                for (int z = -kRange; z <= kRange; ++z) {
                    int cost = std::abs(w) + std::abs(x) + std::abs(y) + std::abs(z);
                    if (cost >= bestCost) continue;
                    glm::quat candidate(step(q.w, w), step(q.x, x), step(q.y, y), step(q.z, z));
                    if (same(glm::normalize(candidate), q)) {
                        best = candidate;
                        bestCost = cost;
                    }
                }
    return best;
}

void appendToVector(void* context, void* data, int size) {
    auto* out = static_cast<std::vector<unsigned char>*>(context);
    const auto* bytes = static_cast<const unsigned char*>(data);
    out->insert(out->end(), bytes, bytes + size);
}

class GltfExporter {
  public:
    GltfExporter(const Scene& scene, const GlbOptions& options) : scene_(scene), options_(options) {}

    tinygltf::Model run() {
        // Not written yet: refused rather than exported as the bind pose (the file would not load back as the
        // same scene).
        if (!scene_.skins.empty() || !scene_.morphDeltas.empty())
            fail("skins and morph targets are not exported yet (the file would lose them)");
        model_.asset.version = "2.0";
        model_.asset.generator = "vct export-scene";
        model_.buffers.emplace_back();
        for (size_t i = 0; i < scene_.textures.size(); ++i) texture(i);
        for (const Material& m : scene_.materials) material(m);
        for (const Mesh& m : scene_.meshes) mesh(m);
        for (const Camera& c : scene_.cameras) camera(c);
        for (const Light& l : scene_.lights) light(l);
        for (const Node& n : scene_.nodes) node(n);
        tinygltf::Scene root;
        root.name = scene_.name;
        root.nodes = scene_.roots;
        model_.scenes.push_back(root);
        model_.defaultScene = 0;
        for (const Animation& a : scene_.animations) animation(a);
        return std::move(model_);
    }

  private:
    [[noreturn]] static void fail(const std::string& message) { throw Error(message); }

    // A buffer view over `size` new bytes at the end of the one buffer, 4-byte aligned (so float accessors
    // are).
    int view(const void* data, size_t size, int target) {
        std::vector<unsigned char>& bytes = model_.buffers[0].data;
        bytes.resize((bytes.size() + 3) & ~size_t(3), 0);
        tinygltf::BufferView v;
        v.buffer = 0;
        v.byteOffset = bytes.size();
        v.byteLength = size;
        v.target = target;
        const auto* p = static_cast<const unsigned char*>(data);
        bytes.insert(bytes.end(), p, p + size);
        model_.bufferViews.push_back(v);
        return int(model_.bufferViews.size()) - 1;
    }

    // A tightly packed accessor of `count` elements over a new buffer view.
    int accessor(const void* data, size_t count, int type, int componentType, int target,
                 std::vector<double> min = {}, std::vector<double> max = {}) {
        size_t elementSize = size_t(tinygltf::GetComponentSizeInBytes(uint32_t(componentType))) *
                             size_t(tinygltf::GetNumComponentsInType(uint32_t(type)));
        tinygltf::Accessor a;
        a.bufferView = view(data, count * elementSize, target);
        a.byteOffset = 0;
        a.componentType = componentType;
        a.count = count;
        a.type = type;
        a.minValues = std::move(min);
        a.maxValues = std::move(max);
        model_.accessors.push_back(std::move(a));
        return int(model_.accessors.size()) - 1;
    }

    int floats(const std::vector<float>& values, int type, int target, bool withBounds = false) {
        int components = tinygltf::GetNumComponentsInType(uint32_t(type));
        size_t count = values.size() / size_t(components);
        std::vector<double> min, max;
        if (withBounds && count > 0) {
            min.assign(size_t(components), std::numeric_limits<double>::max());
            max.assign(size_t(components), -std::numeric_limits<double>::max());
            for (size_t i = 0; i < values.size(); ++i) {
                size_t c = i % size_t(components);
                min[c] = std::min(min[c], double(values[i]));
                max[c] = std::max(max[c], double(values[i]));
            }
        }
        return accessor(values.data(), count, type, TINYGLTF_COMPONENT_TYPE_FLOAT, target, std::move(min),
                        std::move(max));
    }

    // Scene texture i → glTF texture i with its own sampler. Its image is the file's bytes as loaded where it
    // has them (one image for the textures one file image made), else level 0 encoded as PNG.
    void texture(size_t index) {
        const Texture& tex = scene_.textures[index];
        const bool asLoaded = tex.encodedImage && !tex.encodedImage->empty() &&
                              !tex.encodedMimeType.empty() && !options_.reencodeImages;
        if (asLoaded) {
            auto [it, added] = encodedImages_.try_emplace(tex.encodedImage.get(), 0);
            if (added) {
                tinygltf::Image image;
                image.name = tex.name;
                image.mimeType = tex.encodedMimeType;
                image.bufferView = view(tex.encodedImage->data(), tex.encodedImage->size(), 0);
                model_.images.push_back(std::move(image));
                it->second = int(model_.images.size()) - 1;
            }
            addTexture(tex, it->second);
            return;
        }
        std::string what = "texture '" + tex.name + "'";
        size_t pixels = size_t(tex.width) * tex.height;
        if (tex.mips.empty() || pixels == 0 || tex.mips[0].size() != pixels * 4)
            fail(what + " has no RGBA8 level 0 of " + std::to_string(tex.width) + "x" +
                 std::to_string(tex.height));
        const std::vector<uint8_t>& rgba = tex.mips[0];
        bool opaque = true;
        for (size_t i = 3; i < rgba.size() && opaque; i += 4) opaque = rgba[i] == 255;
        std::vector<uint8_t> texels;
        int channels = opaque ? 3 : 4;
        if (opaque) {
            texels.reserve(pixels * 3);
            for (size_t i = 0; i < pixels; ++i) texels.insert(texels.end(), &rgba[i * 4], &rgba[i * 4 + 3]);
        }
        std::vector<unsigned char> png;
        const uint8_t* source = opaque ? texels.data() : rgba.data();
        if (!stbi_write_png_to_func(appendToVector, &png, int(tex.width), int(tex.height), channels, source,
                                    int(tex.width) * channels))
            fail(what + ": PNG encoding failed");

        tinygltf::Image image;
        image.name = tex.name;  // the loader names the texture after its image
        image.mimeType = "image/png";
        image.bufferView = view(png.data(), png.size(), 0);
        model_.images.push_back(std::move(image));
        addTexture(tex, int(model_.images.size()) - 1);
    }

    void addTexture(const Texture& tex, int image) {
        tinygltf::Sampler sampler;
        sampler.magFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
        sampler.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;  // what the renderer samples with
        sampler.wrapS = gltfWrap(tex.wrapS);
        sampler.wrapT = gltfWrap(tex.wrapT);
        model_.samplers.push_back(sampler);

        tinygltf::Texture t;
        t.name = tex.name;
        t.source = image;
        t.sampler = int(model_.samplers.size()) - 1;
        model_.textures.push_back(std::move(t));
    }

    int textureIndex(int sceneTexture, const std::string& material) const {
        if (sceneTexture >= 0 && size_t(sceneTexture) >= scene_.textures.size())
            fail("material '" + material + "': texture " + std::to_string(sceneTexture) + " is out of range");
        return sceneTexture;
    }

    void material(const Material& m) {
        tinygltf::Material out;
        out.name = m.name;
        tinygltf::PbrMetallicRoughness& pbr = out.pbrMetallicRoughness;
        pbr.baseColorFactor = doubles(&m.baseColorFactor.x, 4);
        pbr.metallicFactor = m.metallicFactor;
        pbr.roughnessFactor = m.roughnessFactor;
        pbr.baseColorTexture.index = textureIndex(m.baseColorTexture, m.name);
        pbr.metallicRoughnessTexture.index = textureIndex(m.metallicRoughnessTexture, m.name);
        out.normalTexture.index = textureIndex(m.normalTexture, m.name);
        out.normalTexture.scale = m.normalScale;
        out.occlusionTexture.index = textureIndex(m.occlusionTexture, m.name);
        out.occlusionTexture.strength = m.occlusionStrength;
        out.emissiveTexture.index = textureIndex(m.emissiveTexture, m.name);
        // glTF clamps emissiveFactor to [0, 1]; brighter emission scales it down by a power of two (exact in
        // both directions) and records the power in KHR_materials_emissive_strength.
        float brightest = std::max({m.emissiveFactor.x, m.emissiveFactor.y, m.emissiveFactor.z});
        float strength = brightest > 1.0f ? std::exp2(std::ceil(std::log2(brightest))) : 1.0f;
        glm::vec3 emissive = m.emissiveFactor / strength;
        out.emissiveFactor = doubles(&emissive.x, 3);
        if (strength != 1.0f) {
            tinygltf::Value::Object ext{{"emissiveStrength", tinygltf::Value(double(strength))}};
            out.extensions["KHR_materials_emissive_strength"] = tinygltf::Value(std::move(ext));
            useExtension("KHR_materials_emissive_strength");
        }
        out.alphaMode = m.alphaMode == AlphaMode::Mask    ? "MASK"
                        : m.alphaMode == AlphaMode::Blend ? "BLEND"
                                                          : "OPAQUE";
        out.alphaCutoff = m.alphaCutoff;
        out.doubleSided = m.doubleSided;
        model_.materials.push_back(std::move(out));
    }

    void useExtension(const std::string& name) {
        if (std::find(model_.extensionsUsed.begin(), model_.extensionsUsed.end(), name) ==
            model_.extensionsUsed.end())
            model_.extensionsUsed.push_back(name);
    }

    void mesh(const Mesh& m) {
        tinygltf::Mesh out;
        out.name = m.name;
        for (uint32_t p : m.primitives) {
            if (p >= scene_.primitives.size())
                fail("mesh '" + m.name + "': primitive " + std::to_string(p) + " is out of range");
            // A primitive used by several meshes shares its accessors (the loader still makes one copy each).
            auto [it, added] = primitives_.try_emplace(p);
            if (added) it->second = primitive(scene_.primitives[p], m.name);
            out.primitives.push_back(it->second);
        }
        model_.meshes.push_back(std::move(out));
    }

    tinygltf::Primitive primitive(const Primitive& p, const std::string& meshName) {
        if (size_t(p.vertexOffset) + p.vertexCount > scene_.vertices.size() ||
            size_t(p.firstIndex) + p.indexCount > scene_.indices.size() ||
            p.material >= scene_.materials.size())
            fail("mesh '" + meshName + "': a primitive's range or material is out of range");
        std::vector<float> position, normal, tangent, uv, color;
        for (uint32_t i = 0; i < p.vertexCount; ++i) {
            const Vertex& v = scene_.vertices[size_t(p.vertexOffset) + i];
            position.insert(position.end(), {v.position.x, v.position.y, v.position.z});
            normal.insert(normal.end(), {v.normal.x, v.normal.y, v.normal.z});
            tangent.insert(tangent.end(), {v.tangent.x, v.tangent.y, v.tangent.z, v.tangent.w});
            uv.insert(uv.end(), {v.uv.x, v.uv.y});
            if (p.hasColors) color.insert(color.end(), {v.color.r, v.color.g, v.color.b, v.color.a});
        }
        tinygltf::Primitive out;
        out.mode = TINYGLTF_MODE_TRIANGLES;
        out.material = int(p.material);
        out.attributes["POSITION"] =
            floats(position, TINYGLTF_TYPE_VEC3, TINYGLTF_TARGET_ARRAY_BUFFER, true);  // bounds: required
        out.attributes["NORMAL"] = floats(normal, TINYGLTF_TYPE_VEC3, TINYGLTF_TARGET_ARRAY_BUFFER);
        out.attributes["TANGENT"] = floats(tangent, TINYGLTF_TYPE_VEC4, TINYGLTF_TARGET_ARRAY_BUFFER);
        out.attributes["TEXCOORD_0"] = floats(uv, TINYGLTF_TYPE_VEC2, TINYGLTF_TARGET_ARRAY_BUFFER);
        // As float VEC4, whatever the source file held: the loader's decoded values come back bit for bit.
        if (p.hasColors)
            out.attributes["COLOR_0"] = floats(color, TINYGLTF_TYPE_VEC4, TINYGLTF_TARGET_ARRAY_BUFFER);
        const uint32_t* first = scene_.indices.data() + p.firstIndex;
        for (uint32_t i = 0; i < p.indexCount; ++i)
            if (first[i] >= p.vertexCount)
                fail("mesh '" + meshName + "': index " + std::to_string(first[i]) + " is out of range");
        if (p.vertexCount <= 65536) {  // every index fits in 16 bits
            std::vector<uint16_t> small(first, first + p.indexCount);
            out.indices =
                accessor(small.data(), small.size(), TINYGLTF_TYPE_SCALAR,
                         TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
        } else {
            out.indices =
                accessor(first, p.indexCount, TINYGLTF_TYPE_SCALAR, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
                         TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
        }
        return out;
    }

    void camera(const Camera& c) {
        tinygltf::Camera out;
        out.name = c.name;
        out.type = "perspective";
        out.perspective.yfov = c.yfov;
        out.perspective.znear = c.znear;
        out.perspective.zfar = c.zfar;
        out.perspective.aspectRatio = c.aspectRatio;  // written only when > 0
        model_.cameras.push_back(std::move(out));
    }

    void light(const Light& l) {
        tinygltf::Light out;
        out.name = l.name;
        out.type = l.type == LightType::Spot ? "spot" : l.type == LightType::Point ? "point" : "directional";
        out.color = doubles(&l.color.x, 3);
        out.intensity = l.intensity;
        out.range = l.range;  // written only when > 0 (0 = infinite)
        out.spot.innerConeAngle = l.innerConeAngle;
        out.spot.outerConeAngle = l.outerConeAngle;
        model_.lights.push_back(std::move(out));  // tinygltf adds KHR_lights_punctual to extensionsUsed
    }

    void node(const Node& n) {
        tinygltf::Node out;
        out.name = n.name;
        if (n.matrix) {
            out.matrix = doubles(&(*n.matrix)[0][0], 16);  // both column-major
        } else {
            // Identity parts are left out (the loader's defaults are the same).
            if (n.translation != glm::vec3(0.0f)) out.translation = doubles(&n.translation.x, 3);
            if (n.rotation != glm::quat(1.0f, 0.0f, 0.0f, 0.0f)) {
                glm::quat r = rotationTheLoaderKeeps(n.rotation);
                out.rotation = {r.x, r.y, r.z, r.w};
            }
            if (n.scale != glm::vec3(1.0f)) out.scale = doubles(&n.scale.x, 3);
        }
        out.mesh = n.mesh;
        out.camera = n.camera;
        out.children = n.children;
        if (n.light >= 0) {
            tinygltf::Value::Object ext{{"light", tinygltf::Value(n.light)}};
            out.extensions["KHR_lights_punctual"] = tinygltf::Value(std::move(ext));
        }
        model_.nodes.push_back(std::move(out));
    }

    void animation(const Animation& a) {
        if (a.channels.empty()) return;  // glTF requires at least one channel
        tinygltf::Animation out;
        out.name = a.name;
        for (const AnimationChannel& ch : a.channels) {
            bool rotation = ch.path == AnimationPath::Rotation;
            std::vector<float> values;
            for (const glm::vec4& v : ch.values) {
                values.insert(values.end(), {v.x, v.y, v.z});
                if (rotation) values.push_back(v.w);
            }
            tinygltf::AnimationSampler sampler;
            sampler.input = floats(ch.times, TINYGLTF_TYPE_SCALAR, 0, true);  // bounds: required
            sampler.output = floats(values, rotation ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3, 0);
            sampler.interpolation = ch.interpolation == Interpolation::Step          ? "STEP"
                                    : ch.interpolation == Interpolation::CubicSpline ? "CUBICSPLINE"
                                                                                     : "LINEAR";
            out.samplers.push_back(std::move(sampler));
            tinygltf::AnimationChannel channel;
            channel.sampler = int(out.samplers.size()) - 1;
            channel.target_node = ch.node;
            channel.target_path = rotation                          ? "rotation"
                                  : ch.path == AnimationPath::Scale ? "scale"
                                                                    : "translation";
            out.channels.push_back(std::move(channel));
        }
        model_.animations.push_back(std::move(out));
    }

    const Scene& scene_;
    const GlbOptions options_;
    tinygltf::Model model_;
    std::map<uint32_t, tinygltf::Primitive> primitives_;        // by Scene primitive index
    std::map<const std::vector<uint8_t>*, int> encodedImages_;  // Texture::encodedImage → glTF image
};

}  // namespace

void writeGlb(const Scene& scene, const std::filesystem::path& path, const GlbOptions& options) {
    std::string bytes;
    try {
        tinygltf::Model model = GltfExporter(scene, options).run();
        // The stream variant of WriteGltfSceneToFile (same serialiser, binary, buffers and images embedded):
        // the file variant does not check its writes, this one lets a full disk be an error.
        std::ostringstream stream(std::ios::binary);
        tinygltf::TinyGLTF gltf;
        if (!gltf.WriteGltfSceneToStream(&model, stream, false, true))
            throw Error("tinygltf could not serialise it");
        bytes = std::move(stream).str();
    } catch (const Error& e) {
        throw Error("cannot write " + path.string() + ": " + e.what());
    }
    writeFileReplacing(path, bytes);  // checked, fsync'ed, never through a planted symlink
}

}  // namespace vct
