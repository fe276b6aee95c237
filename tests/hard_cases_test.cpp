// Numerical hard cases on the GPU path (issue 9, docs/design.md §7): κ at the fp16 limit of the guide, a surface
// point at the camera (zero view vector), zero-length mesh normals, a camera in the plane of a surface
// (grazing n·v) and the cone's start offset on cornell. Each renders the case at trace scale 4 (upsampled,
// re-traced) and at trace scale 1 (the reference: every pixel traced) with --aux --validate, and checks every
// EXR written for NaN/Inf and for black pixels where light exists: where the reference's direct light is > 1
// % of its largest value, the final image must be lit; where the reference's diffuse indirect light is, the
// upsampled one must be > 0. The scenes are tiny glTF rooms written here (floor, back wall, left wall, a
// point light, a camera).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/image_io.h"
#include "test_util.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using vct::test::luminance;

// A room of three quads (floor y = 0, back wall z = −2, left wall x = −2; 4 m wide, 3 m tall) under a point
// light, moved by `origin`, seen by a camera at `eye` rotated by the quaternion `rotation` (x, y, z, w).
struct Room {
    std::vector<double> origin = {0.0, 0.0, 0.0};
    bool zeroNormals = false;
    std::vector<double> eye = {0.0, 1.5, 1.9};
    std::vector<double> rotation = {-0.2164396, 0.0, 0.0, 0.9762960};  // 25° down
    double yfov = 1.0, znear = 0.05;
};

fs::path writeRoom(const fs::path& dir, const Room& room) {
    struct Quad {
        float corner[3], u[3], v[3], n[3];
    };
    const Quad quads[] = {{{-2, 0, 2}, {4, 0, 0}, {0, 0, -4}, {0, 1, 0}},
                          {{-2, 0, -2}, {4, 0, 0}, {0, 3, 0}, {0, 0, 1}},
                          {{-2, 0, 2}, {0, 0, -4}, {0, 3, 0}, {1, 0, 0}}};
    std::vector<float> positions, normals;
    std::vector<uint16_t> indices;
    for (const Quad& q : quads) {
        const uint16_t base = uint16_t(positions.size() / 3);
        for (int k = 0; k < 4; ++k) {
            const float a = float(k & 1), b = float(k >> 1);
            for (int c = 0; c < 3; ++c) {
                positions.push_back(q.corner[c] + a * q.u[c] + b * q.v[c]);
                normals.push_back(room.zeroNormals ? 0.0f : q.n[c]);
            }
        }
        // Counter-clockwise seen from the side the normal points to.
        for (int i : {0, 1, 3, 0, 3, 2}) indices.push_back(uint16_t(base + i));
    }
    std::vector<unsigned char> bin(positions.size() * 4 + normals.size() * 4 + indices.size() * 2);
    std::memcpy(bin.data(), positions.data(), positions.size() * 4);
    std::memcpy(bin.data() + positions.size() * 4, normals.data(), normals.size() * 4);
    std::memcpy(bin.data() + positions.size() * 8, indices.data(), indices.size() * 2);
    const size_t pBytes = positions.size() * 4, iBytes = indices.size() * 2;
    json gltf = {
        {"asset", {{"version", "2.0"}}},
        {"extensionsUsed", {"KHR_lights_punctual"}},
        {"extensions",
         {{"KHR_lights_punctual",
           {{"lights", {{{"type", "point"}, {"intensity", 40.0}, {"color", {1, 1, 1}}}}}}}}},
        {"scene", 0},
        {"scenes", {{{"nodes", {0, 1, 2}}}}},
        {"nodes",
         {{{"name", "room"}, {"mesh", 0}, {"translation", room.origin}},
          {{"name", "light"},
           {"translation", {room.origin[0], room.origin[1] + 2.5, room.origin[2]}},
           {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}},
          {{"name", "camera"}, {"camera", 0}, {"translation", room.eye}, {"rotation", room.rotation}}}},
        {"cameras",
         {{{"type", "perspective"},
           {"perspective",
            {{"yfov", room.yfov}, {"znear", room.znear}, {"zfar", 100.0}, {"aspectRatio", 16.0 / 9}}}}}},
        {"meshes",
         {{{"name", "room"},
           {"primitives",
            {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}}}, {"indices", 2}, {"material", 0}}}}}}},
        {"materials",
         {{{"name", "white"},
           {"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.8, 0.8, 1}}, {"roughnessFactor", 0.6}}},
           {"doubleSided", true}}}},
        {"buffers", {{{"uri", "room.bin"}, {"byteLength", bin.size()}}}},
        {"bufferViews",
         {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", pBytes}},
          {{"buffer", 0}, {"byteOffset", pBytes}, {"byteLength", pBytes}},
          {{"buffer", 0}, {"byteOffset", 2 * pBytes}, {"byteLength", iBytes}}}},
        {"accessors",
         {{{"bufferView", 0},
           {"componentType", 5126},
           {"count", 12},
           {"type", "VEC3"},
           {"min", {-2, 0, -2}},
           {"max", {2, 3, 2}}},
          {{"bufferView", 1}, {"componentType", 5126}, {"count", 12}, {"type", "VEC3"}},
          {{"bufferView", 2}, {"componentType", 5123}, {"count", indices.size()}, {"type", "SCALAR"}}}},
    };
    vct::test::writeTextFile(dir / "room.gltf", gltf.dump(2));
    vct::test::writeBinaryFile(dir / "room.bin", bin);
    return dir / "room.gltf";
}

fs::path caseDir(const std::string& name) {
    return vct::test::freshOutputDir("hard_cases/" + name);
}

// Renders `scene` (a file or a built-in name) into dir/out_s<scale> with --aux --validate; extra flags
// appended.
fs::path render(const fs::path& dir, const std::string& scene, int scale,
                const std::vector<std::string>& extra, const std::string& size = "160x90") {
    const fs::path out = dir / ("out_s" + std::to_string(scale));
    std::vector<std::string> args = {"render",
                                     "--scene",
                                     scene,
                                     "--size",
                                     size,
                                     "--voxels",
                                     "32",
                                     "--frames",
                                     "3",
                                     "--aux",
                                     "--validate",
                                     "--trace-scale",
                                     std::to_string(scale),
                                     "--out",
                                     out.string()};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = vct::test::runVct(args);
    EXPECT_TRUE(r.exited() && r.exitCode == 0) << r.describe();
    return out;
}

std::vector<float> pixelLuminance(const vct::ImageRgba32f& image) {
    std::vector<float> l(size_t(image.width) * image.height);
    for (size_t i = 0; i < l.size(); ++i)
        l[i] = luminance(image.pixels[i * 4], image.pixels[i * 4 + 1], image.pixels[i * 4 + 2]);
    return l;
}

struct Holes {
    size_t lit = 0, black = 0;  // pixels where light exists, and those of them that came out black
};

// Pixels where `reference` exceeds 1 % of its largest value ("light exists") that are not > 0 in `image`.
Holes blackWhereLit(const fs::path& reference, const fs::path& image) {
    const std::vector<float> ref = pixelLuminance(vct::readExr(reference)),
                             img = pixelLuminance(vct::readExr(image));
    const float peak = *std::max_element(ref.begin(), ref.end());
    Holes h;
    for (size_t i = 0; i < ref.size(); ++i) {
        if (!(ref[i] > 0.01f * peak)) continue;
        ++h.lit;
        h.black += img[i] > 0.0f ? 0 : 1;
    }
    return h;
}

// The checks of every case: the trace-scale-4 and trace-scale-1 renders in `dir` have no NaN/Inf in any EXR,
// and no black pixel in final (where the reference's direct light is) or in diffuse_indirect (where the
// reference's indirect light is). Returns how many pixels were lit (the case must show light somewhere).
size_t expectFiniteAndLit(const fs::path& low, const fs::path& ref, const std::string& what) {
    for (const fs::path& dir : {low, ref}) {
        size_t files = 0;
        for (const auto& entry : fs::directory_iterator(dir)) {
            if (entry.path().extension() != ".exr") continue;
            ++files;
            EXPECT_EQ(vct::test::countNonFinite(vct::readExr(entry.path()).pixels), 0u)
                << what << ": " << entry.path().filename();
        }
        EXPECT_GE(files, 8u) << what << ": " << dir;
    }
    const Holes direct = blackWhereLit(ref / "direct.exr", low / "final.exr");
    const Holes indirect = blackWhereLit(ref / "diffuse_indirect.exr", low / "diffuse_indirect.exr");
    std::printf("%s: %zu directly lit pixels, %zu black in final; %zu with indirect light, %zu black\n",
                what.c_str(), direct.lit, direct.black, indirect.lit, indirect.black);
    EXPECT_EQ(direct.black, 0u) << what;
    EXPECT_EQ(indirect.black, 0u) << what;
    return direct.lit + indirect.lit;
}

size_t renderAndCheck(const fs::path& dir, const std::string& scene, const std::vector<std::string>& extra,
                      const std::string& what, const std::string& size = "160x90") {
    const fs::path low = render(dir, scene, 4, extra, size), ref = render(dir, scene, 1, extra, size);
    return expectFiniteAndLit(low, ref, what);
}

// κ at the largest value the guide's fp16 storage holds (cornell's floor stripe of roughness 0.05 reaches
// it); more is a one-line usage error, not inf in the guide.
TEST(HardCasesGpu, KappaAtTheFp16Limit) {
    const fs::path dir = caseDir("kappa");
    EXPECT_GT(renderAndCheck(dir, "cornell", {"--kappa", "65504"}, "cornell --kappa 65504"), 1000u);
    for (const char* kappa : {"65505", "1e6", "inf"}) {
        const auto r = vct::test::runVct({"render", "--kappa", kappa});
        ASSERT_TRUE(r.exited()) << r.describe();
        EXPECT_EQ(r.exitCode, 2) << r.describe();
        EXPECT_NE(r.err.find("--kappa"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("65504"), std::string::npos) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    }
}

// A surface point at the camera. Rasterization keeps every G-buffer point at least the near plane away, so
// the camera − p = 0 that viewDirection guards comes only from rounding: the room 1000 m out, where a float's
// step is 6.1e-5 m, its floor one step below the eye (y = 999.99994 under y = 1000), a wide lens looking 45°
// down. The floor is then within float noise of the eye (the view transform cancels at 1000 m), so the image
// is garbage by construction and the check is that it stays finite (light is sparse: "lit" is mostly the
// ambient background). What it found: with near planes of 1e-5 m (against 100 m) the depth resolution runs
// out, pixels store the last depth below 1 and their reconstructed position is not finite: the cone trace and
// the upsample wrote NaN in 37 % of the pixels at trace scale 1 and 4 (before isDegeneratePosition,
// lib/gbuffer_read.glsl).
TEST(HardCasesGpu, SurfaceAtTheCamera) {
    const fs::path dir = caseDir("camera_on_surface");
    Room room;
    room.origin = {1000.0, 999.99993896484375, 1000.0};
    room.eye = {1000.0, 1000.0, 1000.0};
    room.rotation = {-0.3826834, 0.0, 0.0, 0.9238795};  // 45° down
    room.yfov = 1.9;
    for (double znear : {3e-5, 1e-5}) {
        room.znear = znear;
        const fs::path sub = dir / (znear > 2e-5 ? "near3e-5" : "near1e-5");
        fs::create_directories(sub);
        renderAndCheck(sub, writeRoom(sub, room).string(), {},
                       "surface at the camera, znear " + std::to_string(znear));
    }
}

// Zero-length mesh normals (a glTF NORMAL of zeros): the G-buffer falls back to the triangle's geometric
// normal, so the room shades as with its true normals (flat quads: the same), not as a fixed axis and never
// NaN.
TEST(HardCasesGpu, ZeroLengthNormals) {
    const fs::path dir = caseDir("zero_normals");
    Room room;
    room.zeroNormals = true;
    const fs::path zero = writeRoom(dir, room);
    EXPECT_GT(renderAndCheck(dir, zero.string(), {}, "zero normals"), 1000u);
    // Against the same room with its normals: the direct light agrees.
    const fs::path trueDir = caseDir("zero_normals_reference");
    room.zeroNormals = false;
    const fs::path truth = render(trueDir, writeRoom(trueDir, room).string(), 1, {});
    const std::vector<float> a = pixelLuminance(vct::readExr(dir / "out_s1" / "direct.exr"));
    const std::vector<float> b = pixelLuminance(vct::readExr(truth / "direct.exr"));
    ASSERT_EQ(a.size(), b.size());
    double error = 0.0, energy = 0.0;
    for (size_t i = 0; i < a.size(); ++i) {
        error += double(a[i] - b[i]) * (a[i] - b[i]);
        energy += double(b[i]) * b[i];
    }
    std::printf("zero normals: direct light relative MSE %.3g against the true normals\n", error / energy);
    EXPECT_LT(error / energy, 1e-3);
}

// Grazing n·v: the camera in the plane of the floor (on it: the floor edge-on) and a millimetre above it (the
// floor at n·v from 0 to 0.02), looking along it at the walls.
TEST(HardCasesGpu, GrazingView) {
    for (double height : {0.0, 1e-3}) {
        const std::string name = height == 0.0 ? "grazing_on_floor" : "grazing_1mm";
        const fs::path dir = caseDir(name);
        Room room;
        room.eye = {0.3, height, 1.9};
        room.rotation = {0.0, 0.0, 0.0, 1.0};  // along −z, level
        room.znear = 1e-3;
        EXPECT_GT(renderAndCheck(dir, writeRoom(dir, room).string(), {}, name), 1000u);
    }
}

// The cone's start (origin + n·v0, first sample at v0; lib/cone.glsl says why twice) on cornell at the
// coarsest grid, where a voxel is largest against the room (32³): contact shadows and corners traced, no NaN,
// no hole.
TEST(HardCasesGpu, ConeStartOnCornellAtCoarseVoxels) {
    const fs::path dir = caseDir("cone_start");
    EXPECT_GT(renderAndCheck(dir, "cornell", {}, "cornell 32^3"), 1000u);
}

}  // namespace
