// Hostile glTF files (issue 11, classes 1-6, 9, 11): generators that mutate the valid one-triangle scene of
// hostile_util.h along one parameter each (an offset that wraps, a nesting depth, a uri that names a FIFO, a
// count that would allocate gigabytes, a light or camera value that overflows float, ...). Every case must
// end in one stderr line naming the file (exit 1) or in a finite image (hostile_util.h, expectGraceful).
#include <sys/stat.h>
#include <zlib.h>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <functional>
#include <glm/glm.hpp>
#include <iterator>
#include <limits>
#include <tuple>

#include "hostile_util.h"

namespace vct::hostile {
namespace {

constexpr uint64_t kMax64 = std::numeric_limits<uint64_t>::max();

struct GltfCase {
    std::string name;
    std::function<void(GltfScene&)> mutate;
    Expectation expect;
    bool glb = false;
};

// The error names the scene file.
Expectation fails(std::vector<std::string> mentions = {}) {
    mentions.insert(mentions.begin(), "scene.");
    return {Outcome::MustFail, mentions, 1};
}
Expectation rendersOrFails(std::vector<std::string> mentions = {}) {
    mentions.insert(mentions.begin(), "scene.");
    return {Outcome::Either, mentions, 1, true};
}

// Class 1: buffer view / accessor ranges whose end wraps past 2^64 (directly, through the accessor offset,
// through a sparse view) or whose size product overflows.
std::vector<GltfCase> boundsCases() {
    std::vector<GltfCase> cases;
    for (uint64_t offset : {kMax64 - 7, kMax64 - 35, uint64_t(1) << 63})
        cases.push_back({"ViewOffsetWraps" + std::to_string(cases.size()),
                         [offset](GltfScene& s) { s.doc["bufferViews"][0]["byteOffset"] = offset; },
                         fails()});
    cases.push_back({"ViewLengthWraps",
                     [](GltfScene& s) {
                         s.doc["bufferViews"][0]["byteOffset"] = 16;
                         s.doc["bufferViews"][0]["byteLength"] = kMax64 - 7;
                     },
                     fails()});
    for (uint64_t offset : {kMax64 - 7, kMax64 - 11, uint64_t(1) << 62})
        cases.push_back({"AccessorOffsetWraps" + std::to_string(cases.size()),
                         [offset](GltfScene& s) { s.doc["accessors"][0]["byteOffset"] = offset; }, fails()});
    cases.push_back({"AccessorCountOverflowsStride",
                     [](GltfScene& s) { s.doc["accessors"][0]["count"] = (uint64_t(1) << 62) + 1; },
                     fails()});
    for (int which : {0, 1})  // through the sparse indices' view or the sparse values' view
        cases.push_back(
            {std::string("SparseViewWraps") + (which ? "Values" : "Indices"),
             [which](GltfScene& s) {
                 s.doc["bufferViews"].push_back(
                     {{"buffer", 0}, {"byteOffset", kMax64 - 3}, {"byteLength", 8}});
                 s.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 12}});
                 const int wrapping = int(s.doc["bufferViews"].size()) - 2;
                 s.doc["accessors"][0]["sparse"] = {
                     {"count", 1},
                     {"indices", {{"bufferView", which ? wrapping + 1 : wrapping}, {"componentType", 5125}}},
                     {"values", {{"bufferView", which ? wrapping : wrapping + 1}}}};
             },
             fails()});
    cases.push_back(
        {"SparseOffsetWraps",
         [](GltfScene& s) {
             s.doc["accessors"][0]["sparse"] = {
                 {"count", 1},
                 {"indices", {{"bufferView", 0}, {"byteOffset", kMax64 - 1}, {"componentType", 5125}}},
                 {"values", {{"bufferView", 0}}}};
         },
         fails()});
    return cases;
}

// Class 2: an image stored in a buffer view that lies (partly) outside its buffer.
std::vector<GltfCase> imageViewCases() {
    std::vector<GltfCase> cases;
    const std::pair<uint64_t, uint64_t> ranges[] = {
        {1000, 16}, {0, 100000}, {kMax64 - 7, 16}, {8, (uint64_t(1) << 32) + 8}, {56, 8}};
    for (bool glb : {false, true})
        for (size_t i = 0; i < std::size(ranges); ++i) {
            const auto [offset, length] = ranges[i];
            cases.push_back({std::string("ImageViewOutside") + (glb ? "Glb" : "Gltf") + std::to_string(i),
                             [offset, length](GltfScene& s) {
                                 s.doc["bufferViews"].push_back(
                                     {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", length}});
                                 s.doc["images"][0] = {{"bufferView", s.doc["bufferViews"].size() - 1},
                                                       {"mimeType", "image/png"}};
                                 s.texture = false;
                             },
                             fails(), glb});
        }
    return cases;
}

// Class 3: JSON nested very deep (arrays, objects, mixed; in extras of the root, a node, the asset). Built as
// text: a json value this deep would cost the test itself quadratic time and deep recursion.
std::string nestedText(int depth, int kind) {
    std::string open, close;
    for (int i = 0; i < depth; ++i) {
        const bool array = kind == 0 || (kind == 2 && i % 2);
        open += array ? "[" : "{\"a\":";
        close += array ? "]" : "}";
    }
    return open + "1" + close;
}
std::vector<GltfCase> nestingCases() {
    std::vector<GltfCase> cases;
    for (int depth : {20000, 100000})
        for (int kind : {0, 1, 2})
            for (bool glb : {false, true})
                cases.push_back(
                    {"Nested" + std::to_string(depth) + "Kind" + std::to_string(kind) + (glb ? "Glb" : ""),
                     [depth, kind](GltfScene& s) {
                         json& where = kind == 1 ? s.doc["nodes"][0] : kind == 2 ? s.doc["asset"] : s.doc;
                         where["extras"] = "@NESTED@";
                         s.replaceInText = {"\"@NESTED@\"", nestedText(depth, kind)};
                     },
                     fails({"nest"}), glb});
    // Moderately deep extras are harmless either way.
    cases.push_back({"Nested5000",
                     [](GltfScene& s) {
                         s.doc["extras"] = "@NESTED@";
                         s.replaceInText = {"\"@NESTED@\"", nestedText(5000, 0)};
                     },
                     rendersOrFails()});
    return cases;
}

// Class 5 (glTF side): counts that would make us allocate gigabytes from a kilobyte file.
std::vector<GltfCase> allocationCases() {
    std::vector<GltfCase> cases;
    for (uint64_t count : {uint64_t(1) << 27, uint64_t(1) << 31, uint64_t(1) << 40})
        cases.push_back({"HugeCount" + std::to_string(cases.size()),
                         [count](GltfScene& s) { s.doc["accessors"][0]["count"] = count; }, fails()});
    for (uint64_t count : {uint64_t(1) << 27, uint64_t(1) << 33})  // no bufferView: zeros, then sparse values
        cases.push_back({"HugeCountWithoutView" + std::to_string(cases.size()),
                         [count](GltfScene& s) {
                             s.doc["accessors"][0].erase("bufferView");
                             s.doc["accessors"][0]["count"] = count;
                             s.doc["accessors"][1]["count"] = count;
                             s.doc["accessors"][1].erase("bufferView");
                         },
                         fails()});
    cases.push_back({"HugeSparseCount",
                     [](GltfScene& s) {
                         s.doc["accessors"][0]["sparse"] = {
                             {"count", uint64_t(1) << 30},
                             {"indices", {{"bufferView", 0}, {"componentType", 5125}}},
                             {"values", {{"bufferView", 0}}}};
                     },
                     fails()});
    cases.push_back(
        {"HugeIndexCount",
         [](GltfScene& s) {
             s.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 12}});
             s.doc["accessors"].push_back({{"bufferView", s.doc["bufferViews"].size() - 1},
                                           {"componentType", 5125},
                                           {"count", uint64_t(1) << 29},
                                           {"type", "SCALAR"}});
             s.doc["meshes"][0]["primitives"][0]["indices"] = s.doc["accessors"].size() - 1;
         },
         fails()});
    cases.push_back({"HugeBufferByteLength",
                     [](GltfScene& s) { s.doc["buffers"][0]["byteLength"] = uint64_t(1) << 40; }, fails()});
    return cases;
}

// Class 6: light parameters that overflow float or break the spot cone; degenerate light transforms.
// A sampler of key `times` (seconds) and VEC3 `values` (one per key) appended to the buffer: two accessors,
// input then output. Returns the input accessor's index.
size_t addVec3Sampler(GltfScene& s, const std::vector<float>& times, const std::vector<glm::vec3>& values) {
    const size_t offset = s.bin.size(), keys = times.size();
    for (float t : times) appendFloats(s.bin, {t});
    for (const glm::vec3& v : values) appendFloats(s.bin, {v.x, v.y, v.z});
    s.doc["buffers"][0]["byteLength"] = s.bin.size();
    s.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", keys * 16}});
    const size_t view = s.doc["bufferViews"].size() - 1;
    s.doc["accessors"].push_back({{"bufferView", view},
                                  {"componentType", 5126},
                                  {"count", keys},
                                  {"type", "SCALAR"},
                                  {"min", {double(times.front())}},
                                  {"max", {double(times.back())}}});
    s.doc["accessors"].push_back({{"bufferView", view},
                                  {"byteOffset", keys * 4},
                                  {"componentType", 5126},
                                  {"count", keys},
                                  {"type", "VEC3"}});
    return s.doc["accessors"].size() - 2;
}

void addLight(GltfScene& s, json light, json node = json::object()) {
    s.doc["extensionsUsed"] = {"KHR_lights_punctual"};
    s.doc["extensions"]["KHR_lights_punctual"]["lights"] = {light};
    node["extensions"] = {{"KHR_lights_punctual", {{"light", 0}}}};
    if (!node.contains("rotation") && !node.contains("matrix"))
        node["rotation"] = {-0.3826834, 0, 0, 0.9238795};
    s.doc["nodes"].push_back(node);
    s.doc["scenes"][0]["nodes"].push_back(s.doc["nodes"].size() - 1);
}
std::vector<GltfCase> lightCases() {
    std::vector<GltfCase> cases;
    const json bad[] = {
        {{"type", "directional"}, {"intensity", 1e300}},
        {{"type", "point"}, {"intensity", 1e39}},
        {{"type", "directional"}, {"color", {1e300, 1, 1}}},
        {{"type", "spot"}, {"color", {1, -1e39, 1}}, {"spot", json::object()}},
        {{"type", "directional"}, {"intensity", -5}},
        {{"type", "spot"}, {"spot", {{"innerConeAngle", 0.5}, {"outerConeAngle", 0.5}}}},
        {{"type", "spot"}, {"spot", {{"innerConeAngle", 0.9}, {"outerConeAngle", 0.2}}}},
        {{"type", "spot"}, {"spot", {{"outerConeAngle", 1e300}}}},
        {{"type", "point"}, {"range", 1e300}},
        {{"type", "point"}, {"range", -1}},
    };
    for (size_t i = 0; i < std::size(bad); ++i)
        cases.push_back({"LightValue" + std::to_string(i),
                         [light = bad[i]](GltfScene& s) { addLight(s, light); }, rendersOrFails({"light"})});
    const json degenerateNodes[] = {
        {{"scale", {0, 0, 0}}},
        {{"scale", {1, 1, 0}}},
        {{"matrix", json::array({0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0})}},
        {{"matrix", json::array({0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 2, 0, 1})}},
        {{"scale", {1e30, 1e30, 1e30}}, {"translation", {1e30, 0, 0}}},
    };
    for (const char* type : {"directional", "spot", "point"})
        for (size_t i = 0; i < std::size(degenerateNodes); ++i)
            cases.push_back({std::string("LightNode") + type + std::to_string(i),
                             [type, node = degenerateNodes[i]](GltfScene& s) {
                                 json light = {{"type", type}, {"intensity", 2}};
                                 if (type == std::string("spot")) light["spot"] = {{"outerConeAngle", 0.6}};
                                 addLight(s, light, node);
                             },
                             rendersOrFails()});
    // An animation that scales the light's node to 0 (rendered at t = 0 and t = 1/60 .. : frames 1-3).
    cases.push_back(
        {"LightAnimatedToScaleZero",
         [](GltfScene& s) {
             addLight(s, {{"type", "directional"}, {"intensity", 2}});
             const size_t keys = addVec3Sampler(s, {0.0f, 0.01f}, {glm::vec3(1), glm::vec3(0)});
             s.doc["animations"] = {
                 {{"channels",
                   {{{"sampler", 0}, {"target", {{"node", s.doc["nodes"].size() - 1}, {"path", "scale"}}}}}},
                  {"samplers", {{{"input", keys}, {"output", keys + 1}}}}}};
         },
         rendersOrFails()});
    return cases;
}

// Class 6/11: camera parameters and camera transforms out of float's range or degenerate.
void addCamera(GltfScene& s, json perspective, json node = json::object()) {
    s.doc["cameras"] = {{{"type", "perspective"}, {"perspective", perspective}}};
    node["camera"] = 0;
    if (!node.contains("translation") && !node.contains("matrix")) node["translation"] = {0.3, 0.3, 2};
    s.doc["nodes"].push_back(node);
    s.doc["scenes"][0]["nodes"].push_back(s.doc["nodes"].size() - 1);
}
std::vector<GltfCase> cameraCases() {
    std::vector<GltfCase> cases;
    const json lenses[] = {
        {{"yfov", 1e-20}, {"znear", 0.01}},
        {{"yfov", 0.8}, {"znear", 1e-30}},
        {{"yfov", 0.8}, {"znear", 1e-30}, {"zfar", 1e30}},
        {{"yfov", 0.8}, {"znear", 0.01}, {"zfar", 1e300}},
        {{"yfov", 1e300}, {"znear", 0.01}},
        {{"yfov", 3.2}, {"znear", 0.01}},
        {{"yfov", 0.8}, {"znear", 1e300}},
        {{"yfov", 0.8}, {"znear", 0.01}, {"aspectRatio", 1e300}},
        {{"yfov", 0.8}, {"znear", 0.01}, {"aspectRatio", 1e-30}},
    };
    for (size_t i = 0; i < std::size(lenses); ++i)
        cases.push_back({"CameraLens" + std::to_string(i),
                         [lens = lenses[i]](GltfScene& s) { addCamera(s, lens); },
                         rendersOrFails({"camera"})});
    const json nodes[] = {
        {{"scale", {0, 0, 0}}, {"translation", {0.3, 0.3, 2}}},
        {{"scale", {1, 0, 1}}, {"translation", {0.3, 0.3, 2}}},
        {{"matrix", json::array({0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0.3, 0.3, 2, 1})}},
        {{"translation", {3e38, 0, 2}}, {"scale", {1e30, 1, 1}}},
        {{"translation", {1e300, 0, 2}}},
    };
    for (size_t i = 0; i < std::size(nodes); ++i)
        cases.push_back({"CameraNode" + std::to_string(i),
                         [node = nodes[i]](GltfScene& s) {
                             addCamera(s, {{"yfov", 0.8}, {"znear", 0.01}}, node);
                         },
                         rendersOrFails()});
    // The mesh itself flattened (no inverse for its normals) or scaled to nothing.
    for (auto [name, scale] : {std::pair{"MeshFlattened", json{1, 1, 0}},
                               {"MeshFlattenedAcross", json{1, 0, 1}},
                               {"MeshScaleZero", json{0, 0, 0}}})
        cases.push_back({name,
                         [scale = scale](GltfScene& s) { s.doc["nodes"][0]["scale"] = scale; },
                         {Outcome::Either, {"scene."}, 1, false}});
    // Composed transforms that overflow: each node is finite, the product is not.
    cases.push_back({"ComposedTransformOverflows",
                     [](GltfScene& s) {
                         s.doc["nodes"][0]["scale"] = {1e20, 1e20, 1e20};
                         s.doc["nodes"].push_back({{"translation", {1e20, 0, 0}}, {"mesh", 0}});
                         s.doc["nodes"][0]["children"] = {s.doc["nodes"].size() - 1};
                     },
                     rendersOrFails()});
    return cases;
}

// Class 9: textures larger than the device allows in one dimension (16384 on lavapipe).
std::vector<GltfCase> textureCases() {
    std::vector<GltfCase> cases;
    for (auto [w, h] : {std::pair{16385u, 1u}, {1u, 16385u}, {40000u, 2u}})
        cases.push_back({"TextureWide" + std::to_string(w) + "x" + std::to_string(h),
                         [w = w, h = h](GltfScene& s) {
                             s.doc["images"][0]["uri"] = "wide.png";
                             s.extraFiles = [w, h](const fs::path& dir) {
                                 writeTexture(dir / "wide.png", w, h);
                             };
                         },
                         rendersOrFails({"wide.png"})});
    return cases;
}

// Class 5 (images): a few hundred bytes of PNG whose header declares a size that would take gigabytes.
uint32_t crc32(const unsigned char* data, size_t size) {
    uint32_t crc = 0xFFFFFFFFu;
    for (size_t i = 0; i < size; ++i) {
        crc ^= data[i];
        for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    return ~crc;
}
void writePngDeclaring(const fs::path& path, uint32_t width, uint32_t height) {
    writeTexture(path, 1, 1);
    std::ifstream in(path, std::ios::binary);
    std::vector<unsigned char> png((std::istreambuf_iterator<char>(in)), {});
    auto put32 = [&](size_t at, uint32_t v) {
        for (int i = 0; i < 4; ++i) png[at + size_t(i)] = (unsigned char)(v >> (24 - 8 * i));
    };
    put32(16, width);  // IHDR data starts at 16: signature (8), length (4), "IHDR" (4)
    put32(20, height);
    put32(29, crc32(png.data() + 12, 17));  // over "IHDR" and its 13 data bytes
    test::writeBinaryFile(path, png);
}
std::vector<GltfCase> imageBombCases() {
    std::vector<GltfCase> cases;
    for (auto [w, h] : {std::pair{100000u, 100000u}, {16777216u, 8u}, {65536u, 65536u}})
        cases.push_back({"PngDeclares" + std::to_string(w) + "x" + std::to_string(h),
                         [w = w, h = h](GltfScene& s) {
                             s.doc["images"][0]["uri"] = "bomb.png";
                             s.extraFiles = [w, h](const fs::path& dir) {
                                 writePngDeclaring(dir / "bomb.png", w, h);
                             };
                         },
                         fails({"bomb.png"})});
    return cases;
}

// ---- second sweep (issue 21) ----

// Class 7: integers past int32 that tinygltf would narrow (2^32 + 1 -> 1: "mesh": 4294967297 drew mesh 1),
// negative and fractional indices: each refused naming the value.
std::vector<GltfCase> narrowingCases() {
    std::vector<GltfCase> cases;
    const uint64_t wrap = (uint64_t(1) << 32) + 1;
    const std::pair<const char*, std::function<void(GltfScene&, json)>> fields[] = {
        {"Mesh", [](GltfScene& s, json v) { s.doc["nodes"][0]["mesh"] = v; }},
        {"Material", [](GltfScene& s, json v) { s.doc["meshes"][0]["primitives"][0]["material"] = v; }},
        {"Accessor",
         [](GltfScene& s, json v) { s.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = v; }},
        {"BufferView", [](GltfScene& s, json v) { s.doc["accessors"][0]["bufferView"] = v; }},
        {"Buffer", [](GltfScene& s, json v) { s.doc["bufferViews"][0]["buffer"] = v; }},
        {"Scene", [](GltfScene& s, json v) { s.doc["scene"] = v; }},
        {"SceneNode", [](GltfScene& s, json v) { s.doc["scenes"][0]["nodes"][0] = v; }},
        {"TextureSource", [](GltfScene& s, json v) { s.doc["textures"][0]["source"] = v; }},
        {"Children",
         [](GltfScene& s, json v) {
             s.doc["nodes"].push_back({{"name", "parent"}, {"children", {v}}});
             s.doc["scenes"][0]["nodes"].push_back(1);
         }},
        {"SparseCount",
         [](GltfScene& s, json v) {
             s.doc["accessors"][0]["sparse"] = {{"count", v},
                                                {"indices", {{"bufferView", 0}, {"componentType", 5125}}},
                                                {"values", {{"bufferView", 0}}}};
         }},
        {"SparseByteOffset",
         [](GltfScene& s, json v) {
             s.doc["accessors"][0]["sparse"] = {
                 {"count", 1},
                 {"indices", {{"bufferView", 0}, {"byteOffset", v}, {"componentType", 5125}}},
                 {"values", {{"bufferView", 0}}}};
         }},
    };
    for (const auto& [field, set] : fields) {
        cases.push_back({std::string("Wraps") + field, [set = set, wrap](GltfScene& s) { set(s, wrap); },
                         fails({"4294967297"})});
        for (bool glb : {false, true})
            if (glb == (std::string(field) == "Mesh"))  // one GLB: the check reads its JSON chunk too
                cases.push_back({std::string("Wraps") + field + "Glb",
                                 [set = set, wrap](GltfScene& s) { set(s, wrap); }, fails({"4294967297"}),
                                 true});
    }
    cases.push_back({"NegativeMesh", [](GltfScene& s) { s.doc["nodes"][0]["mesh"] = -2; }, fails({"-2"})});
    cases.push_back(
        {"FractionalMesh", [](GltfScene& s) { s.doc["nodes"][0]["mesh"] = 0.5; }, fails({"0.5"})});
    // The node graph: a cycle (0 <-> 1), a mesh without primitives.
    cases.push_back({"NodeCycle",
                     [](GltfScene& s) {
                         s.doc["nodes"][0]["children"] = {1};
                         s.doc["nodes"].push_back({{"name", "other"}, {"mesh", 0}, {"children", {0}}});
                     },
                     fails({"cycle"})});
    cases.push_back({"NodeCycleOfThree",
                     [](GltfScene& s) {
                         s.doc["nodes"][0]["children"] = {1};
                         s.doc["nodes"].push_back({{"name", "b"}, {"children", {2}}});
                         s.doc["nodes"].push_back({{"name", "c"}, {"children", {0}}});
                     },
                     fails({"cycle"})});
    cases.push_back({"MeshWithoutPrimitives",
                     [](GltfScene& s) { s.doc["meshes"][0]["primitives"] = json::array(); },
                     fails({"primitive"})});
    return cases;
}

// Classes 3 and 4: small files that reuse their data until they would take gigabytes or minutes: each is
// refused by a whole-file budget before it is built.
// `keys` keys at 60 Hz, a translation alternating between 0 and 1 cm.
void addSampler(GltfScene& s, size_t keys) {
    std::vector<float> times(keys);
    std::vector<glm::vec3> values(keys);
    for (size_t k = 0; k < keys; ++k) {
        times[k] = float(k) / 60.0f;
        values[k] = glm::vec3(0.0f, float(k % 2) * 0.01f, 0.0f);
    }
    addVec3Sampler(s, times, values);
}
std::vector<GltfCase> amplificationCases() {
    std::vector<GltfCase> cases;
    // 2 000 nodes instancing one 100k-triangle mesh (indexed over 3 vertices: 1.2 MB).
    cases.push_back({"InstancedTriangles",
                     [](GltfScene& s) {
                         const size_t offset = s.bin.size(), indices = 300000;
                         for (size_t i = 0; i < indices; ++i) {
                             const uint32_t v = uint32_t(i % 3);
                             unsigned char b[4];
                             std::memcpy(b, &v, 4);
                             s.bin.insert(s.bin.end(), b, b + 4);
                         }
                         s.doc["buffers"][0]["byteLength"] = s.bin.size();
                         s.doc["bufferViews"].push_back(
                             {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", indices * 4}});
                         s.doc["accessors"].push_back({{"bufferView", s.doc["bufferViews"].size() - 1},
                                                       {"componentType", 5125},
                                                       {"count", indices},
                                                       {"type", "SCALAR"}});
                         s.doc["meshes"][0]["primitives"][0]["indices"] = s.doc["accessors"].size() - 1;
                         for (int n = 0; n < 2000; ++n) {
                             s.doc["nodes"].push_back({{"mesh", 0}, {"translation", {n * 0.001, 0, 0}}});
                             s.doc["scenes"][0]["nodes"].push_back(s.doc["nodes"].size() - 1);
                         }
                     },
                     fails({"instance", "triangles"})});
    // Primitives sharing one accessor without a bufferView (zeros): the budget is the file's, not each's.
    cases.push_back(
        {"SharedZeroFilledAccessor",
         [](GltfScene& s) {
             s.doc["accessors"].push_back({{"componentType", 5126}, {"count", 1000}, {"type", "VEC3"}});
             const size_t zeros = s.doc["accessors"].size() - 1;
             json prims = json::array();
             for (int p = 0; p < 200; ++p) prims.push_back({{"attributes", {{"POSITION", zeros}}}});
             s.doc["meshes"][0]["primitives"] = prims;
         },
         fails({"without a bufferView"})});
    // 120 primitives reusing 40k vertices (4.8M built from 0.5 MB): the vertex budget, summed before building.
    cases.push_back({"SharedVertices",
                     [](GltfScene& s) {
                         const size_t offset = s.bin.size(), count = 40002;
                         for (size_t i = 0; i < count; ++i)
                             appendFloats(s.bin, {float(i % 3 == 1), float(i % 3 == 2), float(i) * 1e-5f});
                         s.doc["buffers"][0]["byteLength"] = s.bin.size();
                         s.doc["bufferViews"].push_back(
                             {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", count * 12}});
                         s.doc["accessors"].push_back({{"bufferView", s.doc["bufferViews"].size() - 1},
                                                       {"componentType", 5126},
                                                       {"count", count},
                                                       {"type", "VEC3"},
                                                       {"min", {0, 0, 0}},
                                                       {"max", {1, 1, double(float(count - 1) * 1e-5f)}}});
                         const size_t shared = s.doc["accessors"].size() - 1;
                         json prims = json::array();
                         for (int p = 0; p < 120; ++p)
                             prims.push_back({{"attributes", {{"POSITION", shared}}}});
                         s.doc["meshes"][0]["primitives"] = prims;
                     },
                     fails({"budget", "vertices"})});
    // 2 500 animation channels sharing one sampler of 2 000 keys (5M keys copied from 48 kB).
    cases.push_back(
        {"SharedAnimationSampler",
         [](GltfScene& s) {
             addSampler(s, 2000);
             const size_t keys = s.doc["accessors"].size() - 2;
             json channels = json::array();
             for (int c = 0; c < 2500; ++c)
                 channels.push_back({{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}});
             s.doc["animations"] = {
                 {{"channels", channels}, {"samplers", {{{"input", keys}, {"output", keys + 1}}}}}};
         },
         fails({"animation keys"})});
    return cases;
}

// Class 5: light that overflows the shaders' 1/d^2 (refused), light below the cap (a finite image), and
// materials whose emission or occlusion would make radiance negative (refused).
std::vector<GltfCase> radianceCases() {
    std::vector<GltfCase> cases;
    const json tooBright[] = {
        {{"type", "point"}, {"intensity", 1e38}},
        {{"type", "point"}, {"color", {1e38, 1, 1}}},
        {{"type", "spot"}, {"intensity", 3e37}, {"spot", json::object()}},
        {{"type", "point"}, {"intensity", 1e21}},
    };
    for (size_t i = 0; i < std::size(tooBright); ++i)
        cases.push_back({"LightTooBright" + std::to_string(i),
                         [light = tooBright[i]](GltfScene& s) {
                             addLight(s, light, {{"translation", {0.2, 0.2, 0.001}}});
                         },
                         fails({"light", "intensity"})});
    // Just below the cap, a millimetre from the triangle: bright, but every value of every EXR finite.
    cases.push_back(
        {"PointLightBelowTheCap",
         [](GltfScene& s) {
             addLight(s, {{"type", "point"}, {"intensity", 1e19}}, {{"translation", {0.2, 0.2, 0.001}}});
         },
         {Outcome::MustRender, {}, 0, true}});
    const std::pair<const char*, std::function<void(json&)>> materials[] = {
        {"NegativeEmissiveFactor",
         [](json& m) {
             m["emissiveFactor"] = {-1, 0, 0};
         }},
        {"NegativeEmissiveStrength",
         [](json& m) {
             m["emissiveFactor"] = {1, 1, 1};
             m["extensions"] = {{"KHR_materials_emissive_strength", {{"emissiveStrength", -5}}}};
         }},
        {"OcclusionStrengthHuge",
         [](json& m) {
             m["occlusionTexture"] = {{"index", 0}, {"strength", 1e30}};
         }},
        {"NegativeBaseColor",
         [](json& m) {
             m["pbrMetallicRoughness"]["baseColorFactor"] = {-1, 1, 1, 1};
         }},
    };
    for (const auto& [name, set] : materials)
        cases.push_back({name,
                         [set = set](GltfScene& s) {
                             set(s.doc["materials"][0]);
                             s.doc["extensionsUsed"] = {"KHR_materials_emissive_strength"};
                         },
                         fails({"material"})});
    return cases;
}

// Class 8: lenses glTF calls invalid (they rendered empty images) are refused; the overflow of an animation
// between two finite keys ends in a line or a finite image.
std::vector<GltfCase> lensCases() {
    std::vector<GltfCase> cases;
    const json lenses[] = {
        {{"yfov", 0}, {"znear", 0.01}},
        {{"yfov", -1}, {"znear", 0.01}},
        {{"yfov", 0.8}, {"znear", 0}},
        {{"yfov", 0.8}, {"znear", -1}},
        {{"yfov", 0.8}, {"znear", 0.01}, {"zfar", -1}},
        {{"yfov", 0.8}, {"znear", 10}, {"zfar", 1}},
        {{"yfov", 0.8}, {"znear", 1}, {"zfar", 1}},
    };
    for (size_t i = 0; i < std::size(lenses); ++i)
        cases.push_back({"InvalidLens" + std::to_string(i),
                         [lens = lenses[i]](GltfScene& s) { addCamera(s, lens); }, fails({"camera"})});
    cases.push_back({"SpanOfFltMax",
                     [](GltfScene& s) {
                         const float m = std::numeric_limits<float>::max();
                         s.bin.clear();
                         appendFloats(s.bin, {-m, -m, 0, m, -m, 0, -m, m, 0});
                         appendFloats(s.bin, {0, 1, 1, 1, 0, 0});
                         s.doc["accessors"][0]["min"] = {-m, -m, 0};
                         s.doc["accessors"][0]["max"] = {m, m, 0};
                     },
                     rendersOrFails()});
    // An animation carrying the triangle 9e5 units (inside the 1e6 kept) renders finite; to float's limit it is
    // refused: the voxel grid spans where the geometry goes (3e38 gave NaN in the indirect light).
    for (auto [name, reach, expect] :
         {std::tuple{"AnimationWithinTheRange", 9e5f, Expectation{Outcome::MustRender, {}, 0, true}},
          std::tuple{"AnimationToFloatLimit", 3e38f, fails({"animations"})}})
        cases.push_back(
            {name,
             [reach = reach](GltfScene& s) {
                 const size_t keys =
                     addVec3Sampler(s, {0.0f, 0.05f}, {glm::vec3(0.0f), glm::vec3(reach, 0.0f, 0.0f)});
                 json channel = {{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}};
                 json sampler = {{"input", keys}, {"output", keys + 1}};
                 s.doc["animations"] = json::array(
                     {{{"channels", json::array({channel})}, {"samplers", json::array({sampler})}}});
             },
             expect});
    return cases;
}

// The lenient list: what the glTF validator calls invalid is refused with one line.
std::vector<GltfCase> lenientCases() {
    std::vector<GltfCase> cases;
    auto sparse = [](GltfScene& s, std::vector<uint32_t> indices, int componentType) {
        const size_t offset = s.bin.size();
        for (uint32_t i : indices) {
            unsigned char b[4];
            std::memcpy(b, &i, 4);
            s.bin.insert(s.bin.end(), b, b + 4);
        }
        appendFloats(s.bin, {0.1f, 0.1f, 0, 0.2f, 0.2f, 0});
        s.doc["buffers"][0]["byteLength"] = s.bin.size();
        s.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", 8}});
        s.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset + 8}, {"byteLength", 24}});
        const size_t view = s.doc["bufferViews"].size() - 2;
        s.doc["accessors"][0]["sparse"] = {
            {"count", 2},
            {"indices", {{"bufferView", view}, {"componentType", componentType}}},
            {"values", {{"bufferView", view + 1}}}};
    };
    cases.push_back({"SparseIndicesDecreasing",
                     [sparse](GltfScene& s) {
                         sparse(s, {2, 1}, 5125);
                     },
                     fails({"increasing"})});
    cases.push_back({"SparseIndicesDuplicate",
                     [sparse](GltfScene& s) {
                         sparse(s, {1, 1}, 5125);
                     },
                     fails({"increasing"})});
    cases.push_back({"SparseIndicesSigned",
                     [sparse](GltfScene& s) {
                         sparse(s, {1, 2}, 5124);
                     },
                     fails({"sparse"})});
    for (int type : {5126, 5122, 5120})
        cases.push_back(
            {"IndexComponentType" + std::to_string(type),
             [type](GltfScene& s) {
                 const size_t offset = s.bin.size();
                 for (int i = 0; i < 3; ++i) appendFloats(s.bin, {0.0f});
                 s.doc["buffers"][0]["byteLength"] = s.bin.size();
                 s.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", 12}});
                 s.doc["accessors"].push_back({{"bufferView", s.doc["bufferViews"].size() - 1},
                                               {"componentType", type},
                                               {"count", 3},
                                               {"type", "SCALAR"}});
                 s.doc["meshes"][0]["primitives"][0]["indices"] = s.doc["accessors"].size() - 1;
             },
             fails({"indices", std::to_string(type)})});
    cases.push_back(
        {"UnknownInterpolation",
         [](GltfScene& s) {
             addSampler(s, 2);
             const size_t keys = s.doc["accessors"].size() - 2;
             s.doc["animations"] = {
                 {{"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}}}},
                  {"samplers", {{{"input", keys}, {"output", keys + 1}, {"interpolation", "SMOOTH"}}}}}};
         },
         fails({"SMOOTH"})});
    cases.push_back({"UnknownAnimationPath",
                     [](GltfScene& s) {
                         addSampler(s, 2);
                         const size_t keys = s.doc["accessors"].size() - 2;
                         s.doc["animations"] = {
                             {{"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "shear"}}}}}},
                              {"samplers", {{{"input", keys}, {"output", keys + 1}}}}}};
                     },
                     fails({"shear"})});
    // An image extension used (not required) beside a PNG source falls back to the PNG; an image nobody uses
    // may be undecodable; a required unsupported extension is refused naming it.
    auto webp = [](GltfScene& s, bool required) {
        s.doc["images"].push_back({{"uri", "texture.webp"}});
        s.doc["textures"][0]["extensions"] = {{"EXT_texture_webp", {{"source", 1}}}};
        s.doc["extensionsUsed"] = {"EXT_texture_webp"};
        if (required) s.doc["extensionsRequired"] = {"EXT_texture_webp"};
        s.extraFiles = [](const fs::path& dir) {
            test::writeTextFile(dir / "texture.webp", "RIFF\x10\0\0\0WEBPVP8 ");
        };
    };
    cases.push_back({"ImageExtensionWithPngFallback",
                     [webp](GltfScene& s) { webp(s, false); },
                     {Outcome::MustRender, {}, 0, true}});
    cases.push_back(
        {"ImageExtensionRequired", [webp](GltfScene& s) { webp(s, true); }, fails({"EXT_texture_webp"})});
    cases.push_back({"UnusedUndecodableImage",
                     [](GltfScene& s) {
                         s.doc["images"].push_back({{"uri", "broken.png"}});
                         s.extraFiles = [](const fs::path& dir) {
                             test::writeTextFile(dir / "broken.png", "not a png");
                         };
                     },
                     {Outcome::MustRender, {}, 0, true}});
    cases.push_back({"UsedUndecodableImage",
                     [](GltfScene& s) {
                         s.doc["images"][0]["uri"] = "broken.png";
                         s.extraFiles = [](const fs::path& dir) {
                             test::writeTextFile(dir / "broken.png", "not a png");
                         };
                     },
                     fails({"broken.png", "decoded"})});
    cases.push_back({"UnknownCameraType",
                     [](GltfScene& s) {
                         addCamera(s, {{"yfov", 0.8}, {"znear", 0.01}});
                         s.doc["cameras"][0]["type"] = "fisheye";
                     },
                     fails({"camera"})});
    cases.push_back({"SceneIndexOutOfRange", [](GltfScene& s) { s.doc["scene"] = 5; }, fails({"scene"})});
    cases.push_back({"UnknownLightType",
                     [](GltfScene& s) {
                         addLight(s, {{"type", "area"}, {"intensity", 2}});
                     },
                     fails({"area"})});
    return cases;
}

// Class 4 (images): a valid PNG of `width` x `height` black 1-bit pixels, a few kB however large, that stb
// decodes to one byte per pixel.
void writeBlackPng(const fs::path& path, uint32_t width, uint32_t height) {
    const size_t row = 1 + (width + 7) / 8;
    const std::vector<unsigned char> raw(row * height, 0);  // filter 0, all pixels 0
    uLongf packedSize = compressBound(uLong(raw.size()));
    std::vector<unsigned char> packed(packedSize);
    ASSERT_EQ(compress2(packed.data(), &packedSize, raw.data(), uLong(raw.size()), 9), Z_OK);
    packed.resize(packedSize);
    std::vector<unsigned char> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    auto chunk = [&](const char* type, const std::vector<unsigned char>& data) {
        for (int i = 0; i < 4; ++i) png.push_back((unsigned char)(data.size() >> (24 - 8 * i)));
        const size_t start = png.size();
        png.insert(png.end(), type, type + 4);
        png.insert(png.end(), data.begin(), data.end());
        const uint32_t crc = crc32(png.data() + start, png.size() - start);
        for (int i = 0; i < 4; ++i) png.push_back((unsigned char)(crc >> (24 - 8 * i)));
    };
    std::vector<unsigned char> header;
    for (uint32_t v : {width, height})
        for (int i = 0; i < 4; ++i) header.push_back((unsigned char)(v >> (24 - 8 * i)));
    header.insert(header.end(), {1, 0, 0, 0, 0});  // 1 bit, greyscale, deflate, filter 0, no interlace
    chunk("IHDR", header);
    chunk("IDAT", packed);
    chunk("IEND", {});
    test::writeBinaryFile(path, png);
}

// Five 8192^2 images in one file: each within the per-image cap, together past the file's 2^28 pixels. The
// fifth (the one the material uses) is refused before it is decoded.
std::vector<GltfCase> pixelBudgetCases() {
    std::vector<GltfCase> cases;
    cases.push_back({"ImagesPastTheFilesPixels",
                     [](GltfScene& s) {
                         s.doc["images"] = json::array();
                         for (int i = 0; i < 5; ++i)
                             s.doc["images"].push_back({{"uri", "big" + std::to_string(i) + ".png"}});
                         s.doc["textures"][0]["source"] = 4;
                         s.texture = false;
                         s.extraFiles = [](const fs::path& dir) {
                             for (int i = 0; i < 5; ++i)
                                 writeBlackPng(dir / ("big" + std::to_string(i) + ".png"), 8192, 8192);
                         };
                     },
                     fails({"big4.png", "together"})});
    // Two 8192^2 images (within the file's decoded pixels) used in five roles: colour and data textures are
    // made separately, 5 x 2^26 texels, refused before any is built.
    cases.push_back({"ImagesInFiveRoles",
                     [](GltfScene& s) {
                         s.doc["images"] = {{{"uri", "big0.png"}}, {{"uri", "big1.png"}}};
                         s.doc["textures"] = {{{"source", 0}}, {{"source", 1}}};
                         json& m = s.doc["materials"][0];
                         m["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
                         m["pbrMetallicRoughness"]["metallicRoughnessTexture"] = {{"index", 0}};
                         m["normalTexture"] = {{"index", 0}};
                         m["emissiveTexture"] = {{"index", 1}};
                         m["occlusionTexture"] = {{"index", 1}};
                         s.texture = false;
                         s.extraFiles = [](const fs::path& dir) {
                             for (int i = 0; i < 2; ++i)
                                 writeBlackPng(dir / ("big" + std::to_string(i) + ".png"), 8192, 8192);
                         };
                     },
                     fails({"textures", "counts twice"})});
    return cases;
}

// Vertex colours (issue 20): a COLOR_0 accessor that glTF does not allow (its type, component type or count)
// is refused with one line naming the file and the attribute; colour sets past COLOR_0 are ignored with a
// note, and the scene renders.
std::vector<GltfCase> vertexColorCases() {
    std::vector<GltfCase> cases;
    // COLOR_0 as accessor `count` elements of `type` × `componentType` (float zeros or 0x80 bytes).
    auto color = [](GltfScene& s, const char* name, const char* type, int componentType, bool normalized,
                    size_t count) {
        const int components = std::string(type) == "VEC4"   ? 4
                               : std::string(type) == "VEC3" ? 3
                               : std::string(type) == "VEC2" ? 2
                                                             : 1;
        const size_t size = componentType >= 5125 ? 4 : componentType >= 5122 ? 2 : 1;
        const size_t offset = s.bin.size();
        s.bin.resize(offset + ((count * size_t(components) * size + 3) & ~size_t(3)), 0x80);
        s.doc["bufferViews"].push_back(
            {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", s.bin.size() - offset}});
        json accessor = {{"bufferView", s.doc["bufferViews"].size() - 1},
                         {"componentType", componentType},
                         {"count", count},
                         {"type", type}};
        if (normalized) accessor["normalized"] = true;
        s.doc["accessors"].push_back(accessor);
        s.doc["buffers"][0]["byteLength"] = s.bin.size();
        s.doc["meshes"][0]["primitives"][0]["attributes"][name] = s.doc["accessors"].size() - 1;
    };
    struct Bad {
        const char* name;
        const char* type;
        int componentType;
        bool normalized;
        size_t count;
    };
    const Bad bad[] = {
        {"Scalar", "SCALAR", 5126, false, 3},
        {"Vec2", "VEC2", 5126, false, 3},
        {"TooFew", "VEC4", 5126, false, 2},
        {"TooMany", "VEC3", 5126, false, 4},
        {"BytesNotNormalized", "VEC4", 5121, false, 3},
        {"SignedBytes", "VEC4", 5120, true, 3},
        {"ShortsNotNormalized", "VEC3", 5123, false, 3},
        {"UnsignedInt", "VEC4", 5125, false, 3},
    };
    for (const Bad& b : bad)
        cases.push_back({std::string("Color0") + b.name,
                         [b, color](GltfScene& s) {
                             color(s, "COLOR_0", b.type, b.componentType, b.normalized, b.count);
                         },
                         fails({"COLOR_0"})});
    cases.push_back({"Color0AccessorOutOfRange",
                     [](GltfScene& s) { s.doc["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] = 99; },
                     fails({"COLOR_0"})});
    cases.push_back(
        {"Color0NotFinite",
         [](GltfScene& s) {
             const float inf = std::numeric_limits<float>::infinity();
             const size_t offset = s.bin.size();
             appendFloats(s.bin, {1, 1, 1, inf, 1, 1, 1, 1, 1});
             s.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", 36}});
             s.doc["accessors"].push_back({{"bufferView", s.doc["bufferViews"].size() - 1},
                                           {"componentType", 5126},
                                           {"count", 3},
                                           {"type", "VEC3"}});
             s.doc["buffers"][0]["byteLength"] = s.bin.size();
             s.doc["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] = s.doc["accessors"].size() - 1;
         },
         fails({"COLOR_0"})});
    cases.push_back({"Color1Ignored",
                     [color](GltfScene& s) {
                         color(s, "COLOR_0", "VEC4", 5121, true, 3);
                         color(s, "COLOR_1", "VEC4", 5121, true, 3);
                     },
                     {Outcome::MustRender, {}, 0, true}});
    return cases;
}

class HostileGltf : public ::testing::TestWithParam<GltfCase> {};

TEST_P(HostileGltf, EndsInOneLineOrAFiniteImage) {
    const GltfCase& c = GetParam();
    const fs::path dir = caseDir();
    GltfScene scene = triangleScene();
    c.mutate(scene);
    const fs::path path = c.glb ? writeGlb(dir, scene) : writeGltf(dir, scene);
    const test::RunResult r = expectGraceful(renderArgs(path, dir / "out"), dir / "out", c.expect);
    EXPECT_LT(r.seconds, 30.0) << "too slow for bad input: " << r.describe();
}

std::string caseName(const ::testing::TestParamInfo<GltfCase>& info) {
    return info.param.name;
}

INSTANTIATE_TEST_SUITE_P(Bounds, HostileGltf, ::testing::ValuesIn(boundsCases()), caseName);
INSTANTIATE_TEST_SUITE_P(ImageViews, HostileGltf, ::testing::ValuesIn(imageViewCases()), caseName);
INSTANTIATE_TEST_SUITE_P(Nesting, HostileGltf, ::testing::ValuesIn(nestingCases()), caseName);
INSTANTIATE_TEST_SUITE_P(Allocation, HostileGltf, ::testing::ValuesIn(allocationCases()), caseName);
INSTANTIATE_TEST_SUITE_P(Lights, HostileGltf, ::testing::ValuesIn(lightCases()), caseName);
INSTANTIATE_TEST_SUITE_P(Cameras, HostileGltf, ::testing::ValuesIn(cameraCases()), caseName);
INSTANTIATE_TEST_SUITE_P(Textures, HostileGltf, ::testing::ValuesIn(textureCases()), caseName);
INSTANTIATE_TEST_SUITE_P(ImageBombs, HostileGltf, ::testing::ValuesIn(imageBombCases()), caseName);
INSTANTIATE_TEST_SUITE_P(Narrowing, HostileGltf, ::testing::ValuesIn(narrowingCases()), caseName);
INSTANTIATE_TEST_SUITE_P(Amplification, HostileGltf, ::testing::ValuesIn(amplificationCases()), caseName);
INSTANTIATE_TEST_SUITE_P(Radiance, HostileGltf, ::testing::ValuesIn(radianceCases()), caseName);
INSTANTIATE_TEST_SUITE_P(Lenses, HostileGltf, ::testing::ValuesIn(lensCases()), caseName);
INSTANTIATE_TEST_SUITE_P(Lenient, HostileGltf, ::testing::ValuesIn(lenientCases()), caseName);
INSTANTIATE_TEST_SUITE_P(PixelBudget, HostileGltf, ::testing::ValuesIn(pixelBudgetCases()), caseName);
INSTANTIATE_TEST_SUITE_P(VertexColors, HostileGltf, ::testing::ValuesIn(vertexColorCases()), caseName);

// Issue 20: a lens of yfov 1e-30 (inside glTF's (0, pi)) is widened to the narrowest the projection keeps
// precise, with a note, and renders: depth.exr and final.exr exist and every value is finite (it exited 0 with
// a non-finite depth.exr once).
TEST(HostileGltfLens, NarrowestYfovRendersAFiniteDepthAndImage) {
    const fs::path dir = caseDir();
    GltfScene scene = triangleScene();
    addCamera(scene, {{"yfov", 1e-30}, {"znear", 0.01}});
    const fs::path path = writeGltf(dir, scene);
    const test::RunResult r =
        expectGraceful(renderArgs(path, dir / "out"), dir / "out", {Outcome::MustRender, {}, 0});
    EXPECT_NE(r.out.find("widened to"), std::string::npos) << r.describe();
    for (const char* name : {"depth.exr", "final.exr"}) {
        ASSERT_TRUE(fs::is_regular_file(dir / "out" / name)) << name;
        const ImageRgba32f image = readExr(dir / "out" / name);
        EXPECT_GT(image.pixels.size(), 0u) << name;
        EXPECT_EQ(test::countNonFinite(image.pixels), 0u) << name;
    }
}

// Class 11: a scene of any finite size without a camera is framed by the default camera: it renders, finite,
// and the triangle covers pixels (albedo.exr is black where nothing was drawn).
class HostileSceneScale : public ::testing::TestWithParam<float> {};

TEST_P(HostileSceneScale, DefaultCameraFramesTheScene) {
    const fs::path dir = caseDir();
    GltfScene scene = triangleScene(GetParam());
    scene.texture = false;
    scene.doc["materials"][0]["pbrMetallicRoughness"] = {{"baseColorFactor", {0.8, 0.6, 0.4, 1.0}},
                                                         {"metallicFactor", 0.0}};
    scene.doc.erase("textures");
    scene.doc.erase("images");
    const fs::path path = writeGltf(dir, scene);
    expectGraceful(renderArgs(path, dir / "out"), dir / "out", {Outcome::MustRender, {}, 0});
    EXPECT_GT(coveredPixels(dir / "out"), 32u * 18u / 20u) << "the triangle is hardly in view";
}

// Class 8 (issue 21): at float's limits too (the rescale went into node matrices as 2^-127, subnormal, and
// drew nothing).
INSTANTIATE_TEST_SUITE_P(FloatLimits, HostileSceneScale, ::testing::Values(3e38f, 1e-38f, 1e-44f),
                         [](const auto& param) { return "Limit" + std::to_string(param.index); });

// Class 8 again, with the size in a node's scale instead of the vertices (a unit triangle under a node scaled by
// 3e38): rescaling the vertices by 2^-127 made them subnormal, flushed to zero on the GPU, and the image was
// empty with exit 0. The scale now goes into the root node; 1e-40 is itself subnormal in float.
class HostileNodeScale : public ::testing::TestWithParam<float> {};

TEST_P(HostileNodeScale, DefaultCameraFramesTheScene) {
    const fs::path dir = caseDir();
    GltfScene scene = triangleScene(1.0f);
    scene.texture = false;
    scene.doc["materials"][0]["pbrMetallicRoughness"] = {{"baseColorFactor", {0.8, 0.6, 0.4, 1.0}},
                                                         {"metallicFactor", 0.0}};
    scene.doc.erase("textures");
    scene.doc.erase("images");
    const double s = GetParam();
    scene.doc["nodes"][0]["scale"] = {s, s, s};
    const fs::path path = writeGltf(dir, scene);
    expectGraceful(renderArgs(path, dir / "out"), dir / "out", {Outcome::MustRender, {}, 0});
    EXPECT_GT(coveredPixels(dir / "out"), 32u * 18u / 20u) << "the triangle is hardly in view";
}

INSTANTIATE_TEST_SUITE_P(FloatLimits, HostileNodeScale, ::testing::Values(3e38f, 1e30f, 1e-30f, 1e-40f),
                         [](const auto& param) { return "Limit" + std::to_string(param.index); });

INSTANTIATE_TEST_SUITE_P(Scales, HostileSceneScale,
                         ::testing::Values(1e-5f, 1e-10f, 1e-20f, 1e-30f, 1e20f, 1e30f),
                         [](const auto& param) { return "Scale" + std::to_string(param.index); });

}  // namespace
}  // namespace vct::hostile
