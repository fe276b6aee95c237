#include "io/vdb_io.h"

#include <fcntl.h>
#include <openvdb/io/File.h>
#include <openvdb/io/Stream.h>
#include <openvdb/openvdb.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <istream>
#include <mutex>
#include <set>
#include <sstream>
#include <system_error>

#include "core/error.h"
#include "io/safe_write.h"
#include "scene/input_limits.h"

extern char** environ;

namespace vct {

namespace {

static_assert(VCT_VOXEL_ACCUM_STRIDE == 13 && VCT_VOXEL_ACCUM_COUNT == 9 &&
                  VCT_VOXEL_ACCUM_TRANSPARENCY == 10 && VCT_VOXEL_ACCUM_METALLIC == 11 &&
                  VCT_VOXEL_ACCUM_ROUGHNESS == 12,
              "static_* grids assume albedo rgb, normal xyz, emission rgb, count, transparency, metallic, "
              "roughness");

// Grid names, in file order.
constexpr const char* kAlbedo = "albedo";
constexpr const char* kNormal = "normal";
constexpr const char* kEmission = "emission";
constexpr const char* kOpacity = "opacity";
constexpr const char* kRadiance = "radiance";
constexpr const char* kStaticCount = "static_count";
constexpr const char* kStaticAlbedo = "static_albedo_sum";
constexpr const char* kStaticNormal = "static_normal_sum";
constexpr const char* kStaticEmission = "static_emission_sum";
constexpr const char* kStaticTransparency = "static_transparency_sum";
constexpr const char* kStaticMetallic = "static_metallic_sum";
constexpr const char* kStaticRoughness = "static_roughness_sum";

constexpr const char* kIndexToWorld =
    "index (i,j,k) is the voxel centred at vct_grid_origin + (ijk + 0.5) * vct_voxel_size (OpenVDB's "
    "cell-centred "
    "convention); vct_grid_origin is the grid's min corner; active voxels lie in [0, vct_resolution)^3";

void initializeOpenVdb() {
    static std::once_flag once;
    std::call_once(once, [] { openvdb::initialize(); });
}

std::string quoted(const std::filesystem::path& path) {
    return "'" + path.string() + "'";
}

// OpenVDB's messages about a damaged file may quote its bytes (NULs, kilobytes of padding): printable
// characters only, runs of blanks folded, at most 160 characters.
std::string what(const std::exception& e) {
    std::string text;
    for (const char* p = e.what(); *p && text.size() < 160; ++p) {
        const unsigned char c = static_cast<unsigned char>(*p);
        const bool blank = c <= ' ' || c >= 0x7f;
        if (blank && (text.empty() || text.back() == ' ')) continue;
        text += blank ? ' ' : char(c);
    }
    while (!text.empty() && text.back() == ' ') text.pop_back();
    return text;
}

openvdb::Coord coord(glm::ivec3 v) {
    return openvdb::Coord(v.x, v.y, v.z);
}
glm::ivec3 ivec(const openvdb::Coord& c) {
    return glm::ivec3(c.x(), c.y(), c.z());
}
openvdb::Vec3s vec3s(glm::vec3 v) {
    return openvdb::Vec3s(v.x, v.y, v.z);
}
glm::vec3 vec3(const openvdb::Vec3s& v) {
    return glm::vec3(v.x(), v.y(), v.z());
}
// The accumulator's uints keep their bits in the int32 grids (normal sums are two's complement anyway).
openvdb::Vec3i vec3i(const uint32_t* u) {
    return openvdb::Vec3i(std::bit_cast<int32_t>(u[0]), std::bit_cast<int32_t>(u[1]),
                          std::bit_cast<int32_t>(u[2]));
}
void fromVec3i(const openvdb::Vec3i& v, uint32_t* u) {
    for (int c = 0; c < 3; ++c) u[c] = std::bit_cast<uint32_t>(v[c]);
}

bool finite3(glm::vec3 v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

bool inGrid(glm::ivec3 ijk, uint32_t n) {
    return glm::all(glm::greaterThanEqual(ijk, glm::ivec3(0))) &&
           glm::all(glm::lessThan(ijk, glm::ivec3(int(n))));
}

void insertCommonMeta(openvdb::MetaMap& meta, const VoxelFileInfo& info) {
    meta.insertMeta("vct_format", openvdb::StringMetadata(kVoxelFileFormat));
    meta.insertMeta("vct_scene", openvdb::StringMetadata(info.scene));
    meta.insertMeta("vct_resolution", openvdb::Int32Metadata(int32_t(info.resolution)));
    meta.insertMeta("vct_grid_origin", openvdb::Vec3SMetadata(vec3s(info.origin)));
    meta.insertMeta("vct_voxel_size", openvdb::FloatMetadata(info.voxelSize));
    meta.insertMeta("vct_index_to_world", openvdb::StringMetadata(kIndexToWorld));
    meta.insertMeta("vct_time", openvdb::FloatMetadata(info.time));
    meta.insertMeta("vct_scene_hash", openvdb::Int64Metadata(std::bit_cast<int64_t>(info.sceneHash)));
}

template <typename GridT>
typename GridT::Ptr makeGrid(const char* name, const char* description, const VoxelFileInfo& info,
                             const openvdb::math::Transform::Ptr& transform) {
    typename GridT::Ptr grid =
        GridT::create(typename GridT::ValueType(openvdb::zeroVal<typename GridT::ValueType>()));
    grid->setName(name);
    grid->setTransform(transform);
    insertCommonMeta(*grid, info);
    grid->insertMeta("vct_description", openvdb::StringMetadata(description));
    return grid;
}

template <typename T>
T requireMeta(const openvdb::MetaMap& meta, const char* name, const std::filesystem::path& path) {
    typename openvdb::TypedMetadata<T>::ConstPtr value = meta.getMetadata<openvdb::TypedMetadata<T>>(name);
    if (!value)
        throw Error("voxel file " + quoted(path) + " has no " + name +
                    " metadata (not written by vct voxelize)");
    return value->value();
}

VoxelFileInfo readInfo(const openvdb::MetaMap& meta, const std::filesystem::path& path) {
    openvdb::StringMetadata::ConstPtr format = meta.getMetadata<openvdb::StringMetadata>("vct_format");
    if (!format)
        throw Error("voxel file " + quoted(path) + " is an OpenVDB file but not one written by vct voxelize");
    if (format->value() != kVoxelFileFormat)
        throw Error("voxel file " + quoted(path) + " has format '" + format->value() + "', expected '" +
                    kVoxelFileFormat + "'");
    VoxelFileInfo info;
    const int32_t n = requireMeta<int32_t>(meta, "vct_resolution", path);
    if (n < 1 || n > 4096)
        throw Error("voxel file " + quoted(path) + ": bad vct_resolution " + std::to_string(n));
    info.resolution = uint32_t(n);
    info.origin = vec3(requireMeta<openvdb::Vec3s>(meta, "vct_grid_origin", path));
    info.voxelSize = requireMeta<float>(meta, "vct_voxel_size", path);
    if (!(info.voxelSize > 0.0f) || !std::isfinite(info.voxelSize))
        throw Error("voxel file " + quoted(path) + ": bad vct_voxel_size " + std::to_string(info.voxelSize));
    info.scene = requireMeta<std::string>(meta, "vct_scene", path);
    info.time = requireMeta<float>(meta, "vct_time", path);
    // Required: without it only the scene's file name could tell another scene's cache from this one's.
    info.sceneHash = std::bit_cast<uint64_t>(requireMeta<int64_t>(meta, "vct_scene_hash", path));
    if (info.sceneHash == 0) throw Error("voxel file " + quoted(path) + " has a zero vct_scene_hash");
    if (!finite3((info.origin)) || !std::isfinite(info.time))
        throw Error("voxel file " + quoted(path) + ": its grid origin or time is not finite");
    return info;
}

// The integrity trailer after the OpenVDB data (vdb_io.h): magic, payload length, FNV-1a 64 of the payload.
constexpr char kTrailerMagic[8] = {'v', 'c', 't', 's', 'u', 'm', '0', '1'};
constexpr uint64_t kTrailerBytes = 24;

uint64_t payloadChecksum(const unsigned char* data, size_t size) {
    uint64_t hash = 0xcbf29ce484222325ull;
    for (size_t i = 0; i < size; ++i) hash = (hash ^ data[i]) * 0x100000001b3ull;
    return hash;
}

void putU64(unsigned char* out, uint64_t v) {
    for (int i = 0; i < 8; ++i) out[i] = (unsigned char)(v >> (8 * i));
}
uint64_t getU64(const unsigned char* in) {
    uint64_t v = 0;
    for (int i = 7; i >= 0; --i) v = (v << 8) | in[i];
    return v;
}

std::string trailerFor(const unsigned char* payload, size_t size) {
    unsigned char trailer[kTrailerBytes];
    std::memcpy(trailer, kTrailerMagic, 8);
    putU64(trailer + 8, size);
    putU64(trailer + 16, payloadChecksum(payload, size));
    return std::string(reinterpret_cast<const char*>(trailer), kTrailerBytes);
}

// An istream over bytes in memory, without copying them; seekable as OpenVDB may ask.
class MemoryBuffer : public std::streambuf {
  public:
    MemoryBuffer(const unsigned char* data, size_t size) {
        char* begin = const_cast<char*>(reinterpret_cast<const char*>(data));
        setg(begin, begin, begin + size);
    }

  protected:
    pos_type seekoff(off_type off, std::ios_base::seekdir dir, std::ios_base::openmode) override {
        const off_type base = dir == std::ios_base::beg   ? 0
                              : dir == std::ios_base::cur ? off_type(gptr() - eback())
                                                          : off_type(egptr() - eback());
        const off_type to = base + off;
        if (to < 0 || to > off_type(egptr() - eback())) return pos_type(off_type(-1));
        setg(eback(), eback() + to, egptr());
        return pos_type(to);
    }
    pos_type seekpos(pos_type pos, std::ios_base::openmode mode) override {
        return seekoff(off_type(pos), std::ios_base::beg, mode);
    }
};

// ---- OpenVDB parses in a process of its own first (setVoxelFileIsolation) ----

std::mutex isolationMutex;
std::filesystem::path isolationProgram;
std::set<std::pair<std::string, uint64_t>> isolationPassed;  // (path, checksum) parsed cleanly already

std::string hexText(uint64_t v) {
    char text[20];
    std::snprintf(text, sizeof(text), "%016llx", (unsigned long long)v);
    return text;
}

// A file whose checksum is right may still be made to crash OpenVDB (written so on purpose): with isolation
// on, `program --vct-check-voxel-file PATH CHECKSUM` parses it first, and only a clean exit lets this
// process parse it. The child's output is discarded: this process says what happened, in one line.
void checkInIsolation(const std::filesystem::path& path, uint64_t checksum, const std::string& name) {
    std::filesystem::path program;
    {
        std::lock_guard<std::mutex> lock(isolationMutex);
        if (isolationProgram.empty() || isolationPassed.count({path.string(), checksum})) return;
        program = isolationProgram;
    }
    const std::string hex = hexText(checksum);
    std::vector<std::string> args = {program.string(), kCheckVoxelFileFlag, path.string(), hex};
    std::vector<char*> argv;
    for (std::string& arg : args) argv.push_back(arg.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    for (int fd : {0, 1, 2})
        posix_spawn_file_actions_addopen(&actions, fd, "/dev/null", fd ? O_WRONLY : O_RDONLY, 0);
    pid_t pid = -1;
    const int spawned = posix_spawn(&pid, program.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (spawned != 0) throw Error(name + ": cannot start its check (" + std::strerror(spawned) + ")");
    constexpr int kTimeoutSeconds = 120;
    int status = 0;
    for (int waited = 0;; ++waited) {
        const pid_t done = waitpid(pid, &status, WNOHANG);
        if (done == pid) break;
        if (done < 0 && errno != EINTR)
            throw Error(name + ": its check was lost (" + std::strerror(errno) + ")");
        if (waited >= kTimeoutSeconds * 100) {
            kill(pid, SIGKILL);
            waitpid(pid, &status, 0);
            throw Error(name + " is damaged: OpenVDB did not finish parsing it in " +
                        std::to_string(kTimeoutSeconds) + " s");
        }
        usleep(10000);
    }
    if (WIFSIGNALED(status))
        throw Error(name + " is damaged: OpenVDB crashed parsing it (" + strsignal(WTERMSIG(status)) +
                    "), though its checksum matches (made so on purpose?)");
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
        throw Error(name + " changed while it was checked (or its check could not run)");
    std::lock_guard<std::mutex> lock(isolationMutex);
    isolationPassed.insert({path.string(), checksum});
}

// A whole voxel file in memory. OpenVDB does not defend itself against a damaged file (lengths trusted,
// garbage sizes allocated, a flipped bit can crash it), so nothing reaches it before (1) the one checked open
// (a regular file: a FIFO must not block), (2) the trailer: present, its payload length the file's, and (3)
// the payload's checksum. The payload is then parsed from a stream that throws at the first read past its
// end.
struct VoxelStream {
    openvdb::MetaMap::Ptr meta;
    openvdb::GridPtrVecPtr grids;
};

VoxelStream openFile(const std::filesystem::path& path) {
    const std::string name = "voxel file " + quoted(path);
    const InputFile file(path);
    if (!file.error().empty()) {
        std::error_code error;
        if (file.error() == "no such file") throw Error(name + " does not exist");
        if (std::filesystem::is_directory(path, error)) throw Error(name + " is a directory");
        throw Error(name + ": " + file.error());
    }
    if (file.size() < kTrailerBytes)
        throw Error(name + " is not a vct voxel file (" + byteSizeText(file.size()) +
                    ", too short for its checksum trailer: truncated?)");
    std::vector<unsigned char> trailer;
    if (std::string problem = file.readAt(file.size() - kTrailerBytes, kTrailerBytes, trailer);
        !problem.empty())
        throw Error(name + ": " + problem);
    if (std::memcmp(trailer.data(), kTrailerMagic, 8) != 0)
        throw Error(name +
                    " is not a vct voxel file (no checksum trailer: truncated, not written by vct "
                    "voxelize, or by a version before checksums: re-run vct voxelize)");
    const uint64_t payloadBytes = getU64(trailer.data() + 8);
    if (payloadBytes != file.size() - kTrailerBytes)
        throw Error(name + " declares " + byteSizeText(payloadBytes) + " of voxel data but holds " +
                    byteSizeText(file.size() - kTrailerBytes) + " (truncated or appended to)");
    std::vector<unsigned char> payload;
    if (std::string problem = file.readAt(0, payloadBytes, payload); !problem.empty())
        throw Error(name + ": " + problem);
    const uint64_t checksum = payloadChecksum(payload.data(), payload.size());
    if (checksum != getU64(trailer.data() + 16))
        throw Error(name + " is damaged (its checksum does not match its contents)");
    checkInIsolation(path, checksum, name);

    MemoryBuffer buffer(payload.data(), payload.size());
    std::istream in(&buffer);
    in.exceptions(std::ios::failbit | std::ios::badbit | std::ios::eofbit);
    try {
        openvdb::io::Stream stream(in, /*delayLoad=*/false);
        return {stream.getMetadata(), stream.getGrids()};
    } catch (const std::ios_base::failure&) {
        throw Error(name + " is not a readable OpenVDB file (it ends early: truncated?)");
    } catch (const std::bad_alloc&) {
        throw Error(name + " is not a readable OpenVDB file (it declares sizes beyond memory)");
    } catch (const std::exception& e) {
        throw Error(name + " is not a readable OpenVDB file (" + what(e) + ")");
    }
}

// OpenVDB's own writer, seekable (grid offsets, as io::File writes them) into memory: io::File does not check
// its writes (a full disk gave a truncated file and "wrote"), the checked writer does.
struct MemoryArchive : openvdb::io::Archive {
    std::string bytes(const openvdb::GridPtrVec& grids, const openvdb::MetaMap& meta) const {
        std::ostringstream out(std::ios::binary);
        out.exceptions(std::ios::failbit | std::ios::badbit);
        Archive::write(out, grids, /*seekable=*/true, meta);
        return std::move(out).str();
    }
};

// The file's grid named `name` (the last, should a file repeat a name), or null.
openvdb::GridBase::Ptr findGrid(const VoxelStream& file, const char* name) {
    openvdb::GridBase::Ptr found;
    for (const openvdb::GridBase::Ptr& grid : *file.grids)
        if (grid && grid->getName() == name) found = grid;
    return found;
}

template <typename GridT>
typename GridT::Ptr readGrid(const VoxelStream& file, const char* name, uint32_t n,
                             const std::filesystem::path& path) {
    const openvdb::GridBase::Ptr base = findGrid(file, name);
    if (!base) throw Error("voxel file " + quoted(path) + " has no '" + name + "' grid");
    typename GridT::Ptr grid = openvdb::gridPtrCast<GridT>(base);
    if (!grid)
        throw Error("voxel file " + quoted(path) + ": grid '" + name + "' holds " + base->valueType() +
                    ", expected " + openvdb::typeNameAsString<typename GridT::ValueType>());
    // Files from other tools may store uniform blocks as tiles: every active value must lie in the grid
    // before they become voxels (a root-level tile alone is 4096^3 of them).
    const openvdb::CoordBBox box = grid->evalActiveVoxelBoundingBox();
    if (grid->activeVoxelCount() > 0 && (!inGrid(ivec(box.min()), n) || !inGrid(ivec(box.max()), n) ||
                                         grid->activeVoxelCount() > uint64_t(n) * n * n)) {
        std::ostringstream message;
        message << "voxel file " << quoted(path) << ": grid '" << name << "' has active values from ("
                << box.min().x() << ", " << box.min().y() << ", " << box.min().z() << ") to ("
                << box.max().x() << ", " << box.max().y() << ", " << box.max().z() << "), outside the " << n
                << "^3 grid";
        throw Error(message.str());
    }
    grid->tree().voxelizeActiveTiles();
    return grid;
}

// The active voxels of `grid` (which decides what is occupied), sorted by linear index, checked to lie in
// the grid.
template <typename GridT>
std::vector<glm::ivec3> activeVoxels(const GridT& grid, uint32_t n, const std::filesystem::path& path) {
    std::vector<glm::ivec3> voxels;
    voxels.reserve(size_t(grid.activeVoxelCount()));
    for (auto it = grid.cbeginValueOn(); it; ++it) {
        const glm::ivec3 ijk = ivec(it.getCoord());
        if (!inGrid(ijk, n)) {
            std::ostringstream message;
            message << "voxel file " << quoted(path) << ": grid '" << grid.getName() << "' has a voxel at ("
                    << ijk.x << ", " << ijk.y << ", " << ijk.z << "), outside the " << n << "^3 grid";
            throw Error(message.str());
        }
        voxels.push_back(ijk);
    }
    std::sort(voxels.begin(), voxels.end(),
              [n](glm::ivec3 a, glm::ivec3 b) { return voxelFileIndex(a, n) < voxelFileIndex(b, n); });
    return voxels;
}

}  // namespace

uint64_t denseVoxelBytes(uint32_t resolution) {
    // albedo, normal, emission, radiance (vec3s) + opacity (float) + static_count and the transparency sum
    // (int32) + 3 sums (vec3i).
    constexpr uint64_t perVoxel =
        4 * sizeof(openvdb::Vec3s) + sizeof(float) + 2 * sizeof(int32_t) + 3 * sizeof(openvdb::Vec3i);
    return uint64_t(resolution) * resolution * resolution * perVoxel;
}

namespace {

// The nine grids of a voxel file, each with its description (what a reader of the .vdb sees in its metadata).
struct VoxelFileGrids {
    openvdb::Vec3SGrid::Ptr albedo, normal, emission, radiance;
    openvdb::FloatGrid::Ptr opacity;
    openvdb::Int32Grid::Ptr count;
    openvdb::Vec3IGrid::Ptr albedoSum, normalSum, emissionSum;
    openvdb::Int32Grid::Ptr transparencySum, metallicSum, roughnessSum;

    openvdb::GridPtrVec all() const {
        return {albedo,    normal,    emission,    opacity,         radiance,    count,
                albedoSum, normalSum, emissionSum, transparencySum, metallicSum, roughnessSum};
    }
};

VoxelFileGrids makeVoxelFileGrids(const VoxelFileInfo& info) {
    // Index → world: scale by the voxel size, then move index 0 to the centre of the min-corner voxel.
    openvdb::math::Transform::Ptr transform =
        openvdb::math::Transform::createLinearTransform(double(info.voxelSize));
    const glm::dvec3 firstCentre = glm::dvec3(info.origin) + 0.5 * double(info.voxelSize);
    transform->postTranslate(openvdb::Vec3d(firstCentre.x, firstCentre.y, firstCentre.z));

    VoxelFileGrids g;
    g.albedo = makeGrid<openvdb::Vec3SGrid>(
        kAlbedo, "resolved albedo (linear RGB) of the frame at vct_time: static + moving instances", info,
        transform);
    g.normal = makeGrid<openvdb::Vec3SGrid>(
        kNormal, "averaged surface normal (world space, not renormalised: shorter where surfaces disagree)",
        info, transform);
    g.emission = makeGrid<openvdb::Vec3SGrid>(kEmission, "emitted radiance (linear RGB)", info, transform);
    g.opacity = makeGrid<openvdb::FloatGrid>(
        kOpacity, "coverage: 1 where an opaque surface touches the voxel, blended ones by their alpha", info,
        transform);
    g.radiance = makeGrid<openvdb::Vec3SGrid>(
        kRadiance,
        "injected outgoing radiance of mip 0 at vct_time (direct light + emission), premultiplied by opacity",
        info, transform);
    g.count = makeGrid<openvdb::Int32Grid>(
        kStaticCount, "voxelize samples of static geometry (the accumulator's count; the voxel cache)", info,
        transform);
    g.albedoSum = makeGrid<openvdb::Vec3IGrid>(
        kStaticAlbedo, "static geometry: sum of albedo x 1023 over static_count samples (uint32 bits)", info,
        transform);
    g.normalSum = makeGrid<openvdb::Vec3IGrid>(
        kStaticNormal, "static geometry: sum of normal x 1023 over static_count samples (two's complement)",
        info, transform);
    g.emissionSum = makeGrid<openvdb::Vec3IGrid>(
        kStaticEmission, "static geometry: sum of emission x 256 over static_count samples (uint32 bits)",
        info, transform);
    g.transparencySum = makeGrid<openvdb::Int32Grid>(
        kStaticTransparency,
        "static geometry: sum of (1 - alpha) x 1023 of alpha-blended samples over static_count (0: opaque)",
        info, transform);
    g.metallicSum = makeGrid<openvdb::Int32Grid>(
        kStaticMetallic, "static geometry: sum of metallic x 1023 over static_count samples", info,
        transform);
    g.roughnessSum = makeGrid<openvdb::Int32Grid>(
        kStaticRoughness, "static geometry: sum of perceptual roughness x 1023 over static_count samples",
        info, transform);
    g.opacity->setGridClass(openvdb::GRID_FOG_VOLUME);
    g.normal->setVectorType(openvdb::VEC_COVARIANT);
    return g;
}

Error voxelOutsideGrid(const std::filesystem::path& path, glm::ivec3 ijk, uint32_t n) {
    std::ostringstream message;
    message << "cannot write voxel file " << quoted(path) << ": voxel (" << ijk.x << ", " << ijk.y << ", "
            << ijk.z << ") is outside the " << n << "^3 grid";
    return Error(message.str());
}

// The frame's resolved voxels: albedo, normal, emission, opacity, radiance.
void fillFrameGrids(const std::filesystem::path& path, const VoxelFile& data, VoxelFileGrids& g) {
    const uint32_t n = data.info.resolution;
    auto a = g.albedo->getAccessor();
    auto nr = g.normal->getAccessor();
    auto e = g.emission->getAccessor();
    auto o = g.opacity->getAccessor();
    auto r = g.radiance->getAccessor();
    for (const VoxelSample& v : data.voxels) {
        if (!inGrid(v.ijk, n)) throw voxelOutsideGrid(path, v.ijk, n);
        // A reader refuses these: never write what cannot be read back.
        if (!finite3(v.albedo) || !finite3(v.normal) || !finite3(v.emission) || !finite3(v.radiance) ||
            !std::isfinite(v.opacity))
            throw Error("cannot write voxel file " + quoted(path) + ": voxel (" + std::to_string(v.ijk.x) +
                        ", " + std::to_string(v.ijk.y) + ", " + std::to_string(v.ijk.z) +
                        ") holds a non-finite value");
        const openvdb::Coord c = coord(v.ijk);
        a.setValueOn(c, vec3s(v.albedo));
        nr.setValueOn(c, vec3s(v.normal));
        e.setValueOn(c, vec3s(v.emission));
        o.setValueOn(c, v.opacity);
        r.setValueOn(c, vec3s(v.radiance));
    }
}

// The static geometry's exact voxelize accumulator (the voxel cache).
void fillStaticGrids(const std::filesystem::path& path, const VoxelFile& data, VoxelFileGrids& g) {
    const uint32_t n = data.info.resolution;
    auto c = g.count->getAccessor();
    auto a = g.albedoSum->getAccessor();
    auto nr = g.normalSum->getAccessor();
    auto e = g.emissionSum->getAccessor();
    auto t = g.transparencySum->getAccessor();
    auto m = g.metallicSum->getAccessor();
    auto ro = g.roughnessSum->getAccessor();
    for (const StaticAccumVoxel& v : data.staticAccum) {
        if (!inGrid(v.ijk, n)) throw voxelOutsideGrid(path, v.ijk, n);
        const openvdb::Coord ijk = coord(v.ijk);
        a.setValueOn(ijk, vec3i(&v.accum[0]));
        nr.setValueOn(ijk, vec3i(&v.accum[3]));
        e.setValueOn(ijk, vec3i(&v.accum[6]));
        c.setValueOn(ijk, std::bit_cast<int32_t>(v.accum[9]));
        t.setValueOn(ijk, std::bit_cast<int32_t>(v.accum[10]));
        m.setValueOn(ijk, std::bit_cast<int32_t>(v.accum[VCT_VOXEL_ACCUM_METALLIC]));
        ro.setValueOn(ijk, std::bit_cast<int32_t>(v.accum[VCT_VOXEL_ACCUM_ROUGHNESS]));
    }
}

// Serialised in memory, sealed with the integrity trailer, then written through the checked writer: a symlink
// planted there is replaced, not followed; a full disk is an error.
void writeSealed(const std::filesystem::path& path, const openvdb::GridPtrVec& grids,
                 const VoxelFileInfo& info) {
    openvdb::MetaMap fileMeta;
    insertCommonMeta(fileMeta, info);
    fileMeta.insertMeta(
        "vct_grids",
        openvdb::StringMetadata("albedo, normal, emission, opacity, radiance: the frame at vct_time; "
                                "static_*: the static geometry's exact voxelize accumulator (the "
                                "voxel cache read by vct render --voxel-cache)"));
    const std::filesystem::path dir =
        path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
    std::error_code error;
    if (!std::filesystem::is_directory(dir, error))
        throw Error("cannot write voxel file " + quoted(path) + ": directory '" + dir.string() +
                    "' does not exist");
    std::string bytes;
    try {
        bytes = MemoryArchive().bytes(grids, fileMeta);
    } catch (const std::exception& e) {
        throw Error("cannot write voxel file " + quoted(path) + " (" + what(e) + ")");
    }
    bytes += trailerFor(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size());
    writeFileReplacing(path, bytes);
}

}  // namespace

std::vector<VoxelGridSummary> writeVoxelFile(const std::filesystem::path& path, const VoxelFile& data) {
    initializeOpenVdb();
    const VoxelFileInfo& info = data.info;
    const uint32_t n = info.resolution;
    if (n < 1 || n > 4096 || !(info.voxelSize > 0.0f))
        throw Error("cannot write voxel file " + quoted(path) + ": bad grid (resolution " +
                    std::to_string(n) + ", voxel size " + std::to_string(info.voxelSize) + ")");
    VoxelFileGrids grids = makeVoxelFileGrids(info);
    fillFrameGrids(path, data, grids);
    fillStaticGrids(path, data, grids);
    writeSealed(path, grids.all(), info);

    std::vector<VoxelGridSummary> summary;
    for (const openvdb::GridBase::Ptr& grid : grids.all())
        summary.push_back({grid->getName(), grid->valueType(), uint64_t(grid->activeVoxelCount())});
    return summary;
}

void setVoxelFileIsolation(const std::filesystem::path& program) {
    std::lock_guard<std::mutex> lock(isolationMutex);
    isolationProgram = program;
}

int checkVoxelFileInIsolation(const std::filesystem::path& path, const std::string& checksum) {
    {
        std::lock_guard<std::mutex> lock(isolationMutex);
        isolationProgram.clear();  // this is the isolated parse: no further process
    }
    try {
        // The whole file, as this version of vct reads it (every grid, tiles voxelized).
        const FileRead file = readRegularFile(path);
        if (!file.error.empty() || file.bytes.size() < kTrailerBytes) return 1;
        if (hexText(payloadChecksum(file.bytes.data(), file.bytes.size() - kTrailerBytes)) != checksum)
            return 1;  // not the file the caller checked
        // Everything this process would do with it; what is refused here (tiles outside the grid, impossible
        // values) the caller refuses too, with its own message: only a crash or a hang is reported for this.
        try {
            readVoxelFile(path, true);
        } catch (const std::exception&) {
        }
        return 0;
    } catch (...) {
        return 1;
    }
}

void sealVoxelFile(const std::filesystem::path& path) {
    const FileRead file = readRegularFile(path);
    if (!file.error.empty()) throw Error("cannot seal voxel file " + quoted(path) + ": " + file.error);
    std::string bytes(file.bytes.begin(), file.bytes.end());
    bytes += trailerFor(file.bytes.data(), file.bytes.size());
    writeFileReplacing(path, bytes);
}

VoxelFileInfo readVoxelFileInfo(const std::filesystem::path& path) {
    initializeOpenVdb();
    return readInfo(*openFile(path).meta, path);
}

namespace {

// The voxelize pass's fixed-point scales (shaders/lib/voxel.glsl): albedo and normals x 1023, emission x 256
// clamped to 4096 per sample. A cached voxel whose sums no sample count can give is damaged or forged: it
// would inject light (or NaN after the division) the scene does not have.
constexpr uint64_t kUnitScale = 1023;
constexpr uint64_t kEmissionPerSample = 4096 * 256;
constexpr uint64_t kMaxSamplesPerVoxel = uint64_t(1) << 22;  // where the albedo sums would wrap

std::string accumProblem(const StaticAccumVoxel& v) {
    const uint64_t count = v.accum[9];
    if (count == 0 || count > kMaxSamplesPerVoxel)
        return "static_count " + std::to_string(int32_t(v.accum[9])) + ", expected 1.." +
               std::to_string(kMaxSamplesPerVoxel);
    // The single-word sums of unit values (× 1023 each sample).
    for (auto [word, name] : {std::pair{VCT_VOXEL_ACCUM_TRANSPARENCY, "transparency"},
                              {VCT_VOXEL_ACCUM_METALLIC, "metallic"},
                              {VCT_VOXEL_ACCUM_ROUGHNESS, "roughness"}})
        if (uint64_t(v.accum[size_t(word)]) > kUnitScale * count)
            return std::string(name) + " sum above 1023 x static_count";
    for (int c = 0; c < 3; ++c) {
        if (uint64_t(v.accum[size_t(c)]) > kUnitScale * count) return "albedo sum above 1023 x static_count";
        if (uint64_t(std::abs(int64_t(std::bit_cast<int32_t>(v.accum[size_t(3 + c)])))) > kUnitScale * count)
            return "normal sum beyond 1023 x static_count";
        if (uint64_t(v.accum[size_t(6 + c)]) > std::min<uint64_t>(UINT32_MAX, kEmissionPerSample * count))
            return "emission sum above 4096 x 256 x static_count";
    }
    return {};
}

VoxelFile readVoxels(const std::filesystem::path& path, bool frame) {
    const VoxelStream file = openFile(path);
    VoxelFile data;
    data.info = readInfo(*file.meta, path);
    const uint32_t n = data.info.resolution;

    {
        auto count = readGrid<openvdb::Int32Grid>(file, kStaticCount, n, path);
        auto albedoSum = readGrid<openvdb::Vec3IGrid>(file, kStaticAlbedo, n, path);
        auto normalSum = readGrid<openvdb::Vec3IGrid>(file, kStaticNormal, n, path);
        auto emissionSum = readGrid<openvdb::Vec3IGrid>(file, kStaticEmission, n, path);
        // Files written before blended surfaces were voxelized by their alpha have no transparency: opaque.
        auto transparencySum = findGrid(file, kStaticTransparency)
                                   ? readGrid<openvdb::Int32Grid>(file, kStaticTransparency, n, path)
                                   : openvdb::Int32Grid::create(0);
        // Files written before the voxels held a material for their specular lobes have no metallic and
        // roughness sums: refused by name (reading them as some default would change the light silently).
        for (const char* name : {kStaticMetallic, kStaticRoughness}) {
            if (!findGrid(file, name))
                throw Error("voxel file " + quoted(path) + " has no " + name +
                            " grid (written by an older vct): write it again with vct voxelize");
        }
        auto metallicSum = readGrid<openvdb::Int32Grid>(file, kStaticMetallic, n, path);
        auto roughnessSum = readGrid<openvdb::Int32Grid>(file, kStaticRoughness, n, path);
        auto m = metallicSum->getConstAccessor();
        auto ro = roughnessSum->getConstAccessor();
        auto t = transparencySum->getConstAccessor();
        auto c = count->getConstAccessor();
        auto a = albedoSum->getConstAccessor();
        auto nr = normalSum->getConstAccessor();
        auto e = emissionSum->getConstAccessor();
        for (glm::ivec3 ijk : activeVoxels(*count, n, path)) {
            StaticAccumVoxel v;
            v.ijk = ijk;
            const openvdb::Coord x = coord(ijk);
            fromVec3i(a.getValue(x), &v.accum[0]);
            fromVec3i(nr.getValue(x), &v.accum[3]);
            fromVec3i(e.getValue(x), &v.accum[6]);
            v.accum[9] = std::bit_cast<uint32_t>(c.getValue(x));
            v.accum[10] = std::bit_cast<uint32_t>(t.getValue(x));
            v.accum[VCT_VOXEL_ACCUM_METALLIC] = std::bit_cast<uint32_t>(m.getValue(x));
            v.accum[VCT_VOXEL_ACCUM_ROUGHNESS] = std::bit_cast<uint32_t>(ro.getValue(x));
            if (std::string bad = accumProblem(v); !bad.empty()) {
                std::ostringstream message;
                message << "voxel file " << quoted(path) << ": voxel (" << ijk.x << ", " << ijk.y << ", "
                        << ijk.z << ") holds values the voxelize pass cannot produce (" << bad << ")";
                throw Error(message.str());
            }
            data.staticAccum.push_back(v);
        }
    }
    if (frame) {
        auto opacity = readGrid<openvdb::FloatGrid>(file, kOpacity, n, path);
        auto albedo = readGrid<openvdb::Vec3SGrid>(file, kAlbedo, n, path);
        auto normal = readGrid<openvdb::Vec3SGrid>(file, kNormal, n, path);
        auto emission = readGrid<openvdb::Vec3SGrid>(file, kEmission, n, path);
        auto radiance = readGrid<openvdb::Vec3SGrid>(file, kRadiance, n, path);
        auto o = opacity->getConstAccessor();
        auto a = albedo->getConstAccessor();
        auto nr = normal->getConstAccessor();
        auto e = emission->getConstAccessor();
        auto r = radiance->getConstAccessor();
        for (glm::ivec3 ijk : activeVoxels(*opacity, n, path)) {
            VoxelSample v;
            v.ijk = ijk;
            const openvdb::Coord x = coord(ijk);
            v.opacity = o.getValue(x);
            v.albedo = vec3(a.getValue(x));
            v.normal = vec3(nr.getValue(x));
            v.emission = vec3(e.getValue(x));
            v.radiance = vec3(r.getValue(x));
            if (!finite3((v.albedo)) || !finite3((v.normal)) || !finite3((v.emission)) ||
                !finite3((v.radiance)) || !std::isfinite(v.opacity) ||
                glm::any(glm::lessThan(v.radiance, glm::vec3(0.0f))) ||
                glm::any(glm::lessThan(v.emission, glm::vec3(0.0f)))) {
                std::ostringstream message;
                message << "voxel file " << quoted(path) << ": voxel (" << ijk.x << ", " << ijk.y << ", "
                        << ijk.z << ") holds a non-finite or negative value";
                throw Error(message.str());
            }
            data.voxels.push_back(v);
        }
    }
    return data;
}

}  // namespace

VoxelFile readVoxelFile(const std::filesystem::path& path, bool frame) {
    initializeOpenVdb();
    try {
        return readVoxels(path, frame);
    } catch (const Error&) {
        throw;  // names the file already
    } catch (const std::bad_alloc&) {
        throw Error("voxel file " + quoted(path) +
                    ": out of memory (it declares more voxels than this machine can hold)");
    } catch (const std::exception& e) {
        throw Error("voxel file " + quoted(path) + ": " + what(e));
    }
}

}  // namespace vct
