// What an input file may make vct read and allocate, and the checked reads and arithmetic that hold it to
// that. Shared by the glTF loader, the voxel cache and the camera paths: a hostile file (a uri naming a FIFO,
// an offset that wraps past 2^64, JSON nested 100 000 deep, a count that would allocate gigabytes) ends in a
// vct::Error instead of a hang, a crash or an allocation the file's size does not justify.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace vct {

// The largest file read whole (a .gltf/.glb, a buffer, an image, a voxel cache): tinygltf and stb take sizes
// as 32-bit ints.
inline constexpr uint64_t kMaxInputFileBytes = (uint64_t(1) << 31) - 1;
// Deepest JSON nesting accepted. glTF itself needs 6 levels; extras a few more. tinygltf copies extras
// recursively and overflows the stack somewhere past 5 000.
inline constexpr int kMaxJsonDepth = 128;
// Largest decoded texture (8192 x 8192): a small PNG of one colour can declare any size.
inline constexpr uint64_t kMaxTexturePixels = uint64_t(1) << 26;
// Most elements one accessor may have (2^25 vertices is ~1.6 GB of vertex data).
inline constexpr uint64_t kMaxAccessorElements = uint64_t(1) << 25;

// Whole-file budgets (a small file must not make us build gigabytes by reusing its data):
// vertices + indices built from all primitives together, and animation keys copied into all channels
// together: at most one per byte of input (at least kMinElementBudget), and never more than kMaxSceneElements.
inline constexpr uint64_t kMaxSceneElements = uint64_t(1) << 25;
inline constexpr uint64_t kMinElementBudget = uint64_t(1) << 22;
// Texels of all decoded images together, and of all textures made from them (an image used as colour and
// as data is two textures): 2^28 is 16 textures of 4096^2 (1 GB as RGBA8).
inline constexpr uint64_t kMaxSceneTexels = uint64_t(1) << 28;
// Triangles drawn per frame over every instance of every mesh (2 000 nodes instancing one 100k-triangle mesh
// are 200M: minutes per frame on a CPU device).
inline constexpr uint64_t kMaxInstancedTriangles = uint64_t(1) << 24;

// Reads a whole file after checking, on the opened descriptor (no race with a swapped path, no blocking open
// of a FIFO), that it is a regular file of at most `maxBytes`. Returns the problem instead of the bytes
// when it cannot ("not a regular file (a FIFO)", "is 3 GB, more than the 2 GB allowed", ...).
struct FileRead {
    std::vector<unsigned char> bytes;
    std::string error;  // empty on success
};
FileRead readRegularFile(const std::filesystem::path& path, uint64_t maxBytes = kMaxInputFileBytes);

// The one checked open every input goes through: O_NONBLOCK (a FIFO never blocks), the type and size checked
// on the descriptor. `error` is empty when it is open; reads are bounded by the size it had when opened.
class InputFile {
  public:
    InputFile(const std::filesystem::path& path, uint64_t maxBytes = kMaxInputFileBytes);
    ~InputFile();
    InputFile(const InputFile&) = delete;
    InputFile& operator=(const InputFile&) = delete;
    const std::string& error() const { return error_; }
    uint64_t size() const { return size_; }
    // `length` bytes from `offset` (within size()); the problem when it cannot read them all.
    std::string readAt(uint64_t offset, uint64_t length, std::vector<unsigned char>& out) const;

  private:
    int fd_ = -1;
    uint64_t size_ = 0;
    std::string error_;
};

// The one checked write every output goes through: `bytes` into a fresh file beside `path` (O_EXCL), every
// write checked, fsync'ed, then renamed over `path` (a symlink planted there is replaced, never followed; a
// half-written file never carries the final name). Refuses a `path` that exists and is neither a regular file
// nor a symlink (a device node, a FIFO, a directory). Throws vct::Error "cannot write PATH: why".
void writeFileReplacing(const std::filesystem::path& path, std::string_view bytes);

// Why `path` cannot be opened as an input file (missing, not a regular file, too large), or nothing. Only
// stat(): a FIFO is never opened.
std::optional<std::string> regularFileProblem(const std::filesystem::path& path,
                                              uint64_t maxBytes = kMaxInputFileBytes);

// Depth of the deepest array/object nesting in JSON text (strings skipped), stopping early once past
// `limit`. Cheap and without recursion, so it can run before a recursive parser sees the text.
int jsonNestingDepth(std::string_view text, int limit);

// Overflow-checked size arithmetic: false when the exact result does not fit in 64 bits.
inline bool checkedAdd(uint64_t a, uint64_t b, uint64_t& out) {
    return !__builtin_add_overflow(a, b, &out);
}
inline bool checkedMul(uint64_t a, uint64_t b, uint64_t& out) {
    return !__builtin_mul_overflow(a, b, &out);
}
// Whether [offset, offset + length) lies within [0, size), without overflow.
inline bool rangeWithin(uint64_t offset, uint64_t length, uint64_t size) {
    return offset <= size && length <= size - offset;
}

// Text from a file or a library made fit for a one-line message: control characters escaped (\n, \x1b),
// at most `maxChars` characters kept (the middle elided).
std::string printableText(std::string_view text, size_t maxChars = 200);

// "1.5 GB" style sizes for messages.
std::string byteSizeText(uint64_t bytes);
// A number for messages, %g style ("1e-20", "0.5", "inf"): std::to_string prints 1e-20 as 0.000000.
std::string numberText(double value);

}  // namespace vct
