// OpenVDB files of the voxelized scene (`vct voxelize --out FILE.vdb`, `--voxel-cache FILE.vdb`). Pure CPU:
// the data goes in and out as plain arrays of occupied voxels, so this is testable without Vulkan; only
// vdb_io.cpp includes OpenVDB.
//
// What a file holds (sparse: only occupied voxels are active, every background value is 0):
//   albedo    Vec3f  resolved albedo of the frame at t = 0 (static + moving instances), what the renderer's
//                    RGBA8 volume held
//   normal    Vec3f  averaged surface normal (not renormalised: shorter where the surfaces in a voxel
//   disagree) emission  Vec3f  emitted radiance opacity   float  coverage (1 for every occupied voxel:
//   binary, as in the renderer); a fog volume radiance  Vec3f  injected outgoing radiance of mip 0 at t = 0
//   (direct light + emission), premultiplied by
//                    opacity, i.e. equal to the radiance since opacity is 0 or 1
//   static_count         Int32  samples of static geometry per voxel (active where > 0)
//   static_albedo_sum    Vec3i  } the static geometry's fixed-point accumulator (shaders/lib/voxel.glsl),
//   static_normal_sum    Vec3i  } raw uint32 bits stored as int32: albedo × 1023, normal × 1023 (two's
//   static_emission_sum  Vec3i  } complement), emission × 256; mean = sum / (scale × static_count)
//   static_transparency_sum, static_metallic_sum, static_roughness_sum  Int32  the same for (1 − alpha) of
//                        blended samples, metallic and perceptual roughness, × 1023 (older files without the
//                        metallic and roughness sums are refused by name)
// The static_* grids make `--voxel-cache` exact: they are what the voxelize pass would accumulate for the
// static instances, so a cached run renders bit for bit the image of an uncached one. Moving instances
// are voxelized every frame anyway and are not part of the cache.
//
// Transform (every grid): linear, voxel size s, translated so that index (i,j,k) maps to the voxel's centre,
// world = origin + (ijk + 0.5)·s — OpenVDB's cell-centred convention, so other tools place the voxels right;
// origin is the grid's min corner (VoxelGrid::origin()) and active indices lie in [0, N)³.
// Integrity: the OpenVDB data is followed by a 24-byte trailer, "vctsum01", the data's length and its FNV-1a
// 64 hash (little-endian u64s), checked before OpenVDB parses anything (OpenVDB trusts what it reads: a
// flipped bit could crash it). OpenVDB tools ignore the trailer.
// Metadata (file and every grid): vct_format, vct_scene, vct_resolution, vct_grid_origin (Vec3s, min corner),
// vct_voxel_size, vct_index_to_world, vct_time, vct_scene_hash; each grid also gets vct_description (one of
// the lines above).
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "lib/shared.h"

namespace vct {

// Format tag written into every file; readers refuse files without it.
inline constexpr const char* kVoxelFileFormat = "vct-voxels/1";

// The grid a file describes: N³ voxels from `origin` (min corner) with edge `voxelSize`, as VoxelGrid.
struct VoxelFileInfo {
    uint32_t resolution = 0;
    glm::vec3 origin{0.0f};
    float voxelSize = 0.0f;
    std::string scene;  // --scene as given when it was written
    float time = 0.0f;  // animation time of the frame the albedo..radiance grids come from
    // sceneContentHash (scene/scene.h) of the scene voxelized; 0 when unknown (files written before it
    // existed).
    uint64_t sceneHash = 0;
    bool operator==(const VoxelFileInfo&) const = default;
};

// One occupied voxel of the frame's resolved volumes.
struct VoxelSample {
    glm::ivec3 ijk{0};
    glm::vec3 albedo{0.0f};
    float opacity = 0.0f;
    glm::vec3 normal{0.0f};
    glm::vec3 emission{0.0f};
    glm::vec3 radiance{0.0f};
    bool operator==(const VoxelSample&) const = default;
};

// One voxel of the static accumulator with at least one sample: its VCT_VOXEL_ACCUM_STRIDE uints as the
// voxelize shader leaves them (albedo rgb, normal xyz, emission rgb, count).
struct StaticAccumVoxel {
    glm::ivec3 ijk{0};
    std::array<uint32_t, VCT_VOXEL_ACCUM_STRIDE> accum{};
    bool operator==(const StaticAccumVoxel&) const = default;
};

struct VoxelFile {
    VoxelFileInfo info;
    std::vector<VoxelSample> voxels;            // read: sorted by linear index i + N·(j + N·k)
    std::vector<StaticAccumVoxel> staticAccum;  // likewise
    bool operator==(const VoxelFile&) const = default;
};

// What was written: one entry per grid, in file order.
struct VoxelGridSummary {
    std::string name;
    std::string type;  // OpenVDB value type, e.g. "vec3s"
    uint64_t activeVoxels = 0;
};

// Linear index of a voxel, as voxelLinearIndex() in shaders/lib/voxel.glsl.
inline uint64_t voxelFileIndex(glm::ivec3 ijk, uint32_t n) {
    return uint64_t(ijk.x) + uint64_t(n) * (uint64_t(ijk.y) + uint64_t(n) * uint64_t(ijk.z));
}

// Bytes the same fields would take as dense N³ arrays (every grid's value size × N³): the size a sparse
// file is compared with.
uint64_t denseVoxelBytes(uint32_t resolution);

// Writes the grids above. Throws vct::Error naming the path when it cannot (bad directory, voxel outside
// [0, N)³, N not positive). Voxels need not be sorted; each ijk should appear once per list.
std::vector<VoxelGridSummary> writeVoxelFile(const std::filesystem::path& path, const VoxelFile& file);

// Reads a file written by writeVoxelFile. `frame` false skips the albedo..radiance grids (the cache needs
// only the static_* ones). Throws vct::Error with a one-line message naming the path for a missing file, a
// file that is not a regular file or is larger than kMaxInputFileBytes, a file without its integrity trailer
// or whose checksum does not match, a file that is not OpenVDB, an OpenVDB file without vct's metadata (the
// scene hash included) or grids, active values (voxels or tiles) outside the grid, or values the voxelize
// pass cannot produce (accumulator sums beyond their sample count, non-finite or negative light).
VoxelFile readVoxelFile(const std::filesystem::path& path, bool frame = true);

// Isolation: a file whose checksum matches may still be written to crash OpenVDB. With `program` set (the vct
// executable; main() sets it), every file is first parsed by `program --vct-check-voxel-file PATH CHECKSUM` in
// a process of its own, and refused in one line when that process crashes, fails or runs past 120 s; each
// (path, checksum) is checked once per process. Off (empty) by default: tests read files in process.
inline constexpr const char* kCheckVoxelFileFlag = "--vct-check-voxel-file";
void setVoxelFileIsolation(const std::filesystem::path& program);
// The isolated parse (`vct --vct-check-voxel-file PATH CHECKSUM`): reads the file as readVoxelFile does and
// returns 0 (vct's own refusals included: the caller repeats them in one line); 1 when the file no longer has
// that checksum. A crash ends it by a signal, which is what the caller looks for.
int checkVoxelFileInIsolation(const std::filesystem::path& path, const std::string& checksum);

// Appends the integrity trailer to an OpenVDB file written by other means (tests, tools that edit a cache).
void sealVoxelFile(const std::filesystem::path& path);

// Only the metadata (cheap: no grid is read). Same errors as readVoxelFile.
VoxelFileInfo readVoxelFileInfo(const std::filesystem::path& path);

}  // namespace vct
